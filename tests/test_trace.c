/*
 * Tests of the functional ray tracing core (hls/units/trace): primary rays of generated scenes
 * (two-level trees, instancing with scale and rotation, a morphing object in the dynamic region)
 * traced through the memory image with fp24 units, against brute force in double precision over
 * every instanced triangle of the scene: hit/miss agreement and the distance to the closest hit.
 * Also: rays with zero direction components and rays that disagree within a packet.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "f24_fast.h"
#include "memimage.h"
#include "scene.h"
#include "scenes.h"
#include "trace.h"

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

static void check_scene(const char *name, double time)
{
    const scene_generator *g = scene_generator_find(name);
    assert_non_null(g);
    scene s;
    char err[256];
    const scene_gen_params gp = { 1, 0 };
    assert_int_equal(g->build(&s, &gp, err, sizeof err), 0);
    assert_int_equal(scene_evaluate(&s, time, 1), 0);
    mi_params p;
    mi_params_default(&p);
    p.width = 64;
    p.height = 48;
    mi_builder *b = mi_build(&s, &p, err, sizeof err);
    assert_non_null(b);
    uint32_t n;
    const uint32_t *mem = mi_words(b, &n);
    assert_int_equal(mi_validate(mem, n, err, sizeof err), 0);
    const uint32_t *cam = mem + mem[MI_H_REGION_TABLE + 2 * MI_R_CAMERA];
    trace_counters c;
    memset(&c, 0, sizeof c);
    uint32_t rays = 0, hit_agree = 0, t_close = 0, both_hit = 0;
    for (uint32_t y = 0; y < p.height; y += 2) {
        for (uint32_t x = 0; x < p.width; x += 2) {
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
    const scene_generator *g = scene_generator_find("cornell");
    scene s;
    char err[256];
    const scene_gen_params gp = { 1, 0 };
    assert_int_equal(g->build(&s, &gp, err, sizeof err), 0);
    assert_int_equal(scene_evaluate(&s, 0, 0), 0);
    mi_params p;
    mi_params_default(&p);
    mi_builder *b = mi_build(&s, &p, err, sizeof err);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cornell), cmocka_unit_test(room), cmocka_unit_test(animated),
        cmocka_unit_test(zero_components_and_disagreeing_packets),
    };
    return cmocka_run_group_tests_name("trace", tests, NULL, NULL);
}
