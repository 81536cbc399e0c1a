/*
 * Tests of the memory image (host/memimage): triangle transformations (A, B, C, N map to the
 * unit triangle within tolerance; degenerate triangles are detected), the image layout and its
 * validator, instancing end to end in fp24 (world vertex -> instance matrix -> triangle matrix
 * lands on the unit-triangle corner), the too-small-memory error, per-frame updates of rigid and
 * morphing objects, and random corruption of valid images (rejected, or still safe to walk).
 */
#define _GNU_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "f24.h"
#include "shade_encode.h"
#include "f24_fast.h"
#include "image_probe.h"
#include "memimage.h"
#include "rgs.h"
#include "trace.h"
#include "scene.h"

static double f24d(uint32_t w) { return f24_fast_decode(w); }

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double urand(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

/* ---- triangle transformations ------------------------------------------------------------ */

/* A triangle transformation as the record holds it, M^-1 and the vertex C: p -> M^-1 (p - C). */
static void apply(const affine *t, const double p[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = t->m[i][0] * (p[0] - t->m[0][3]) + t->m[i][1] * (p[1] - t->m[1][3]) + t->m[i][2] * (p[2] - t->m[2][3]);
}

static void transform_maps_vertices(void **state)
{
    (void)state;
    for (int i = 0; i < 1000; i++) {
        double a[3], b[3], c[3], n[3];
        const double scale = pow(10.0, 6 * urand() - 3);
        for (int k = 0; k < 3; k++) {
            a[k] = scale * (urand() - 0.5) + 100 * urand();
            b[k] = a[k] + scale * (urand() - 0.5);
            c[k] = a[k] + scale * (urand() - 0.5);
        }
        affine t;
        if (!mi_triangle_transform(a, b, c, 1e6, &t))
            continue;
        double pa[3], pb[3], pc[3], pn[3];
        apply(&t, a, pa);
        apply(&t, b, pb);
        apply(&t, c, pc);
        const double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; k++)
            n[k] /= len;
        affine_apply_vector(&t, n, pn);
        const double want[4][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 0 }, { 0, 0, 1 } };
        const double *got[4] = { pa, pb, pc, pn };
        for (int v = 0; v < 4; v++)
            for (int k = 0; k < 3; k++)
                assert_float_equal(got[v][k], want[v][k], 1e-7);
    }
}

static void degenerate_triangles(void **state)
{
    (void)state;
    affine t;
    const double o[3] = { 0, 0, 0 }, x[3] = { 1, 0, 0 }, y[3] = { 0, 1, 0 }, x2[3] = { 2, 0, 0 };
    const double sliver[3] = { 0.5, 1e-9, 0 }, thin[3] = { 0.5, 1e-3, 0 }, inf[3] = { INFINITY, 0, 0 };
    assert_int_equal(mi_triangle_transform(o, x, y, 1 << 24, &t), 1);
    assert_int_equal(mi_triangle_transform(o, x, x2, 1 << 24, &t), 0);  /* collinear */
    assert_int_equal(mi_triangle_transform(o, x, x, 1 << 24, &t), 0);   /* repeated vertex */
    assert_int_equal(mi_triangle_transform(o, o, o, 1 << 24, &t), 0);   /* a point */
    assert_int_equal(mi_triangle_transform(o, x, sliver, 1 << 24, &t), 0); /* aspect 1e9 */
    assert_int_equal(mi_triangle_transform(o, x, thin, 1 << 24, &t), 1);   /* aspect 1e3 is kept */
    assert_int_equal(mi_triangle_transform(o, x, thin, 100, &t), 0);       /* ... unless K is small */
    assert_int_equal(mi_triangle_transform(o, x, inf, 1 << 24, &t), 0);
    /* size alone is not a degeneracy */
    const double tiny_x[3] = { 1e-6, 0, 0 }, tiny_y[3] = { 0, 1e-6, 0 };
    assert_int_equal(mi_triangle_transform(o, tiny_x, tiny_y, 1 << 24, &t), 1);
}

/* ---- test scenes ------------------------------------------------------------------------- */

static float *floats(const float *v, size_t n)
{
    float *p = malloc(n * sizeof *p);
    memcpy(p, v, n * sizeof *p);
    return p;
}

/* A tetrahedron (+ one degenerate triangle), instanced `copies` times along x; optionally a
 * second mesh with one morph target on its own node. */
