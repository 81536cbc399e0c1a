/*
 * Host fast path of the intersection unit's packet test (isect_unit_packet, hls/units/isect_unit.c):
 * before the bit-exact fp24 work, a binary64 test over the packet's lanes that proves rays miss
 * the triangle; a packet whose needed rays are all proven misses returns misses at once, any other
 * takes isect_unit_packet_exact (the hls/ function, the truth) whole. A simulation build whose
 * packet values are vectors (F24_SIM_LANES, tb/fp/f24_fast.h) takes this definition; the hardware
 * arithmetic build (SIM_ARITH=hw), clang's and the RTL benches keep the hls/ one, and the capture
 * build records the one-ray function instead. The hit flags are the exact path's, and so are a
 * hit's fields; a proven miss's fields are zeros, which op_tri_isect never reads
 * (tests/test_isect_unit.c filter_proves_misses checks that every proven miss is a miss of the
 * exact path on millions of random and adversarial packets).
 *
 * The proof. From the same fp24 inputs (decoded exactly), binary64 computes per ray the exact
 * formula of the unit's path with its roundings removed: P = (p.hi - C.hi) + (p.lo - C.lo),
 * OZ = n.P (n: row 2 of M^-1), DZ = n.d, TL = -OZ/DZ, T = te + TL, OX = m0.P, DX = m0.d,
 * U = OX + TL DX, V alike with row 1, W = U + V; and beside each a bound E on the distance of the
 * fp24 path's value from it. Every fp24 operation's result is r (1 + delta) + eta with |delta| <=
 * u = 2^-(M+1) (round to nearest) and |eta| < tau = the smallest normal (a flush to zero), so,
 * with Pa = |p.hi - C.hi| + |p.lo - C.lo| and sums over the three components:
 *   offset c     2u Pa + 3 tau                 (two roundings, p.lo - C.lo rounded first)
 *   oz           2u sum |n| Pa + tau (1 + sum |n|)   (the exact sum: its terms' p.lo - C.lo
 *                                              rounded, then one rounding)
 *   dz, dx, dy   3u sum |m d| + 5 tau          (a row: 3 products, 2 adds, ((a + b) + c))
 *   ox, oy       5u sum |m| Pa + 3 tau sum |m| + 5 tau   (a row of c, whose own error adds)
 *   tl           (E_oz + |TL| E_dz) / (|DZ| - E_dz) + u |TL| + tau   (when E_dz < |DZ|)
 *   t            E_tl + u (|te| + |TL|) + tau
 *   tl dx        |TL| E_dx + |DX| E_tl + E_tl E_dx + u (|TL| + E_tl)(|DX| + E_dx) + tau
 *   u            E_ox + E_q + u (|OX| + |Q| + E_ox + E_q) + tau, and w = u + v alike.
 * A ray misses for sure if T + S E_t < tmin, T - S E_t >= tmax, U + S E_u < lo, V + S E_v < lo or
 * W - S E_w > hi, where lo and hi are the widest barycentric bounds (a shared edge's) and S = 16 a
 * safety factor. The bounds above are first order: S covers their second-order terms (with
 * u <= 2^-9 and at most 6 roundings in a chain, below 2^-5 of them) and binary64's own roundings
 * of the formula (2^-53 an operation, below 2^-27 of them). The unit's hit needs tmin <= t < tmax,
 * u >= lo, v >= lo and u + v <= hi, so one of the five is enough. The proof needs the model to
 * hold, so a ray is not proven unless |DZ| > 2 E_dz (not parallel to the plane or nearly so) and
 * the sum of the magnitudes that bound every fp24 intermediate (Pa, sum |m| Pa, sum |m d|, |TL|,
 * |T|, |Q|, |U|, |W|) and of their bounds is below 2^(bias-1): then no fp24 value overflows (the
 * exact sum's products are exact whatever their size), and an Inf or NaN input, which makes that
 * sum Inf or NaN, fails the test (every comparison with NaN is false).
 */
#include "isect_unit.h" /* (its f24.h reads the build's F24_SIM_HEADER, which defines F24_SIM_LANES) */

#ifdef F24_SIM_LANES

F24V_INLINE f24v vabs(f24v x) { return (f24v)((f24v_i)x & f24v_k.abs52); }

F24V_INLINE f24v splat(double x) { return (f24v){ x, x, x, x }; }

/* The words of the lanes, decoded; a lane outside keep (all ones or zero) computes on zeros, as in
 * isect_unit_packet_exact: no word of a ray that does not need the triangle is used. */
F24V_INLINE f24v lanes_of(f24_t w0, f24_t w1, f24_t w2, f24_t w3, const f24_t keep[F24Q_LANES])
{
    const f24_t w[F24Q_LANES] = { w0 & keep[0], w1 & keep[1], w2 & keep[2], w3 & keep[3] };
    return f24v_of(w);
}
F24V_INLINE f24v words_of(const f24_t a[F24Q_LANES], const f24_t keep[F24Q_LANES])
{
    return lanes_of(a[0], a[1], a[2], a[3], keep);
}

/* The rays' vectors by component, one lane per ray. */
F24V_INLINE void by_axis(f24_vec3 v0, f24_vec3 v1, f24_vec3 v2, f24_vec3 v3, const f24_t keep[F24Q_LANES], f24v out[3])
{
    out[0] = lanes_of(v0.x, v1.x, v2.x, v3.x, keep);
    out[1] = lanes_of(v0.y, v1.y, v2.y, v3.y, keep);
    out[2] = lanes_of(v0.z, v1.z, v2.z, v3.z, keep);
}

/* x . y over the three components */
F24V_INLINE f24v dot(const f24v x[3], const f24v y[3]) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; }

