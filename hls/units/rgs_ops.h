/*
 * Operations of the RGS's shading (hls/units/rgs.c, docs/shading.md) that live outside rgs.c so
 * that the RTL co-simulation (rtl/tb/tb_shade.cpp) can call them and the unit capture
 * (tb/cli/capture.c) can wrap them: the integer colour arithmetic in Q12 (4096 = 1.0, saturating
 * at 65535), the fp24 vector helpers, the barycentric interpolation and the frame of a hit
 * (hls/units/rgs_geom.c), a light's
 * weights and shadow rays (hls/units/rgs_light.c), the child rays (hls/units/rgs_spawn.c), the
 * bilinear texture sample
 * (hls/units/rgs_tex.c).
 */
#ifndef SAARCOR_RGS_OPS_H
#define SAARCOR_RGS_OPS_H

#include "rgs.h"

#define RGS_Q12_MAX 65535u

/* material words (docs/memory-image.md): the index of refraction, the shader words kd | kr << 13 |
 * k << 26 and kt | ks << 13 */
enum { M_ETA = 13, M_SHADER0 = 14, M_SHADER1 = 15 };

static inline uint32_t q_sat(uint32_t x) { return x < RGS_Q12_MAX ? x : RGS_Q12_MAX; }
static inline uint32_t q_mul(uint32_t a, uint32_t b) { return q_sat((a * b + 2048u) >> 12); }
static inline uint32_t q_add(uint32_t a, uint32_t b) { return q_sat(a + b); }
static inline uint32_t q_byte(uint32_t t) { return (t << 4) | (t >> 4); } /* 8-bit -> Q12, 255 -> 4095 */

/* The shading's operations compute on working values (f24w, f24.h: bit-identical to the fp24
 * operators; decoded once in the simulator's fast build) and store only their results as fp24:
 * the _w forms take and give working values, the others fp24 (the interfaces the unit capture
 * records). */

/* num / den (the constants of shading: 1/2). */
static inline f24w rgs_ratio_w(int32_t num, int32_t den) { return f24w_div(f24w_from_i32(num), f24w_from_i32(den)); }
static inline f24_t rgs_ratio(int32_t num, int32_t den) { return f24w_bits(rgs_ratio_w(num, den)); }

/* fp24 -> Q12: one multiplier, one adder, the float-to-int converter; clamps to [0, 65535]
 * (hls/units/rgs_geom.c: one definition, so that the operators count once). */
uint32_t rgs_q_of_w(f24w x);
uint32_t rgs_q_of(f24_t x);

/* fp24 vectors: the dot product ((x y + x y) + z z, f24w_dot3), a negated vector, a difference,
 * the length (rgs_geom.c). */
f24_t rgs_dot3(f24_vec3 a, f24_vec3 b);
static inline f24_vec3 neg3(f24_vec3 a) { return (f24_vec3){ f24_neg(a.x), f24_neg(a.y), f24_neg(a.z) }; }
static inline f24w_vec3 neg3_w(f24w_vec3 a) { return (f24w_vec3){ f24w_neg(a.x), f24w_neg(a.y), f24w_neg(a.z) }; }
static inline f24w_vec3 sub3_w(f24w_vec3 a, f24w_vec3 b)
{
    return (f24w_vec3){ f24w_sub(a.x, b.x), f24w_sub(a.y, b.y), f24w_sub(a.z, b.z) };
}
f24w rgs_length3_w(f24w_vec3 a);
f24_t rgs_length3(f24_vec3 a);

/* T_R = [D^, N^, D^; O]: the transformation of every secondary ray of a hit. */
static inline f24_affine t_r(f24_vec3 o, f24_vec3 d, f24_vec3 n)
{
    const f24_affine m = { { { d.x, n.x, d.x, o.x }, { d.y, n.y, d.y, o.y }, { d.z, n.z, d.z, o.z } } };
    return m;
}

/* u A + v B + (1 - u - v) C: a component of the hit's interpolated vertex normal or texture
 * coordinates (barycentrics u, v). */
f24_t rgs_lerp(f24_t a, f24_t b, f24_t c, f24_t u, f24_t v);
/* The hit's interpolated vertex normal: rgs_lerp of each component of the three decoded normals
 * (n[c][k]: component c of normal k, shade_rec_normals), the products of a component side by side
 * (lanes: the weights u, v, 1 - u - v), then their sum in rgs_lerp's order. */
f24_vec3 rgs_lerp_normal(const f24_t n[3][F24Q_LANES], f24_t u, f24_t v);

/* The frame of a hit of the ray (o, d) at distance t: into sf the unit direction d, the unit shading
 * normal (object-space normal n through the transposed 3x3 of the world-to-object matrix w2o,
 * turned towards the ray), entering (the sign of the hit's cos_n), t_hat = t |d|, T_R and the hit
 * point P = T_R (0, 0, t_hat). */
void rgs_surface_frame(f24_vec3 o, f24_vec3 d, f24_t t, f24_t cos_n, f24_vec3 n, const f24_affine *w2o, surface *sf);

/* Diffuse and highlight weights of light l (its 16-word record) at the packet's surfaces and the
 * shadow packet that tests them (hls/units/rgs_light.c); rays whose weights are zero are not
 * traced. k_of: the surfaces' highlight exponents (cos^(2^k)). */
void rgs_light_packet(const uint32_t *l, const surface sf[], f24_t eps, ray_packet *sh, uint32_t diff[], uint32_t spec[],
                      const uint32_t k_of[]);

/* Light colour (the record's words 1..3) scaled to a maximum component of one, in Q12. */
void rgs_light_colour(const uint32_t *l, uint32_t out[3]);

/* The light of a visible light source added to a ray's Q12 diffuse and highlight sums: its
 * weights diff and spec times the light's colour. */
void rgs_add_light(uint32_t diffuse[3], uint32_t highlight[3], uint32_t diff, uint32_t spec, const uint32_t colour[3]);

/* The child rays of surface sf (ray i of the packet; m: its material record, weight: the ray's Q12
 * weight, eps: the ray offset e) into refl and trans: reflection (weight kr tint) and transmission
 * (weight kt base; refraction, straight transparency for eta = 1, or reflection on total internal
 * reflection), each active if its largest weight component is at least 16 (hls/units/rgs_spawn.c). */
void rgs_spawn_children(const uint32_t *m, const uint32_t weight[3], f24_t eps, int i, const surface *sf,
                        rgs_task *refl, rgs_task *trans);

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
