/*
 * Tests of the scene generators (scenes/) and the glTF writer (host/scene/gltf_write.cpp): each
 * generator builds a valid scene with the designed counts (instancing as designed), is
 * deterministic for a seed, and survives a round trip through .glb and .gltf and
 * scene_load_gltf with the same counts and the same world-space triangles; the animated scene
 * moves and morphs over time, also after the round trip. Writer errors are one line.
 */
#define _GNU_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "test_tmpdir.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene.h"
#include "scenes.h"


static const char *tmp(const char *name)
{
    static char path[4][256];
    static int k;
    k = (k + 1) % 4;
    snprintf(path[k], sizeof path[k], "%s/%s", test_dir, name);
    return path[k];
}

static void build(const char *name, uint64_t seed, uint32_t detail, scene *s)
{
    const scene_generator *g = scene_generator_find(name);
    if (!g)
        fail_msg("generator '%s' is not in the table", name);
    const scene_gen_params p = { seed, detail };
    char err[256] = "";
    if (g->build(s, &p, err, sizeof err) != 0)
        fail_msg("%s: %s", name, err);
}

static uint64_t unique_triangles(const scene *s)
{
    uint64_t n = 0;
    for (uint32_t i = 0; i < s->n_meshes; i++)
        n += s->meshes[i].n_triangles;
    return n;
}

static uint64_t scene_triangles(const scene *s)
{
    uint64_t n = 0;
    for (uint32_t i = 0; i < s->n_instances; i++)
        n += s->meshes[s->instances[i].mesh].n_triangles;
    return n;
}

static uint32_t mesh_named(const scene *s, const char *name)
{
    for (uint32_t i = 0; i < s->n_meshes; i++)
        if (strcmp(s->meshes[i].name, name) == 0)
            return i;
    fail_msg("no mesh named '%s'", name);
    return SCENE_NONE;
}

static uint32_t instances_of(const scene *s, uint32_t mesh)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->n_instances; i++)
        n += s->instances[i].mesh == mesh;
    return n;
}

/* Everything a consumer relies on: finite data, indices and references in range, a camera and
 * a light, distinct material colours. */
static void check_valid(const scene *s)
{
    assert_true(s->n_meshes > 0 && s->n_instances > 0 && s->n_materials >= 2);
    for (uint32_t i = 0; i < s->n_meshes; i++) {
        const scene_mesh *m = &s->meshes[i];
        assert_true(m->n_vertices > 0 && m->n_triangles > 0);
        for (size_t k = 0; k < 3 * (size_t)m->n_vertices; k++) {
            if (!isfinite(m->positions[k]))
                fail_msg("mesh %s: non-finite position %zu", m->name, k / 3);
            if (m->normals && !isfinite(m->normals[k]))
                fail_msg("mesh %s: non-finite normal %zu", m->name, k / 3);
        }
        for (size_t k = 0; k < 3 * (size_t)m->n_triangles; k++)
            if (m->indices[k] >= m->n_vertices)
                fail_msg("mesh %s: index %u >= %u vertices", m->name, m->indices[k], m->n_vertices);
        for (uint32_t t = 0; t < m->n_triangles; t++) {
            assert_true(m->material[t] < s->n_materials);
            /* no degenerate triangles; the winding agrees with the vertex normals (outside) */
            const uint32_t *id = &m->indices[3 * t];
            double e1[3], e2[3], n[3], vn[3] = { 0, 0, 0 };
            for (int k = 0; k < 3; k++) {
                e1[k] = (double)m->positions[3 * id[1] + k] - m->positions[3 * id[0] + k];
                e2[k] = (double)m->positions[3 * id[2] + k] - m->positions[3 * id[0] + k];
                for (int v = 0; v < 3 && m->normals; v++)
                    vn[k] += m->normals[3 * id[v] + k];
            }
            n[0] = e1[1] * e2[2] - e1[2] * e2[1];
            n[1] = e1[2] * e2[0] - e1[0] * e2[2];
            n[2] = e1[0] * e2[1] - e1[1] * e2[0];
            if (n[0] == 0 && n[1] == 0 && n[2] == 0)
                fail_msg("mesh %s: triangle %u is degenerate", m->name, t);
            if (m->normals && n[0] * vn[0] + n[1] * vn[1] + n[2] * vn[2] <= 0)
                fail_msg("mesh %s: triangle %u is wound against its normals", m->name, t);
        }
    }
    for (uint32_t i = 0; i < s->n_instances; i++)
        assert_true(s->instances[i].mesh < s->n_meshes && s->instances[i].node < s->n_nodes);
    assert_true(s->n_cameras >= 1);
    for (uint32_t i = 0; i < s->n_cameras; i++) {
        assert_true(s->cameras[i].node < s->n_nodes);
        assert_int_equal(s->nodes[s->cameras[i].node].camera, i);
        assert_true(s->cameras[i].yfov > 0 && s->cameras[i].yfov < M_PI);
    }
    int point_or_directional = 0;
    for (uint32_t i = 0; i < s->n_lights; i++) {
        assert_true(s->lights[i].node < s->n_nodes);
        assert_int_equal(s->nodes[s->lights[i].node].light, i);
        point_or_directional |= s->lights[i].kind == LIGHT_POINT || s->lights[i].kind == LIGHT_DIRECTIONAL;
    }
    assert_true(point_or_directional);
    for (uint32_t a = 1; a < s->n_materials; a++)
        for (uint32_t b = a + 1; b < s->n_materials; b++)
            if (memcmp(s->materials[a].base_color, s->materials[b].base_color, sizeof s->materials[a].base_color) == 0)
                fail_msg("materials %u and %u have the same base colour", a, b);
}

