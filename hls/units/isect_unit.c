/* Unit-triangle intersection unit: see isect_unit.h. */
#include "isect_unit.h"

#include "config.h"
#include "xform_unit.h"

#define F24_ZERO 0u

/* The barycentric bounds -eps and 1 + eps for eps = 2^-k (k = 0: 0 and 1). Constants, so the
 * margins cost no operator and no cycle: only the comparators' constant inputs change, chosen per
 * bound by the triangle's shared-edge flag. */
#define ISECT_LO(k) ((k) > 0 ? F24_SIGN_BIT | (uint32_t)(F24_BIAS - (k)) << F24_MAN_BITS : F24_ZERO)
#define ISECT_HI(k) ((k) > 0 ? F24_ONE | 1u << (F24_MAN_BITS - (k)) : F24_ONE)
/* A shared edge takes the wider of its own margin and the robust option's (0 is no margin). */
#define ISECT_SHARED_K                                                                                 \
    (SAARCOR_CFG_EDGE_EPS > 0 &&                                                                       \
             (SAARCOR_CFG_SHARED_EDGE_EPS == 0 || SAARCOR_CFG_EDGE_EPS < SAARCOR_CFG_SHARED_EDGE_EPS) \
         ? SAARCOR_CFG_EDGE_EPS                                                                        \
         : SAARCOR_CFG_SHARED_EDGE_EPS)
#if SAARCOR_CFG_EDGE_EPS < 0 || SAARCOR_CFG_EDGE_EPS > F24_MAN_BITS || SAARCOR_CFG_EDGE_EPS >= F24_BIAS
#error "SAARCOR_CFG_EDGE_EPS must be 0 or in 1 .. min(F24_MAN_BITS, bias - 1)"
#endif
#if SAARCOR_CFG_SHARED_EDGE_EPS < 0 || SAARCOR_CFG_SHARED_EDGE_EPS > F24_MAN_BITS || SAARCOR_CFG_SHARED_EDGE_EPS >= F24_BIAS
#error "SAARCOR_CFG_SHARED_EDGE_EPS must be 0 or in 1 .. min(F24_MAN_BITS, bias - 1)"
#endif

/* A bound's constant: the widened one if the triangle flags its edge as shared. */
static f24w bound(uint32_t shared, uint32_t flag, f24_t plain, f24_t widened)
{
    return f24w_of(shared & flag ? widened : plain);
}

isect_result isect_unit_triangle(f24_vec3 o, f24_vec3 d, f24_t te, f24_t tmin, f24_t tmax, uint32_t shared)
{
    const f24w tl = f24w_div(f24w_neg(f24w_of(o.z)), f24w_of(d.z)); /* from the rebased origin */
    const f24w t = f24w_add(f24w_of(te), tl), u = f24w_add(f24w_of(o.x), f24w_mul(tl, f24w_of(d.x))),
               v = f24w_add(f24w_of(o.y), f24w_mul(tl, f24w_of(d.y)));
    const f24_t lo = ISECT_LO(SAARCOR_CFG_EDGE_EPS), lo_s = ISECT_LO(ISECT_SHARED_K);
    const f24_t hi = ISECT_HI(SAARCOR_CFG_EDGE_EPS), hi_s = ISECT_HI(ISECT_SHARED_K);
    isect_result r;
    r.cos_n = d.z;
    r.t = f24w_bits(t);
    r.u = f24w_bits(u);
    r.v = f24w_bits(v);
    r.hit = f24w_le(bound(shared, TRI_SHARED_U, lo, lo_s), u) && f24w_le(bound(shared, TRI_SHARED_V, lo, lo_s), v) &&
            f24w_le(f24w_add(u, v), bound(shared, TRI_SHARED_W, hi, hi_s)) && f24w_le(f24w_of(tmin), t) &&
            f24w_lt(t, f24w_of(tmax));
    return r;
}

/* The rebased origin p relative to the vertex C, per component (hi - c_hi) + (lo - c_lo): hi -
 * c_hi is exact or as small as the leaf, and lo - c_lo tiny. The three components side by side
 * (lane 3 unused). */
static F24Q_FN f24_vec3 offset_from_vertex(const f24_triangle *tri, f24_vec3x2 p, f24_vec3 *lo)
{
    const f24_affine *m = &tri->m;
    const f24_t p_hi[4] = { p.hi.x, p.hi.y, p.hi.z, 0 }, p_lo[4] = { p.lo.x, p.lo.y, p.lo.z, 0 },
                c_hi[4] = { m->m[0][3], m->m[1][3], m->m[2][3], 0 }, c_lo[4] = { tri->c_lo.x, tri->c_lo.y, tri->c_lo.z, 0 };
    const f24q l = f24q_sub(f24q_of(p_lo), f24q_of(c_lo));
    f24_t lb[4], cb[4];
    f24q_bits(l, lb);
    f24q_bits(f24q_add(f24q_sub(f24q_of(p_hi), f24q_of(c_hi)), l), cb);
    *lo = (f24_vec3){ lb[0], lb[1], lb[2] };
    return (f24_vec3){ cb[0], cb[1], cb[2] };
}

/* Row 2 of M^-1 is the unit normal n: O'z = n.p.hi - n.C.hi + n.(p.lo - C.lo) from exact products
 * with one rounding, the origin's distance from the plane to fp24's precision however far the
 * origin lies from C along a large triangle (a rounded offset would carry |p - C| 2^-(M+1)). */
static f24_t plane_distance(const f24_triangle *tri, f24_vec3x2 p, f24_vec3 lo)
{
    const f24_t *n = tri->m.m[2];
    const f24_t a[9] = { n[0], n[1], n[2], n[0], n[1], n[2], n[0], n[1], n[2] };
    const f24_t b[9] = { p.hi.x, p.hi.y, p.hi.z,
                         f24_neg(tri->m.m[0][3]), f24_neg(tri->m.m[1][3]), f24_neg(tri->m.m[2][3]),
                         lo.x, lo.y, lo.z };
    return f24_sum_exact(a, b, 9).hi;
}

/* O' from the offset c to the vertex and the plane distance oz: rows 0 and 1 of M^-1, then oz. */
static f24_vec3 origin_from(const f24_triangle *tri, f24_vec3 c, f24_t oz)
{
    const f24_vec3 o = { xform_row(tri->m.m[0], c, 0), xform_row(tri->m.m[1], c, 0), oz };
    return o;
}

f24_vec3 isect_origin(const f24_triangle *tri, f24_vec3x2 p)
{
    f24_vec3 lo;
    const f24_vec3 c = offset_from_vertex(tri, p, &lo);
    return origin_from(tri, c, plane_distance(tri, p, lo));
}

isect_result isect_unit_rebased(const f24_triangle *tri, f24_vec3x2 p, f24_t te, f24_vec3 d, f24_t tmin, f24_t tmax)
{
    f24_vec3 lo;
    const f24_vec3 c = offset_from_vertex(tri, p, &lo);
    const f24_t oz = plane_distance(tri, p, lo), dz = xform_row(tri->m.m[2], d, 0);
    const f24w tw = f24w_add(f24w_of(te), f24w_div(f24w_neg(f24w_of(oz)), f24w_of(dz)));
    const f24_t t = f24w_bits(tw);
    if (f24w_le(f24w_of(tmin), tw) && f24w_lt(tw, f24w_of(tmax)))
        return isect_unit_triangle(origin_from(tri, c, oz), xform_vector(&tri->m, d), te, tmin, tmax, tri->shared);
    const isect_result miss = { 0, t, F24_ZERO, F24_ZERO, dz };
    return miss;
}