static void make_scene(scene *s, uint32_t copies, int morph)
{
    memset(s, 0, sizeof *s);
    static const float tet[] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    static const uint32_t tet_idx[] = { 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 0, 1 };
    s->n_meshes = morph ? 2 : 1;
    s->meshes = calloc(s->n_meshes, sizeof *s->meshes);
    for (uint32_t m = 0; m < s->n_meshes; m++) {
        scene_mesh *me = &s->meshes[m];
        snprintf(me->name, sizeof me->name, "mesh%u", m);
        me->n_vertices = 4;
        me->n_triangles = 5;
        me->positions = floats(tet, 12);
        me->indices = malloc(sizeof tet_idx);
        memcpy(me->indices, tet_idx, sizeof tet_idx);
        me->material = calloc(5, sizeof *me->material);
    }
    if (morph) {
        scene_mesh *me = &s->meshes[1];
        static const float delta[] = { 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 1 };
        me->n_targets = 1;
        me->base_positions = floats(tet, 12);
        me->target_deltas = floats(delta, 12);
        me->weights = calloc(1, sizeof(float));
    }
    s->n_materials = 1;
    s->materials = calloc(1, sizeof *s->materials);
    s->materials[0].base_color[0] = 0.8f;
    s->materials[0].base_color_texture = s->materials[0].emissive_texture = SCENE_NONE;
    s->n_nodes = copies + (morph ? 1 : 0);
    s->nodes = calloc(s->n_nodes, sizeof *s->nodes);
    s->roots = calloc(s->n_nodes, sizeof *s->roots);
    s->n_roots = s->n_nodes;
    for (uint32_t i = 0; i < s->n_nodes; i++) {
        scene_node *n = &s->nodes[i];
        n->parent = -1;
        n->mesh = i < copies ? 0 : 1;
        n->camera = n->light = SCENE_NONE;
        n->translation[0] = 3.0 * i;
        n->rotation[3] = 1;
        n->scale[0] = n->scale[1] = n->scale[2] = 1 + 0.25 * i;
        s->roots[i] = i;
        if (n->mesh == 1) {
            n->n_weights = 1;
            n->weights = calloc(1, sizeof(double));
        }
    }
    assert_int_equal(scene_evaluate(s, 0, 0), 0);
}

static mi_builder *build_with(const scene *s, uint64_t mem, uint32_t accel)
{
    mi_params p;
    mi_params_default(&p);
    p.accel = accel;
    if (mem)
        p.memory_bytes = mem;
    char err[256];
    mi_builder *b = mi_build(s, &p, err, sizeof err);
    if (!b)
        fail_msg("mi_build: %s", err);
    return b;
}

static mi_builder *build(const scene *s, uint64_t mem) { return build_with(s, mem, 0); }

