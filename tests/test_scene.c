/*
 * Tests of the glTF loader and the scene model (host/scene): counts of the shared real scenes
 * (../shared/scenes, skipped with a message when absent), instancing, animation evaluation,
 * skinning (a generated two-joint file against hand-computed vertices, the shared fox), and
 * malformed files (truncated, wrong accessor types, out-of-range indices, NaN positions, broken
 * hierarchies), which must give a one-line error and an empty scene, never a crash.
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

#ifndef SAARCOR_SRC_DIR
#define SAARCOR_SRC_DIR "."
#endif
#define SHARED SAARCOR_SRC_DIR "/../shared/scenes/"


static int have_shared(void)
{
    if (access(SHARED "SOURCES.md", R_OK) == 0)
        return 1;
    print_message("../shared/scenes is absent: shared-scene tests skipped\n");
    return 0;
}

static uint64_t instanced_triangles(const scene *s)
{
    uint64_t n = 0;
    for (uint32_t i = 0; i < s->n_instances; i++)
        n += s->meshes[s->instances[i].mesh].n_triangles;
    return n;
}

static uint64_t unique_triangles(const scene *s)
{
    uint64_t n = 0;
    for (uint32_t i = 0; i < s->n_meshes; i++)
        n += s->meshes[i].n_triangles;
    return n;
}

/* Triangle counts from ../shared/scenes/SOURCES.md. */
static void shared_scene_counts(void **state)
{
    (void)state;
    if (!have_shared())
        skip();
    const struct { const char *file; uint64_t tris, scene_tris; uint32_t textures_min; } expect[] = {
        { "Box.glb", 12, 12, 0 }, { "BoxTextured.glb", 12, 12, 1 }, { "BoxAnimated.glb", 254, 254, 0 },
        { "CesiumMilkTruck.glb", 2856, 3624, 1 }, { "Fox.glb", 576, 576, 1 }, { "Avocado/Avocado.gltf", 682, 682, 1 },
        { "cornell_box.glb", 32, 32, 0 }, { "teapot.glb", 9128, 9128, 0 }, { "primitives.glb", 3636, 3636, 0 },
        { "subpass_scene_opaque.glb", 11132, 23388, 0 }, { "bunny.glb", 69451, 69451, 0 },
        { "bunny_instanced16.glb", 69451, 1111216, 0 }, { "gallery_ccby_503k.glb", 503770, 503770, 0 },
    };
    for (size_t i = 0; i < sizeof expect / sizeof expect[0]; i++) {
        char path[512], err[512];
        scene s;
        snprintf(path, sizeof path, SHARED "%s", expect[i].file);
        if (scene_load_gltf(path, &s, err, sizeof err) != 0)
            fail_msg("%s", err);
        if (unique_triangles(&s) != expect[i].tris || instanced_triangles(&s) != expect[i].scene_tris)
            fail_msg("%s: %llu/%llu triangles, expected %llu/%llu", expect[i].file,
                     (unsigned long long)unique_triangles(&s), (unsigned long long)instanced_triangles(&s),
                     (unsigned long long)expect[i].tris, (unsigned long long)expect[i].scene_tris);
        assert_true(s.n_textures >= expect[i].textures_min);
        for (uint32_t m = 0; m < s.n_meshes; m++)
            for (uint32_t k = 0; k < 3 * s.meshes[m].n_triangles; k++)
                assert_true(s.meshes[m].indices[k] < s.meshes[m].n_vertices);
        scene_free(&s);
    }
}

/* The wheel mesh of the milk truck is stored once and drawn twice; the truck and the bunny field
 * place copies by their node transformations. */
