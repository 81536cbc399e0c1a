/*
 * Tests of the unit-triangle intersection unit (hls/units/isect_unit): hand-computed hits,
 * edges and vertices, parallel rays, the t interval, an origin on the plane; and end to end in
 * fp24 (triangle transformation from the host, transformation unit, intersection unit) against
 * a double-precision Moller-Trumbore test on random well-shaped triangles and non-grazing rays:
 * the hit decisions agree except close to edges, and t agrees to fp24 accuracy; and small
 * triangles seen from far away, with the origin rebased as at a leaf (rebase_unit).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "f24_fast.h"
#include "isect_unit.h"
#include "memimage.h"
#include "rebase_unit.h"
#include "scene.h"
#include "scenes.h"
#include "xform_unit.h"

#ifndef F24_SIM_LANES /* builds without the binary64 proof of misses: the packet function is the exact one */
#define isect_unit_packet_exact isect_unit_packet
#endif

static f24_t F(double x) { return f24_fast_encode(x); }
static double D(f24_t x) { return f24_fast_decode(x); }
static f24_vec3 V(double x, double y, double z) { return (f24_vec3){ F(x), F(y), F(z) }; }

static uint64_t rng = 0x2545F4914F6CDD1Dull;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

static isect_result shoot_flags(f24_vec3 o, f24_vec3 d, uint32_t shared)
{
    return isect_unit_triangle(o, d, 0, F(0), F24_POS_INF, shared);
}
static isect_result shoot(f24_vec3 o, f24_vec3 d) { return shoot_flags(o, d, 0); }

static void hand_cases(void **state)
{
    (void)state;
    const f24_vec3 down = V(0, 0, -1);
    isect_result r = shoot(V(0.25, 0.5, 2), down);
    assert_true(r.hit);
    assert_int_equal(r.t, F(2));
    assert_int_equal(r.u, F(0.25));
    assert_int_equal(r.v, F(0.5));
    assert_int_equal(r.cos_n, F(-1));
    assert_true(shoot(V(0.5, 0, 1), down).hit);      /* on edge v = 0 */
    assert_true(shoot(V(0.5, 0.5, 1), down).hit);    /* on edge u + v = 1 */
    assert_true(shoot(V(0, 0, 1), down).hit);        /* vertex C */
    assert_true(shoot(V(1, 0, 1), down).hit);        /* vertex A */
    assert_false(shoot(V(0.6, 0.6, 1), down).hit);   /* u + v > 1 */
    assert_false(shoot(V(-0.01, 0.5, 1), down).hit); /* u < 0 */
    assert_false(shoot(V(0.2, 0.2, -1), down).hit);  /* behind the origin: t < 0 */
    /* oblique ray from below */
    r = shoot(V(0, 0, -1), V(0.25, 0.25, 1));
    assert_true(r.hit);
    assert_int_equal(r.t, F(1));
    assert_int_equal(r.u, F(0.25));
}

static void parallel_and_interval(void **state)
{
    (void)state;
    /* parallel to the plane: t = -1/0 = -Inf, or 0/0 = NaN in the plane: never a hit */
    isect_result r = shoot(V(0.2, 0.2, 1), V(1, 0, 0));
    assert_false(r.hit);
    r = shoot(V(0.2, 0.2, 0), V(1, 0, 0));
    assert_false(r.hit);
    assert_true(f24_is_nan(r.t));
    /* the interval is [tmin, tmax) */
    const f24_vec3 o = V(0.25, 0.25, 3), d = V(0, 0, -1);
    assert_false(isect_unit_triangle(o, d, 0, F(0), F(3), 0).hit);
    assert_true(isect_unit_triangle(o, d, 0, F(3), F(4), 0).hit);
    assert_false(isect_unit_triangle(o, d, 0, F(3.01), F(4), 0).hit);
    /* origin on the plane: t = +-0, a hit only if tmin <= 0 (secondary rays start at tmin > 0) */
    r = isect_unit_triangle(V(0.25, 0.25, 0), d, 0, F(0), F24_POS_INF, 0);
    assert_true(r.hit && f24_is_zero(r.t));
    assert_false(isect_unit_triangle(V(0.25, 0.25, 0), d, 0, F(1e-4), F24_POS_INF, 0).hit);
}

