/* Transformation unit: see xform_unit.h. */
#include "xform_unit.h"

#include "rebase_unit.h"

#ifdef F24_SIM_LANES
#define xform_enter_rays xform_enter_rays_per_ray /* the simulation build's is side by side (xform_unit.h) */
#endif

/* One row for p = { x, y, z, 1 }: the three products side by side (the unit's multipliers; lane 3
 * is unused), summed in the contract's order. The translation goes through a mux, not an add of
 * zero, so a -0 sum keeps its sign. */
static F24Q_FN f24_t row_of(const f24_t row[4], const f24_t p[4], int with_translation)
{
    const f24q m = f24q_mul(f24q_of(row), f24q_of(p));
    const f24w s = f24w_add(f24w_add(f24q_lane(m, 0), f24q_lane(m, 1)), f24q_lane(m, 2));
    return f24w_bits(with_translation ? f24w_add(s, f24w_of(row[3])) : s);
}

f24_t xform_row(const f24_t row[4], f24_vec3 p, int with_translation)
{
    const f24_t q[4] = { p.x, p.y, p.z, F24_ONE };
    return row_of(row, q, with_translation);
}

/* The three rows side by side (lane r: row r, lane 3 unused), each in row_of's order:
 * ((m0 x + m1 y) + m2 z) (+ t). */
static F24Q_FN f24_vec3 xform_step(const f24_affine *m, f24_vec3 p, int with_translation)
{
    f24q col[4];
    f24q_columns(m->m, col);
    const f24_t pw[F24Q_LANES] = { p.x, p.y, p.z, 0 };
    const f24q pq = f24q_of(pw); /* p's components decoded together, each broadcast to the rows */
    f24q s = f24q_add(f24q_add(f24q_mul(col[0], f24q_broadcast(pq, 0)), f24q_mul(col[1], f24q_broadcast(pq, 1))),
                      f24q_mul(col[2], f24q_broadcast(pq, 2)));
    if (with_translation)
        s = f24q_add(s, col[3]);
    f24_t out[F24Q_LANES];
    f24q_bits(s, out);
    const f24_vec3 r = { out[0], out[1], out[2] };
    return r;
}

f24_vec3 xform_point(const f24_affine *m, f24_vec3 p) { return xform_step(m, p, 1); }

f24_vec3 xform_vector(const f24_affine *m, f24_vec3 v) { return xform_step(m, v, 0); }

/* The wide mode, one rounding into a double word per row, the three rows side by side (lane 3
 * unused): a point's m0 x + m1 y + m2 z + t + tlo for x, y, z in double words, a vector's
 * m0 x + m1 y + m2 z of their high words (directions come in single words). */
static F24Q_FN f24_vec3x2 xform_step_wide(const f24_affine *m, f24_vec3 tlo, f24_vec3x2 p, int with_translation)
{
    f24q col[4];
    f24q_columns(m->m, col);
    const f24_t t_lo[F24Q_LANES] = { tlo.x, tlo.y, tlo.z, 0 };
    f24q a[8], b[8];
    a[0] = a[3] = col[0];
    a[1] = a[4] = col[1];
    a[2] = a[5] = col[2];
    /* p's words decoded together, each broadcast to the rows */
    const f24_t p_hi[F24Q_LANES] = { p.hi.x, p.hi.y, p.hi.z, 0 }, p_lo[F24Q_LANES] = { p.lo.x, p.lo.y, p.lo.z, 0 };
    const f24q hq = f24q_of(p_hi);
    b[0] = f24q_broadcast(hq, 0);
    b[1] = f24q_broadcast(hq, 1);
    b[2] = f24q_broadcast(hq, 2);
    const uint32_t n = with_translation ? 8u : 3u; /* a vector's terms: its high words' three */
    if (with_translation) {
        const f24q lq = f24q_of(p_lo);
        a[6] = col[3];
        a[7] = f24q_of(t_lo);
        b[3] = f24q_broadcast(lq, 0);
        b[4] = f24q_broadcast(lq, 1);
        b[5] = f24q_broadcast(lq, 2);
        b[6] = b[7] = f24q_splat(F24_ONE);
    }
    f24_t hi[F24Q_LANES], lo[F24Q_LANES];
    f24q_sum_exact(a, b, n, hi, lo);
    const f24_vec3x2 r = { { hi[0], hi[1], hi[2] }, { lo[0], lo[1], lo[2] } };
    return r;
}

f24_vec3x2 xform_point_wide(const f24_affine *m, f24_vec3 tlo, f24_vec3x2 p) { return xform_step_wide(m, tlo, p, 1); }

f24_vec3x2 xform_vector_wide(const f24_affine *m, f24_vec3 v)
{
    const f24_vec3 none = { 0, 0, 0 };
    const f24_vec3x2 w = { v, none };
    return xform_step_wide(m, none, w, 0);
}

void xform_enter_rays(const f24_affine *w2o, f24_vec3 t_lo, uint32_t rays, const f24_vec3 o[], const f24_vec3 d[],
                      const f24_t tn[], f24_vec3 o_hi[], f24_vec3 o_lo[], f24_vec3 d_hi[], f24_vec3 d_lo[], f24_t t0[])
{
    const f24_vec3 none = { 0, 0, 0 };
enter_rays:
    for (int i = 0; i < F24Q_LANES; i++) {
        if (!(rays >> i & 1u))
            continue;
        const f24_t t = rebase_distance(tn[i]);
        const f24_vec3x2 p = rebase_origin((f24_vec3x2){ o[i], none }, (f24_vec3x2){ d[i], none }, t);
        const f24_vec3x2 po = xform_point_wide(w2o, t_lo, p), pd = xform_vector_wide(w2o, d[i]);
        o_hi[i] = po.hi;
        o_lo[i] = po.lo;
        d_hi[i] = pd.hi;
        d_lo[i] = pd.lo;
        t0[i] = t;
    }
}

f24_vec3 xform_identity(const f24_affine *m, f24_vec3 v, int point)
{
    const f24_t c[3] = { v.x, v.y, v.z };
    /* the common case, as one check: no component is zero, Inf or NaN, so every row passes its
     * own component through (the rows below give the same) */
    if ((uint32_t)(f24_exp(v.x) - 1) < F24_EXP_MAX - 1u && (uint32_t)(f24_exp(v.y) - 1) < F24_EXP_MAX - 1u &&
        (uint32_t)(f24_exp(v.z) - 1) < F24_EXP_MAX - 1u)
        return v;
    f24_t r[3];
identity_rows:
    for (int k = 0; k < 3; k++) {
        int nan = f24_is_nan(c[k]);
        uint32_t negative = point ? f24_sign(m->m[k][3]) : 1u; /* all terms of the zero sum are -0 */
        for (int j = 0; j < 3; j++) {
            if (j != k && f24_exp(c[j]) == F24_EXP_MAX)
                nan = 1; /* 0 x Inf or 0 x NaN */
            negative &= j == k ? f24_sign(c[j]) : f24_sign(m->m[k][j]) ^ f24_sign(c[j]);
        }
        if (nan)
            r[k] = F24_DEFAULT_NAN;
        else if (!f24_is_zero(c[k]))
            r[k] = c[k];
        else
            r[k] = negative ? F24_SIGN_BIT : 0u;
    }
    const f24_vec3 out = { r[0], r[1], r[2] };
    return out;
}

int xform_is_identity(const f24_affine *m)
{
    int id = 1;
identity_check:
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            id &= r == c ? m->m[r][c] == F24_ONE : f24_is_zero(m->m[r][c]);
    return id;
}