/* The camera looks at the content: the centre of the instances' bounding box is in front of it. */
static void check_camera_faces_content(const scene *s)
{
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (uint32_t i = 0; i < s->n_instances; i++) {
        const scene_mesh *m = &s->meshes[s->instances[i].mesh];
        for (uint32_t v = 0; v < m->n_vertices; v += 7) {
            const double p[3] = { m->positions[3 * v], m->positions[3 * v + 1], m->positions[3 * v + 2] };
            double w[3];
            affine_apply_point(&s->instances[i].world, p, w);
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], w[k]);
                hi[k] = fmax(hi[k], w[k]);
            }
        }
    }
    const affine *c = &s->cameras[0].world;
    const double fwd[3] = { -c->m[0][2], -c->m[1][2], -c->m[2][2] };
    double d = 0, len = 0;
    for (int k = 0; k < 3; k++) {
        const double to = 0.5 * (lo[k] + hi[k]) - c->m[k][3];
        d += to * fwd[k];
        len += to * to;
    }
    assert_true(d > 0.5 * sqrt(len)); /* within 60 degrees of the view direction */
}

/* ---- designed counts ---------------------------------------------------------------------- */

static void cornell_counts(void **state)
{
    (void)state;
    scene s;
    build("cornell", 1, 0, &s);
    check_valid(&s);
    check_camera_faces_content(&s);
    assert_int_equal(s.n_meshes, 3);
    assert_int_equal(unique_triangles(&s), 24);
    assert_int_equal(s.n_instances, 4);
    assert_int_equal(scene_triangles(&s), 36);
    assert_int_equal(instances_of(&s, mesh_named(&s, "block")), 2);
    int emissive = 0;
    for (uint32_t i = 0; i < s.n_materials; i++)
        emissive |= s.materials[i].emissive[0] > 1.0f;
    assert_true(emissive);
    assert_int_equal(s.n_lights, 1);
    assert_int_equal(s.lights[0].kind, LIGHT_POINT);
    assert_true(s.lights[0].position[1] > 1.5 && s.lights[0].position[1] < 2.0);
    scene_free(&s);
}