/* Only a flagged bound is widened, by one ulp at 1 (2^-M, SAARCOR_CFG_SHARED_EDGE_EPS default):
 * a ray an ulp outside an edge hits when that edge is shared, and misses beyond the margin or
 * when another edge is flagged. */
static void shared_edges(void **state)
{
    (void)state;
    const f24_vec3 down = V(0, 0, -1);
    const double ulp = ldexp(1.0, -F24_MAN_BITS);
    assert_false(shoot(V(-ulp, 0.5, 1), down).hit);
    assert_true(shoot_flags(V(-ulp, 0.5, 1), down, TRI_SHARED_U).hit);
    assert_false(shoot_flags(V(-ulp, 0.5, 1), down, TRI_SHARED_V | TRI_SHARED_W).hit);
    assert_false(shoot_flags(V(-2 * ulp, 0.5, 1), down, TRI_SHARED_U).hit);
    assert_false(shoot(V(0.5, -ulp, 1), down).hit);
    assert_true(shoot_flags(V(0.5, -ulp, 1), down, TRI_SHARED_V).hit);
    assert_false(shoot_flags(V(0.5, -ulp, 1), down, TRI_SHARED_U | TRI_SHARED_W).hit);
    /* u + v = 1 + 2^-M, the next value above 1 */
    assert_false(shoot(V(0.5, 0.5 + ulp, 1), down).hit);
    assert_true(shoot_flags(V(0.5, 0.5 + ulp, 1), down, TRI_SHARED_W).hit);
    assert_false(shoot_flags(V(0.5, 0.5 + ulp, 1), down, TRI_SHARED_U | TRI_SHARED_V).hit);
    assert_false(shoot_flags(V(0.5, 0.5 + 2 * ulp, 1), down, TRI_SHARED_W).hit);
}

/* Moller-Trumbore in double: returns 1 and t, (u, v) weights of a and b, edge distance margin. */
static int mt_uv(const double o[3], const double d[3], const double a[3], const double b[3], const double c[3],
                 double *t, double *uu, double *vv, double *margin)
{
    double e1[3], e2[3], p[3], s[3], q[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = a[k] - c[k];
        e2[k] = b[k] - c[k];
        s[k] = o[k] - c[k];
    }
    p[0] = d[1] * e2[2] - d[2] * e2[1];
    p[1] = d[2] * e2[0] - d[0] * e2[2];
    p[2] = d[0] * e2[1] - d[1] * e2[0];
    const double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (det == 0)
        return 0;
    const double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    const double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
    *t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    *margin = fmin(fmin(fabs(u), fabs(v)), fabs(1 - u - v));
    *uu = u;
    *vv = v;
    return u >= 0 && v >= 0 && u + v <= 1 && *t >= 0;
}

static int mt(const double o[3], const double d[3], const double a[3], const double b[3], const double c[3],
              double *t, double *margin)
{
    double u, v;
    return mt_uv(o, d, a, b, c, t, &u, &v, margin);
}

/* The record the host writes for a triangle transformation: M^-1 rounded, C in two words. */
static f24_triangle record_of(const affine *tx)
{
    f24_triangle t;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            t.m.m[i][j] = F(tx->m[i][j]);
    t.c_lo = V(tx->m[0][3] - D(t.m.m[0][3]), tx->m[1][3] - D(t.m.m[1][3]), tx->m[2][3] - D(t.m.m[2][3]));
    t.shared = 0;
    return t;
}

/* The origin o moved to distance te along d, as the rebase unit moves it at a leaf. */
static f24_vec3x2 rebased(f24_vec3 o, f24_vec3 d, f24_t te)
{
    const f24_vec3 zero = { 0, 0, 0 };
    return rebase_origin((f24_vec3x2){ o, zero }, (f24_vec3x2){ d, zero }, te);
}

