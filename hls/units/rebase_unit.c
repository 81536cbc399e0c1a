/* Rebase unit: see rebase_unit.h. */
#include "rebase_unit.h"

#ifdef F24_SIM_LANES
#define rebase_rays rebase_rays_per_ray /* the simulation build's is side by side (rebase_unit.h) */
#endif

f24_t rebase_distance(f24_t t) { return f24_exp(t) == F24_EXP_MAX ? 0u : t; }

/* The three components side by side (lane 3 unused): o_hi + o_lo + t d_hi + t d_lo each. */
F24Q_FN f24_vec3x2 rebase_origin(f24_vec3x2 o, f24_vec3x2 d, f24_t t)
{
    const f24_t oh[F24Q_LANES] = { o.hi.x, o.hi.y, o.hi.z, 0 }, ol[F24Q_LANES] = { o.lo.x, o.lo.y, o.lo.z, 0 },
                dh[F24Q_LANES] = { d.hi.x, d.hi.y, d.hi.z, 0 }, dl[F24Q_LANES] = { d.lo.x, d.lo.y, d.lo.z, 0 };
    const f24q one = f24q_splat(F24_ONE), te = f24q_splat(rebase_distance(t));
    const f24q a[4] = { f24q_of(oh), f24q_of(ol), te, te }, b[4] = { one, one, f24q_of(dh), f24q_of(dl) };
    f24_t hi[F24Q_LANES], lo[F24Q_LANES];
    f24q_sum_exact(a, b, 4, hi, lo);
    const f24_vec3x2 p = { { hi[0], hi[1], hi[2] }, { lo[0], lo[1], lo[2] } };
    return p;
}

void rebase_rays(uint32_t rays, const f24_vec3 o[], const f24_vec3 o_lo[], const f24_vec3 d[], const f24_vec3 d_lo[],
                 const f24_t t[], f24_vec3x2 p[], f24_t te[])
{
rebase_each:
    for (int i = 0; i < F24Q_LANES; i++) {
        if (!(rays >> i & 1u))
            continue;
        p[i] = rebase_origin((f24_vec3x2){ o[i], o_lo[i] }, (f24_vec3x2){ d[i], d_lo[i] }, t[i]);
        te[i] = rebase_distance(t[i]);
    }
}