static void room_counts(void **state)
{
    (void)state;
    scene s;
    build("room", 1, 0, &s);
    check_valid(&s);
    check_camera_faces_content(&s);
    const uint32_t chair = mesh_named(&s, "chair");
    assert_int_equal(instances_of(&s, chair), 4);
    uint32_t chair_nodes = 0;
    for (uint32_t i = 0; i < s.n_nodes; i++)
        chair_nodes += s.nodes[i].mesh == chair;
    assert_int_equal(chair_nodes, 4);
    assert_int_equal(instances_of(&s, mesh_named(&s, "fruit")), 3);
    assert_int_equal(instances_of(&s, mesh_named(&s, "cup")), 2);
    assert_true(unique_triangles(&s) >= 2000 && unique_triangles(&s) <= 6000);
    assert_int_equal(s.n_textures, 1);
    assert_int_equal(s.textures[0].width, 64);
    int textured = 0;
    for (uint32_t i = 0; i < s.n_materials; i++)
        textured |= s.materials[i].base_color_texture == 0;
    assert_true(textured);
    scene_free(&s);
}

static void plants_counts(void **state)
{
    (void)state;
    scene s;
    build("plants", 1, 0, &s);
    check_valid(&s);
    check_camera_faces_content(&s);
    assert_int_equal(s.n_meshes, 2);
    const uint32_t plant = mesh_named(&s, "sunflower");
    assert_true(s.meshes[plant].n_triangles >= 28000 && s.meshes[plant].n_triangles <= 32000);
    assert_int_equal(instances_of(&s, plant), 5000);
    assert_int_equal(s.n_instances, 5001);
    /* instances differ in rotation, scale and position */
    const affine *a = &s.instances[1].world, *b = &s.instances[2].world;
    assert_true(fabs(a->m[0][3] - b->m[0][3]) + fabs(a->m[2][3] - b->m[2][3]) > 1e-6);
    assert_true(fabs(a->m[0][0] - b->m[0][0]) > 1e-9);
    scene_free(&s);
    build("plants", 1, 123, &s);
    assert_int_equal(instances_of(&s, mesh_named(&s, "sunflower")), 123);
    scene_free(&s);
    const scene_generator *g = scene_generator_find("plants");
    const scene_gen_params huge = { 1, 1u << 30 };
    char err[256] = "";
    memset(&s, 0xA5, sizeof s);
    assert_int_equal(g->build(&s, &huge, err, sizeof err), -1);
    assert_non_null(strstr(err, "detail"));
    assert_int_equal(s.n_meshes, 0);
}

static void terrain_counts(void **state)
{
    (void)state;
    scene s;
    build("terrain", 1, 0, &s);
    check_valid(&s);
    check_camera_faces_content(&s);
    assert_int_equal(s.n_meshes, 3);
    assert_int_equal(s.meshes[mesh_named(&s, "terrain")].n_triangles, 2 * 256 * 256);
    const uint32_t c = instances_of(&s, mesh_named(&s, "conifer")), b = instances_of(&s, mesh_named(&s, "broadleaf"));
    assert_int_equal(c + b, 300);
    assert_true(c > 0 && b > 0);
    /* the height field has relief and uses more than one material */
    const scene_mesh *t = &s.meshes[mesh_named(&s, "terrain")];
    float lo = INFINITY, hi = -INFINITY;
    for (uint32_t v = 0; v < t->n_vertices; v++) {
        lo = fminf(lo, t->positions[3 * v + 1]);
        hi = fmaxf(hi, t->positions[3 * v + 1]);
    }
    assert_true(hi - lo > 10.0f);
    int mats = 0;
    for (uint32_t k = 0; k < t->n_triangles; k++)
        mats |= 1 << (t->material[k] & 15);
    assert_true(__builtin_popcount(mats) >= 2);
    scene_free(&s);
    build("terrain", 1, 32, &s);
    assert_int_equal(s.meshes[mesh_named(&s, "terrain")].n_triangles, 2 * 32 * 32);
    scene_free(&s);
    const scene_gen_params tiny = { 1, 1 };
    char err[256] = "";
    assert_int_equal(scene_generator_find("terrain")->build(&s, &tiny, err, sizeof err), -1);
    assert_non_null(strstr(err, "detail"));
    assert_null(s.meshes);
}

static const scene_channel *find_channel(const scene *s, const char *node, anim_path path)
{
    for (uint32_t a = 0; a < s->n_animations; a++)
        for (uint32_t c = 0; c < s->animations[a].n_channels; c++) {
            const scene_channel *ch = &s->animations[a].channels[c];
            if (ch->path == path && strcmp(s->nodes[ch->node].name, node) == 0)
                return ch;
        }
    fail_msg("no channel for node '%s'", node);
    return NULL;
}