static void against_double_precision(void **state)
{
    (void)state;
    int tested = 0, agree = 0, far_disagree = 0;
    double worst_t = 0;
    for (int n = 0; n < 20000; n++) {
        double a[3], b[3], c[3], o[3], d[3], target[3];
        for (int k = 0; k < 3; k++) {
            a[k] = 10 * urand() - 5;
            b[k] = 10 * urand() - 5;
            c[k] = 10 * urand() - 5;
            o[k] = 40 * urand() - 20;
        }
        const double w0 = 1.2 * urand() - 0.1, w1 = (1.2 - w0) * urand() - 0.05; /* aim near the triangle */
        for (int k = 0; k < 3; k++) {
            target[k] = w0 * a[k] + w1 * b[k] + (1 - w0 - w1) * c[k];
            d[k] = target[k] - o[k];
        }
        affine tx;
        if (!mi_triangle_transform(a, b, c, 64, &tx)) /* well-shaped: slivers are the stress suite's job */
            continue;
        /* grazing rays (|cos| < 0.1 with the normal) amplify every rounding by 1/|cos|: also the
         * stress suite's job; here the angle is bounded so that a fixed tolerance is meaningful */
        const double e1[3] = { a[0] - c[0], a[1] - c[1], a[2] - c[2] }, e2[3] = { b[0] - c[0], b[1] - c[1], b[2] - c[2] };
        const double nn[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0] };
        const double cosang = (nn[0] * d[0] + nn[1] * d[1] + nn[2] * d[2]) /
                              (sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]) * sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
        if (fabs(cosang) < 0.1)
            continue;
        const f24_triangle t24 = record_of(&tx);
        const f24_vec3 o24 = V(o[0], o[1], o[2]), d24 = V(d[0], d[1], d[2]);
        const isect_result r = isect_unit_rebased(&t24, rebased(o24, d24, F(0.9)), F(0.9), d24, F(0), F24_POS_INF);
        /* reference on the fp24-rounded ray, so that only the units' arithmetic differs */
        const double ro[3] = { D(o24.x), D(o24.y), D(o24.z) }, rd[3] = { D(d24.x), D(d24.y), D(d24.z) };
        double t = 0, margin = 0;
        const int ref = mt(ro, rd, a, b, c, &t, &margin);
        tested++;
        if (ref == r.hit) {
            agree++;
            if (ref)
                worst_t = fmax(worst_t, fabs(D(r.t) - t) / t);
        } else if (margin > 1e-3) {
            far_disagree++;
        }
    }
    print_message("isect: %d rays, %d agree (%.3f%%), %d disagreements farther than 1e-3 from an edge, "
                  "worst relative t error %.2e\n", tested, agree, 100.0 * agree / tested, far_disagree, worst_t);
    assert_true(tested > 15000);
    assert_int_equal(far_disagree, 0);
    assert_true(worst_t < 1e-3);
    assert_true(agree > tested * 0.99);
}

/* Triangles of size 2^-10 seen from 2^4 away (a ratio of 2^14: unrebased, u = O'x + t D'x would
 * cancel 14 of fp24's 17 bits): with the origin moved to the last fp24 distance before the
 * triangle, as the traversal's leaf entry moves it, the barycentrics stay within 1e-3 of the exact
 * ones on the same fp24 ray, and the distance within 1e-4; from the unmoved origin they do not. */
static void small_and_far(void **state)
{
    (void)state;
    double worst = 0, worst_unmoved = 0;
    int hits = 0;
    for (int n = 0; n < 5000; n++) {
        const double s = 0x1p-10, far = 0x1p4;
        double a[3], b[3], c[3], o[3], d[3];
        for (int k = 0; k < 3; k++) {
            c[k] = 1 + urand();
            a[k] = c[k] + s * (urand() - 0.5);
            b[k] = c[k] + s * (urand() - 0.5);
        }
        a[0] += s;
        b[1] += s;
        const double w0 = 0.9 * urand() + 0.05, w1 = (0.95 - w0) * urand() + 0.025;
        for (int k = 0; k < 3; k++) {
            const double target = w0 * a[k] + w1 * b[k] + (1 - w0 - w1) * c[k];
            d[k] = urand() - 0.5 + (k == 2);
            o[k] = target - far * d[k];
        }
        affine tx;
        if (!mi_triangle_transform(a, b, c, 16, &tx))
            continue;
        const f24_triangle t24 = record_of(&tx);
        const f24_vec3 o24 = V(o[0], o[1], o[2]), d24 = V(d[0], d[1], d[2]);
        const f24_t te = F(far) - 1u; /* the fp24 number before 16 */
        const isect_result r = isect_unit_rebased(&t24, rebased(o24, d24, te), te, d24, F(0), F24_POS_INF);
        const isect_result r0 = isect_unit_rebased(&t24, rebased(o24, d24, 0), 0, d24, F(0), F24_POS_INF);
        const double ro[3] = { D(o24.x), D(o24.y), D(o24.z) }, rd[3] = { D(d24.x), D(d24.y), D(d24.z) };
        double t = 0, margin = 0, u, v;
        if (!mt_uv(ro, rd, a, b, c, &t, &u, &v, &margin) || margin < 1e-3)
            continue;
        assert_true(r.hit);
        hits++;
        worst = fmax(worst, fmax(fabs(D(r.u) - u), fabs(D(r.v) - v)));
        worst_unmoved = fmax(worst_unmoved, fmax(fabs(D(r0.u) - u), fabs(D(r0.v) - v)));
        assert_true(fabs(D(r.t) - t) <= 1e-4 * t);
    }
    print_message("small and far: %d hits, worst barycentric error %.2e rebased, %.2e from the origin\n", hits, worst,
                  worst_unmoved);
    assert_true(hits > 3000);
    assert_true(worst < 1e-3);
    assert_true(worst_unmoved > 1e-2);
}

