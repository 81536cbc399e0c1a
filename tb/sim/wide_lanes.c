/*
 * Host fast path of the wide mode's per-ray loops, bit-identical to them: xform_enter_rays
 * (hls/units/xform_unit.c: a packet's rays into an instance's object space) and rebase_rays
 * (hls/units/rebase_unit.c: their origins moved to a leaf's entry). A simulation build whose packet
 * values are vectors (F24_SIM_LANES, tb/fp/f24_fast.h) takes these definitions; the per-ray ones
 * there keep the names xform_enter_rays_per_ray and rebase_rays_per_ray (the truth).
 *
 * The per-ray datapath sums each ray's three components (rows) side by side, one exact sum
 * (f24q_sum_exact) per ray and step, lane 3 unused; here each sum takes one component (row) of the
 * four rays, one lane each: three sums per step for the packet instead of three per ray, every lane
 * full (with 3 or 4 rays; fewer take the per-ray functions, which then sum fewer times). The
 * exact sum of a lane depends on that lane's terms only, which are the per-ray version's
 * in the same order, decoded by the same f24v_of (tests/test_xform_unit.c enter_rays_lanes and
 * rebase_rays_lanes compare both on random rays, matrices and special words). Rays outside the
 * mask compute zeros (a sum of zeros stays on the sums' fast path) and keep their outputs.
 */
#include "rebase_unit.h" /* (its f24.h reads the build's F24_SIM_HEADER, which defines F24_SIM_LANES) */
#include "xform_unit.h"

#ifdef F24_SIM_LANES

/* Fewer than 3 rays: one ray's sums side by side, ray after ray, take fewer sums than the packet's
 * components (rebase: 1 a ray against 3; into an instance: 3 a ray against 9). */
static int few(uint32_t rays) { return (rays & (rays - 1u) & ((rays & (rays - 1u)) - 1u)) == 0; }

/* The rays' vectors v by component, one lane per ray of the mask (zero elsewhere). */
F24V_INLINE void by_axis(const f24_vec3 v[], uint32_t rays, f24v out[3])
{
    f24_t w[3][F24Q_LANES];
    for (int i = 0; i < F24Q_LANES; i++) {
        const int on = rays >> i & 1u;
        w[0][i] = on ? v[i].x : 0u;
        w[1][i] = on ? v[i].y : 0u;
        w[2][i] = on ? v[i].z : 0u;
    }
    for (int k = 0; k < 3; k++)
        out[k] = f24v_of(w[k]);
}

/* rebase_distance of the rays of the mask (zero elsewhere). */
static void distances(const f24_t t[], uint32_t rays, f24_t te[F24Q_LANES])
{
    for (int i = 0; i < F24Q_LANES; i++)
        te[i] = rays >> i & 1u ? rebase_distance(t[i]) : 0u;
}

/* rebase_origin's component sums o.hi + o.lo + t d.hi + t d.lo, one lane per ray. */
F24V_INLINE void rebase_lanes(const f24v oh[3], const f24v ol[3], const f24v dh[3], const f24v dl[3], f24v te,
                              f24_t hi[3][F24Q_LANES], f24_t lo[3][F24Q_LANES])
{
    const f24v one = f24v_splat(F24_ONE);
    for (int k = 0; k < 3; k++) {
        const f24v a[4] = { oh[k], ol[k], te, te }, b[4] = { one, one, dh[k], dl[k] };
        f24_fast_sum_exact_lanes(a, b, 4, hi[k], lo[k]);
    }
}

/* Lane i of the three components' words as ray i's vector. */
static f24_vec3 ray_of(const f24_t c[3][F24Q_LANES], int i) { return (f24_vec3){ c[0][i], c[1][i], c[2][i] }; }

F24V_FN void rebase_rays(uint32_t rays, const f24_vec3 o[], const f24_vec3 o_lo[], const f24_vec3 d[],
                         const f24_vec3 d_lo[], const f24_t t[], f24_vec3x2 p[], f24_t te[])
{
    if (few(rays)) {
        rebase_rays_per_ray(rays, o, o_lo, d, d_lo, t, p, te);
        return;
    }
    f24_t e[F24Q_LANES], hi[3][F24Q_LANES], lo[3][F24Q_LANES];
    f24v oh[3], ol[3], dh[3], dl[3];
    distances(t, rays, e);
    by_axis(o, rays, oh);
    by_axis(o_lo, rays, ol);
    by_axis(d, rays, dh);
    by_axis(d_lo, rays, dl);
    rebase_lanes(oh, ol, dh, dl, f24v_of(e), hi, lo);
    for (int i = 0; i < F24Q_LANES; i++) {
        if (!(rays >> i & 1u))
            continue;
        p[i] = (f24_vec3x2){ ray_of(hi, i), ray_of(lo, i) };
        te[i] = e[i];
    }
}

/* Per row r of the matrix: the origins' 8 terms (xform_step_wide's order: the row's products with
 * the rebased origin's high and low words, the translation in two words) and the directions' 3. */
F24V_FN void xform_enter_rays(const f24_affine *w2o, f24_vec3 t_lo, uint32_t rays, const f24_vec3 o[],
                              const f24_vec3 d[], const f24_t tn[], f24_vec3 o_hi[], f24_vec3 o_lo[], f24_vec3 d_hi[],
                              f24_vec3 d_lo[], f24_t t0[])
{
    if (few(rays)) {
        xform_enter_rays_per_ray(w2o, t_lo, rays, o, d, tn, o_hi, o_lo, d_hi, d_lo, t0);
        return;
    }
    f24_t e[F24Q_LANES], ph[3][F24Q_LANES], pl[3][F24Q_LANES];
    f24v oq[3], dq[3];
    distances(tn, rays, e);
    by_axis(o, rays, oq);
    by_axis(d, rays, dq);
    const f24v zero = f24v_splat(0u), one = f24v_splat(F24_ONE), none[3] = { zero, zero, zero };
    rebase_lanes(oq, none, dq, none, f24v_of(e), ph, pl);
    const f24v p[6] = { f24v_of(ph[0]), f24v_of(ph[1]), f24v_of(ph[2]), f24v_of(pl[0]), f24v_of(pl[1]), f24v_of(pl[2]) };
    const f24_t tlo_w[F24Q_LANES] = { t_lo.x, t_lo.y, t_lo.z, 0 };
    const f24v tlo = f24v_of(tlo_w);
    f24_t oh[3][F24Q_LANES], ol[3][F24Q_LANES], dh[3][F24Q_LANES], dl[3][F24Q_LANES];
    for (int r = 0; r < 3; r++) {
        const f24v row = f24v_of(w2o->m[r]), m0 = f24v_broadcast(row, 0), m1 = f24v_broadcast(row, 1),
                   m2 = f24v_broadcast(row, 2);
        const f24v a[8] = { m0, m1, m2, m0, m1, m2, f24v_broadcast(row, 3), f24v_broadcast(tlo, r) },
                   b[8] = { p[0], p[1], p[2], p[3], p[4], p[5], one, one };
        f24_fast_sum_exact_lanes(a, b, 8, oh[r], ol[r]);
        f24_fast_sum_exact_lanes(a, dq, 3, dh[r], dl[r]);
    }
    for (int i = 0; i < F24Q_LANES; i++) {
        if (!(rays >> i & 1u))
            continue;
        o_hi[i] = ray_of(oh, i);
        o_lo[i] = ray_of(ol, i);
        d_hi[i] = ray_of(dh, i);
        d_lo[i] = ray_of(dl, i);
        t0[i] = e[i];
    }
}

#endif
