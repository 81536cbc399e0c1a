/* Unit-triangle intersection unit: see isect_unit.h. */
#include "isect_unit.h"

#include "config.h"
#include "xform_unit.h"

#define F24_ZERO 0u

/* The barycentric bounds: 0 and 1, or -eps and 1 + eps for the robust edge option. Constants,
 * so the option costs no operator and no cycle (only the comparators' constant inputs change). */
#if SAARCOR_CFG_EDGE_EPS > 0
#if SAARCOR_CFG_EDGE_EPS > F24_MAN_BITS || SAARCOR_CFG_EDGE_EPS >= F24_BIAS
#error "SAARCOR_CFG_EDGE_EPS must be in 1 .. min(F24_MAN_BITS, bias - 1)"
#endif
#define ISECT_LO (F24_SIGN_BIT | ((uint32_t)(F24_BIAS - SAARCOR_CFG_EDGE_EPS) << F24_MAN_BITS))
#define ISECT_HI (F24_ONE | (1u << (F24_MAN_BITS - SAARCOR_CFG_EDGE_EPS)))
#else
#define ISECT_LO F24_ZERO
#define ISECT_HI F24_ONE
#endif

isect_result isect_unit_triangle(f24_vec3 o, f24_vec3 d, f24_t tmin, f24_t tmax)
{
    isect_result r;
    r.cos_n = d.z;
    r.t = f24_div(f24_neg(o.z), d.z);
    r.u = f24_add(o.x, f24_mul(r.t, d.x));
    r.v = f24_add(o.y, f24_mul(r.t, d.y));
    const f24_t uv = f24_add(r.u, r.v);
    r.hit = f24_le(ISECT_LO, r.u) && f24_le(ISECT_LO, r.v) && f24_le(uv, ISECT_HI) && f24_le(tmin, r.t) &&
            f24_lt(r.t, tmax);
    return r;
}

isect_result isect_unit_transformed(const f24_affine *m, f24_vec3 o, f24_vec3 d, f24_t tmin, f24_t tmax)
{
    const f24_t oz = xform_row(m->m[2], o, 1), dz = xform_row(m->m[2], d, 0);
    const f24_t t = f24_div(f24_neg(oz), dz);
    if (f24_le(tmin, t) && f24_lt(t, tmax))
        return isect_unit_triangle(xform_point(m, o), xform_vector(m, d), tmin, tmax);
    const isect_result miss = { 0, t, F24_ZERO, F24_ZERO, dz };
    return miss;
}