/* isect_unit_packet against isect_unit_rebased ray by ray: random triangles (shared-edge flags
 * included) and packets of rays aimed near them or at their edges from rebased origins, intervals
 * that hold, cut or miss the hit distance (NaN too), now and then a ray parallel to the plane or
 * a zero direction; every
 * mask of rays that need the triangle. Each needed lane of the exact packet function bit for bit
 * the one-ray result, the others zeros; the simulation build's isect_unit_packet (binary64 proof of
 * misses first) the same hit flags and hits. */
static void packet_as_single(void **state)
{
    (void)state;
    int bad = 0, lanes = 0, hits = 0, outside = 0;
    for (int n = 0; n < 20000 && bad < 5; n++) {
        double a[3], b[3], c[3];
        for (int k = 0; k < 3; k++) {
            a[k] = 10 * urand() - 5;
            b[k] = 10 * urand() - 5;
            c[k] = 10 * urand() - 5;
        }
        affine tx;
        if (!mi_triangle_transform(a, b, c, 64, &tx))
            continue;
        f24_triangle t24 = record_of(&tx);
        t24.shared = (uint32_t)(urand() * 8) & (TRI_SHARED_U | TRI_SHARED_V | TRI_SHARED_W);
        f24_vec3x2 p[F24Q_LANES];
        f24_vec3 d[F24Q_LANES];
        f24_t te[F24Q_LANES], tmin[F24Q_LANES], tmax[F24Q_LANES];
        for (int i = 0; i < F24Q_LANES; i++) {
            double o[3], dd[3];
            const int kind = (int)(urand() * 16);
            double w0 = 1.2 * urand() - 0.1, w1 = (1.2 - w0) * urand() - 0.05;
            if (kind >= 2 && kind <= 7) /* at an edge (u = 0, v = 0, u + v = 1), where the margins decide */
                w0 = kind % 3 == 0 ? 0 : w0, w1 = kind % 3 == 1 ? 0 : kind % 3 == 2 ? 1 - w0 : w1;
            for (int k = 0; k < 3; k++) {
                o[k] = 40 * urand() - 20;
                dd[k] = w0 * a[k] + w1 * b[k] + (1 - w0 - w1) * c[k] - o[k];
            }
            d[i] = kind == 0 ? V(0, 0, 0) : V(dd[0], dd[1], dd[2]);
            if (kind == 1) /* parallel to the plane: D'z = 0 up to rounding */
                d[i] = V(a[0] - c[0], a[1] - c[1], a[2] - c[2]);
            te[i] = F(urand() < 0.5 ? 0 : 0.9 * urand());
            p[i] = rebased(V(o[0], o[1], o[2]), d[i], te[i]);
            const double t = urand() * 1.5;
            tmin[i] = F(urand() < 0.7 ? 0 : t - 0.5);
            tmax[i] = urand() < 0.5 ? F24_POS_INF : urand() < 0.05 ? F24_DEFAULT_NAN : F(t);
        }
        const uint32_t need = (uint32_t)n % 16u;
        isect_result r[F24Q_LANES], fast[F24Q_LANES];
        isect_unit_packet_exact(&t24, need, p, te, d, tmin, tmax, r);
        isect_unit_packet(&t24, need, p, te, d, tmin, tmax, fast);
        for (int i = 0; i < F24Q_LANES; i++) {
            if (fast[i].hit != r[i].hit || (r[i].hit && memcmp(&fast[i], &r[i], sizeof r[i]) != 0)) {
                print_message("packet %d lane %d: the proving packet function differs on a hit flag or a hit\n", n, i);
                bad++;
            }
            const isect_result none = { 0, 0, 0, 0, 0 },
                               ref = need >> i & 1u ? isect_unit_rebased(&t24, p[i], te[i], d[i], tmin[i], tmax[i]) : none;
            lanes += need >> i & 1u;
            hits += ref.hit;
            outside += (need >> i & 1u) && !ref.hit && ref.u == 0 && ref.v == 0;
            if (r[i].hit != ref.hit || r[i].t != ref.t || r[i].u != ref.u || r[i].v != ref.v || r[i].cos_n != ref.cos_n) {
                print_message("packet %d (need %x) lane %d: hit %d t %06x u %06x v %06x cos %06x, one ray: %d %06x %06x %06x %06x\n",
                              n, need, i, r[i].hit, r[i].t, r[i].u, r[i].v, r[i].cos_n, ref.hit, ref.t, ref.u, ref.v, ref.cos_n);
                bad++;
            }
        }
    }
    assert_int_equal(bad, 0);
    assert_true(hits > lanes / 8 && outside > lanes / 8); /* both sides of the early-out well covered */
}

