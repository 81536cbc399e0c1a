/*
 * Tests of the double-precision reference (tb/ref): the BVH finds the same closest hit as brute
 * force over every instanced triangle; the watertight test never lets a ray slip through the
 * shared edges and vertices of a closed mesh; instance transformations (scale, rotation,
 * mirroring) give the hits of the pre-transformed geometry; shading of a lit square equals the
 * shading model of docs/shading.md computed by hand.
 */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "memimage.h"
#include "ref_render.h"
#include "scenes.h"
#include "shading_model.h"

/* Closest hit over all instances and triangles, Moller-Trumbore in double. */
static double brute_force(const scene *s, const double o[3], const double d[3], uint32_t *inst, uint32_t *tri)
{
    double best = INFINITY;
    for (uint32_t i = 0; i < s->n_instances; i++) {
        const scene_mesh *m = &s->meshes[s->instances[i].mesh];
        for (uint32_t t = 0; t < m->n_triangles; t++) {
            double v[3][3], e1[3], e2[3], sv[3];
            for (int k = 0; k < 3; k++) {
                double p[3];
                ref_vertex(m, t, k, p);
                affine_apply_point(&s->instances[i].world, p, v[k]);
            }
            for (int k = 0; k < 3; k++) {
                e1[k] = v[1][k] - v[0][k];
                e2[k] = v[2][k] - v[0][k];
                sv[k] = o[k] - v[0][k];
            }
            const double pv[3] = { d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0] };
            const double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
            if (det == 0)
                continue;
            const double qv[3] = { sv[1] * e1[2] - sv[2] * e1[1], sv[2] * e1[0] - sv[0] * e1[2], sv[0] * e1[1] - sv[1] * e1[0] };
            const double u = (sv[0] * pv[0] + sv[1] * pv[1] + sv[2] * pv[2]) / det;
            const double w = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) / det;
            const double tt = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
            if (u >= 0 && w >= 0 && u + w <= 1 && tt >= 0 && tt < best) {
                best = tt;
                *inst = i;
                *tri = t;
            }
        }
    }
    return best;
}

static void generated(scene *s, const char *name, double time)
{
    char err[256];
    const scene_gen_params gp = { 1, 0 };
    assert_int_equal(scene_generator_find(name)->build(s, &gp, err, sizeof err), 0);
    assert_int_equal(scene_evaluate(s, time, 1), 0);
}

static void random_unit(unsigned *seed, double d[3])
{
    double l;
    do {
        for (int k = 0; k < 3; k++)
            d[k] = 2.0 * rand_r(seed) / RAND_MAX - 1;
        l = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    } while (l < 0.01 || l > 1);
    for (int k = 0; k < 3; k++)
        d[k] /= sqrt(l);
}

static void bvh_against_brute_force(void **state)
{
    (void)state;
    static const char *const names[] = { "cornell", "room", "animated" };
    for (int sc = 0; sc < 3; sc++) {
        scene s;
        generated(&s, names[sc], 1.0);
        ref_scene r;
        assert_int_equal(ref_scene_build(&r, &s), 0);
        unsigned seed = 5;
        int rays = 0, agree = 0;
        for (int i = 0; i < 400; i++) {
            double o[3], d[3];
            for (int k = 0; k < 3; k++)
                o[k] = r.lo[k] + (0.05 + 0.9 * rand_r(&seed) / RAND_MAX) * (r.hi[k] - r.lo[k]);
            random_unit(&seed, d);
            uint32_t bi = UINT32_MAX, bt = UINT32_MAX;
            const double want = brute_force(&s, o, d, &bi, &bt);
            ref_hit h;
            const int hit = ref_intersect(&r, o, d, 0, INFINITY, &h);
            rays++;
            agree += hit ? isfinite(want) && fabs(h.t - want) <= 1e-9 * want : !isfinite(want);
        }
        print_message("%s: %d of %d rays agree with brute force\n", names[sc], agree, rays);
        assert_true(agree >= rays - 2); /* Moller-Trumbore may differ from the watertight test at an edge */
        ref_scene_free(&r);
        scene_free(&s);
    }
}

/* A closed octahedron (8 triangles sharing 12 edges and 6 vertices), instanced rotated and
 * non-uniformly scaled: rays from inside aimed exactly at vertices, edge midpoints and random
 * directions must all hit, and so must rays from outside aimed at the vertices and edges. */