static void instancing(void **state)
{
    (void)state;
    if (!have_shared())
        skip();
    scene s;
    char err[512];
    assert_int_equal(scene_load_gltf(SHARED "bunny_instanced16.glb", &s, err, sizeof err), 0);
    assert_int_equal(s.n_meshes, 1);
    assert_int_equal(s.n_instances, 16);
    /* instance k's world-space vertex = its world transformation applied to the object vertex */
    const scene_mesh *m = &s.meshes[0];
    double first[3] = { 0 };
    for (uint32_t k = 0; k < s.n_instances; k++) {
        const double p[3] = { m->positions[0], m->positions[1], m->positions[2] };
        double q[3];
        affine_apply_point(&s.instances[k].world, p, q);
        if (k == 0)
            memcpy(first, q, sizeof q);
        else
            assert_true(fabs(q[0] - first[0]) + fabs(q[1] - first[1]) + fabs(q[2] - first[2]) > 1e-6);
    }
    scene_free(&s);
    assert_int_equal(scene_load_gltf(SHARED "CesiumMilkTruck.glb", &s, err, sizeof err), 0);
    uint32_t uses[8] = { 0 };
    for (uint32_t k = 0; k < s.n_instances; k++)
        uses[s.instances[k].mesh]++;
    assert_int_equal(s.n_meshes, 2);
    assert_true(uses[0] == 2 || uses[1] == 2);
    scene_free(&s);
}

static void animation(void **state)
{
    (void)state;
    if (!have_shared())
        skip();
    scene s;
    char err[512];
    assert_int_equal(scene_load_gltf(SHARED "BoxAnimated.glb", &s, err, sizeof err), 0);
    assert_true(s.n_animations >= 1 && s.animations[0].duration > 0);
    affine a0[8], a1[8];
    assert_true(s.n_instances <= 8);
    for (uint32_t i = 0; i < s.n_instances; i++)
        a0[i] = s.instances[i].world;
    assert_int_equal(scene_evaluate(&s, 0.3 * s.animations[0].duration, 1), 0);
    double moved = 0;
    for (uint32_t i = 0; i < s.n_instances; i++) {
        a1[i] = s.instances[i].world;
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 4; c++)
                moved += fabs(a1[i].m[r][c] - a0[i].m[r][c]);
    }
    assert_true(moved > 1e-3);
    /* looping: t and t + duration give the same pose */
    assert_int_equal(scene_evaluate(&s, 1.3 * s.animations[0].duration, 1), 0);
    for (uint32_t i = 0; i < s.n_instances; i++)
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 4; c++)
                assert_float_equal(s.instances[i].world.m[r][c], a1[i].m[r][c], 1e-5);
    scene_free(&s);
}

static void affine_algebra(void **state)
{
    (void)state;
    const double t[3] = { 1, -2, 3 }, q[4] = { 0.1825742, 0.3651484, 0.5477226, 0.7302967 }, sc[3] = { 2, 0.5, 3 };
    const affine a = affine_from_trs(t, q, sc);
    affine inv, id;
    assert_int_equal(affine_invert(&a, &inv), 1);
    id = affine_mul(&a, &inv);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            assert_float_equal(id.m[r][c], r == c ? 1.0 : 0.0, 1e-12);
    affine sing = affine_identity();
    sing.m[1][1] = 0;
    assert_int_equal(affine_invert(&sing, &inv), 0);
}

/* ---- malformed files --------------------------------------------------------------------- */

static void base64(const unsigned char *in, size_t n, char *out)
{
    static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t o = 0;
    for (size_t i = 0; i < n; i += 3) {
        const uint32_t v = (uint32_t)in[i] << 16 | (i + 1 < n ? (uint32_t)in[i + 1] << 8 : 0) | (i + 2 < n ? in[i + 2] : 0);
        out[o++] = tab[v >> 18 & 63];
        out[o++] = tab[v >> 12 & 63];
        out[o++] = i + 1 < n ? tab[v >> 6 & 63] : '=';
        out[o++] = i + 2 < n ? tab[v & 63] : '=';
    }
    out[o] = '\0';
}

/* One triangle: 3 float positions then 3 uint16 indices; the caller may break any part, add to
 * the node (extra_nodes) and add top-level members (extra_top: "\"key\":value,"). */
static const char *write_gltf_top(const char *name, const float pos[9], const uint16_t idx[3], const char *pos_type,
                                  const char *extra_nodes, const char *extra_top)
{
    unsigned char buf[44] = { 0 };
    memcpy(buf, pos, 36);
    memcpy(buf + 36, idx, 6);
    char b64[80];
    base64(buf, 42, b64);
    static char path[128];
    snprintf(path, sizeof path, "%s/%s", test_dir, name);
    FILE *f = fopen(path, "w");
    fprintf(f,
            "{%s\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
            "\"nodes\":[{\"mesh\":0%s}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
            "\"buffers\":[{\"byteLength\":42,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"%s\",\"max\":[1,1,0],\"min\":[0,0,0]},"
            "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]}",
            extra_top, extra_nodes, b64, pos_type);
    fclose(f);
    return path;
}

