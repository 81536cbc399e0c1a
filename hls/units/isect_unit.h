/*
 * Unit-triangle intersection unit (paper section 2.1, Figure 2: path e, results back on path f;
 * Table 2: 3 adders, 2 multipliers, 1 divider; saarcor adds the origin path below).
 *
 * The ray is taken into the space where the triangle is (1,0,0), (0,1,0), (0,0,0) and its normal
 * is (0,0,1): its direction by the transformation unit (xform_unit), its origin here, from the
 * origin the rebase unit moved to the leaf entry te (double words, rebase_unit.h) and the
 * triangle's vertex C (isect_origin; docs/numerics.md says why). Then
 *   t' = -O'z / D'z,  t = te + t',  u = O'x + t' D'x,  v = O'y + t' D'y,
 *   hit when u >= 0, v >= 0, u + v <= 1 and tmin <= t < tmax.
 * u is the barycentric weight of vertex A, v of B; D'z is the cosine between the ray direction
 * and the normal (times the direction's length) for shading, for free.
 * Edge cases, by the fp24 rules (docs/fp24.md): a ray parallel to the plane (D'z = 0) gives
 * t = +-Inf or NaN and misses, because no comparison with NaN or with a finite tmax succeeds;
 * edges and vertices (u = 0, v = 0 or u + v = 1 exactly) are hits, so neighbouring triangles
 * sharing an edge cannot both miss a ray that meets the edge in exact arithmetic; an origin on
 * the plane gives t = +-0, a hit if tmin <= 0 (secondary rays use tmin > 0 against acne).
 * In fp24 the two triangles round u and v independently, so a ray through their shared edge can
 * miss both by an ulp: the bounds on edges the host flagged as shared (TRI_SHARED_*, vec3.h) are
 * widened by 2^-SAARCOR_CFG_SHARED_EDGE_EPS (default one ulp at 1), the others stay exact so
 * silhouettes do not move (the robust option SAARCOR_CFG_EDGE_EPS widens all; docs/stress.md).
 * Datapath: the test is 1 divider, 2 multipliers, 4 adders (u, v, u+v, te + t'), 5 comparators
 * (rtl/isect_unit.sv); the origin path 9 adders (the offset from C in double words), 6
 * multipliers and 4 adders (rows 0 and 1 of M^-1), 9 unrounded products into one exact
 * accumulator (row 2); rays are intersected one at a time.
 * Latency 29 cycles for the test (rtl/isect_unit.sv: divider 11 + multiplier 4 + two adders 6 +
 * comparator 2; the cycle model's default, docs/cycle-model.md), throughput one ray per cycle (one
 * issue slot per ray); docs/synth.md has the test's area. The core's operation on it is
 * op_tri_isect in trace.c (closest hits per ray, any-hit for shadow packets).
 */
#ifndef SAARCOR_ISECT_UNIT_H
#define SAARCOR_ISECT_UNIT_H

#include "config.h"
#include "vec3.h"

/* The barycentric bounds -eps and 1 + eps for eps = 2^-k (k = 0: 0 and 1). Constants, so the
 * margins cost no operator and no cycle: only the comparators' constant inputs change, chosen per
 * bound by the triangle's shared-edge flag. */
#define ISECT_LO(k) ((k) > 0 ? F24_SIGN_BIT | (uint32_t)(F24_BIAS - (k)) << F24_MAN_BITS : 0u)
#define ISECT_HI(k) ((k) > 0 ? F24_ONE | 1u << (F24_MAN_BITS - (k)) : F24_ONE)
/* A shared edge takes the wider of its own margin and the robust option's (0 is no margin), so
 * its bounds are the widest of the unit's. */
#define ISECT_SHARED_K                                                                                 \
    (SAARCOR_CFG_EDGE_EPS > 0 &&                                                                       \
             (SAARCOR_CFG_SHARED_EDGE_EPS == 0 || SAARCOR_CFG_EDGE_EPS < SAARCOR_CFG_SHARED_EDGE_EPS) \
         ? SAARCOR_CFG_EDGE_EPS                                                                        \
         : SAARCOR_CFG_SHARED_EDGE_EPS)