static void animated_counts(void **state)
{
    (void)state;
    scene s;
    build("animated", 1, 0, &s);
    check_valid(&s);
    check_camera_faces_content(&s);
    assert_int_equal(s.n_animations, 1);
    assert_float_equal(s.animations[0].duration, 4.0, 1e-6);
    int interp[3] = { 0 }, path[4] = { 0 }, nonuniform = 0;
    for (uint32_t c = 0; c < s.animations[0].n_channels; c++) {
        const scene_channel *ch = &s.animations[0].channels[c];
        interp[ch->interp]++;
        path[ch->path]++;
        if (ch->path == ANIM_SCALE) {
            const uint32_t stride = ch->interp == INTERP_CUBICSPLINE ? 9 : 3, off = ch->interp == INTERP_CUBICSPLINE ? 3 : 0;
            for (uint32_t k = 0; k < ch->n_keys; k++) {
                const float *v = &ch->values[k * stride + off];
                nonuniform |= v[0] != v[1] || v[1] != v[2];
            }
        }
    }
    for (int i = 0; i < 3; i++)
        assert_true(interp[i] > 0);
    for (int i = 0; i < 4; i++)
        assert_true(path[i] > 0);
    assert_true(nonuniform);
    const uint32_t blob = mesh_named(&s, "blob");
    assert_int_equal(s.meshes[blob].n_targets, 2);
    /* a hierarchy: the arm's children move with it */
    uint32_t children = 0;
    for (uint32_t i = 0; i < s.n_nodes; i++)
        children += s.nodes[i].parent >= 0;
    assert_true(children >= 2);
    scene_free(&s);
}

/* ---- determinism -------------------------------------------------------------------------- */

/* 0 if the two scenes have bit-identical geometry and instance transforms. */
static int scenes_differ(const scene *a, const scene *b)
{
    if (a->n_meshes != b->n_meshes || a->n_instances != b->n_instances || a->n_nodes != b->n_nodes)
        return 1;
    for (uint32_t i = 0; i < a->n_meshes; i++) {
        const scene_mesh *x = &a->meshes[i], *y = &b->meshes[i];
        if (x->n_vertices != y->n_vertices || x->n_triangles != y->n_triangles ||
            memcmp(x->positions, y->positions, 3 * sizeof(float) * x->n_vertices) != 0 ||
            memcmp(x->indices, y->indices, 3 * sizeof(uint32_t) * x->n_triangles) != 0)
            return 1;
    }
    for (uint32_t i = 0; i < a->n_instances; i++)
        if (memcmp(&a->instances[i].world, &b->instances[i].world, sizeof(affine)) != 0)
            return 1;
    if (a->n_textures != b->n_textures)
        return 1;
    for (uint32_t i = 0; i < a->n_textures; i++)
        if (memcmp(a->textures[i].rgba, b->textures[i].rgba, (size_t)a->textures[i].width * a->textures[i].height * 4))
            return 1;
    return 0;
}

static void deterministic(void **state)
{
    (void)state;
    for (unsigned g = 0; g < scene_generator_count; g++) {
        const char *name = scene_generators[g].name;
        const uint32_t detail = strcmp(name, "plants") == 0 ? 50 : strcmp(name, "terrain") == 0 ? 48 : 0;
        scene a, b, c;
        build(name, 7, detail, &a);
        build(name, 7, detail, &b);
        build(name, 8, detail, &c);
        if (scenes_differ(&a, &b))
            fail_msg("%s: two builds with seed 7 differ", name);
        if (strcmp(name, "animated") == 0) { /* the seed moves the animation phases */
            scene_evaluate(&a, 1.0, 0);
            scene_evaluate(&c, 1.0, 0);
        }
        if (!scenes_differ(&a, &c))
            fail_msg("%s: seeds 7 and 8 give the same scene", name);
        scene_free(&a);
        scene_free(&b);
        scene_free(&c);
    }
}