static const char *write_gltf(const char *name, const float pos[9], const uint16_t idx[3], const char *pos_type,
                              const char *extra_nodes)
{
    return write_gltf_top(name, pos, idx, pos_type, extra_nodes, "");
}

static void expect_load_error(const char *path, const char *needle)
{
    scene s;
    char err[512] = "";
    if (scene_load_gltf(path, &s, err, sizeof err) == 0)
        fail_msg("%s loaded, expected an error mentioning '%s'", path, needle);
    assert_null(strchr(err, '\n'));
    if (!strstr(err, needle))
        fail_msg("error '%s' does not mention '%s'", err, needle);
    assert_int_equal(s.n_meshes, 0);
    assert_null(s.meshes);
}

static void malformed_files(void **state)
{
    (void)state;
    const float ok_pos[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    const uint16_t ok_idx[3] = { 0, 1, 2 }, bad_idx[3] = { 0, 1, 7 };
    float nan_pos[9];
    memcpy(nan_pos, ok_pos, sizeof nan_pos);
    nan_pos[4] = NAN;

    scene s;
    char err[512];
    assert_int_equal(scene_load_gltf(write_gltf("ok.gltf", ok_pos, ok_idx, "VEC3", ""), &s, err, sizeof err), 0);
    assert_int_equal(s.n_meshes, 1);
    assert_int_equal(s.meshes[0].n_triangles, 1);
    scene_free(&s);

    expect_load_error(write_gltf("badidx.gltf", ok_pos, bad_idx, "VEC3", ""), "out of range");
    expect_load_error(write_gltf("nan.gltf", nan_pos, ok_idx, "VEC3", ""), "non-finite");
    expect_load_error(write_gltf("type.gltf", ok_pos, ok_idx, "VEC4", ""), "accessor");
    expect_load_error(write_gltf("cycle.gltf", ok_pos, ok_idx, "VEC3", ",\"children\":[0]"), "parent");
    expect_load_error(write_gltf("badmesh.gltf", ok_pos, ok_idx, "VEC3", "},{\"mesh\":5"), "mesh");
    char path[128];
    snprintf(path, sizeof path, "%s/missing.glb", test_dir);
    expect_load_error(path, "missing.glb");
    snprintf(path, sizeof path, "%s/garbage.gltf", test_dir);
    FILE *f = fopen(path, "w");
    fputs("{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [", f);
    fclose(f);
    expect_load_error(path, "garbage.gltf");
}

/* ---- skinning ------------------------------------------------------------------------------ */

typedef struct {
    unsigned char data[512];
    size_t n;
    char views[1024], accessors[1024]; /* JSON array bodies */
    int count;                         /* views = accessors so far */
} gltf_buf;

/* Appends bytes as a new buffer view with an accessor over it; returns the accessor index. */
static int add_accessor(gltf_buf *g, const void *bytes, size_t size, int ctype, int normalized, int count,
                        const char *type)
{
    memcpy(g->data + g->n, bytes, size);
    snprintf(g->views + strlen(g->views), sizeof g->views - strlen(g->views), "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}",
             g->count ? "," : "", g->n, size);
    snprintf(g->accessors + strlen(g->accessors), sizeof g->accessors - strlen(g->accessors),
             "%s{\"bufferView\":%d,\"componentType\":%d,\"normalized\":%s,\"count\":%d,\"type\":\"%s\"}", g->count ? "," : "",
             g->count, ctype, normalized ? "true" : "false", count, type);
    g->n += (size + 3) & ~(size_t)3;
    return g->count++;
}

/* A triangle skinned to two joints: joint 0 (node 1, at (1,0,0)) and its child joint 1 (node 2,
 * 1 up); vertex 0 follows joint 0, vertex 1 joint 1, vertex 2 both by halves. The animation moves
 * joint 0 by (0,0,2) and turns joint 1 by 90 degrees about z over one second. The mesh's node is
 * at (100,0,0), which glTF says must not move a skinned mesh. With small, the influences are
 * unsigned bytes (weights normalized), else unsigned shorts and floats; bad_joint names a joint the
 * skin does not have. */
static const char *write_skinned_gltf(const char *name, int small, int bad_joint)
{
    const float pos[9] = { 1, 0, 0, 1, 2, 0, 2, 1, 0 }, nrm[9] = { 1, 0, 0, 1, 0, 0, 0, 0, 1 };
    const uint8_t j8[12] = { 0, 0, 0, 0, bad_joint ? 5 : 1, 0, 0, 0, 0, 1, 0, 0 }, w8[12] = { 255, 0, 0, 0, 255, 0, 0, 0, 128, 128, 0, 0 };
    const uint16_t j16[12] = { 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0 };
    const float wf[12] = { 1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0 };
    const float ibm[32] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1,    /* column-major: T(-1,0,0) */
                            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, -1, 0, 1 }; /* T(-1,-1,0) */
    const float times[2] = { 0, 1 }, moves[6] = { 1, 0, 0, 1, 0, 2 }, turns[8] = { 0, 0, 0, 1, 0, 0, 0.70710678f, 0.70710678f };
    gltf_buf g = { .n = 0 };
    const int ap = add_accessor(&g, pos, sizeof pos, 5126, 0, 3, "VEC3");
    const int an = add_accessor(&g, nrm, sizeof nrm, 5126, 0, 3, "VEC3");
    const int aj = small ? add_accessor(&g, j8, sizeof j8, 5121, 0, 3, "VEC4") : add_accessor(&g, j16, sizeof j16, 5123, 0, 3, "VEC4");
    const int aw = small ? add_accessor(&g, w8, sizeof w8, 5121, 1, 3, "VEC4") : add_accessor(&g, wf, sizeof wf, 5126, 0, 3, "VEC4");
    const int ai = add_accessor(&g, ibm, sizeof ibm, 5126, 0, 2, "MAT4");
    const int at = add_accessor(&g, times, sizeof times, 5126, 0, 2, "SCALAR");
    const int am = add_accessor(&g, moves, sizeof moves, 5126, 0, 2, "VEC3");
    const int ar = add_accessor(&g, turns, sizeof turns, 5126, 0, 2, "VEC4");
    char b64[700];
    base64(g.data, g.n, b64);
    static char path[128];
    snprintf(path, sizeof path, "%s/%s", test_dir, name);
    FILE *f = fopen(path, "w");
    fprintf(f,
            "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1]}],"
            "\"nodes\":[{\"mesh\":0,\"skin\":0,\"translation\":[100,0,0]},{\"translation\":[1,0,0],\"children\":[2]},"
            "{\"translation\":[0,1,0]}],"
            "\"skins\":[{\"joints\":[1,2],\"inverseBindMatrices\":%d}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d,\"JOINTS_0\":%d,\"WEIGHTS_0\":%d}}]}],"
            "\"animations\":[{\"name\":\"bend\",\"channels\":[{\"sampler\":0,\"target\":{\"node\":1,\"path\":\"translation\"}},"
            "{\"sampler\":1,\"target\":{\"node\":2,\"path\":\"rotation\"}}],"
            "\"samplers\":[{\"input\":%d,\"output\":%d},{\"input\":%d,\"output\":%d}]}],"
            "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
            "\"bufferViews\":[%s],\"accessors\":[%s]}",
            ai, ap, an, aj, aw, at, am, at, ar, g.n, b64, g.views, g.accessors);
    fclose(f);
    return path;
}

