/*
 * Tests of the transformation unit (hls/units/xform_unit): exact cases, the translation only on
 * points, the fixed summation order (bit-exact against a step-by-step evaluation), loading from
 * the memory image, and the error bound against double precision on random inputs.
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
#include "rebase_unit.h"
#include "xform_unit.h"

static f24_t F(double x) { return f24_fast_encode(x); }
static double D(f24_t x) { return f24_fast_decode(x); }

static uint64_t rng = 88172645463325252ull;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

static f24_affine affine_of(const double m[3][4])
{
    f24_affine a;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            a.m[i][j] = F(m[i][j]);
    return a;
}

static void exact_cases(void **state)
{
    (void)state;
    const double m[3][4] = { { 2, 0, 0, 1 }, { 0, 0.5, 0, -2 }, { 0, 0, -4, 0.25 } };
    const f24_affine a = affine_of(m);
    const f24_vec3 p = { F(3), F(8), F(0.5) };
    const f24_vec3 q = xform_point(&a, p), v = xform_vector(&a, p);
    assert_int_equal(q.x, F(7));
    assert_int_equal(q.y, F(2));
    assert_int_equal(q.z, F(-1.75));
    assert_int_equal(v.x, F(6)); /* no translation for directions */
    assert_int_equal(v.y, F(4));
    assert_int_equal(v.z, F(-2));
}

/* The unit's result equals ((m0 x + m1 y) + m2 z) + t with each operation rounded, bit for bit. */
static void summation_order(void **state)
{
    (void)state;
    for (int n = 0; n < 20000; n++) {
        double m[3][4];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 4; j++)
                m[i][j] = (urand() - 0.5) * pow(2.0, 20 * urand() - 10);
        const f24_affine a = affine_of(m);
        const f24_vec3 p = { F(urand() - 0.5), F(1000 * (urand() - 0.5)), F(1e-3 * (urand() - 0.5)) };
        const f24_vec3 q = xform_point(&a, p);
        const f24_t in[3] = { p.x, p.y, p.z }, out[3] = { q.x, q.y, q.z };
        for (int i = 0; i < 3; i++) {
            f24_t s = f24_fast_mul(a.m[i][0], in[0]);
            s = f24_fast_add(s, f24_fast_mul(a.m[i][1], in[1]));
            s = f24_fast_add(s, f24_fast_mul(a.m[i][2], in[2]));
            s = f24_fast_add(s, a.m[i][3]);
            assert_int_equal(out[i], s);
            /* and the error against exact arithmetic on the fp24 inputs is within gamma_4 */
            double exact = D(a.m[i][3]), mag = fabs(D(a.m[i][3]));
            for (int k = 0; k < 3; k++) {
                exact += D(a.m[i][k]) * D(in[k]);
                mag += fabs(D(a.m[i][k]) * D(in[k]));
            }
            const double u = ldexp(1.0, -(F24_MAN_BITS + 1));
            assert_true(fabs(D(out[i]) - exact) <= 4.5 * u * mag);
        }
    }
}

static void load_from_image(void **state)
{
    (void)state;
    uint32_t mem[20] = { 0 };
    for (int k = 0; k < 12; k++)
        mem[5 + k] = F(k + 1) | 0xFF000000u; /* bits above the format are ignored */
    const f24_affine a = f24_affine_load(mem, 5);
    assert_int_equal(a.m[0][0], F(1));
    assert_int_equal(a.m[2][3], F(12));
    const f24_vec3 o = { 0, 0, 0 };
    const f24_vec3 t = xform_point(&a, o);
    assert_int_equal(t.x, F(4));
    assert_int_equal(t.y, F(8));
    assert_int_equal(t.z, F(12));
}

/* xform_identity gives xform_point/xform_vector's bits for identities with signed zeros, on
 * vectors of edge values (signed zeros, subnormals, Inf, NaN, extremes) and random values. */
static void identity_shortcut(void **state)
{
    (void)state;
    const f24_t edge[] = { 0, F24_SIGN_BIT, 1, F24_SIGN_BIT | 1, F24_MIN_NORMAL, F24_ONE, F24_ONE | F24_SIGN_BIT,
                           F24_MAX_NORMAL, F24_POS_INF, F24_POS_INF | F24_SIGN_BIT, F24_DEFAULT_NAN, F(-3.25), F(1e-3) };
    const int n_edge = sizeof edge / sizeof *edge;
    uint64_t checked = 0;
    for (uint32_t signs = 0; signs < 4096; signs += 37) { /* sign patterns of the 9 zeros (+1 walks them) */
        f24_affine m;
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 4; c++) {
                const uint32_t bit = (uint32_t)(4 * r + c);
                m.m[r][c] = r == c ? F24_ONE : (signs >> bit & 1u ? F24_SIGN_BIT : (bit & 1u) ? 1u : 0u);
            }
        assert_true(xform_is_identity(&m));
        for (int a = 0; a < n_edge; a++)
            for (int b = 0; b < n_edge; b++)
                for (int c = 0; c < n_edge; c++) {
                    const f24_vec3 v = { edge[a], edge[b], edge[(c + (int)signs) % n_edge] };
                    for (int point = 0; point < 2; point++) {
                        const f24_vec3 want = point ? xform_point(&m, v) : xform_vector(&m, v);
                        const f24_vec3 got = xform_identity(&m, v, point);
                        assert_int_equal(got.x, want.x);
                        assert_int_equal(got.y, want.y);
                        assert_int_equal(got.z, want.z);
                        checked++;
                    }
                }
        for (int i = 0; i < 200; i++) {
            const f24_vec3 v = { F(urand() - 0.5), F(urand() < 0.2 ? 0.0 : -urand()), F(1e3 * (urand() - 0.5)) };
            const f24_vec3 got = xform_identity(&m, v, i & 1), want = i & 1 ? xform_point(&m, v) : xform_vector(&m, v);
            assert_memory_equal(&got, &want, sizeof got);
        }
    }
    f24_affine not_id = { { { F24_ONE, 0, 0, 0 }, { 0, F24_ONE, 0, 0 }, { 0, 0, F(0.5), 0 } } };
    assert_false(xform_is_identity(&not_id));
    not_id.m[2][2] = F24_ONE;
    not_id.m[1][3] = F(1e-3);
    assert_false(xform_is_identity(&not_id));
    print_message("identity shortcut: %llu edge vectors equal\n", (unsigned long long)checked);
}