/* ---- round trip through glTF -------------------------------------------------------------- */

/* The writer's triangle order: grouped by material in order of first use (one primitive each). */
static uint32_t *grouped_order(const scene_mesh *m)
{
    uint32_t *order = malloc((m->n_triangles ? m->n_triangles : 1) * sizeof *order), n = 0;
    assert_non_null(order);
    for (uint32_t t = 0; t < m->n_triangles; t++) {
        int first = 1;
        for (uint32_t u = 0; u < t && first; u++)
            first = m->material[u] != m->material[t];
        if (!first)
            continue;
        for (uint32_t u = t; u < m->n_triangles; u++)
            if (m->material[u] == m->material[t])
                order[n++] = u;
    }
    assert_int_equal(n, m->n_triangles);
    return order;
}

static int close_rel(double a, double b)
{
    return fabs(a - b) <= 1e-5 * fmax(1.0, fmax(fabs(a), fabs(b)));
}

/* Same world-space triangles (instance by instance, in the writer's order) within 1e-5. */
static void compare_world(const scene *a, const scene *b, const char *what)
{
    assert_int_equal(a->n_instances, b->n_instances);
    uint32_t **order = calloc(a->n_meshes, sizeof *order);
    assert_non_null(order);
    for (uint32_t i = 0; i < a->n_instances; i++) {
        const scene_instance *ia = &a->instances[i], *ib = &b->instances[i];
        assert_int_equal(ia->mesh, ib->mesh);
        assert_int_equal(ia->node, ib->node);
        const scene_mesh *ma = &a->meshes[ia->mesh], *mb = &b->meshes[ib->mesh];
        assert_int_equal(ma->n_triangles, mb->n_triangles);
        if (!order[ia->mesh])
            order[ia->mesh] = grouped_order(ma);
        for (uint32_t t = 0; t < ma->n_triangles; t++) {
            const uint32_t ta = order[ia->mesh][t];
            assert_int_equal(mb->material[t], ma->material[ta]);
            for (int k = 0; k < 3; k++) {
                const uint32_t va = ma->indices[3 * ta + k], vb = mb->indices[3 * t + k];
                const double pa[3] = { ma->positions[3 * va], ma->positions[3 * va + 1], ma->positions[3 * va + 2] };
                const double pb[3] = { mb->positions[3 * vb], mb->positions[3 * vb + 1], mb->positions[3 * vb + 2] };
                double wa[3], wb[3];
                affine_apply_point(&ia->world, pa, wa);
                affine_apply_point(&ib->world, pb, wb);
                for (int c = 0; c < 3; c++)
                    if (!close_rel(wa[c], wb[c]))
                        fail_msg("%s: instance %u (%s) triangle %u vertex %d: %.9g vs %.9g", what, i, ma->name, t, k,
                                 wa[c], wb[c]);
            }
        }
    }
    for (uint32_t m = 0; m < a->n_meshes; m++)
        free(order[m]);
    free(order);
}

/* KHR_texture_transform survives writing and loading. */
static void same_uv_map(const scene_uv_map *a, const scene_uv_map *b)
{
    assert_int_equal(a->set, b->set);
    if (!a->set)
        return;
    const double x[5] = { a->offset[0], a->offset[1], a->rotation, a->scale[0], a->scale[1] };
    const double y[5] = { b->offset[0], b->offset[1], b->rotation, b->scale[0], b->scale[1] };
    for (int k = 0; k < 5; k++)
        assert_true(close_rel(x[k], y[k]));
}

