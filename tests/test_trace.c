/*
 * Tests of the functional ray tracing core (hls/units/trace): primary rays of generated scenes
 * (two-level trees, instancing with scale and rotation, a morphing object in the dynamic region)
 * traced through the memory image with fp24 units, against brute force in double precision over
 * every instanced triangle of the scene: hit/miss agreement and the distance to the closest hit.
 * Also: rays with zero direction components, rays lying in split planes, and rays that
 * disagree within a packet.
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

#include "f24_fast.h"
#include "memimage.h"
#include "ref_units.h"
#include "rgs.h"
#include "scene.h"
#include "scenes.h"
#include "isect_unit.h"
#include "trace.h"
#include "xform_unit.h"

static double D(f24_t x) { return f24_fast_decode(x); }
static f24_t F(double x) { return f24_fast_encode(x); }

/* Closest hit distance in double over all instanced triangles (Moller-Trumbore), or INFINITY. */
static double brute_force(const scene *s, const double o[3], const double d[3])
{
    double best = INFINITY;
    for (uint32_t i = 0; i < s->n_instances; i++) {
        const scene_mesh *m = &s->meshes[s->instances[i].mesh];
        for (uint32_t t = 0; t < m->n_triangles; t++) {
            double v[3][3];
            for (int k = 0; k < 3; k++) {
                const float *p = &m->positions[3 * (size_t)m->indices[3 * t + (uint32_t)k]];
                const double q[3] = { p[0], p[1], p[2] };
                affine_apply_point(&s->instances[i].world, q, v[k]);
            }
            double e1[3], e2[3], pv[3], sv[3], qv[3];
            for (int k = 0; k < 3; k++) {
                e1[k] = v[1][k] - v[0][k];
                e2[k] = v[2][k] - v[0][k];
                sv[k] = o[k] - v[0][k];
            }
            pv[0] = d[1] * e2[2] - d[2] * e2[1];
            pv[1] = d[2] * e2[0] - d[0] * e2[2];
            pv[2] = d[0] * e2[1] - d[1] * e2[0];
            const double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
            if (det == 0)
                continue;
            const double u = (sv[0] * pv[0] + sv[1] * pv[1] + sv[2] * pv[2]) / det;
            qv[0] = sv[1] * e1[2] - sv[2] * e1[1];
            qv[1] = sv[2] * e1[0] - sv[0] * e1[2];
            qv[2] = sv[0] * e1[1] - sv[1] * e1[0];
            const double w = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) / det;
            const double tt = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
            if (u >= 0 && w >= 0 && u + w <= 1 && tt >= 0 && tt < best)
                best = tt;
        }
    }
    return best;
}

/* The generated scene `name` evaluated at `time` and its memory image for a width x height camera
 * (asserts that both build). */
static uint32_t walked_with = TRAV_STACK; /* mi_params.traversal of the images built here */

static mi_builder *generated_image_with(const char *name, double time, uint32_t width, uint32_t height, uint32_t accel,
                                       scene *s)
{
    const scene_generator *g = scene_generator_find(name);
    assert_non_null(g);
    char err[256];
    const scene_gen_params gp = { 1, 0 };
    assert_int_equal(g->build(s, &gp, err, sizeof err), 0);
    assert_int_equal(scene_evaluate(s, time, 1), 0);
    mi_params p;
    mi_params_default(&p);
    p.width = width;
    p.height = height;
    p.accel = accel;
    p.traversal = walked_with;
    if (accel)
        p.memory_bytes = 64u << 20; /* every accelerator at once: more than the prototype's 24 MB */
    mi_builder *b = mi_build(s, &p, err, sizeof err);
    assert_non_null(b);
    return b;
}

static mi_builder *generated_image(const char *name, double time, uint32_t width, uint32_t height, scene *s)
{
    return generated_image_with(name, time, width, height, 0, s);
}