static void expect_vertex(const float *p, double x, double y, double z)
{
    assert_float_equal(p[0], x, 1e-5);
    assert_float_equal(p[1], y, 1e-5);
    assert_float_equal(p[2], z, 1e-5);
}

/* Hand-computed: at t = 1 joint 0 is T(1,0,2), so jointMatrix 0 = T(0,0,2); joint 1 turns 90
 * degrees about z at (1,1,2), jointMatrix 1 = T(1,1,2) Rz(90) T(-1,-1,0). Vertex 0 (1,0,0) ->
 * (1,0,2); vertex 1 (1,2,0) -> (1,1,2) + Rz(90)(0,1,0) = (0,1,2); vertex 2 (2,1,0) -> half of
 * (2,1,2) and (1,2,2). At t = 0.5 (z 1, 45 degrees) vertex 1 is (1 - r, 1 + r, 1), r = 1/sqrt 2. */
static void skinning(void **state)
{
    (void)state;
    const double r = sqrt(0.5);
    for (int small = 0; small < 2; small++) {
        scene s;
        char err[512];
        const char *path = write_skinned_gltf(small ? "skin8.gltf" : "skin16.gltf", small, 0);
        if (scene_load_gltf(path, &s, err, sizeof err) != 0)
            fail_msg("%s", err);
        assert_int_equal(s.warnings, 0);
        assert_int_equal(s.n_skins, 1);
        assert_int_equal(s.n_instances, 1);
        const scene_mesh *m = &s.meshes[0];
        assert_non_null(m->joints);
        assert_true(scene_mesh_deforms(m));
        expect_vertex(&m->positions[3], 1, 2, 0); /* t = 0: the bind pose, not moved by its node */
        for (int k = 0; k < 12; k++)
            assert_true(s.instances[0].world.m[k / 4][k % 4] == (k % 5 == 0)); /* the identity */
        const uint32_t rev = m->revision;
        assert_int_equal(scene_evaluate(&s, 1.0, 0), 0);
        assert_int_not_equal(m->revision, rev);
        expect_vertex(&m->positions[0], 1, 0, 2);
        expect_vertex(&m->positions[3], 0, 1, 2);
        expect_vertex(&m->positions[6], 1.5, 1.5, 2);
        expect_vertex(&m->normals[0], 1, 0, 0);
        expect_vertex(&m->normals[3], 0, 1, 0); /* turned with joint 1 */
        assert_int_equal(scene_evaluate(&s, 0.5, 0), 0);
        expect_vertex(&m->positions[3], 1 - r, 1 + r, 1);
        const uint32_t rev_half = m->revision;
        assert_int_equal(scene_evaluate(&s, 0.5, 0), 0); /* the same pose: nothing to rebuild */
        assert_int_equal(m->revision, rev_half);
        /* written back (rest pose, influences, skin) and loaded again: the same pose */
        char again[128];
        snprintf(again, sizeof again, "%s/skin_again.glb", test_dir);
        if (scene_write_gltf(&s, again, err, sizeof err) != 0)
            fail_msg("%s", err);
        scene_free(&s);
        assert_int_equal(scene_load_gltf(again, &s, err, sizeof err), 0);
        assert_int_equal(scene_evaluate(&s, 1.0, 0), 0);
        expect_vertex(&s.meshes[0].positions[3], 0, 1, 2);
        expect_vertex(&s.meshes[0].positions[6], 1.5, 1.5, 2);
        scene_free(&s);
    }
    expect_load_error(write_skinned_gltf("badjoint.gltf", 1, 1), "JOINTS_0 names joint 5");
}