static void compare_scenes(const scene *a, const scene *b, const char *what)
{
    assert_int_equal(a->n_meshes, b->n_meshes);
    assert_int_equal(unique_triangles(a), unique_triangles(b));
    assert_int_equal(a->n_nodes, b->n_nodes);
    assert_int_equal(a->n_instances, b->n_instances);
    assert_int_equal(scene_triangles(a), scene_triangles(b));
    assert_int_equal(a->n_materials, b->n_materials);
    assert_int_equal(a->n_textures, b->n_textures);
    assert_int_equal(a->n_cameras, b->n_cameras);
    assert_int_equal(a->n_lights, b->n_lights);
    assert_int_equal(a->n_animations, b->n_animations);
    assert_int_equal(a->n_roots, b->n_roots);
    assert_int_equal(b->warnings, 0);
    for (uint32_t i = 0; i < a->n_meshes; i++) {
        assert_string_equal(a->meshes[i].name, b->meshes[i].name);
        assert_int_equal(a->meshes[i].n_targets, b->meshes[i].n_targets);
        assert_true((a->meshes[i].normals != NULL) == (b->meshes[i].normals != NULL));
        assert_true((a->meshes[i].texcoords != NULL) == (b->meshes[i].texcoords != NULL));
        assert_true((a->meshes[i].texcoords1 != NULL) == (b->meshes[i].texcoords1 != NULL));
        assert_true((a->meshes[i].colours != NULL) == (b->meshes[i].colours != NULL));
    }
    for (uint32_t i = 0; i < a->n_nodes; i++) {
        assert_string_equal(a->nodes[i].name, b->nodes[i].name);
        assert_int_equal(a->nodes[i].parent, b->nodes[i].parent);
        assert_int_equal(a->nodes[i].mesh, b->nodes[i].mesh);
        assert_int_equal(a->nodes[i].camera, b->nodes[i].camera);
        assert_int_equal(a->nodes[i].light, b->nodes[i].light);
    }
    for (uint32_t i = 0; i < a->n_materials; i++) {
        const scene_material *x = &a->materials[i], *y = &b->materials[i];
        for (int c = 0; c < 4; c++)
            assert_float_equal(x->base_color[c], y->base_color[c], 1e-6);
        for (int c = 0; c < 3; c++)
            assert_true(close_rel(x->emissive[c], y->emissive[c]));
        assert_float_equal(x->metallic, y->metallic, 1e-6);
        assert_float_equal(x->roughness, y->roughness, 1e-6);
        assert_float_equal(x->transmission, y->transmission, 1e-6);
        assert_float_equal(x->ior, y->ior, 1e-6);
        assert_int_equal(x->base_color_texture, y->base_color_texture);
        assert_int_equal(x->double_sided, y->double_sided);
        assert_int_equal(x->texcoord_set, y->texcoord_set);
        assert_int_equal(x->emissive_texture, y->emissive_texture);
        assert_int_equal(x->emissive_texcoord, y->emissive_texcoord);
        assert_int_equal(x->unlit, y->unlit);
        same_uv_map(&x->base_uv, &y->base_uv);
        same_uv_map(&x->emissive_uv, &y->emissive_uv);
    }
    for (uint32_t i = 0; i < a->n_textures; i++) {
        assert_int_equal(a->textures[i].width, b->textures[i].width);
        assert_int_equal(a->textures[i].height, b->textures[i].height);
        assert_memory_equal(a->textures[i].rgba, b->textures[i].rgba, (size_t)a->textures[i].width * a->textures[i].height * 4);
    }
    for (uint32_t i = 0; i < a->n_cameras; i++) {
        assert_int_equal(a->cameras[i].node, b->cameras[i].node);
        assert_float_equal(a->cameras[i].yfov, b->cameras[i].yfov, 1e-12);
        assert_float_equal(a->cameras[i].aspect, b->cameras[i].aspect, 1e-12);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 4; c++)
                assert_true(close_rel(a->cameras[i].world.m[r][c], b->cameras[i].world.m[r][c]));
    }
    for (uint32_t i = 0; i < a->n_lights; i++) {
        const scene_light *x = &a->lights[i], *y = &b->lights[i];
        assert_int_equal(x->kind, y->kind);
        assert_int_equal(x->node, y->node);
        assert_float_equal(x->intensity, y->intensity, 1e-6);
        for (int c = 0; c < 3; c++) {
            assert_float_equal(x->color[c], y->color[c], 1e-6);
            assert_true(close_rel(x->position[c], y->position[c]));
            assert_true(close_rel(x->direction[c], y->direction[c]));
        }
    }
    for (uint32_t i = 0; i < a->n_animations; i++) {
        assert_int_equal(a->animations[i].n_channels, b->animations[i].n_channels);
        assert_float_equal(a->animations[i].duration, b->animations[i].duration, 1e-6);
        for (uint32_t c = 0; c < a->animations[i].n_channels; c++) {
            const scene_channel *x = &a->animations[i].channels[c], *y = &b->animations[i].channels[c];
            assert_int_equal(x->node, y->node);
            assert_int_equal(x->path, y->path);
            assert_int_equal(x->interp, y->interp);
            assert_int_equal(x->n_keys, y->n_keys);
            assert_int_equal(x->components, y->components);
        }
    }
    compare_world(a, b, what);
}