static void check_scene(const char *name, double time)
{
    enum { W = 64, H = 48 };
    scene s;
    char err[256];
    mi_builder *b = generated_image(name, time, W, H, &s);
    uint32_t n;
    const uint32_t *mem = mi_words(b, &n);
    assert_int_equal(mi_validate(mem, n, err, sizeof err), 0);
    const uint32_t *cam = mem + mem[MI_H_REGION_TABLE + 2 * MI_R_CAMERA];
    trace_counters c;
    memset(&c, 0, sizeof c);
    uint32_t rays = 0, hit_agree = 0, t_close = 0, both_hit = 0;
    for (uint32_t y = 0; y < H; y += 2) {
        for (uint32_t x = 0; x < W; x += 2) {
            ray_packet rp = { .active = 0xF };
            for (int i = 0; i < TRACE_PACKET; i++) {
                const double px = x + (i & 1) + 0.5, py = y + (i >> 1) + 0.5;
                for (int k = 0; k < 3; k++) {
                    const double dir = D(cam[13 + k]) + px * D(cam[7 + k]) + py * D(cam[10 + k]);
                    (&rp.d[i].x)[k] = F(dir);
                    (&rp.o[i].x)[k] = cam[4 + k];
                }
                rp.tmin[i] = 0;
                rp.tmax[i] = F24_POS_INF;
            }
            hit_record h[TRACE_PACKET];
            trace_packet(mem, &rp, h, &c);
            for (int i = 0; i < TRACE_PACKET; i++) {
                const double o[3] = { D(rp.o[i].x), D(rp.o[i].y), D(rp.o[i].z) };
                const double d[3] = { D(rp.d[i].x), D(rp.d[i].y), D(rp.d[i].z) };
                const double ref = brute_force(&s, o, d);
                const int unit_hit = h[i].instance != TRACE_NO_HIT;
                rays++;
                hit_agree += unit_hit == isfinite(ref);
                if (unit_hit && isfinite(ref)) {
                    both_hit++;
                    t_close += fabs(D(h[i].t) - ref) <= 1e-3 * ref;
                }
            }
        }
    }
    print_message("%s: %u rays, hit/miss agree %u, both hit %u, t within 1e-3: %u; steps %llu, leaves %llu, "
                  "list %llu, mailbox skips %llu, intersections %llu\n", name, rays, hit_agree, both_hit, t_close,
                  (unsigned long long)c.traversal_steps, (unsigned long long)c.leaves,
                  (unsigned long long)c.list_entries, (unsigned long long)c.mailbox_skips,
                  (unsigned long long)c.intersections);
    assert_true(hit_agree >= rays - rays / 200);      /* silhouettes and edges may differ */
    assert_true(both_hit > rays / 4);
    assert_true(t_close >= both_hit - both_hit / 100); /* a neighbouring surface at an edge */
    assert_true(c.intersections > 0);
    mi_free(b);
    scene_free(&s);
}

static void cornell(void **state) { (void)state; check_scene("cornell", 0); }
static void room(void **state) { (void)state; check_scene("room", 0); }
static void animated(void **state) { (void)state; check_scene("animated", 1.3); }

/* Axis-parallel rays (direction components +0 and -0) and a packet whose rays point in opposite
 * directions through the Cornell box: each ray must equal the same ray traced alone. */
static void zero_components_and_disagreeing_packets(void **state)
{
    (void)state;
    scene s;
    mi_builder *b = generated_image("cornell", 0, 512, 384, &s);
    uint32_t n;
    const uint32_t *mem = mi_words(b, &n);
    const uint32_t *bounds = mem + MI_H_SCENE_BOUNDS;
    double ctr[3];
    for (int k = 0; k < 3; k++)
        ctr[k] = 0.5 * (D(bounds[k]) + D(bounds[3 + k]));
    const f24_t dirs[6][3] = { { F24_ONE, 0, 0 }, { F24_ONE | F24_SIGN_BIT, F24_SIGN_BIT, 0 }, { 0, F24_ONE, F24_SIGN_BIT },
                               { F24_SIGN_BIT, F24_ONE | F24_SIGN_BIT, 0 }, { 0, 0, F24_ONE }, { F24_SIGN_BIT, 0, F24_ONE | F24_SIGN_BIT } };
    trace_counters c;
    memset(&c, 0, sizeof c);
    int hits = 0;
    for (int first = 0; first < 6; first += 2) {
        ray_packet rp = { .active = 0xF };
        for (int i = 0; i < TRACE_PACKET; i++) {
            const int k = (first + i) % 6;
            rp.o[i] = (f24_vec3){ F(ctr[0]), F(ctr[1]), F(ctr[2]) };
            rp.d[i] = (f24_vec3){ dirs[k][0], dirs[k][1], dirs[k][2] };
            rp.tmin[i] = 0;
            rp.tmax[i] = F24_POS_INF;
        }
        hit_record h[TRACE_PACKET];
        trace_packet(mem, &rp, h, &c);
        for (int i = 0; i < TRACE_PACKET; i++) {
            ray_packet one = rp;
            one.active = 1u << i;
            hit_record h1[TRACE_PACKET];
            trace_packet(mem, &one, h1, &c);
            assert_int_equal(h[i].instance, h1[i].instance);
            assert_int_equal(h[i].t, h1[i].t);
            const double o[3] = { D(rp.o[i].x), D(rp.o[i].y), D(rp.o[i].z) }, d[3] = { D(rp.d[i].x), D(rp.d[i].y), D(rp.d[i].z) };
            const double ref = brute_force(&s, o, d);
            assert_int_equal(h[i].instance != TRACE_NO_HIT, isfinite(ref)); /* the box is open at the front */
            if (isfinite(ref))
                assert_float_equal(D(h[i].t), ref, 1e-3 * ref);
            hits += isfinite(ref);
        }
    }
    assert_true(hits >= 8); /* most axis rays from the centre meet a wall or a block */
    mi_free(b);
    scene_free(&s);
}