static void watertight_closed_mesh(void **state)
{
    (void)state;
    static const float pos[] = { 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1 };
    static const uint32_t idx[] = { 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5 };
    scene s;
    memset(&s, 0, sizeof s);
    s.meshes = calloc(1, sizeof *s.meshes);
    s.meshes[0] = (scene_mesh){ .n_vertices = 6, .n_triangles = 8, .positions = malloc(sizeof pos),
                                .indices = malloc(sizeof idx), .material = calloc(8, sizeof(uint32_t)) };
    memcpy(s.meshes[0].positions, pos, sizeof pos);
    memcpy(s.meshes[0].indices, idx, sizeof idx);
    s.materials = calloc(1, sizeof *s.materials);
    s.nodes = calloc(1, sizeof *s.nodes);
    s.nodes[0] = (scene_node){ .parent = -1, .mesh = 0, .camera = SCENE_NONE, .light = SCENE_NONE,
                               .rotation = { 0.2, 0.3, 0.1, 0.927 }, .scale = { 3, 0.5, 1.7 }, .translation = { 1, 2, 3 } };
    s.roots = calloc(1, sizeof *s.roots);
    s.n_meshes = s.n_materials = s.n_nodes = s.n_roots = 1;
    assert_int_equal(scene_evaluate(&s, 0, 0), 0);
    ref_scene r;
    assert_int_equal(ref_scene_build(&r, &s), 0);
    const affine *w = &s.instances[0].world;
    double centre[3], targets[6 + 12 + 1000][3];
    const double zero[3] = { 0, 0, 0 };
    affine_apply_point(w, zero, centre);
    int n = 0;
    for (int v = 0; v < 6; v++) {
        const double p[3] = { pos[3 * v], pos[3 * v + 1], pos[3 * v + 2] };
        affine_apply_point(w, p, targets[n++]);
    }
    for (int a = 0; a < 6; a++)
        for (int b = a + 1; b < 6; b++)
            if (a / 2 != b / 2) { /* not opposite vertices: an edge */
                const double p[3] = { 0.5 * (pos[3 * a] + pos[3 * b]), 0.5 * (pos[3 * a + 1] + pos[3 * b + 1]),
                                      0.5 * (pos[3 * a + 2] + pos[3 * b + 2]) };
                affine_apply_point(w, p, targets[n++]);
            }
    unsigned seed = 9;
    for (int i = 0; i < 1000; i++) {
        double d[3];
        random_unit(&seed, d);
        for (int k = 0; k < 3; k++)
            targets[n][k] = centre[k] + d[k];
        n++;
    }
    for (int i = 0; i < n; i++) {
        double d[3], o[3];
        ref_hit h;
        for (int k = 0; k < 3; k++)
            d[k] = targets[i][k] - centre[k];
        assert_true(ref_intersect(&r, centre, d, 0, INFINITY, &h)); /* from inside */
        if (i >= 18)
            continue;
        for (int k = 0; k < 3; k++) { /* from outside, through the vertex or edge towards the centre */
            o[k] = centre[k] + 3 * d[k];
            d[k] = -d[k];
        }
        assert_true(ref_intersect(&r, o, d, 0, INFINITY, &h));
    }
    ref_scene_free(&r);
    scene_free(&s);
}

/* A lit square seen head-on: the reference's colour equals docs/shading.md by hand. Square
 * z = 0, [-1,1]^2, base 0.5 grey, roughness 1 (kd = 1, no highlight or reflection); a white
 * point light at (0, 1, 1); the centre pixel's ray hits (x, y, 0) near the origin. */
static void shading_by_hand(void **state)
{
    (void)state;
    static const float pos[] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 };
    static const uint32_t idx[] = { 0, 1, 2, 0, 2, 3 };
    scene s;
    memset(&s, 0, sizeof s);
    s.meshes = calloc(1, sizeof *s.meshes);
    s.meshes[0] = (scene_mesh){ .n_vertices = 4, .n_triangles = 2, .positions = malloc(sizeof pos),
                                .indices = malloc(sizeof idx), .material = calloc(2, sizeof(uint32_t)) };
    memcpy(s.meshes[0].positions, pos, sizeof pos);
    memcpy(s.meshes[0].indices, idx, sizeof idx);
    s.materials = calloc(1, sizeof *s.materials);
    s.materials[0] = (scene_material){ .base_color = { 0.5f, 0.5f, 0.5f, 1 }, .base_color_texture = SCENE_NONE,
                                       .roughness = 1, .ior = 1.5f };
    s.nodes = calloc(1, sizeof *s.nodes);
    s.nodes[0] = (scene_node){ .parent = -1, .mesh = 0, .camera = SCENE_NONE, .light = SCENE_NONE,
                               .rotation = { 0, 0, 0, 1 }, .scale = { 1, 1, 1 } };
    s.roots = calloc(1, sizeof *s.roots);
    s.lights = calloc(1, sizeof *s.lights);
    s.lights[0] = (scene_light){ .kind = LIGHT_POINT, .color = { 1, 1, 1 }, .intensity = 5, .node = SCENE_NONE,
                                 .position = { 0, 1, 1 } };
    s.n_meshes = s.n_materials = s.n_nodes = s.n_roots = s.n_lights = 1;
    assert_int_equal(scene_evaluate(&s, 0, 0), 0);
    mi_params mp;
    mi_params_default(&mp);
    mp.width = mp.height = 8;
    mp.explicit_view = 1;
    const double eye[3] = { 0, 0, 3 }, at[3] = { 0, 0, 0 }, up[3] = { 0, 1, 0 };
    memcpy(mp.eye, eye, sizeof eye);
    memcpy(mp.at, at, sizeof at);
    memcpy(mp.up, up, sizeof up);
    char err[256];
    mi_builder *b = mi_build(&s, &mp, err, sizeof err);
    assert_non_null(b);
    ref_scene r;
    assert_int_equal(ref_scene_build(&r, &s), 0);
    ref_params p;
    assert_int_equal(ref_params_init(&p, b, &r, 3, 1), 0);
    double rgb[3], o[3], d[3];
    ref_hit h;
    ref_pixel(&r, &p, 4, 4, rgb, &h);
    ref_primary(&p.cam, 4, 4, o, d);
    const double P[3] = { o[0] + h.t * d[0], o[1] + h.t * d[1], o[2] + h.t * d[2] };
    const double L[3] = { -P[0], 1 - P[1], 1 - P[2] }, len = sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
    const double want = 0.5 * (SHADE_AMBIENT + SHADE_DIFFUSE * L[2] / len);
    assert_true(fabs(P[2]) < 1e-12);
    for (int k = 0; k < 3; k++)
        assert_float_equal(rgb[k], want, 1e-9);
    ref_params_free(&p);
    ref_scene_free(&r);
    mi_free(b);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = { cmocka_unit_test(bvh_against_brute_force), cmocka_unit_test(watertight_closed_mesh),
                                        cmocka_unit_test(shading_by_hand) };
    return cmocka_run_group_tests_name("ref", tests, NULL, NULL);
}