static void round_trip(const char *name, uint32_t detail)
{
    scene a, b;
    char err[512] = "", path[2][64];
    build(name, 3, detail, &a);
    snprintf(path[0], sizeof path[0], "%s.glb", name);
    snprintf(path[1], sizeof path[1], "%s.gltf", name);
    for (int f = 0; f < 2; f++) {
        const char *file = tmp(path[f]);
        if (scene_write_gltf(&a, file, err, sizeof err) != 0)
            fail_msg("write %s: %s", file, err);
        if (scene_load_gltf(file, &b, err, sizeof err) != 0)
            fail_msg("load %s: %s", file, err);
        compare_scenes(&a, &b, file);
        if (a.n_animations) { /* the animations give the same poses (and morphs) later on */
            const double times[] = { 0.3, 1.3, 2.75, 5.1 };
            for (size_t k = 0; k < sizeof times / sizeof times[0]; k++) {
                assert_int_equal(scene_evaluate(&a, times[k], 1), 0);
                assert_int_equal(scene_evaluate(&b, times[k], 1), 0);
                compare_world(&a, &b, file);
            }
            assert_int_equal(scene_evaluate(&a, 0.0, 0), 0);
        }
        scene_free(&b);
    }
    scene_free(&a);
}

static void round_trip_cornell(void **state)
{
    (void)state;
    round_trip("cornell", 0);
}

static void round_trip_room(void **state)
{
    (void)state;
    round_trip("room", 0);
}

static void round_trip_plants(void **state)
{
    (void)state;
    round_trip("plants", 40);
}

static void round_trip_terrain(void **state)
{
    (void)state;
    round_trip("terrain", 0);
}

static void round_trip_animated(void **state)
{
    (void)state;
    round_trip("animated", 0);
}

/* Emissive textures, vertex colours, texture transforms, TEXCOORD_1 and unlit materials. */
static void round_trip_shading(void **state)
{
    (void)state;
    round_trip("emissive", 0);
    round_trip("vertex_colours", 0);
    round_trip("uv_transform", 0);
    round_trip("unlit", 0);
}

/* ---- animation ---------------------------------------------------------------------------- */

static uint32_t node_named(const scene *s, const char *name)
{
    for (uint32_t i = 0; i < s->n_nodes; i++)
        if (strcmp(s->nodes[i].name, name) == 0)
            return i;
    fail_msg("no node named '%s'", name);
    return SCENE_NONE;
}

static double affine_distance(const affine *a, const affine *b)
{
    double d = 0;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            d += fabs(a->m[r][c] - b->m[r][c]);
    return d;
}

