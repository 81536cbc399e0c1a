/*
 * Operations of the RGS's shading (hls/units/rgs.c, docs/shading.md) that live outside rgs.c so
 * that the RTL co-simulation (rtl/tb/tb_shade.cpp) can call them and the unit capture
 * (tb/cli/capture.c) can wrap them: the integer colour arithmetic in Q12 (4096 = 1.0, saturating
 * at 65535) and the bilinear texture sample (hls/units/rgs_tex.c).
 */
#ifndef SAARCOR_RGS_OPS_H
#define SAARCOR_RGS_OPS_H

#include "trace.h"

#define RGS_Q12_MAX 65535u

static inline uint32_t q_sat(uint32_t x) { return x < RGS_Q12_MAX ? x : RGS_Q12_MAX; }
static inline uint32_t q_mul(uint32_t a, uint32_t b) { return q_sat((a * b + 2048u) >> 12); }
static inline uint32_t q_add(uint32_t a, uint32_t b) { return q_sat(a + b); }
static inline uint32_t q_byte(uint32_t t) { return (t << 4) | (t >> 4); } /* 8-bit -> Q12, 255 -> 4095 */

/* num / den in fp24 (the constants of shading: 1/2). */
static inline f24_t rgs_ratio(int32_t num, int32_t den) { return f24_div(f24_from_i32(num), f24_from_i32(den)); }

/* Texel coordinate of texture coordinate s over n texels (1 <= n < 2^31; centres at +1/2): the
 * wrapped integer part i0, its right neighbour i1 and the fraction in Q8 (0..256). */
void rgs_texel_axis(f24_t s, uint32_t n, uint32_t *i0, uint32_t *i1, uint32_t *frac);

/* The bilinear blend (Q12 per channel R, G, B) of the texel words t00, t10, t01, t11 (bytes R, G,
 * B from bit 0 up) with the fractions fx, fy in Q8. */
void rgs_bilinear_blend(const uint32_t texel[4], uint32_t fx, uint32_t fy, uint32_t out[3]);

/* Bilinear sample (Q12) of texture entry tex (width, height, texel address) at (s, t): the two
 * axes, the 4 texel reads (noted in op), the blend. */
void rgs_sample_bilinear(const uint32_t *mem, const uint32_t *tex, f24_t s, f24_t t, uint32_t out[3], unit_op *op,
                         trace_counters *c);

#endif