/* A word of every kind the wide mode meets: raw bits (subnormal encodings, Inf, NaN included),
 * signed zeros and Infs, unit-size values, and values 2^-17 .. 2^-40 of unit size (low words,
 * terms that cancel or lie far apart, which the exact sums decide on their slow paths). */
static f24_t wide_word(unsigned *seed)
{
    const int kind = rand_r(seed) % 8;
    if (kind == 0)
        return (f24_t)rand_r(seed) & F24_MASK;
    if (kind == 1) {
        const f24_t special[5] = { 0, F24_SIGN_BIT, F24_POS_INF, F24_POS_INF | F24_SIGN_BIT, F24_DEFAULT_NAN };
        return special[rand_r(seed) % 5];
    }
    const double x = 4.0 * rand_r(seed) / RAND_MAX - 2;
    return F(kind == 2 ? ldexp(x, -17 - rand_r(seed) % 24) : kind == 3 ? 1.0 + ldexp(x, -16) : x);
}

static f24_vec3 wide_vec(unsigned *seed)
{
    const f24_t x = wide_word(seed), y = wide_word(seed);
    return (f24_vec3){ x, y, wide_word(seed) };
}

#ifdef F24_SIM_LANES
/* The simulation build's xform_enter_rays and rebase_rays compute the rays of a packet side by
 * side (tb/sim/wide_lanes.c): the same words as the per-ray datapath of hls/units (the truth) for
 * every ray of the mask, the other rays' outputs untouched, on random matrices and rays with
 * special words, low words and cancelling terms. */
static void enter_rays_lanes(void **state)
{
    (void)state;
    unsigned seed = 19;
    for (int t = 0; t < 20000; t++) {
        f24_affine m;
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 4; c++)
                m.m[r][c] = t & 1 ? F(urand() * 2 - 1) : wide_word(&seed); /* half of them without specials */
        const f24_vec3 t_lo = wide_vec(&seed);
        f24_vec3 o[F24Q_LANES], d[F24Q_LANES];
        f24_t tn[F24Q_LANES];
        for (int i = 0; i < F24Q_LANES; i++) {
            o[i] = wide_vec(&seed);
            d[i] = wide_vec(&seed);
            tn[i] = wide_word(&seed);
        }
        const uint32_t rays = (uint32_t)rand_r(&seed) & 0xFu;
        struct { f24_vec3 oh[F24Q_LANES], ol[F24Q_LANES], dh[F24Q_LANES], dl[F24Q_LANES]; f24_t t0[F24Q_LANES]; } got, want;
        memset(&got, 0x55, sizeof got);
        memset(&want, 0x55, sizeof want);
        xform_enter_rays(&m, t_lo, rays, o, d, tn, got.oh, got.ol, got.dh, got.dl, got.t0);
        xform_enter_rays_per_ray(&m, t_lo, rays, o, d, tn, want.oh, want.ol, want.dh, want.dl, want.t0);
        assert_memory_equal(&got, &want, sizeof got);
    }
}

static void rebase_rays_lanes(void **state)
{
    (void)state;
    unsigned seed = 23;
    for (int t = 0; t < 20000; t++) {
        f24_vec3 o[F24Q_LANES], ol[F24Q_LANES], d[F24Q_LANES], dl[F24Q_LANES];
        f24_t tn[F24Q_LANES];
        for (int i = 0; i < F24Q_LANES; i++) {
            o[i] = wide_vec(&seed);
            ol[i] = wide_vec(&seed);
            d[i] = wide_vec(&seed);
            dl[i] = wide_vec(&seed);
            tn[i] = wide_word(&seed);
        }
        const uint32_t rays = (uint32_t)rand_r(&seed) & 0xFu;
        struct { f24_vec3x2 p[F24Q_LANES]; f24_t te[F24Q_LANES]; } got, want;
        memset(&got, 0x55, sizeof got);
        memset(&want, 0x55, sizeof want);
        rebase_rays(rays, o, ol, d, dl, tn, got.p, got.te);
        rebase_rays_per_ray(rays, o, ol, d, dl, tn, want.p, want.te);
        assert_memory_equal(&got, &want, sizeof got);
    }
}
#else
static void enter_rays_lanes(void **state)
{
    (void)state;
    skip(); /* one definition only: the per-ray one */
}

static void rebase_rays_lanes(void **state)
{
    (void)state;
    skip();
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(exact_cases), cmocka_unit_test(summation_order), cmocka_unit_test(load_from_image),
        cmocka_unit_test(identity_shortcut), cmocka_unit_test(enter_rays_lanes), cmocka_unit_test(rebase_rays_lanes),
    };
    return cmocka_run_group_tests_name("xform_unit", tests, NULL, NULL);
}
