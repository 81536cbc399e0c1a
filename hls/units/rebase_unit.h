/*
 * Rebase unit: moves each ray's object-space origin to where it enters the current leaf, before
 * the leaf's triangles are tested (saarcor's accuracy datapath; the paper has none, docs/numerics.md).
 *
 * Why: the intersection unit works in each triangle's unit-triangle space, where a triangle of
 * size s is 1 and a ray origin at distance d is d/s away. u = O'x + t D'x then cancels log2(d/s)
 * of fp24's M+1 bits: small triangles seen from afar (dense meshes, small instances) lose their
 * barycentrics and let rays through closed meshes. Moved to the leaf entry, the origin is about a
 * leaf (a few triangles) away from every triangle it meets, and the hit distance is
 * t = t_entry + t' with t' as short as the leaf.
 * The origin moves in double words, exactly: p = o + t_entry d with o and d the object-space ray
 * in double words (the transformation unit's wide mode) and each component one f24_sum_exact of
 * four terms (o.hi, o.lo, t d.hi, t d.lo). The intersection unit takes p in double words
 * (isect_unit.h).
 * Datapath: per component 2 multipliers whose products are not rounded and one 4-term exact
 * accumulator: 6 multipliers, 3 accumulators. One ray per cycle, when the list unit opens a leaf
 * (one issue slot per ray of the leaf on the list unit, trace.c). RTL: rtl/rebase_unit.sv, three
 * pipelined exact accumulators (rtl/f24_sum_exact.sv, N = 4) with te beside them: latency 25
 * cycles (SUM_STAGES), one ray per cycle, co-simulated bit for bit by rtl/tb/tb_wide.cpp. The
 * cycle model counts its issue slots on the list unit and no latency of its own
 * (docs/cycle-model.md).
 */
#ifndef SAARCOR_REBASE_UNIT_H
#define SAARCOR_REBASE_UNIT_H

#include "vec3.h"

/* o + t d per component, exact up to the double word's rounding. A t that is not finite (a ray
 * with no entry distance) moves nothing: t = 0. */
f24_vec3x2 rebase_origin(f24_vec3x2 o, f24_vec3x2 d, f24_t t);

/* The distance rebase_origin moved by for entry distance t (0 for t not finite). */
f24_t rebase_distance(f24_t t);

/* The rays of mask rays (of a packet's F24Q_LANES) one after the other, as the list unit issues
 * them when it opens a leaf: p = rebase_origin((o, o_lo), (d, d_lo), t), te = rebase_distance(t).
 * The other rays' outputs are untouched. */
void rebase_rays(uint32_t rays, const f24_vec3 o[], const f24_vec3 o_lo[], const f24_vec3 d[], const f24_vec3 d_lo[],
                 const f24_t t[], f24_vec3x2 p[], f24_t te[]);
#ifdef F24_SIM_LANES
/* The simulation build with vector packet values computes them side by side (tb/sim/wide_lanes.c,
 * the same bits); the per-ray one, the truth, then keeps this name for the test comparing them. */
void rebase_rays_per_ray(uint32_t rays, const f24_vec3 o[], const f24_vec3 o_lo[], const f24_vec3 d[],
                         const f24_vec3 d_lo[], const f24_t t[], f24_vec3x2 p[], f24_t te[]);
#endif

#endif