typedef struct {
    int hit;
    f24_t t, u, v;
    f24_t cos_n; /* D'z */
} isect_result;

/* The test on a ray in unit-triangle space whose origin o lies at distance te along the ray (the
 * rebase unit moved it there): t' = -O'z / D'z from o, and the hit distance t = te + t'; shared:
 * the triangle's shared-edge flags (TRI_SHARED_*). */
isect_result isect_unit_triangle(f24_vec3 o, f24_vec3 d, f24_t te, f24_t tmin, f24_t tmax, uint32_t shared);

/* The ray origin p (double words, object space, rebased to a leaf) in unit-triangle space: the
 * offset from the triangle's vertex C (double words in the triangle record, docs/memory-image.md),
 * (p.hi - C.hi) + (p.lo - C.lo) per component, through rows 0 and 1 of M^-1; row 2, the unit
 * normal, from exact products summed once (f24_sum_exact of 9 terms), so that O'z is the origin's
 * distance from the plane to fp24's precision even where the origin is far from C on a large
 * triangle. p.hi and C.hi lie within a leaf of each other or C lies on a triangle as large as the
 * offset, so u and v keep their bits. */
f24_vec3 isect_origin(const f24_triangle *tri, f24_vec3x2 p);

/* A triangle's whole test (path e) on one ray: the origin p (rebased to entry distance te, in
 * double words) through isect_origin,
 * the direction d through M^-1 (the transformation unit's part), then isect_unit_triangle. A ray
 * whose distance lies outside [tmin, tmax) misses whatever u and v are, so only the z rows are
 * computed for it: the hit flag, and for hits every field, equal those of the full test at about
 * a third of the arithmetic (the simulator's saving; a hardware unit may gate its x/y rows alike). */
isect_result isect_unit_rebased(const f24_triangle *tri, f24_vec3x2 p, f24_t te, f24_vec3 d, f24_t tmin, f24_t tmax);

/* isect_unit_rebased on the rays of a packet that need the triangle (bit i of need: lane i), bit
 * for bit: r[i] for each of them, zeros for the others. The simulator's form of the unit's stream
 * of rays (one per cycle): the lanes side by side (f24q), branch-free. */
void isect_unit_packet(const f24_triangle *tri, uint32_t need, const f24_vec3x2 p[F24Q_LANES], const f24_t te[F24Q_LANES],
                       const f24_vec3 d[F24Q_LANES], const f24_t tmin[F24Q_LANES], const f24_t tmax[F24Q_LANES],
                       isect_result r[F24Q_LANES]);
#ifdef F24_SIM_LANES
/* A simulation build with vector packet values first tries to prove in binary64 that every needed
 * ray misses (tb/sim/isect_lanes.c: its own definition of isect_unit_packet); only the hit flags
 * and, for hits, the fields are then those of the one-ray function: a proven miss gives zeros,
 * which nothing reads (op_tri_isect reads a ray's fields only on a hit; the capture build records
 * the one-ray function). The exact packet function keeps this name, the fallback and the truth
 * for the test comparing them. */
void isect_unit_packet_exact(const f24_triangle *tri, uint32_t need, const f24_vec3x2 p[F24Q_LANES],
                             const f24_t te[F24Q_LANES], const f24_vec3 d[F24Q_LANES], const f24_t tmin[F24Q_LANES],
                             const f24_t tmax[F24Q_LANES], isect_result r[F24Q_LANES]);
/* The rays of need (bit i: lane i) the binary64 test proves to miss: for each of them
 * isect_unit_packet_exact's hit flag is 0. The other lanes' words are not used. */
uint32_t isect_packet_proven_misses(const f24_triangle *tri, uint32_t need, const f24_vec3x2 p[F24Q_LANES],
                                    const f24_t te[F24Q_LANES], const f24_vec3 d[F24Q_LANES],
                                    const f24_t tmin[F24Q_LANES], const f24_t tmax[F24Q_LANES]);
#endif

#endif