/* The shared Fox.glb at two times: its skinned vertices (and their bounds) move. */
static void skinned_fox(void **state)
{
    (void)state;
    if (!have_shared())
        skip();
    scene s;
    char err[512];
    assert_int_equal(scene_load_gltf(SHARED "Fox.glb", &s, err, sizeof err), 0);
    assert_int_equal(s.warnings, 0); /* no "drawn in bind pose" */
    assert_int_equal(scene_select_animation(&s, "Run"), 0);
    assert_int_equal(s.n_animations, 1);
    double box[2][6];
    for (int i = 0; i < 2; i++) {
        assert_int_equal(scene_evaluate(&s, 0.1 + 0.25 * i, 1), 0);
        const scene_mesh *m = &s.meshes[s.instances[0].mesh];
        assert_non_null(m->joints);
        for (int k = 0; k < 3; k++) {
            box[i][k] = INFINITY;
            box[i][3 + k] = -INFINITY;
            for (uint32_t v = 0; v < m->n_vertices; v++) {
                box[i][k] = fmin(box[i][k], m->positions[3 * v + (uint32_t)k]);
                box[i][3 + k] = fmax(box[i][3 + k], m->positions[3 * v + (uint32_t)k]);
            }
        }
    }
    double moved = 0;
    for (int k = 0; k < 6; k++)
        moved = fmax(moved, fabs(box[1][k] - box[0][k]));
    assert_true(moved > 1.0); /* the fox is about 150 units long */
    assert_int_equal(scene_select_animation(&s, "Nope"), -1);
    scene_free(&s);
}

