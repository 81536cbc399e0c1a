/* Unit-triangle intersection unit: see isect_unit.h. */
#include "isect_unit.h"

#include "xform_unit.h"

#ifdef F24_SIM_LANES
#define isect_unit_packet isect_unit_packet_exact /* the simulation build's proves misses first (isect_unit.h) */
#endif

#define F24_ZERO 0u

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

/* One row of M^-1 (its first three words, the lanes of mr) times the vector v, xform_row's order
 * and roundings ((m0 x + m1 y) + m2 z), one lane per ray. */
F24Q_INLINE f24q packet_row(f24q mr, const f24q v[3])
{
    return f24q_add(f24q_add(f24q_mul(f24q_broadcast(mr, 0), v[0]), f24q_mul(f24q_broadcast(mr, 1), v[1])),
                    f24q_mul(f24q_broadcast(mr, 2), v[2]));
}

/* isect_unit_rebased's operations, one lane per ray, every lane through the whole test (also the
 * x/y rows that function skips for a ray outside [tmin, tmax): selects give its miss fields),
 * unless no ray lies within [tmin, tmax], where the packet skips them as that function does. The
 * lanes outside need compute on zeros: none of their inputs is read. A single ray takes the lanes
 * too: its early-out in isect_unit_rebased once cost less than four lanes (plants: 1.2 rays a
 * test), but no longer does (callgrind, render_region, 1 thread: plants 128x96 118,245 -> 114,997,
 * bunny.glb primary 256x192 17,526 -> 16,766, room 256x192 49,237 -> 49,007 Ir/px). */
F24Q_FN void isect_unit_packet(const f24_triangle *tri, uint32_t need, const f24_vec3x2 p[F24Q_LANES],
                               const f24_t te[F24Q_LANES], const f24_vec3 d[F24Q_LANES], const f24_t tmin[F24Q_LANES],
                               const f24_t tmax[F24Q_LANES], isect_result r[F24Q_LANES])
{
    const f24_t(*m)[4] = tri->m.m;
    const f24_t c_lo[F24Q_LANES] = { tri->c_lo.x, tri->c_lo.y, tri->c_lo.z, 0 };
    /* the triangle's words as lanes, each operand of the per-ray datapaths one of them broadcast */
    const f24q mq[3] = { f24q_of(m[0]), f24q_of(m[1]), f24q_of(m[2]) }, c_loq = f24q_of(c_lo);
    f24_t hi[3][F24Q_LANES], lo[3][F24Q_LANES], dir[3][F24Q_LANES], te_l[F24Q_LANES], tmin_l[F24Q_LANES],
        tmax_l[F24Q_LANES];
packet_lanes:
    for (int i = 0; i < F24Q_LANES; i++) {
        const int on = need >> i & 1u;
        const f24_vec3 none = { 0, 0, 0 }, ph = on ? p[i].hi : none, pl = on ? p[i].lo : none, di = on ? d[i] : none;
        hi[0][i] = ph.x, hi[1][i] = ph.y, hi[2][i] = ph.z;
        lo[0][i] = pl.x, lo[1][i] = pl.y, lo[2][i] = pl.z;
        dir[0][i] = di.x, dir[1][i] = di.y, dir[2][i] = di.z;
        te_l[i] = on ? te[i] : 0;
        tmin_l[i] = on ? tmin[i] : 0;
        tmax_l[i] = on ? tmax[i] : 0;
    }
    /* offset_from_vertex per component, and plane_distance's nine terms per lane */
    f24q c[3], dq[3], a[9], b[9];
packet_offset:
    for (int k = 0; k < 3; k++) {
        const f24q l = f24q_sub(f24q_of(lo[k]), f24q_broadcast(c_loq, k)), h = f24q_of(hi[k]);
        c[k] = f24q_add(f24q_sub(h, f24q_broadcast(mq[k], 3)), l);
        dq[k] = f24q_of(dir[k]);
        a[k] = a[3 + k] = a[6 + k] = f24q_broadcast(mq[2], k);
        b[k] = h;
        b[3 + k] = f24q_splat(f24_neg(m[k][3]));
        b[6 + k] = l;
    }
    f24_t oz[F24Q_LANES], neg_oz[F24Q_LANES];
    f24q_sum_exact_hi(a, b, 9, oz); /* plane_distance: the high word alone */
packet_neg:
    for (int i = 0; i < F24Q_LANES; i++)
        neg_oz[i] = f24_neg(oz[i]);
    /* rows of M^-1, xform_row's order and roundings ((m0 x + m1 y) + m2 z): the direction's z row,
     * then for isect_unit_triangle the x and y rows of origin_from and of the direction */
    const f24q *const vec[5] = { dq, c, c, dq, dq };
    const uint32_t row[5] = { 2, 0, 1, 0, 1 };
    f24q rows[5];
    rows[0] = packet_row(mq[row[0]], vec[0]);
    const f24q dz = rows[0], tl = f24q_div(f24q_of(neg_oz), dz), t = f24q_add(f24q_of(te_l), tl);
    const uint32_t in = f24q_le(f24q_of(tmin_l), t) & f24q_lt(t, f24q_of(tmax_l));
    f24_t tb[F24Q_LANES], ub[F24Q_LANES] = { 0 }, vb[F24Q_LANES] = { 0 }, cb[F24Q_LANES];
    f24q_bits(t, tb);
    f24q_bits(dz, cb);
    uint32_t hit = 0;
    if (in & need) { /* else every lane misses with the fields isect_unit_rebased gives: no x/y rows */
    packet_rows:
        for (int j = 1; j < 5; j++)
            rows[j] = packet_row(mq[row[j]], vec[j]);
        const f24q u = f24q_add(rows[1], f24q_mul(tl, rows[3])), v = f24q_add(rows[2], f24q_mul(tl, rows[4]));
        const f24_t lo_b = ISECT_LO(SAARCOR_CFG_EDGE_EPS), lo_s = ISECT_LO(ISECT_SHARED_K);
        const f24_t hi_b = ISECT_HI(SAARCOR_CFG_EDGE_EPS), hi_s = ISECT_HI(ISECT_SHARED_K);
        const uint32_t shared = tri->shared;
        hit = in & f24q_le(f24q_splat(shared & TRI_SHARED_U ? lo_s : lo_b), u) &
              f24q_le(f24q_splat(shared & TRI_SHARED_V ? lo_s : lo_b), v) &
              f24q_le(f24q_add(u, v), f24q_splat(shared & TRI_SHARED_W ? hi_s : hi_b));
        f24q_bits(u, ub);
        f24q_bits(v, vb);
    }
packet_results:
    for (int i = 0; i < F24Q_LANES; i++) {
        const int on = need >> i & 1u, full = in >> i & 1u;
        const isect_result ri = { (int)(hit >> i & 1u), tb[i], full ? ub[i] : F24_ZERO, full ? vb[i] : F24_ZERO, cb[i] },
                           none = { 0, 0, 0, 0, 0 };
        r[i] = on ? ri : none;
    }
}