#ifdef F24_SIM_LANES
/* ---- the simulation build's binary64 proof of misses (tb/sim/isect_lanes.c) ----------------- */

/* The triangles of a generated scene's meshes (object space): real geometry. */
static double *scene_triangles(const char *name, uint32_t *count)
{
    const scene_generator *g = scene_generator_find(name);
    assert_non_null(g);
    scene s;
    char err[256];
    const scene_gen_params gp = { 1, 0 };
    assert_int_equal(g->build(&s, &gp, err, sizeof err), 0);
    uint32_t n = 0;
    for (uint32_t m = 0; m < s.n_meshes; m++)
        n += s.meshes[m].n_triangles;
    double *v = malloc(sizeof(double) * 9 * n), *w = v;
    assert_non_null(v);
    for (uint32_t m = 0; m < s.n_meshes; m++)
        for (uint32_t t = 0; t < 3 * s.meshes[m].n_triangles; t++)
            for (int k = 0; k < 3; k++)
                *w++ = s.meshes[m].positions[3 * s.meshes[m].indices[t] + k];
    scene_free(&s);
    *count = n;
    return v;
}

/* One of the words that break the rounding model: zeros, a subnormal encoding, the extremes,
 * Inf, NaN, or any pattern. */
static f24_t special_word(void)
{
    const f24_t w[8] = { 0, F24_SIGN_BIT, 1, F24_MAX_NORMAL, F24_MIN_NORMAL, F24_POS_INF, F24_SIGN_BIT | F24_POS_INF,
                         F24_DEFAULT_NAN };
    const int k = (int)(urand() * 9);
    return k < 8 ? w[k] : (f24_t)(urand() * (double)F24_MASK) & F24_MASK;
}

/* A word near 2^e in size (either sign), for records without geometric meaning. */
static f24_t word_near(int e) { return F((urand() < 0.5 ? -1 : 1) * ldexp(0.5 + urand(), e + (int)(urand() * 9) - 4)); }

/* 1 + 2^-k for a barycentric coordinate or distance a few ulps off a boundary. */
static double nudge(void) { return (urand() < 0.5 ? -1 : 1) * ldexp(1, -(int)(6 + urand() * 20)); }

typedef struct {
    const double *real;
    uint32_t n_real;
} tri_source;

/* A triangle: random, scaled by 2^+-40 and moved far from the origin now and then, a sliver, one
 * of a real scene's, or a record of random words. Returns the three corners (unused for random
 * records). */
