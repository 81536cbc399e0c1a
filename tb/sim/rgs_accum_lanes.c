/*
 * Host fast path of rgs_accumulate_rays (hls/units/rgs_accum.c), bit-identical to it: a simulation
 * build whose packet values are vectors (F24_SIM_LANES, tb/fp/f24_fast.h) takes this definition,
 * and the per-ray loop there keeps the name rgs_accumulate_rays_per_ray (hls/units/rgs_ops.h).
 *
 * The per-ray datapath spawns each surface's child rays in turn (rgs_spawn_children: the cosine
 * c = N.D, the back and ahead points and the mirror direction through T_R, the refraction with its
 * total internal reflection), each operation one scalar working value and each T_R step a call of
 * the transformation unit; here every operation of that chain computes the four rays at once, one
 * lane each, in the same order and roundings per lane (tests/test_rgs.c accumulate_rays_lanes
 * compares both on random surfaces and materials). Every lane computes; the rays that spawn keep
 * their results, whose weights and active bits rgs_child_rays sets as the per-ray function does.
 * The colours stay per ray (integer Q12, rgs_ray_colour).
 */
#include "rgs_lanes.h"

#ifdef F24_SIM_LANES

/* A T_R step per lane (xform_step's order and roundings): row r of the surfaces' T_R times
 * (p0, p1, p2) (+ the translation for a point), into words by component. */
F24V_INLINE void tr_step_lanes(const f24v m[3][4], f24v p0, f24v p1, f24v p2, int point, f24_t out[3][TRACE_PACKET])
{
    for (int r = 0; r < 3; r++) {
        f24v s = f24v_add(f24v_add(f24v_mul(m[r][0], p0), f24v_mul(m[r][1], p1)), f24v_mul(m[r][2], p2));
        if (point)
            s = f24v_add(s, m[r][3]);
        f24v_bits(s, out[r]);
    }
}

/* The geometry of rgs_spawn_children for the packet's surfaces (eta: the materials' words M_ETA):
 * per ray i the back point, the mirror direction and the transmission ray's origin and direction. */
typedef struct {
    f24_t back[3][TRACE_PACKET], ahead[3][TRACE_PACKET], mirror[3][TRACE_PACKET], refr[3][TRACE_PACKET];
    uint32_t refracts, tir; /* eta != 1; k < 0 */
} child_geometry;

static F24V_FN void children_lanes(const surface sf[], const f24_t eta[TRACE_PACKET], f24_t eps, child_geometry *g)
{
    f24v m[3][4], n[3], d[3];
    f24_t w[3][4][TRACE_PACKET], t_hat[TRACE_PACKET];
    uint32_t entering = 0;
    for (int i = 0; i < TRACE_PACKET; i++) {
        for (int r = 0; r < 3; r++)
            for (int k = 0; k < 4; k++)
                w[r][k][i] = sf[i].tr.m[r][k];
        t_hat[i] = sf[i].t_hat;
        entering |= (uint32_t)(sf[i].entering != 0) << i;
    }
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 4; k++)
            m[r][k] = f24v_of(w[r][k]);
    f24_vec3 nv[TRACE_PACKET], dv[TRACE_PACKET];
    for (int i = 0; i < TRACE_PACKET; i++)
        nv[i] = sf[i].n, dv[i] = sf[i].d;
    vec_lanes(nv, n);
    vec_lanes(dv, d);
    const f24v zero = f24v_splat(0u), one = f24v_splat(F24_ONE), th = f24v_of(t_hat);
    const f24v c = f24v_add(f24v_add(f24v_mul(n[0], d[0]), f24v_mul(n[1], d[1])), f24v_mul(n[2], d[2]));
    tr_step_lanes(m, f24v_splat(f24_neg(eps)), zero, th, 1, g->back);
    tr_step_lanes(m, f24v_splat(eps), zero, th, 1, g->ahead);
    tr_step_lanes(m, one, -f24v_add(c, c), zero, 0, g->mirror);
    g->refracts = g->tir = 0;
#if SAARCOR_CFG_REFRACTION
    /* rgs_refract: k = 1 - eta_r^2 (1 - c^2), mu = -eta_r c - sqrt(k), (eta_r, mu, 0) through T_R(0, D, N) */
    const f24v ior = f24v_of(eta), eta_r = f24v_pick(entering, f24v_div(one, ior), ior);
    const f24v k = f24v_sub(one, f24v_mul(f24v_mul(eta_r, eta_r), f24v_sub(one, f24v_mul(c, c))));
    const f24v mu = f24v_sub(-f24v_mul(eta_r, c), f24v_sqrt(k));
    const f24v dn[3][4] = { { d[0], n[0], d[0] }, { d[1], n[1], d[1] }, { d[2], n[2], d[2] } };
    tr_step_lanes(dn, eta_r, mu, zero, 0, g->refr);
    g->refracts = f24v_mask(ior != one); /* !f24_eq(ior, 1): a NaN refracts */
    g->tir = f24v_lt(k, zero);
#else
    (void)eta;
#endif
}

uint32_t rgs_accumulate_rays(const uint32_t *mem, const surface sf[], uint32_t active, const uint32_t weight[][3],
                             const uint32_t diffuse[][3], const uint32_t highlight[][3], f24_t eps, uint32_t spawn,
                             uint32_t acc[][3], rgs_task *refl, rgs_task *trans)
{
    uint32_t spawning = 0;
    f24_t eta[TRACE_PACKET];
    for (int i = 0; i < TRACE_PACKET; i++) {
        const uint32_t *m = sf[i].valid ? &mem[sf[i].mat] : 0;
        eta[i] = sf[i].valid ? m[M_ETA] : F24_ONE;
        if (!(active >> i & 1u))
            continue;
        rgs_ray_colour(m, &sf[i], weight[i], diffuse[i], highlight[i], acc[i]);
        if (SAARCOR_CFG_SECONDARY && sf[i].valid && (spawn & RGS_SPAWN_ON))
            spawning |= 1u << i;
    }
    if (!spawning)
        return 0;
    child_geometry g;
    children_lanes(sf, eta, eps, &g);
    uint32_t children = 0;
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!(spawning >> i & 1u))
            continue;
        const int tir = (g.refracts & g.tir) >> i & 1u;
        const f24_vec3 back = lane_vec(g.back, i), mirror = lane_vec(g.mirror, i);
        const f24_vec3 t_o = tir ? back : lane_vec(g.ahead, i);
        const f24_vec3 t_d = tir ? mirror : (g.refracts >> i & 1u) ? lane_vec(g.refr, i) : sf[i].d;
        const uint32_t spawned = refl->rays.active | trans->rays.active;
        rgs_child_rays(&mem[sf[i].mat], weight[i], i, &sf[i], back, mirror, t_o, t_d, refl, trans);
        children += (uint32_t)rgs_child_steps(spawn, spawned, refl, trans);
    }
    return children;
}
#endif
