/* Rebase unit: see rebase_unit.h. */
#include "rebase_unit.h"

f24_t rebase_distance(f24_t t) { return f24_exp(t) == F24_EXP_MAX ? 0u : t; }

static f24x2 rebase_component(f24_t o_hi, f24_t o_lo, f24_t d_hi, f24_t d_lo, f24_t t)
{
    const f24_t a[4] = { o_hi, o_lo, t, t }, b[4] = { F24_ONE, F24_ONE, d_hi, d_lo };
    return f24_sum_exact(a, b, 4);
}

f24_vec3x2 rebase_origin(f24_vec3x2 o, f24_vec3x2 d, f24_t t)
{
    const f24_t te = rebase_distance(t);
    const f24x2 x = rebase_component(o.hi.x, o.lo.x, d.hi.x, d.lo.x, te),
                y = rebase_component(o.hi.y, o.lo.y, d.hi.y, d.lo.y, te),
                z = rebase_component(o.hi.z, o.lo.z, d.hi.z, d.lo.z, te);
    const f24_vec3x2 p = { { x.hi, y.hi, z.hi }, { x.lo, y.lo, z.lo } };
    return p;
}