static f24_triangle packet_triangle(const tri_source *src, double abc[3][3], double *scale)
{
    const int kind = (int)(urand() * 10);
    f24_triangle t24;
    *scale = kind < 3 ? ldexp(1, (int)(urand() * 81) - 40) : 1;
    if (kind == 9) {
        const int e = (int)(urand() * 41) - 20;
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 4; j++)
                t24.m.m[i][j] = word_near(j == 3 ? -e : e);
        t24.c_lo = V(ldexp(urand(), -e - 20), -ldexp(urand(), -e - 20), 0);
        for (int k = 0; k < 3; k++)
            abc[0][k] = abc[1][k] = abc[2][k] = 0;
        *scale = ldexp(1, -e);
    } else {
        for (;;) {
            const double far = urand() < 0.3 ? 1000 * urand() : 0;
            if (kind >= 6 && kind <= 7 && src->n_real) {
                const uint32_t t = (uint32_t)(urand() * src->n_real) % src->n_real;
                memcpy(abc, &src->real[9 * t], sizeof(double) * 9);
            } else
                for (int i = 0; i < 3; i++)
                    for (int k = 0; k < 3; k++)
                        abc[i][k] = (10 * urand() - 5 + far) * *scale;
            if (kind == 8) /* a sliver: c near the line through a and b */
                for (int k = 0; k < 3; k++)
                    abc[2][k] = abc[0][k] + 0.5 * (abc[1][k] - abc[0][k]) + ldexp(urand(), -12) * *scale;
            affine tx;
            if (mi_triangle_transform(abc[0], abc[1], abc[2], kind == 8 ? 1e7 : 64, &tx)) {
                t24 = record_of(&tx);
                break;
            }
        }
    }
    t24.shared = (uint32_t)(urand() * 8) & (TRI_SHARED_U | TRI_SHARED_V | TRI_SHARED_W);
    return t24;
}

/* A ray of a packet at the triangle abc: aimed inside, at an edge or a vertex exactly or a few ulps
 * off, far off, nearly parallel to the plane or with a zero direction, from a rebased origin; an
 * interval [tmin, tmax) that holds the hit distance, ends a few ulps before or after it, or is any;
 * now and then one input word that breaks the rounding model. */
static void packet_ray(const f24_triangle *t24, const double abc[3][3], double scale, f24_vec3x2 *p, f24_t *te,
                       f24_vec3 *d, f24_t *tmin, f24_t *tmax)
{
    const int kind = (int)(urand() * 12);
    double w0 = 1.2 * urand() - 0.1, w1 = (1.2 - w0) * urand() - 0.05;
    if (kind < 6) /* edges u = 0, v = 0, u + v = 1 and the vertices, exactly or nudged */
        w0 = kind % 3 == 0 ? (kind < 3 ? 0 : nudge()) : w0, w1 = kind % 3 == 1 ? (kind < 3 ? 0 : nudge()) : w1;
    if (kind == 2 || kind == 5)
        w1 = 1 - w0 + (kind == 5 ? nudge() : 0);
    if (kind == 6) /* near a vertex */
        w0 = urand() < 0.5 ? 1 + nudge() : nudge(), w1 = nudge();
    if (kind == 7)
        w0 = 6 * urand() - 3, w1 = 6 * urand() - 3;
    double o[3], dd[3];
    for (int k = 0; k < 3; k++) {
        o[k] = (40 * urand() - 20) * scale + abc[2][k];
        dd[k] = w0 * abc[0][k] + w1 * abc[1][k] + (1 - w0 - w1) * abc[2][k] - o[k];
    }
    if (kind == 8) { /* nearly parallel to the plane: along an edge, tilted by a nudge */
        for (int k = 0; k < 3; k++)
            dd[k] = (abc[0][k] - abc[2][k]) + nudge() * (abc[1][k] - abc[2][k]) * (urand() < 0.5 ? 0 : 1);
    }
    *d = kind == 9 ? V(0, 0, 0) : V(dd[0], dd[1], dd[2]);
    *te = F(urand() < 0.5 ? 0 : 0.9 * urand());
    *p = rebased(V(o[0], o[1], o[2]), *d, *te);
    const isect_result r = isect_unit_rebased(t24, *p, *te, *d, F(0), F24_POS_INF);
    const int ends = (int)(urand() * 8), ulps = (int)(urand() * 5) - 2;
    const f24_t at = f24_is_nan(r.t) || f24_is_inf(r.t) ? F(urand()) : r.t;
    const f24_t near = (f24_t)((int32_t)at + ulps) & F24_MASK;
    *tmin = ends == 0 ? near : ends == 1 ? F(urand() - 0.5) : 0;
    *tmax = ends == 2 ? near : ends == 3 ? F(D(at) * (1 + nudge())) : ends == 4 ? F(urand() * 2) : F24_POS_INF;
    if (urand() < 1.0 / 32) {
        f24_t *words[11] = { &p->hi.x, &p->hi.y, &p->hi.z, &p->lo.x, &p->lo.y, &p->lo.z, &d->x, &d->y, &d->z, te, tmin };
        *words[(int)(urand() * 11) % 11] = special_word();
    }
}