/* Every truncation of a valid .glb is refused cleanly (or, if it happens to still parse, loads). */
static void truncated_glb(void **state)
{
    (void)state;
    if (!have_shared())
        skip();
    FILE *f = fopen(SHARED "Box.glb", "rb");
    assert_non_null(f);
    unsigned char data[4096];
    const size_t n = fread(data, 1, sizeof data, f);
    fclose(f);
    char path[128];
    snprintf(path, sizeof path, "%s/cut.glb", test_dir);
    for (size_t cut = 0; cut < n; cut += 7) {
        f = fopen(path, "wb");
        fwrite(data, 1, cut, f);
        fclose(f);
        scene s;
        char err[512];
        if (scene_load_gltf(path, &s, err, sizeof err) == 0)
            scene_free(&s);
        else
            assert_null(strchr(err, '\n'));
    }
}


/* ---- extensions, ignored features, GPU instancing, default camera ------------------------- */

static const float tri_pos[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
static const uint16_t tri_idx[3] = { 0, 1, 2 };

/* A required extension the loader lacks is refused with one line naming it; required ones it
 * implements load. */
static void required_extensions(void **state)
{
    (void)state;
    expect_load_error(write_gltf_top("req.gltf", tri_pos, tri_idx, "VEC3", "",
                                     "\"extensionsUsed\":[\"KHR_lights_punctual\",\"EXT_foo\"],"
                                     "\"extensionsRequired\":[\"KHR_lights_punctual\",\"EXT_foo\"],"),
                      "requires extension EXT_foo, which saarcor does not implement");
    scene s;
    char err[512];
    const char *ok = write_gltf_top("req_ok.gltf", tri_pos, tri_idx, "VEC3", "",
                                    "\"extensionsUsed\":[\"KHR_mesh_quantization\",\"EXT_mesh_gpu_instancing\"],"
                                    "\"extensionsRequired\":[\"KHR_mesh_quantization\",\"EXT_mesh_gpu_instancing\"],");
    if (scene_load_gltf(ok, &s, err, sizeof err) != 0)
        fail_msg("%s", err);
    assert_int_equal(s.n_ignored, 0);
    scene_free(&s);
}

/* Each unimplemented feature is listed (and warned) once, however many materials use it. */
static void ignored_features(void **state)
{
    (void)state;
    const char *path = write_gltf_top(
        "ignored.gltf", tri_pos, tri_idx, "VEC3", "",
        "\"extensionsUsed\":[\"KHR_materials_clearcoat\",\"KHR_lights_punctual\"],\"textures\":[{}],"
        "\"materials\":[{\"normalTexture\":{\"index\":0}},{\"normalTexture\":{\"index\":0},"
        "\"occlusionTexture\":{\"index\":0}}],");
    scene s;
    char err[512];
    if (scene_load_gltf(path, &s, err, sizeof err) != 0)
        fail_msg("%s", err);
    assert_int_equal(s.n_ignored, 3);
    assert_string_equal(s.ignored[0], "KHR_materials_clearcoat");
    assert_string_equal(s.ignored[1], "normalTexture");
    assert_string_equal(s.ignored[2], "occlusionTexture");
    assert_int_equal(s.warnings, 3);
    scene_free(&s);
}

/* One triangle drawn by a node (translation 0,1,0, scale 2) with n EXT_mesh_gpu_instancing rows:
 * row i translates by (3i, 0, 0) and turns 90 degrees about y. */
static const char *write_instanced(const char *name, uint32_t n)
{
    unsigned char buf[44 + 28 * 8] = { 0 };
    const float q[4] = { 0, (float)sqrt(0.5), 0, (float)sqrt(0.5) };
    memcpy(buf, tri_pos, 36);
    memcpy(buf + 36, tri_idx, 6);
    for (uint32_t i = 0; i < n; i++) {
        const float t[3] = { 3.0f * (float)i, 0, 0 };
        memcpy(buf + 44 + 12 * i, t, 12);
        memcpy(buf + 44 + 12 * n + 16 * i, q, 16);
    }
    const size_t len = 44 + 28 * (size_t)n;
    char b64[sizeof buf * 4 / 3 + 8];
    base64(buf, len, b64);
    static char path[128];
    snprintf(path, sizeof path, "%s/%s", test_dir, name);
    FILE *f = fopen(path, "w");
    fprintf(f,
            "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"EXT_mesh_gpu_instancing\"],\"scenes\":[{\"nodes\":[0]}],"
            "\"nodes\":[{\"mesh\":0,\"translation\":[0,1,0],\"scale\":[2,2,2],\"extensions\":{\"EXT_mesh_gpu_instancing\":"
            "{\"attributes\":{\"TRANSLATION\":2,\"ROTATION\":3}}}}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
            "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6},"
            "{\"buffer\":0,\"byteOffset\":44,\"byteLength\":%u},{\"buffer\":0,\"byteOffset\":%u,\"byteLength\":%u}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"max\":[1,1,0],\"min\":[0,0,0]},"
            "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"},"
            "{\"bufferView\":2,\"componentType\":5126,\"count\":%u,\"type\":\"VEC3\"},"
            "{\"bufferView\":3,\"componentType\":5126,\"count\":%u,\"type\":\"VEC4\"}]}",
            len, b64, 12 * n, 44 + 12 * n, 16 * n, n, n);
    fclose(f);
    return path;
}