/* Rays lying in the split planes of the top-level tree (origin on the plane, direction
 * component along the split axis +0 or -0) in the room scene: the traversal must send them to
 * both children or the correct one: their closest hits equal brute force over all triangles with
 * the same units, up to where each moved the ray's origin (1e-4 of the distance; brute force in
 * double may differ where such a ray grazes an edge that lies in the plane, within fp24
 * precision). */
static void rays_in_split_planes(void **state)
{
    (void)state;
    scene s;
    mi_builder *b = generated_image("room", 0, 512, 384, &s);
    uint32_t n;
    const uint32_t *mem = mi_words(b, &n);
    const uint32_t *nodes = mem + mem[MI_H_REGION_TABLE + 2 * MI_R_TOP_NODES], *bounds = mem + MI_H_SCENE_BOUNDS;
    trace_counters c;
    memset(&c, 0, sizeof c);
    unsigned seed = 3;
    uint32_t rays = 0, agree = 0, planes = 0;
    for (uint32_t k = 0, rep = 0; k < mem[MI_H_TOP_NODES]; k += rep == 7, rep = (rep + 1) % 8) {
        const uint32_t w0 = nodes[2 * k], axis = w0 & 3u;
        if (axis == 3)
            continue; /* a leaf */
        planes += rep == 0;
        ray_packet rp = { .active = 0xF };
        for (int i = 0; i < TRACE_PACKET; i++) {
            double o[3], d[3];
            for (uint32_t j = 0; j < 3; j++) {
                const double lo = D(bounds[j]), hi = D(bounds[3 + j]), r = (double)rand_r(&seed) / RAND_MAX;
                o[j] = j == axis ? D(nodes[2 * k + 1]) : lo + (0.1 + 0.8 * r) * (hi - lo);
                d[j] = j == axis ? 0 : 2.0 * rand_r(&seed) / RAND_MAX - 1;
            }
            rp.o[i] = (f24_vec3){ F(o[0]), F(o[1]), F(o[2]) };
            rp.d[i] = (f24_vec3){ F(d[0]), F(d[1]), F(d[2]) };
            if (i & 1) /* -0 along the axis for half of the rays */
                (&rp.d[i].x)[axis] = F24_SIGN_BIT;
            rp.tmin[i] = 0;
            rp.tmax[i] = F24_POS_INF;
        }
        hit_record h[TRACE_PACKET];
        trace_packet(mem, &rp, h, &c);
        for (int i = 0; i < TRACE_PACKET; i++) {
            const f24_t ref = ref_units_closest(mem, rp.o[i], rp.d[i], 0, F24_POS_INF, NULL);
            rays++;
            /* the same distance up to the rounding of where each moved the origin (ref_units.h) */
            agree += h[i].instance == TRACE_NO_HIT ? ref == F24_POS_INF : fabs(D(h[i].t) - D(ref)) <= 1e-4 * D(ref);
        }
    }
    print_message("split planes: %u planes, %u rays, %u agree with brute force\n", planes, rays, agree);
    assert_true(planes >= 5);
    assert_int_equal(agree, rays);
    mi_free(b);
    scene_free(&s);
}

/* One packet with the given TRACE_* flags, step by step as trace_packet runs it; the number of
 * operations it took (TRACE_STEP_LIMIT would mean a walk that never ends). */
static uint32_t trace_with(const uint32_t *mem, const ray_packet *rp, uint32_t flags, hit_record h[], trace_counters *c)
{
    trace_state st;
    unit_op op;
    uint32_t n = 0;
    trace_begin(rp, flags, &st);
    while (n < TRACE_STEP_LIMIT && trace_step(mem, &st, &op, c))
        n++;
    memcpy(h, st.hits, sizeof st.hits);
    return n;
}

/* The traversal algorithms (short stack, kd-restart, push-down, ropes, grids) find the stack's
 * surfaces on the primary rays of scenes with deep trees and overlapping instances (hits may
 * differ by ulps where a triangle's rounded distance lies just outside its cell, which the walk
 * order decides), every walk ends, the stackless ones take more traversal steps and the ropes
 * fewer; the accelerators in the image change none of the stack's bits. */