/* Packets of filter_proves_misses: fewer under AddressSanitizer, whose run is for memory errors (a
 * quarter minute of make test's for 2 M there), not for the random space the plain build covers. */
#ifdef __SANITIZE_ADDRESS__
#define FILTER_TEST_PACKETS 200000
#else
#define FILTER_TEST_PACKETS 2000000
#endif

/* The proof of misses against the exact packet function: on random and adversarial packets (see
 * packet_triangle, packet_ray), every lane the proof gives is a miss of the exact path, and the
 * proving isect_unit_packet gives the exact path's hit flags and hits for every mask. */
static void filter_proves_misses(void **state)
{
    (void)state;
    tri_source src;
    uint32_t n_room, n_cornell;
    double *room = scene_triangles("room", &n_room), *cornell = scene_triangles("cornell", &n_cornell);
    double *all = malloc(sizeof(double) * 9 * (n_room + n_cornell));
    assert_non_null(all);
    memcpy(all, room, sizeof(double) * 9 * n_room);
    memcpy(all + 9 * n_room, cornell, sizeof(double) * 9 * n_cornell);
    src.real = all;
    src.n_real = n_room + n_cornell;
    long lanes = 0, misses = 0, proven = 0, wrong = 0, skipped = 0, packets = FILTER_TEST_PACKETS;
    for (long n = 0; n < packets && wrong < 5; n++) {
        double abc[3][3], scale;
        f24_triangle t24 = packet_triangle(&src, abc, &scale);
        if (urand() < 1.0 / 64)
            t24.m.m[(int)(urand() * 3) % 3][(int)(urand() * 4) % 4] = special_word();
        f24_vec3x2 p[F24Q_LANES];
        f24_vec3 d[F24Q_LANES];
        f24_t te[F24Q_LANES], tmin[F24Q_LANES], tmax[F24Q_LANES];
        for (int i = 0; i < F24Q_LANES; i++)
            packet_ray(&t24, abc, scale, &p[i], &te[i], &d[i], &tmin[i], &tmax[i]);
        const uint32_t need = 1u + (uint32_t)(urand() * 15) % 15u, sure = isect_packet_proven_misses(&t24, need, p, te, d, tmin, tmax);
        isect_result exact[F24Q_LANES], fast[F24Q_LANES];
        isect_unit_packet_exact(&t24, 15u, p, te, d, tmin, tmax, exact);
        isect_unit_packet(&t24, need, p, te, d, tmin, tmax, fast);
        skipped += (need & ~sure) == 0;
        for (int i = 0; i < F24Q_LANES; i++) {
            const int on = need >> i & 1u, bad_proof = (sure >> i & 1u) && (exact[i].hit || !on);
            lanes += on;
            misses += on && !exact[i].hit;
            proven += sure >> i & 1u;
            const int bad_fast = fast[i].hit != (on && exact[i].hit) || (fast[i].hit && memcmp(&fast[i], &exact[i], sizeof fast[i]));
            if (bad_proof || bad_fast) {
                print_message("packet %ld lane %d: proven %d, exact hit %d t %06x u %06x v %06x, proving packet hit %d\n", n, i,
                              sure >> i & 1u, exact[i].hit, exact[i].t, exact[i].u, exact[i].v, fast[i].hit);
                wrong++;
            }
        }
    }
    print_message("%ld lanes: %ld misses, %ld proven (%.1f%%), %ld packets skipped the exact path\n", lanes, misses,
                  proven, 100.0 * proven / (double)misses, skipped);
    free(all);
    free(room);
    free(cornell);
    assert_int_equal(wrong, 0);
    assert_true(proven > misses / 3 && misses > lanes / 4); /* the proof is tried on both sides */
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(hand_cases), cmocka_unit_test(parallel_and_interval), cmocka_unit_test(shared_edges),
        cmocka_unit_test(against_double_precision), cmocka_unit_test(small_and_far), cmocka_unit_test(packet_as_single),
#ifdef F24_SIM_LANES
        cmocka_unit_test(filter_proves_misses),
#endif
    };
    return cmocka_run_group_tests_name("isect_unit", tests, NULL, NULL);
}