/* N rows are N instances at node world x row (the rows are in the node's local space). */
static void gpu_instancing(void **state)
{
    (void)state;
    for (uint32_t n = 1; n <= 8; n += 7) {
        scene s;
        char err[512];
        if (scene_load_gltf(write_instanced("inst.gltf", n), &s, err, sizeof err) != 0)
            fail_msg("%s", err);
        assert_int_equal(s.n_instances, n);
        assert_int_equal(scene_count_instances(&s), n);
        for (uint32_t i = 0; i < n; i++) {
            const affine *w = &s.instances[i].world;
            assert_true(fabs(w->m[0][3] - 6.0 * i) < 1e-9 && fabs(w->m[1][3] - 1.0) < 1e-9 && fabs(w->m[2][3]) < 1e-9);
            assert_true(fabs(w->m[0][2] - 2.0) < 1e-6 && fabs(w->m[2][0] + 2.0) < 1e-6); /* scale 2, then turned */
        }
        scene_free(&s);
    }
    if (!have_shared())
        skip();
    scene s;
    char err[512];
    if (scene_load_gltf(SHARED "SimpleInstancing.glb", &s, err, sizeof err) != 0)
        fail_msg("%s", err);
    assert_int_equal(s.n_instances, 125);
    assert_int_equal(s.warnings, 0);
    scene_free(&s);
}

/* A mesh of five primitives where only the second has normals, texture coordinates (normalized
 * shorts: the loader's general path) and colours (normalized bytes): the vertices of the others
 * get the defaults, before and after it (the loader fills an attribute's array only once a
 * primitive has it, and pads the vertices before). The fourth is an indexed triangle strip and the
 * fifth a fan without indices: each one triangle, whose indices continue the list. */