/* The bound of the rounded sum a + b of values with bounds ea, eb. */
F24V_INLINE f24v sum_bound(f24v a, f24v b, f24v ea, f24v eb, double u, double tau)
{
    return ea + eb + u * (vabs(a) + vabs(b) + ea + eb) + tau;
}

F24V_FN uint32_t isect_packet_proven_misses(const f24_triangle *tri, uint32_t need, const f24_vec3x2 p[F24Q_LANES],
                                            const f24_t te[F24Q_LANES], const f24_vec3 d[F24Q_LANES],
                                            const f24_t tmin[F24Q_LANES], const f24_t tmax[F24Q_LANES])
{
    const double u = __builtin_ldexp(1.0, -(F24_MAN_BITS + 1)), tau = __builtin_ldexp(1.0, 1 - F24_BIAS);
    const double safety = 16, limit = __builtin_ldexp(1.0, F24_BIAS - 1);
    const f24_t c_lo[F24Q_LANES] = { tri->c_lo.x, tri->c_lo.y, tri->c_lo.z, 0 };
    const f24v rows[3] = { f24v_of(tri->m.m[0]), f24v_of(tri->m.m[1]), f24v_of(tri->m.m[2]) }, cl = f24v_of(c_lo);
    const f24_t keep[F24Q_LANES] = { 0u - (need & 1u), 0u - (need >> 1 & 1u), 0u - (need >> 2 & 1u), 0u - (need >> 3 & 1u) };
    f24v m[3][3], am[3][3], hi[3], lo[3], dir[3], adir[3], P[3], Pa[3];
    by_axis(p[0].hi, p[1].hi, p[2].hi, p[3].hi, keep, hi);
    by_axis(p[0].lo, p[1].lo, p[2].lo, p[3].lo, keep, lo);
    by_axis(d[0], d[1], d[2], d[3], keep, dir);
    for (int r = 0; r < 3; r++) {
        const f24v ar = vabs(rows[r]);
        for (int k = 0; k < 3; k++)
            m[r][k] = f24v_broadcast(rows[r], k), am[r][k] = f24v_broadcast(ar, k);
    }
    for (int k = 0; k < 3; k++) {
        const f24v a = hi[k] - f24v_broadcast(rows[k], 3), b = lo[k] - f24v_broadcast(cl, k);
        P[k] = a + b;
        Pa[k] = vabs(a) + vabs(b);
        adir[k] = vabs(dir[k]);
    }
    const f24v *n = m[2], *an = am[2], te_v = words_of(te, keep);
    const f24v OZ = dot(n, P), DZ = dot(n, dir), OZa = dot(an, Pa), DZa = dot(an, adir);
    const f24v e_oz = 2 * u * OZa + tau * (1 + an[0] + an[1] + an[2]), e_dz = 3 * u * DZa + 5 * tau;
    const f24v den = vabs(DZ) - e_dz, TL = -OZ / DZ, aTL = vabs(TL), T = te_v + TL;
    const f24v e_tl = (e_oz + aTL * e_dz) / den + u * aTL + tau, e_t = sum_bound(te_v, TL, splat(0), e_tl, u, tau);
    f24v U[2], e_u[2], mag = Pa[0] + Pa[1] + Pa[2] + OZa + DZa + aTL + e_tl + vabs(T) + e_t;
    for (int r = 0; r < 2; r++) {
        const f24v OX = dot(m[r], P), DX = dot(m[r], dir), OXa = dot(am[r], Pa), DXa = dot(am[r], adir), Q = TL * DX;
        const f24v e_ox = 5 * u * OXa + 3 * tau * (am[r][0] + am[r][1] + am[r][2]) + 5 * tau, e_dx = 3 * u * DXa + 5 * tau;
        const f24v e_q = (aTL + e_tl) * (vabs(DX) + e_dx) * (1 + u) - aTL * vabs(DX) + tau;
        U[r] = OX + Q;
        e_u[r] = sum_bound(OX, Q, e_ox, e_q, u, tau);
        mag += OXa + DXa + vabs(Q) + e_q + vabs(U[r]) + e_u[r];
    }
    const f24v W = U[0] + U[1], e_w = sum_bound(U[0], U[1], e_u[0], e_u[1], u, tau);
    const f24v lo_b = f24v_splat(ISECT_LO(ISECT_SHARED_K)), hi_b = f24v_splat(ISECT_HI(ISECT_SHARED_K));
    const f24v_i miss = (T + safety * e_t < words_of(tmin, keep)) | (T - safety * e_t >= words_of(tmax, keep)) |
                        (U[0] + safety * e_u[0] < lo_b) | (U[1] + safety * e_u[1] < lo_b) | (W - safety * e_w > hi_b);
    const f24v_i valid = (den > e_dz) & (mag + vabs(W) + e_w < splat(limit));
    return f24v_mask(miss & valid); /* a lane outside need computes on zeros: D'z = 0, not proven */
}

F24V_FN void isect_unit_packet(const f24_triangle *tri, uint32_t need, const f24_vec3x2 p[F24Q_LANES],
                               const f24_t te[F24Q_LANES], const f24_vec3 d[F24Q_LANES], const f24_t tmin[F24Q_LANES],
                               const f24_t tmax[F24Q_LANES], isect_result r[F24Q_LANES])
{
    if (need & ~isect_packet_proven_misses(tri, need, p, te, d, tmin, tmax)) {
        isect_unit_packet_exact(tri, need, p, te, d, tmin, tmax, r);
        return;
    }
    for (int i = 0; i < F24Q_LANES; i++)
        r[i] = (isect_result){ 0, 0, 0, 0, 0 };
}

#endif