static void animation_moves_and_morphs(void **state)
{
    (void)state;
    scene s;
    build("animated", 1, 0, &s);
    affine *w0 = malloc(s.n_instances * sizeof *w0);
    assert_non_null(w0);
    for (uint32_t i = 0; i < s.n_instances; i++)
        w0[i] = s.instances[i].world;
    const scene_mesh *blob = &s.meshes[mesh_named(&s, "blob")];
    float *p0 = malloc(3 * sizeof(float) * blob->n_vertices);
    assert_non_null(p0);
    memcpy(p0, blob->positions, 3 * sizeof(float) * blob->n_vertices);

    assert_int_equal(scene_evaluate(&s, 1.3, 1), 0);
    uint32_t moved = 0;
    for (uint32_t i = 0; i < s.n_instances; i++)
        moved += affine_distance(&w0[i], &s.instances[i].world) > 1e-4;
    assert_true(moved >= 6); /* spinner, hopper, ball, pulser, the arm's two children */
    double change = 0;
    for (uint32_t k = 0; k < 3 * blob->n_vertices; k++)
        change = fmax(change, fabs(blob->positions[k] - p0[k]));
    assert_true(change > 0.05);

    /* the arm's children follow the pivot's rotation */
    const uint32_t weight = node_named(&s, "arm_weight");
    const double o[3] = { 0, 0, 0 };
    double pw[3];
    affine_apply_point(&s.nodes[weight].world, o, pw);
    assert_true(fabs(pw[0]) > 0.1); /* swung sideways from x = 0 */

    /* STEP holds between keys; CUBICSPLINE passes through its key values */
    const uint32_t hopper = node_named(&s, "hopper"), ball = node_named(&s, "ball");
    assert_int_equal(scene_evaluate(&s, 0.6, 0), 0);
    const affine h06 = s.nodes[hopper].world;
    assert_int_equal(scene_evaluate(&s, 0.95, 0), 0);
    assert_true(affine_distance(&h06, &s.nodes[hopper].world) < 1e-12);
    assert_int_equal(scene_evaluate(&s, 1.05, 0), 0);
    assert_true(affine_distance(&h06, &s.nodes[hopper].world) > 1e-3);
    const scene_channel *bt = find_channel(&s, "ball", ANIM_TRANSLATION);
    assert_int_equal(bt->interp, INTERP_CUBICSPLINE);
    assert_int_equal(scene_evaluate(&s, bt->times[3], 0), 0);
    for (int k = 0; k < 3; k++)
        assert_float_equal(s.nodes[ball].translation[k], bt->values[9 * 3 + 3 + k], 1e-6);
    /* looping: t and t + duration agree */
    assert_int_equal(scene_evaluate(&s, 1.7, 1), 0);
    affine *w1 = malloc(s.n_instances * sizeof *w1);
    assert_non_null(w1);
    for (uint32_t i = 0; i < s.n_instances; i++)
        w1[i] = s.instances[i].world;
    assert_int_equal(scene_evaluate(&s, 1.7 + s.animations[0].duration, 1), 0);
    for (uint32_t i = 0; i < s.n_instances; i++)
        assert_true(affine_distance(&w1[i], &s.instances[i].world) < 1e-6);
    free(w0);
    free(w1);
    free(p0);
    scene_free(&s);
}

/* ---- writer errors ------------------------------------------------------------------------ */

static void writer_errors(void **state)
{
    (void)state;
    scene s;
    char err[512] = "";
    build("cornell", 1, 0, &s);
    assert_int_equal(scene_write_gltf(&s, "/nonexistent-dir/x.glb", err, sizeof err), -1);
    assert_non_null(strstr(err, "x.glb"));
    assert_null(strchr(err, '\n'));
    assert_int_equal(scene_write_gltf(&s, tmp("x.obj"), err, sizeof err), -1);
    assert_non_null(strstr(err, "extension"));
    s.meshes[0].indices[0] = s.meshes[0].n_vertices; /* broken scene: refused, not written */
    assert_int_equal(scene_write_gltf(&s, tmp("bad.glb"), err, sizeof err), -1);
    assert_non_null(strstr(err, "index"));
    assert_null(strchr(err, '\n'));
    scene_free(&s);
    assert_null(scene_generator_find("no-such-scene"));
}



int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cornell_counts),     cmocka_unit_test(room_counts),
        cmocka_unit_test(plants_counts),      cmocka_unit_test(terrain_counts),
        cmocka_unit_test(animated_counts),    cmocka_unit_test(deterministic),
        cmocka_unit_test(round_trip_cornell), cmocka_unit_test(round_trip_room),
        cmocka_unit_test(round_trip_plants),  cmocka_unit_test(round_trip_terrain),
        cmocka_unit_test(round_trip_animated), cmocka_unit_test(round_trip_shading), cmocka_unit_test(animation_moves_and_morphs),
        cmocka_unit_test(writer_errors),
    };
    return cmocka_run_group_tests_name("scenes", tests, test_tmpdir_setup, test_tmpdir_teardown);
}
