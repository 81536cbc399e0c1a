/*
 * Transformation unit (paper sections 2.1, 2.2 and 3, Figure 2: paths a, d, e; Table 2:
 * 9 adders, 9 multipliers).
 *
 * One affine map per step: three rows, each m0*x + m1*y + m2*z (+ t). A point (ray origin)
 * takes the translation, a vector (ray direction) does not: the translation adder is bypassed,
 * not fed with zero, so that a -0 result keeps its sign. The summation order is fixed and part
 * of the contract with the RTL: ((m0*x + m1*y) + m2*z) + t.
 * Datapath: 9 fp24 multipliers, 6 adders for the dot products and 3 for the translation;
 * pipelined, one step per cycle. A ray entering an instance takes two steps (its rebased origin,
 * its direction: rebased origins are per ray, so a packet's rays no longer share the origin step);
 * a ray meeting a triangle takes one (its direction; the intersection unit transforms the origin).
 * Latency 22 cycles (rtl/xform_unit.sv: multiplier 4 + three adders 6; the cycle model's default,
 * docs/cycle-model.md), throughput one step per cycle; docs/synth.md: 6653 LUTs, 9 DSP at e7m16.
 * Its users: the core's operations op_inst_xform (an instance, path d, in the wide mode below)
 * and op_tri_xform (a triangle's directions, path e) in trace.c, the RGS's ray generation (rgs.c,
 * path a).
 */
#ifndef SAARCOR_XFORM_UNIT_H
#define SAARCOR_XFORM_UNIT_H

#include "vec3.h"

/* One row of the map: ((m0*x + m1*y) + m2*z), plus t when with_translation. */
f24_t xform_row(const f24_t row[4], f24_vec3 p, int with_translation);

f24_vec3 xform_point(const f24_affine *m, f24_vec3 p);
f24_vec3 xform_vector(const f24_affine *m, f24_vec3 v);

/* The wide mode (instances, path d): each row's products exact and summed once into a double word
 * (f24_sum_exact), so that object-space rays keep about 2(M+1) bits wherever they go: a point p in
 * double words with the translation in two words, m's column 3 and tlo (the instance record's low
 * words), a vector without. Hardware: the multipliers skip rounding and per row one 128-bit
 * accumulator of 8 terms takes the place of the three adders; a point in double words takes the
 * unit's 9 multipliers twice (docs/numerics.md). RTL: rtl/xform_wide.sv, a module of its own with
 * all 24 products in one pass (three f24_sum_exact of 8 terms; a vector's 5 other terms -0 * +0,
 * which leave the 3-term sum's bits as they are): latency 25 cycles, one point or vector per cycle,
 * co-simulated by rtl/tb/tb_wide.cpp. */
f24_vec3x2 xform_point_wide(const f24_affine *m, f24_vec3 tlo, f24_vec3x2 p);
f24_vec3x2 xform_vector_wide(const f24_affine *m, f24_vec3 v);

/* The rays of mask rays (of a packet's F24Q_LANES) into an instance's object space, one after the
 * other as the unit takes them (the core's op_inst_xform, path d): each ray's origin o moved to
 * where it enters the top-level leaf, t0 = rebase_distance(tn) (the rebase unit in front), then
 * the origin through xform_point_wide (translation low words t_lo) and the direction through
 * xform_vector_wide, into o_hi/o_lo, d_hi/d_lo and t0. The other rays' outputs are untouched. */
void xform_enter_rays(const f24_affine *w2o, f24_vec3 t_lo, uint32_t rays, const f24_vec3 o[], const f24_vec3 d[],
                      const f24_t tn[], f24_vec3 o_hi[], f24_vec3 o_lo[], f24_vec3 d_hi[], f24_vec3 d_lo[], f24_t t0[]);
#ifdef F24_SIM_LANES
/* A simulation build with vector packet values computes the rays of xform_enter_rays side by side
 * (tb/sim/wide_lanes.c: its own definition of that name, the same bits); the per-ray one here, the
 * truth, then keeps this name, for the test that compares the two. */
void xform_enter_rays_per_ray(const f24_affine *w2o, f24_vec3 t_lo, uint32_t rays, const f24_vec3 o[],
                              const f24_vec3 d[], const f24_t tn[], f24_vec3 o_hi[], f24_vec3 o_lo[], f24_vec3 d_hi[],
                              f24_vec3 d_lo[], f24_t t0[]);
#endif

/* What xform_point (point != 0) or xform_vector compute, bit for bit, for a map m that is the
 * identity up to the signs of its zeros (1 on the diagonal, +-0 elsewhere), without an
 * arithmetic operator: a nonzero component passes through; a zero one is the sum of zero
 * products (and the translation), -0 only if all of them are -0; a row that multiplies Inf or NaN
 * by 0 is NaN. In hardware: sign logic and muxes (the profile's identity path, trace.h). */
f24_vec3 xform_identity(const f24_affine *m, f24_vec3 v, int point);

/* 1 if m is the identity up to the signs of its zeros. */
int xform_is_identity(const f24_affine *m);

#endif
