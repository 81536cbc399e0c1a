/*
 * Host fast path of rgs_light_packet (hls/units/rgs_light.c), bit-identical to it: a simulation
 * build whose packet values are vectors (F24_SIM_LANES, tb/fp/f24_fast.h) takes this definition,
 * and the per-ray one there keeps the name rgs_light_packet_per_ray (hls/units/rgs_ops.h).
 *
 * The per-ray datapath computes the light's weights and shadow ray of each surface in turn, each
 * operation one scalar working value; here every operation of the chain computes the four rays
 * at once, one lane each (about a third of the instructions: tests/test_rgs.c light_packet_lanes
 * compares both on random surfaces and lights), the cosines' conversions to Q12 included. Every
 * lane computes; the surfaces that take light keep their results. A surface's mirror direction
 * is rgs_reflect's T_R product on lanes, and the chain reads its results as the values their words
 * hold (the round trip through the words keeps every value; a NaN's sign, which it may not keep,
 * reaches no result: every operation on a NaN gives the default NaN, and a comparison with one is
 * false).
 */
#include "rgs_lanes.h"

#ifdef F24_SIM_LANES

/* rgs_reflect (rgs.c) per lane: T_R's rows (d, n, d) times (1, -(c + c), 0) for c = n.d, in
 * xform_vector's order and roundings */
F24V_INLINE void reflect_lanes(const f24v d[3], const f24v n[3], f24v out[3])
{
    const f24v c = dot3_lanes(n, d), k = -f24v_add(c, c), one = f24v_splat(F24_ONE), zero = f24v_splat(0u);
    for (int r = 0; r < 3; r++)
        out[r] = f24v_add(f24v_add(f24v_mul(d[r], one), f24v_mul(n[r], k)), f24v_mul(d[r], zero));
}

/* The surfaces' hit points, normals and directions by component, one lane per ray. */
F24V_INLINE void surface_lanes(const surface sf[], f24v p[3], f24v n[3], f24v d[3])
{
    f24_t w[9][TRACE_PACKET];
    for (int i = 0; i < TRACE_PACKET; i++) {
        w[0][i] = sf[i].p.x, w[1][i] = sf[i].p.y, w[2][i] = sf[i].p.z;
        w[3][i] = sf[i].n.x, w[4][i] = sf[i].n.y, w[5][i] = sf[i].n.z;
        w[6][i] = sf[i].d.x, w[7][i] = sf[i].d.y, w[8][i] = sf[i].d.z;
    }
    for (int k = 0; k < 3; k++) {
        p[k] = f24v_of(w[k]);
        n[k] = f24v_of(w[3 + k]);
        d[k] = f24v_of(w[6 + k]);
    }
}

/* rgs_q_of_w per lane: x 4096 + 1/2 rounded twice, then f24w_to_i32 (toward zero, NaN 0,
 * saturating) clamped to [0, 65535], which is the rounded value clamped first, NaN to 0. */
F24V_INLINE void q_of_lanes(f24v x, uint32_t out[TRACE_PACKET])
{
    const int32_t scale[F24Q_LANES] = { 4096, 4096, 4096, 4096 }, one[F24Q_LANES] = { 1, 1, 1, 1 },
                  two[F24Q_LANES] = { 2, 2, 2, 2 };
    const f24v y = f24v_add(f24v_mul(x, f24v_from_i32(scale)), f24v_div(f24v_from_i32(one), f24v_from_i32(two)));
    for (int i = 0; i < TRACE_PACKET; i++)
        out[i] = !(y[i] > 0) ? 0u : y[i] >= RGS_Q12_MAX ? RGS_Q12_MAX : (uint32_t)y[i];
}

/* The weights and shadow rays of the rays whose surface takes light, from the lanes (qw, qh: the
 * cosines in Q12). */
static void light_rays(const uint32_t *l, const surface sf[], f24_t eps, const f24_t dir[3][TRACE_PACKET],
                       const f24_t tmin[], uint32_t lit, const uint32_t qw[], const uint32_t qh[], ray_packet *sh,
                       uint32_t diff[], uint32_t spec[], const uint32_t k_of[])
{
    sh->active = 0;
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!rgs_takes_light(&sf[i], sh, diff, spec, i))
            continue;
        rgs_shadow_ray(l, &sf[i], eps, (f24_vec3){ dir[0][i], dir[1][i], dir[2][i] }, tmin[i], sh, i);
        if ((lit >> i & 1u) && rgs_light_weights_q(qw[i], qh[i], k_of[i], &diff[i], &spec[i]))
            sh->active |= 1u << i; /* else the light is behind the surface, or its weights are zero */
    }
}

F24V_FN void rgs_light_packet(const uint32_t *l, const surface sf[], f24_t eps, ray_packet *sh, uint32_t diff[],
                              uint32_t spec[], const uint32_t k_of[])
{
    const f24v zero = f24v_splat(0u);
    f24v p[3], n[3], d[3], to_light[3], mirror[3];
    surface_lanes(sf, p, n, d);
    /* the direction to the light (a directional light's is its words' negation, not rounded) */
    for (int k = 0; k < 3; k++)
        to_light[k] = l[0] == 0 ? f24v_splat(f24_neg(l[7 + k])) : f24v_sub(f24v_splat(l[4 + k]), p[k]);
    const f24v dist = f24v_sqrt(dot3_lanes(to_light, to_light));
    /* cosines of the light direction with the normal, the cone axis, the mirror direction */
    f24v w = f24v_div(dot3_lanes(n, to_light), dist);
    const uint32_t lit = f24v_lt(zero, w);
    if (SAARCOR_CFG_SPOT_LIGHTS && l[0] == 2) { /* spot: smooth step from the outer to the inner cone */
        const f24v axis[3] = { f24v_splat(l[7]), f24v_splat(l[8]), f24v_splat(l[9]) };
        const f24v c = -f24v_div(dot3_lanes(axis, to_light), dist);
        const f24v f = f24v_div(f24v_sub(c, f24v_splat(l[12])), f24v_sub(f24v_splat(l[11]), f24v_splat(l[12])));
        w = f24v_mul(w, f24v_max(zero, f24v_min(f, f24v_splat(F24_ONE))));
    }
    reflect_lanes(d, n, mirror);
    const f24v highlight = f24v_max(zero, f24v_div(dot3_lanes(mirror, to_light), dist));
    f24_t dir[3][TRACE_PACKET], tmin[TRACE_PACKET];
    for (int k = 0; k < 3; k++)
        f24v_bits(to_light[k], dir[k]);
    f24v_bits(f24v_div(f24v_splat(eps), dist), tmin);
    uint32_t qw[TRACE_PACKET], qh[TRACE_PACKET];
    q_of_lanes(w, qw);
    q_of_lanes(highlight, qh);
    light_rays(l, sf, eps, dir, tmin, lit, qw, qh, sh, diff, spec, k_of);
}
#endif
