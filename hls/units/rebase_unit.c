/* Rebase unit: see rebase_unit.h. */
#include "rebase_unit.h"

f24_t rebase_distance(f24_t t) { return f24_exp(t) == F24_EXP_MAX ? 0u : t; }

/* The three components side by side (lane 3 unused): o_hi + o_lo + t d_hi + t d_lo each. */
f24_vec3x2 rebase_origin(f24_vec3x2 o, f24_vec3x2 d, f24_t t)
{
    const f24_t te = rebase_distance(t);
    const f24_t a[4][F24Q_LANES] = { { o.hi.x, o.hi.y, o.hi.z, 0 }, { o.lo.x, o.lo.y, o.lo.z, 0 }, { te, te, te, 0 }, { te, te, te, 0 } };
    const f24_t b[4][F24Q_LANES] = { { F24_ONE, F24_ONE, F24_ONE, 0 }, { F24_ONE, F24_ONE, F24_ONE, 0 },
                                     { d.hi.x, d.hi.y, d.hi.z, 0 }, { d.lo.x, d.lo.y, d.lo.z, 0 } };
    f24_t hi[F24Q_LANES], lo[F24Q_LANES];
    f24q_sum_exact(a, b, 4, hi, lo);
    const f24_vec3x2 p = { { hi[0], hi[1], hi[2] }, { lo[0], lo[1], lo[2] } };
    return p;
}