static void traversal_algorithms_agree(void **state)
{
    (void)state;
    static const char *const names[] = { "room", "terrain", "cornell" }; /* cornell: one object, no top level */
    walked_with = TRAV_RESTART; /* the trees every walker can walk (mi_compact_trees) */
    for (size_t sc = 0; sc < 3; sc++) {
        enum { W = 96, H = 72 };
        scene s, s_plain;
        char err[256];
        mi_builder *b = generated_image_with(names[sc], 0, W, H, MI_ACCEL_ALL, &s);
        mi_builder *plain = generated_image(names[sc], 0, W, H, &s_plain);
        uint32_t nw, np;
        const uint32_t *mem = mi_words(b, &nw), *mem_plain = mi_words(plain, &np);
        assert_int_equal(mi_validate(mem, nw, err, sizeof err), 0);
        trace_counters c[TRAV_KINDS], c_plain;
        memset(c, 0, sizeof c);
        memset(&c_plain, 0, sizeof c_plain);
        uint32_t differ = 0, ulps = 0, longest = 0, plain_differ = 0;
        const uint32_t profile = trace_flags_of(trace_profile(mem), 0);
        for (uint32_t y = 0; y < H; y += 2)
            for (uint32_t x = 0; x < W; x += 2) {
                ray_packet rp;
                rgs_primary(mem, x, y, &rp);
                hit_record ref[TRACE_PACKET], h[TRACE_PACKET];
                trace_with(mem, &rp, profile | TRAV_STACK << TRACE_TRAV_SHIFT, ref, &c[TRAV_STACK]);
                trace_with(mem_plain, &rp, profile | TRAV_STACK << TRACE_TRAV_SHIFT, h, &c_plain);
                plain_differ += memcmp(h, ref, sizeof h) != 0;
                for (uint32_t a = TRAV_SHORT_STACK; a < TRAV_KINDS; a++) {
                    const uint32_t n = trace_with(mem, &rp, profile | a << TRACE_TRAV_SHIFT, h, &c[a]);
                    longest = n > longest ? n : longest;
                    for (int i = 0; i < TRACE_PACKET; i++) {
                        /* a surface lost or found: the distances differ beyond rounding */
                        const double t = D(h[i].t), tr = D(ref[i].t);
                        differ += (h[i].instance == TRACE_NO_HIT) != (ref[i].instance == TRACE_NO_HIT) ||
                                  fabs(t - tr) > 1e-4 * tr || (h[i].t == ref[i].t && h[i].instance != ref[i].instance);
                        ulps += h[i].t != ref[i].t;
                    }
                }
            }
        print_message("%s: traversal steps / leaves or cells: stack %llu/%llu, short stack %llu/%llu, restart %llu/%llu, "
                      "push-down %llu/%llu, ropes %llu/%llu, grid %llu/%llu, grid2 %llu/%llu; longest walk %u operations; "
                      "%u surfaces lost or found, %u hits a few ulps apart\n", names[sc],
                      (unsigned long long)c[0].traversal_steps, (unsigned long long)c[0].leaves,
                      (unsigned long long)c[1].traversal_steps, (unsigned long long)c[1].leaves,
                      (unsigned long long)c[2].traversal_steps, (unsigned long long)c[2].leaves,
                      (unsigned long long)c[3].traversal_steps, (unsigned long long)c[3].leaves,
                      (unsigned long long)c[4].traversal_steps, (unsigned long long)c[4].leaves,
                      (unsigned long long)c[5].traversal_steps, (unsigned long long)c[5].leaves,
                      (unsigned long long)c[6].traversal_steps, (unsigned long long)c[6].leaves, longest, differ, ulps);
        assert_int_equal(plain_differ, 0);
        assert_int_equal(c_plain.traversal_steps, c[TRAV_STACK].traversal_steps);
        assert_int_equal(differ, 0);
        assert_true(longest < 100000);
        assert_int_equal(c[TRAV_GRID2].traversal_steps, 0); /* no kd-tree left to walk */
        if (sc < 2) { /* trees deep enough to tell the algorithms apart */
            assert_true(c[TRAV_RESTART].traversal_steps > c[TRAV_STACK].traversal_steps);
            assert_true(c[TRAV_PUSH_DOWN].traversal_steps <= c[TRAV_RESTART].traversal_steps);
            assert_true(c[TRAV_ROPES].traversal_steps < c[TRAV_STACK].traversal_steps);
        }
        mi_free(b);
        mi_free(plain);
        scene_free(&s);
        scene_free(&s_plain);
    }
    walked_with = TRAV_STACK;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(traversal_algorithms_agree),
        cmocka_unit_test(cornell), cmocka_unit_test(room), cmocka_unit_test(animated),
        cmocka_unit_test(zero_components_and_disagreeing_packets), cmocka_unit_test(rays_in_split_planes),
    };
    return cmocka_run_group_tests_name("trace", tests, NULL, NULL);
}