static void mixed_primitives(void **state)
{
    (void)state;
    unsigned char buf[104] = { 0 };
    const float pos[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, nrm[9] = { 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    const uint16_t idx[3] = { 0, 1, 2 }, uv[6] = { 0, 65535, 32768, 0, 0, 65535 };
    const unsigned char rgba[12] = { 255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255 };
    memcpy(buf, pos, 36);
    memcpy(buf + 36, idx, 6);
    memcpy(buf + 44, nrm, 36);
    memcpy(buf + 80, uv, 12);
    memcpy(buf + 92, rgba, 12);
    char b64[160], path[128];
    base64(buf, sizeof buf, b64);
    snprintf(path, sizeof path, "%s/mixed.gltf", test_dir);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fprintf(f,
            "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1},"
            "{\"attributes\":{\"POSITION\":0,\"NORMAL\":2,\"TEXCOORD_0\":3,\"COLOR_0\":4},\"indices\":1},"
            "{\"attributes\":{\"POSITION\":0},\"indices\":1},{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":5},"
            "{\"attributes\":{\"POSITION\":0},\"mode\":6}]}],"
            "\"buffers\":[{\"byteLength\":104,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6},"
            "{\"buffer\":0,\"byteOffset\":44,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":80,\"byteLength\":12},"
            "{\"buffer\":0,\"byteOffset\":92,\"byteLength\":12}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"max\":[1,1,0],\"min\":[0,0,0]},"
            "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"},"
            "{\"bufferView\":2,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
            "{\"bufferView\":3,\"componentType\":5123,\"normalized\":true,\"count\":3,\"type\":\"VEC2\"},"
            "{\"bufferView\":4,\"componentType\":5121,\"normalized\":true,\"count\":3,\"type\":\"VEC4\"}]}",
            b64);
    fclose(f);
    scene s;
    char err[512];
    if (scene_load_gltf(path, &s, err, sizeof err) != 0)
        fail_msg("%s", err);
    assert_int_equal(s.n_meshes, 1);
    const scene_mesh *m = &s.meshes[0];
    assert_int_equal(m->n_vertices, 15);
    assert_int_equal(m->n_triangles, 5);
    assert_non_null(m->normals);
    assert_non_null(m->texcoords);
    assert_non_null(m->colours);
    assert_null(m->texcoords1);
    for (uint32_t v = 0; v < 15; v++) {
        const int mid = v >= 3 && v < 6;
        expect_vertex(&m->positions[3 * v], pos[3 * (v % 3)], pos[3 * (v % 3) + 1], pos[3 * (v % 3) + 2]);
        expect_vertex(&m->normals[3 * v], 0, 0, mid);
        assert_true(m->texcoords[2 * v] == (mid ? (float)(uv[2 * (v % 3)] / 65535.0) : 0.0f));
        assert_true(m->texcoords[2 * v + 1] == (mid ? (float)(uv[2 * (v % 3) + 1] / 65535.0) : 0.0f));
        for (int c = 0; c < 3; c++)
            assert_true(m->colours[3 * v + c] == (mid ? (c == (int)(v % 3) ? 1.0f : 0.0f) : 1.0f));
        assert_int_equal(m->indices[v], v);
    }
    scene_free(&s);
}

/* Without a camera the view is raised and turned: it looks down at a plane at y = 0 (the old
 * view along -Z saw it edge-on) and its forward axis points at the box centre. */
static void default_camera(void **state)
{
    (void)state;
    const double lo[3] = { -1, 0, -1 }, hi[3] = { 1, 0, 1 };
    const scene_camera c = scene_default_camera(lo, hi);
    const double fwd[3] = { -c.world.m[0][2], -c.world.m[1][2], -c.world.m[2][2] };
    assert_true(fwd[1] < -0.3 && fwd[1] > -0.6); /* slightly elevated */
    assert_true(fwd[0] < -0.2 && fwd[2] < -0.5);  /* from the front right */
    for (int k = 0; k < 3; k++) /* eye + distance x forward = centre */
        assert_true(fabs(c.world.m[k][3] + 1.2 * sqrt(8.0) * fwd[k]) < 1e-9);
    assert_true(c.world.m[1][3] > 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shared_scene_counts), cmocka_unit_test(instancing), cmocka_unit_test(animation),
        cmocka_unit_test(affine_algebra), cmocka_unit_test(malformed_files), cmocka_unit_test(truncated_glb),
        cmocka_unit_test(required_extensions), cmocka_unit_test(ignored_features), cmocka_unit_test(gpu_instancing),
        cmocka_unit_test(default_camera), cmocka_unit_test(mixed_primitives),
        cmocka_unit_test(skinning), cmocka_unit_test(skinned_fox),
    };
    return cmocka_run_group_tests_name("scene", tests, test_tmpdir_setup, test_tmpdir_teardown);
}