static void layout_and_validate(void **state)
{
    (void)state;
    scene s;
    make_scene(&s, 3, 0);
    mi_builder *b = build(&s, 0);
    uint32_t n;
    const uint32_t *w = mi_words(b, &n);
    char err[256];
    if (mi_validate(w, n, err, sizeof err) != 0)
        fail_msg("%s", err);
    assert_int_equal(w[MI_H_MAGIC], MI_MAGIC);
    assert_int_equal(w[MI_H_OBJECTS], 1);
    assert_int_equal(w[MI_H_INSTANCES], 3);
    assert_int_equal(w[MI_H_USED_WORDS], n);
    const mi_stats *st = mi_get_stats(b);
    assert_int_equal(st->degenerate_triangles, 1);
    const uint32_t *obj = w + w[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
    assert_int_equal(obj[MI_O_N_TRIANGLES], 4);
    /* the object's bounds contain the tetrahedron, rounded outward */
    for (int k = 0; k < 3; k++) {
        assert_true(f24d(obj[MI_O_BOUNDS + k]) <= 0.0);
        assert_true(f24d(obj[MI_O_BOUNDS + 3 + k]) >= 1.0);
    }
    mi_free(b);
    scene_free(&s);
}

/* World-space vertex -> instance world-to-object -> triangle transformation, all in fp24 values,
 * lands on the unit-triangle corners: the instanced object equals the flattened mesh. */
static void instancing_end_to_end(void **state)
{
    (void)state;
    scene s;
    make_scene(&s, 4, 0);
    mi_builder *b = build(&s, 0);
    uint32_t n;
    const uint32_t *w = mi_words(b, &n);
    const uint32_t *obj = w + w[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
    for (uint32_t i = 0; i < w[MI_H_INSTANCES]; i++) {
        const uint32_t *in = w + w[MI_H_REGION_TABLE + 2 * MI_R_INSTANCES] + MI_INSTANCE_WORDS * i;
        affine w2o, tri;
        for (int r = 0; r < 3; r++) {
            for (int c = 0; c < 4; c++)
                w2o.m[r][c] = f24d(in[4 * r + c]);
            w2o.m[r][3] += f24d(in[MI_I_T_LO + r]); /* the translation's low word */
        }
        const scene_instance *si = &s.instances[i];
        for (uint32_t t = 0; t < obj[MI_O_N_TRIANGLES]; t++) {
            const uint32_t tw = obj[MI_O_TRIANGLES] + MI_TRIANGLE_WORDS * t;
            const f24_triangle rec = f24_triangle_load(w, tw);
            const f24_t c_lo[3] = { rec.c_lo.x, rec.c_lo.y, rec.c_lo.z };
            for (int r = 0; r < 3; r++) {
                for (int c = 0; c < 4; c++)
                    tri.m[r][c] = f24d(rec.m.m[r][c]);
                tri.m[r][3] += f24d(c_lo[r]); /* C's low part */
            }
            const scene_mesh *m = &s.meshes[0];
            for (int k = 0; k < 3; k++) { /* image triangle t is mesh triangle t (the degenerate one is last) */
                const float *p = &m->positions[3 * m->indices[3 * t + (uint32_t)k]];
                const double op[3] = { p[0], p[1], p[2] };
                double wp[3], q[3], u[3];
                affine_apply_point(&si->world, op, wp);
                affine_apply_point(&w2o, wp, q);
                apply(&tri, q, u);
                for (int j = 0; j < 3; j++)
                    assert_float_equal(u[j], j == k && k < 2 ? 1.0 : 0.0, 1e-3);
            }
        }
    }
    mi_free(b);
    scene_free(&s);
}

static void too_small_memory(void **state)
{
    (void)state;
    scene s;
    make_scene(&s, 20000, 0);
    mi_params p;
    mi_params_default(&p);
    p.memory_bytes = 64 * 1024;
    char err[256] = "";
    assert_null(mi_build(&s, &p, err, sizeof err));
    assert_non_null(strstr(err, "does not fit"));
    assert_non_null(strstr(err, "INSTANCES"));
    scene_free(&s);
}

static void frames_upload_only_what_changed(void **state)
{
    (void)state;
    scene s;
    make_scene(&s, 2, 1);
    mi_builder *b = build(&s, 0);
    uint32_t n0;
    const uint32_t *w0 = mi_words(b, &n0);
    const uint32_t static_off = w0[MI_H_REGION_TABLE + 2 * MI_R_STATIC_GEOMETRY];
    const uint32_t static_len = w0[MI_H_REGION_TABLE + 2 * MI_R_STATIC_GEOMETRY + 1];
    uint32_t *saved = malloc(static_len * sizeof *saved);
    memcpy(saved, w0 + static_off, static_len * sizeof *saved);
    const uint64_t full = mi_get_stats(b)->frame_upload_bytes;
    assert_int_equal(full, (uint64_t)n0 * 4);

    /* move an instance: per-frame regions only */
    s.nodes[0].translation[1] = 5;
    assert_int_equal(scene_evaluate(&s, 0, 0), 0);
    char err[256];
    assert_int_equal(mi_update(b, &s, err, sizeof err), 0);
    uint32_t n1;
    const uint32_t *w1 = mi_words(b, &n1);
    assert_int_equal(mi_get_stats(b)->rebuilt_objects, 0);
    assert_true(mi_get_stats(b)->frame_upload_bytes < full);
    assert_memory_equal(w1 + static_off, saved, static_len * sizeof *saved);
    assert_int_equal(w1[MI_H_FRAME], 1);
    assert_int_equal(mi_validate(w1, n1, err, sizeof err), 0);

    /* change the morph weight: the morphing object is rebuilt, the rigid one is not */
    const double hi_x = f24d((w1 + w1[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS] + MI_OBJECT_WORDS)[MI_O_BOUNDS + 3]);
    s.nodes[2].weights[0] = 0.5;
    assert_int_equal(scene_evaluate(&s, 0, 0), 0);
    assert_int_equal(mi_update(b, &s, err, sizeof err), 0);
    const uint32_t *w2 = mi_words(b, &n1);
    assert_int_equal(mi_get_stats(b)->rebuilt_objects, 1);
    assert_memory_equal(w2 + static_off, saved, static_len * sizeof *saved);
    const uint32_t *obj1 = w2 + w2[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS] + MI_OBJECT_WORDS;
    assert_true(obj1[MI_O_FLAGS] & MI_OBJECT_DYNAMIC);
    assert_float_equal(f24d(obj1[MI_O_BOUNDS + 3]) - hi_x, 0.5, 1e-3); /* vertex 1 moved from x = 1 to 1.5 */
    assert_int_equal(mi_validate(w2, n1, err, sizeof err), 0);
    free(saved);
    mi_free(b);
    scene_free(&s);
}

/* ---- corruption ---------------------------------------------------------------------------- */

/* Reads what a device would read, following every tree from its root: with a validated image,
 * every access must be inside the image (AddressSanitizer watches the reads). */
static uint64_t walk_tree(const uint32_t *w, uint32_t n, uint32_t nodes, uint32_t count, uint32_t lists)
{
    uint64_t sum = 0;
    uint32_t stack[128], sp = 0;
    stack[sp++] = 0;
    while (sp) {
        const uint32_t i = stack[--sp];
        assert_true(i < count && nodes + 2 * i + 1 < n);
        const uint32_t w0 = w[nodes + 2 * i], w1 = w[nodes + 2 * i + 1];
        if ((w0 & 3) == MI_NODE_LEAF) {
            for (uint32_t k = 0; k < (w0 >> 2); k++) {
                assert_true(lists + w1 + k < n);
                sum += w[lists + w1 + k];
            }
        } else if (sp + 2 <= 128) { /* the stored children: one if a side is an empty leaf */
            const uint32_t child = w0 >> MI_NODE_CHILD_SHIFT;
            stack[sp++] = child;
            if (!(w0 >> 2 & 3u))
                stack[sp++] = child + 1;
        }
    }
    return sum;
}

static void corruption(void **state)
{
    (void)state;
    scene s;
    make_scene(&s, 5, 1);
    mi_builder *b = build(&s, 0);
    uint32_t n;
    const uint32_t *good = mi_words(b, &n);
    uint32_t *w = malloc(n * sizeof *w);
    char err[256];
    uint32_t rejected = 0;
    for (int trial = 0; trial < 20000; trial++) {
        memcpy(w, good, n * sizeof *w);
        const int flips = 1 + (int)(urand() * 3);
        for (int f = 0; f < flips; f++) {
            const uint32_t at = (uint32_t)(urand() * n);
            w[at] = urand() < 0.5 ? w[at] ^ (1u << (int)(urand() * 32)) : (uint32_t)(urand() * 4294967295.0);
        }
        const uint32_t len = urand() < 0.05 ? (uint32_t)(urand() * n) : n; /* sometimes truncated */
        if (mi_validate(w, len, err, sizeof err) != 0) {
            rejected++;
            assert_null(strchr(err, '\n'));
            continue;
        }
        const uint32_t *objs = w + w[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
        for (uint32_t o = 0; o < w[MI_H_OBJECTS]; o++) {
            const uint32_t *d = objs + MI_OBJECT_WORDS * o;
            walk_tree(w, len, d[MI_O_NODES], d[MI_O_N_NODES], d[MI_O_LISTS]);
        }
        walk_tree(w, len, w[MI_H_REGION_TABLE + 2 * MI_R_TOP_NODES], w[MI_H_TOP_NODES],
                  w[MI_H_REGION_TABLE + 2 * MI_R_TOP_LISTS]);
    }
    print_message("corruption: %u of 20000 corrupted images rejected, the rest walked safely\n", rejected);
    assert_true(rejected > 1000);
    free(w);
    mi_free(b);
    scene_free(&s);
}

/* Set word at of a copy of good to v: the validator must reject it. */
static void rejects(const uint32_t *good, uint32_t n, uint32_t at, uint32_t v, const char *what)
{
    uint32_t *w = malloc(n * sizeof *w);
    assert_non_null(w);
    memcpy(w, good, n * sizeof *w);
    w[at] = v;
    char err[256];
    if (mi_validate(w, n, err, sizeof err) == 0)
        fail_msg("a corrupted %s was accepted", what);
    free(w);
}

/* Shading records (hls/units/shade_rec.h): none for a bare mesh of one material (the object
 * names it), 1 word per triangle for a bare mesh of several, 9 with normals and texture
 * coordinates, decoding to what the mesh holds; the validator rejects an object material out of
 * range, non-zero padding, a malformed missing-normal mark, a material out of range and a
 * non-finite texture coordinate. */
static void shading_records(void **state)
{
    (void)state;
    scene s;
    make_scene(&s, 1, 0);
    uint32_t n;
    mi_builder *b = build(&s, 0);
    const uint32_t *w = mi_words(b, &n);
    const uint32_t *obj = w + w[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
    const uint32_t flags_at = (uint32_t)(obj - w) + MI_O_FLAGS;
    assert_int_equal(obj[MI_O_FLAGS], SHADE_ONE_MATERIAL); /* material 0 */
    assert_int_equal(shade_rec_words(obj[MI_O_FLAGS]), 0);
    rejects(w, n, flags_at, SHADE_ONE_MATERIAL | 1u << SHADE_OBJ_MATERIAL_SHIFT, "object material");
    rejects(w, n, flags_at, 1u << SHADE_OBJ_MATERIAL_SHIFT, "material bits without the flag");
    mi_free(b);

    scene_material *two = realloc(s.materials, 2 * sizeof *two);
    assert_non_null(two);
    two[1] = two[0];
    s.materials = two;
    s.n_materials = 2;
    s.meshes[0].material[1] = 1;
    b = build(&s, 0);
    w = mi_words(b, &n);
    obj = w + w[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
    assert_int_equal(shade_rec_words(obj[MI_O_FLAGS]), 1);
    rejects(w, n, obj[MI_O_SHADING] + 1, 1u << 16, "record padding");
    mi_free(b);

    static const float nrm[] = { 0, 0, 1, 0.6f, 0.8f, 0, -1, 0, 0, 0, -0.28f, -0.96f };
    static const float uv[] = { 0.5f, 0.25f, -2, 3, 1e4f, 0, 0.125f, 1 };
    s.meshes[0].normals = floats(nrm, 12);
    s.meshes[0].texcoords = floats(uv, 8);
    b = build(&s, 0);
    w = mi_words(b, &n);
    obj = w + w[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
    char err[256];
    if (mi_validate(w, n, err, sizeof err) != 0)
        fail_msg("%s", err);
    assert_int_equal(obj[MI_O_FLAGS] & 3u, MI_OBJECT_HAS_NORMALS | MI_OBJECT_HAS_TEXCOORDS);
    const uint32_t stride = shade_rec_words(obj[MI_O_FLAGS]), tail = SHADE_NORMAL_WORDS;
    assert_int_equal(stride, F24_WIDTH == 24 ? 9 : stride);
    for (uint32_t t = 0; t < obj[MI_O_N_TRIANGLES]; t++) { /* triangle t is the mesh's triangle t (the degenerate one is last) */
        const uint32_t *rec = w + obj[MI_O_SHADING] + stride * t;
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t v = s.meshes[0].indices[3 * t + k];
            const f24_vec3 d = shade_rec_normal(rec, k);
            assert_true(fabs(f24d(d.x) - nrm[3 * v]) + fabs(f24d(d.y) - nrm[3 * v + 1]) + fabs(f24d(d.z) - nrm[3 * v + 2]) < 1e-4);
            for (uint32_t i = 0; i < 2; i++)
                assert_true(f24d(shade_rec_texcoord(obj[MI_O_FLAGS], rec + tail, 0, 2 * k + i)) == uv[2 * v + i]);
        }
    }
    const uint32_t rec = obj[MI_O_SHADING];
    rejects(w, n, rec, 1u << 20 | 1u << 21, "normal"); /* x = -2^20 (missing) with y != 0 */
    rejects(w, n, rec + SHADE_NORMAL_WORDS - 1, w[rec + SHADE_NORMAL_WORDS - 1] | 1u << 31, "normal padding");
    rejects(w, n, rec + tail, w[rec + tail] | 3u, "material");
    uint32_t t2[SHADE_MAX_WORDS];
    memcpy(t2, w + rec + tail, (stride - tail) * sizeof *t2);
    shade_encode_texcoord(t2, obj[MI_O_FLAGS], 0, 2, F24_POS_INF); /* bits 64..87: word 2 alone */
    rejects(w, n, rec + tail + 2, t2[2], "texture coordinate");
    mi_free(b);
    scene_free(&s);
}

/* The instance table starts at a multiple of the triangle record size (one matrices cache line
 * each) and its records take whole lines; the lights' region is padded with zeros to get there,
 * and the validator rejects padding that is not zero or too long. */
static void instance_table_on_lines(void **state)
{
    (void)state;
    scene s;
    make_scene(&s, 2, 0);
    mi_builder *b = build(&s, 0);
    uint32_t n;
    const uint32_t *w = mi_words(b, &n);
    const uint32_t lights = w[MI_H_REGION_TABLE + 2 * MI_R_LIGHTS], n_lights = w[MI_H_REGION_TABLE + 2 * MI_R_LIGHTS + 1];
    assert_int_equal(w[MI_H_REGION_TABLE + 2 * MI_R_INSTANCES] % MI_TRIANGLE_WORDS, 0);
    assert_int_equal(MI_INSTANCE_WORDS % MI_TRIANGLE_WORDS, 0);
    assert_true(MI_INSTANCE_WORDS >= 14);
    const uint32_t records = MI_LIGHT_WORDS * w[MI_H_LIGHTS];
    assert_true(n_lights >= records && n_lights - records < MI_TRIANGLE_WORDS);
    if (n_lights > records)
        rejects(w, n, lights + n_lights - 1, 1, "lights padding");
    mi_free(b);
    scene_free(&s);
}

/* Triangle transformations are packed records at multiples of their size; the validator rejects
 * one with a non-finite value (every slot, including the ones that straddle two words) or with
 * padding bits set (formats whose 12 values do not fill the last word). */
static void packed_triangle_records(void **state)
{
    (void)state;
    scene s;
    make_scene(&s, 1, 0);
    mi_builder *b = build(&s, 0);
    uint32_t n;
    const uint32_t *good = mi_words(b, &n);
    const uint32_t *obj = good + good[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
    const uint32_t tri = obj[MI_O_TRIANGLES] + MI_TRIANGLE_WORDS * (obj[MI_O_N_TRIANGLES] - 1);
    assert_int_equal(obj[MI_O_TRIANGLES] % MI_TRIANGLE_WORDS, 0);
    uint32_t *w = malloc(n * sizeof *w);
    assert_non_null(w);
    char err[256];
    for (uint32_t i = 0; i < 12; i++) {
        memcpy(w, good, n * sizeof *w);
        f24_t v[12];
        for (uint32_t k = 0; k < 12; k++)
            v[k] = f24_record_get(w, tri, k);
        v[i] = i % 2 ? F24_POS_INF : F24_DEFAULT_NAN;
        f24_record_put(w + tri, v, 12);
        if (mi_validate(w, n, err, sizeof err) == 0)
            fail_msg("a non-finite value %u of a triangle transformation was accepted", i);
        assert_non_null(strstr(err, "triangle transformation"));
    }
    if (12 * F24_WIDTH % 32) {
        memcpy(w, good, n * sizeof *w);
        w[tri + MI_TRIANGLE_WORDS - 1] |= 0x80000000u;
        assert_int_not_equal(mi_validate(w, n, err, sizeof err), 0);
    }
    free(w);
    mi_free(b);
    scene_free(&s);
}

/* Shared edges are found by vertex position (a repeated vertex, -0 and +0 alike), a coincident
 * copy of a triangle shares none with it, and the image's records carry the flags: every edge of
 * the closed tetrahedron is shared. */
static void shared_edge_flags(void **state)
{
    (void)state;
    static const float pos[] = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 1, -0.0f };
    uint32_t idx[] = { 0, 1, 2, 0, 4, 3, 2, 1, 0 };
    const uint32_t tri[] = { 0, 1, 2 };
    const scene_mesh quad = { .n_vertices = 5, .n_triangles = 3, .positions = (float *)pos, .indices = idx };
    uint8_t f[3];
    assert_int_equal(mi_shared_edges(&quad, tri, 2, f, NULL), 0); /* the quad: its diagonal */
    assert_int_equal(f[0], TRI_SHARED_V);
    assert_int_equal(f[1], TRI_SHARED_W);
    assert_int_equal(mi_shared_edges(&quad, tri, 3, f, NULL), 0); /* and a copy of triangle 0, reversed */
    assert_int_equal(f[0], TRI_SHARED_V);
    assert_int_equal(f[1], TRI_SHARED_W);
    assert_int_equal(f[2], TRI_SHARED_V);
    mi_edge_table table = { 0 }; /* a table kept between calls, larger than the second needs: the same flags */
    assert_int_equal(mi_shared_edges(&quad, tri, 3, f, &table), 0);
    assert_int_equal(f[2], TRI_SHARED_V);
    assert_int_equal(mi_shared_edges(&quad, tri, 2, f, &table), 0);
    assert_int_equal(f[0], TRI_SHARED_V);
    assert_int_equal(f[1], TRI_SHARED_W);
    mi_edge_table_free(&table);
    scene s;
    make_scene(&s, 1, 0);
    mi_builder *b = build(&s, 0);
    uint32_t n;
    const uint32_t *w = mi_words(b, &n);
    const uint32_t *obj = w + w[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
    assert_int_equal(obj[MI_O_N_TRIANGLES], 4);
    for (uint32_t t = 0; t < 4; t++)
        assert_int_equal(f24_triangle_load(w, obj[MI_O_TRIANGLES] + MI_TRIANGLE_WORDS * t).shared, 7);
    mi_free(b);
    scene_free(&s);
}

/* An image with ropes and grids at both levels validates; ropes out of range, missing rope
 * records, bad grid sizes and cell lists are rejected; random corruption either fails
 * validation or renders safely with every traversal algorithm (image_probe.h). */
static void accelerators(void **state)
{
    (void)state;
    scene s;
    make_scene(&s, 5, 1);
    mi_builder *b = build_with(&s, 0, MI_ACCEL_ALL);
    uint32_t n;
    const uint32_t *good = mi_words(b, &n);
    char err[256];
    if (mi_validate(good, n, err, sizeof err) != 0)
        fail_msg("%s", err);
    assert_int_equal(good[MI_H_FORMAT] >> MI_ACCEL_SHIFT, MI_ACCEL_ALL);
    image_probe(good, 4); /* every traversal algorithm over the image */
    const uint32_t *obj = good + good[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
    const uint32_t grid = obj[MI_O_GRID], top_grid = good[MI_H_REGION_TABLE + 2 * MI_R_TOP_GRID];
    const uint32_t top_nodes = good[MI_H_REGION_TABLE + 2 * MI_R_TOP_NODES];
    uint32_t leaf = 0;
    while ((good[obj[MI_O_NODES] + 2 * leaf] & 3u) != MI_NODE_LEAF)
        leaf++;
    const uint32_t record = obj[MI_O_LISTS] + good[obj[MI_O_NODES] + 2 * leaf + 1] - MI_ROPE_WORDS;
    rejects(good, n, record + 7, obj[MI_O_N_NODES], "rope");
    rejects(good, n, record + 1, F24_POS_INF, "leaf box");
    rejects(good, n, obj[MI_O_NODES] + 2 * leaf + 1, 0, "leaf without rope record");
    rejects(good, n, grid + MI_G_N + 1, 0, "grid size");
    rejects(good, n, grid + MI_G_N, 1024, "grid size");
    rejects(good, n, good[grid + MI_G_CELLS] + 1, good[grid + MI_G_N_LIST] + 1, "grid cell");
    rejects(good, n, top_grid + MI_G_LISTS, n, "top-level grid");
    rejects(good, n, top_nodes + 1, 0x7FFFFFFFu, "top-level split");
    rejects(good, n, MI_H_FORMAT, good[MI_H_FORMAT] | 8u << MI_ACCEL_SHIFT, "accelerator bits");
    uint32_t *w = malloc(n * sizeof *w), rejected = 0;
    assert_non_null(w);
    const uint32_t from = good[MI_H_REGION_TABLE + 2 * MI_R_STATIC_GEOMETRY];
    for (int trial = 0; trial < 400; trial++) {
        memcpy(w, good, n * sizeof *w);
        const uint32_t at = from + (uint32_t)(urand() * (n - from));
        w[at] = urand() < 0.5 ? w[at] ^ (1u << (int)(urand() * 32)) : (uint32_t)(urand() * 4294967295.0);
        if (mi_validate(w, n, err, sizeof err) != 0)
            rejected++;
        else
            image_probe(w, 4);
    }
    print_message("accelerators: %u of 400 corrupted images rejected, the rest traced safely\n", rejected);
    assert_true(rejected > 0 && rejected < 400);
    free(w);
    mi_free(b);
    scene_free(&s);
}

/* A scene of one object (the profile skips the top level): with the accelerators, the instance
 * comes from the top-level leaf's list after its rope record, and every algorithm hits it. */
static void single_object_accelerators(void **state)
{
    (void)state;
    scene s;
    make_scene(&s, 1, 0);
    s.nodes[0].translation[0] = 2.5; /* scene bounds away from 0: a rope record word is no instance index */
    s.nodes[0].translation[1] = 1.5;
    assert_int_equal(scene_evaluate(&s, 0, 0), 0);
    mi_builder *b = build_with(&s, 0, MI_ACCEL_ALL);
    uint32_t n, hits = 0;
    const uint32_t *w = mi_words(b, &n);
    char err[256];
    if (mi_validate(w, n, err, sizeof err) != 0)
        fail_msg("%s", err);
    assert_true(trace_profile(w) & PROFILE_SINGLE_OBJECT);
    for (uint32_t y = 0; y < 384; y += 24) /* the default 512x384 view of the scene */
        for (uint32_t x = 0; x < 512; x += 32)
            for (uint32_t a = 0; a < TRAV_KINDS; a++) {
                ray_packet rp;
                rgs_primary(w, x, y, &rp);
                trace_state st;
                unit_op op;
                trace_counters c = { 0 };
                trace_begin(&rp, trace_flags_of(trace_profile(w), 0) | a << TRACE_TRAV_SHIFT, &st);
                for (uint32_t k = 0; k < 100000 && trace_step(w, &st, &op, &c); k++)
                    ;
                for (int i = 0; i < TRACE_PACKET; i++) {
                    assert_true(st.hits[i].instance == 0 || st.hits[i].instance == TRACE_NO_HIT);
                    hits += st.hits[i].instance == 0;
                }
            }
    assert_true(hits > 0);
    mi_free(b);
    scene_free(&s);
}

/* ---- objects built concurrently ------------------------------------------------------------ */

/* Meshes of tris[i] random small triangles, one instance each, moved apart along x. */
static void make_soup(scene *s, const uint32_t *tris, uint32_t n)
{
    memset(s, 0, sizeof *s);
    s->n_meshes = s->n_nodes = s->n_roots = n;
    s->meshes = calloc(n, sizeof *s->meshes);
    s->nodes = calloc(n, sizeof *s->nodes);
    s->roots = calloc(n, sizeof *s->roots);
    for (uint32_t m = 0; m < n; m++) {
        scene_mesh *me = &s->meshes[m];
        snprintf(me->name, sizeof me->name, "soup%u", m);
        me->n_triangles = tris[m];
        me->n_vertices = 3 * tris[m];
        me->positions = malloc(3 * (size_t)me->n_vertices * sizeof *me->positions);
        me->indices = malloc((size_t)me->n_vertices * sizeof *me->indices);
        me->material = calloc(tris[m], sizeof *me->material);
        for (uint32_t t = 0; t < tris[m]; t++) {
            double c[3] = { urand(), urand(), urand() };
            for (uint32_t v = 3 * t; v < 3 * t + 3; v++) {
                me->indices[v] = v;
                for (int k = 0; k < 3; k++)
                    me->positions[3 * v + (uint32_t)k] = (float)(c[k] + 0.05 * urand());
            }
        }
        scene_node *no = &s->nodes[m];
        no->parent = -1;
        no->mesh = m;
        no->camera = no->light = SCENE_NONE;
        no->translation[0] = 1.5 * m;
        no->rotation[3] = 1;
        no->scale[0] = no->scale[1] = no->scale[2] = 1;
        s->roots[m] = m;
    }
    s->n_materials = 1;
    s->materials = calloc(1, sizeof *s->materials);
    s->materials[0].base_color[0] = 0.8f;
    s->materials[0].base_color_texture = s->materials[0].emissive_texture = SCENE_NONE;
    assert_int_equal(scene_evaluate(s, 0, 0), 0);
}

/* mi_build with p.bottom.threads = threads and p.max_nodes = max_nodes: the image (NULL: the build
 * failed, with err) and its words. */
static mi_builder *build_threads(const scene *s, uint32_t threads, uint64_t max_nodes, char *err, size_t errlen)
{
    mi_params p;
    mi_params_default(&p);
    p.memory_bytes = 64u << 20;
    p.bottom.threads = threads;
    p.max_nodes = max_nodes;
    return mi_build(s, &p, err, errlen);
}

/* The objects' trees are built several at a time (and a large one with all threads): the image
 * is the same words for any thread count, and the node limit fails the same way, naming the
 * object where a build one object after the other would have stopped. */
static void objects_in_parallel(void **state)
{
    (void)state;
    /* 3 threads: no object has a third of the triangles, so all five share the threads;
     * 2: the largest is built alone first */
    static const uint32_t tris[] = { 700, 1300, 1100, 1000, 40 };
    scene s;
    make_soup(&s, tris, 5);
    char err[512];
    mi_builder *one = build_threads(&s, 1, 0, err, sizeof err);
    assert_non_null(one);
    uint32_t n1, nk;
    const uint32_t *w1 = mi_words(one, &n1);
    assert_int_equal(mi_validate(w1, n1, err, sizeof err), 0);
    for (uint32_t threads = 2; threads <= 4; threads++) {
        mi_builder *b = build_threads(&s, threads, 0, err, sizeof err);
        assert_non_null(b);
        const uint32_t *wk = mi_words(b, &nk);
        assert_int_equal(nk, n1);
        assert_memory_equal(wk, w1, (size_t)n1 * sizeof *w1);
        assert_memory_equal(mi_get_stats(b), mi_get_stats(one), offsetof(mi_stats, bottom_sah) + sizeof(double));
        mi_free(b);
    }

    /* one node short of the trees (the last object's build passes the limit), and short of what
     * the first object alone needs */
    const mi_stats *st = mi_get_stats(one);
    const uint64_t limits[] = { st->bottom_nodes + st->top_nodes, st->bottom_nodes - 1, 10 };
    const char *failing[] = { NULL, "soup4", "soup0" };
    for (uint32_t l = 0; l < 3; l++)
        for (uint32_t threads = 1; threads <= 3; threads++) {
            mi_builder *b = build_threads(&s, threads, limits[l], err, sizeof err);
            if (!failing[l]) {
                assert_non_null(b);
                mi_free(b);
                continue;
            }
            assert_null(b);
            char want[64];
            snprintf(want, sizeof want, "mesh '%s'", failing[l]);
            if (!strstr(err, "limit kd-nodes exceeded") || !strstr(err, want))
                fail_msg("%u threads, limit %llu: '%s' does not name %s", threads, (unsigned long long)limits[l],
                         err, want);
        }
    mi_free(one);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(transform_maps_vertices), cmocka_unit_test(degenerate_triangles),
        cmocka_unit_test(layout_and_validate), cmocka_unit_test(instancing_end_to_end),
        cmocka_unit_test(too_small_memory), cmocka_unit_test(frames_upload_only_what_changed),
        cmocka_unit_test(corruption), cmocka_unit_test(accelerators),
        cmocka_unit_test(single_object_accelerators), cmocka_unit_test(shading_records),
        cmocka_unit_test(packed_triangle_records), cmocka_unit_test(shared_edge_flags), cmocka_unit_test(instance_table_on_lines),
        cmocka_unit_test(objects_in_parallel),
    };
    return cmocka_run_group_tests_name("memimage", tests, NULL, NULL);
}
