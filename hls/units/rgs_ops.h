/*
 * Operations of the RGS's shading (hls/units/rgs.c, docs/shading.md) that live outside rgs.c so
 * that the RTL co-simulation (rtl/tb/tb_shade.cpp) can call them and the unit capture
 * (tb/cli/capture.c) can wrap them: the integer colour arithmetic in Q12 (4096 = 1.0, saturating
 * at 65535), the fp24 vector helpers, the barycentric interpolation and the frame of a hit
 * (hls/units/rgs_geom.c), the surface at a hit (hls/units/rgs_surface.c), a light's
 * weights and shadow rays (hls/units/rgs_light.c), the child rays (hls/units/rgs_spawn.c), the
 * bilinear texture sample
 * (hls/units/rgs_tex.c).
 */
#ifndef SAARCOR_RGS_OPS_H
#define SAARCOR_RGS_OPS_H

#include "rgs.h"
#include "trace_ops.h"

#define RGS_Q12_MAX 65535u
#define RGS_Q12_DIFFUSE 3482u /* 0.85: the weight of a light's diffuse term */

/* material words (docs/memory-image.md): the index of refraction, the shader words kd | kr << 13 |
 * k << 26 and kt | ks << 13 */
enum { M_ETA = 13, M_SHADER0 = 14, M_SHADER1 = 15 };

/* Material shader words (docs/memory-image.md): kd | kr << 13 | k << 26 and kt | ks << 13. */
static inline uint32_t rgs_mat_kd(const uint32_t *m) { return m[M_SHADER0] & 0x1FFFu; }
static inline uint32_t rgs_mat_k(const uint32_t *m) { return m[M_SHADER0] >> 26 & 0xFu; }
static inline uint32_t rgs_mat_ks(const uint32_t *m) { return m[M_SHADER1] >> 13 & 0x1FFFu; }

/* The image's words a surface reads (docs/memory-image.md): the header's texture count and region
 * table (start of region r at word H_REGIONS + 2 r), the records' strides and the fields of the
 * object descriptor and the material record that surface_at uses. */
enum {
    H_TEXTURES = 9, H_REGIONS = 18, R_MATERIALS = 1, R_TEXTURES = 2, R_OBJECTS = 5, R_INSTANCES = 8,
    TEX_WORDS = 4, OBJ_WORDS = 16, O_TRIANGLES = 2, O_SHADING = 3, O_FLAGS = 7,
    INST_WORDS = F24_INSTANCE_RECORD_WORDS, TRI_WORDS = F24_TRIANGLE_RECORD_WORDS, MAT_WORDS = 16,
    M_EMISSIVE = 4, M_TEXTURE = 7, M_METALLIC = 10,
};

static inline uint32_t region_start(const uint32_t *mem, uint32_t r) { return mem[H_REGIONS + 2 * r]; }

/* Notes a shading read in op (the shading cache's view) and counts it. */
static inline void shade_read(unit_op *op, trace_counters *c, uint32_t addr, uint32_t words)
{
    op_read(op, c, MEM_SHADING, addr, words);
}

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

/* The surface of ray i of packet rp at its hit h (hls/units/rgs_surface.c): the instance, object
 * descriptor (words 2..7) and shading record reads, the object-space normal (the interpolated
 * decoded vertex normals, or the geometric normal if their squared length is zero), the frame
 * (rgs_surface_frame), the material, its colours (factors, vertex colours, base-colour and emissive
 * textures) and the tint; its reads are noted in op (at most 15, UNIT_OP_READS). An invalid surface
 * (all zero) for an inactive ray or a miss. */
surface rgs_surface_at(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h, unit_op *op,
                       trace_counters *c);
/* rgs_surface_at's steps: the vertex normals of ray i's hit decoded into normals (n[c][k]: component
 * c of normal k, shade_rec_normals) if it is shaded and its object has them (returns 1, else 0);
 * then, with their interpolation vn (rgs_lerp_normal, zero without them) and flat (vn's squared
 * length is zero), everything but the frame: its reads, the object-space normal n (vn, or the
 * geometric normal if flat) and the world-to-object matrix w2o that the frame takes, the material,
 * colours and tint (an invalid surface as rgs_surface_at's). */
int rgs_vertex_normals(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h,
                       f24_t normals[3][F24Q_LANES]);
surface rgs_surface_material(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h, f24_vec3 vn,
                             int flat, f24_vec3 *n, f24_affine *w2o, unit_op *op, trace_counters *c);
/* rgs_surface_at of each ray of packet rp at its hit h[i] into sf[i] (op_surfaces). */
void rgs_surfaces(const uint32_t *mem, const ray_packet *rp, const hit_record h[], surface sf[], unit_op *op,
                  trace_counters *c);
#ifdef F24_SIM_LANES
/* A simulation build with vector packet values computes the packet's frames side by side
 * (tb/sim/rgs_surface_lanes.c, the same bits); the per-ray loop of rgs_surface.c, the truth,
 * then keeps this name, for the test that compares the two. */
void rgs_surfaces_per_ray(const uint32_t *mem, const ray_packet *rp, const hit_record h[], surface sf[], unit_op *op,
                          trace_counters *c);
/* Its frames: rgs_surface_frame of each ray i in valid (rp's o[i] and d[i], h[i]'s t and cos_n,
 * n[i], w2o[i]) into sf[i], as lanes. */
void rgs_surface_frames(const ray_packet *rp, const hit_record h[], const f24_vec3 n[], const f24_affine w2o[],
                        uint32_t valid, surface sf[]);
#endif

/* Diffuse and highlight weights of light l (its 16-word record) at the packet's surfaces and the
 * shadow packet that tests them (hls/units/rgs_light.c); rays whose weights are zero are not
 * traced. k_of: the surfaces' highlight exponents (cos^(2^k)). */
void rgs_light_packet(const uint32_t *l, const surface sf[], f24_t eps, ray_packet *sh, uint32_t diff[], uint32_t spec[],
                      const uint32_t k_of[]);
#ifdef F24_SIM_LANES
/* A simulation build with vector packet values computes the rays of rgs_light_packet side by side
 * instead of one after the other (its own definition of that name, the same bits); the per-ray
 * datapath of rgs_light.c, the truth, then keeps this name, for the test that compares the two. */
void rgs_light_packet_per_ray(const uint32_t *l, const surface sf[], f24_t eps, ray_packet *sh, uint32_t diff[],
                              uint32_t spec[], const uint32_t k_of[]);
#endif

/* Clears ray i's weights and shadow ray; returns whether its surface takes light (a valid one that
 * is not unlit). */
static inline int rgs_takes_light(const surface *sf, ray_packet *sh, uint32_t diff[], uint32_t spec[], int i)
{
    diff[i] = spec[i] = 0;
    sh->o[i] = sh->d[i] = (f24_vec3){ 0, 0, 0 };
    sh->tmin[i] = sh->tmax[i] = 0;
    return sf->valid && !sf->unlit; /* an unlit surface takes no light */
}

/* Ray i of a light's shadow packet, from surface sf's hit point: along a directional light's
 * negated direction words (light record l) from eps on, or over [eps / |L|, 1] of the vector L to a
 * point or spot light (dir: L's words, tmin: eps / |L|). */
static inline void rgs_shadow_ray(const uint32_t *l, const surface *sf, f24_t eps, f24_vec3 dir, f24_t tmin, ray_packet *sh,
                                  int i)
{
    const int directional = l[0] == 0;
    sh->o[i] = sf->p;
    sh->d[i] = directional ? neg3((f24_vec3){ l[7], l[8], l[9] }) : dir;
    sh->tmin[i] = directional ? eps : tmin;
    sh->tmax[i] = directional ? F24_POS_INF : F24_ONE;
}

/* A lit surface's Q12 weights for a light from its cosines in Q12 (rgs_q_of_w): the diffuse one
 * from the cosine qw with the normal, the highlight from the cosine qh with the mirror direction to
 * the power 2^k (k squarings); returns whether either is nonzero (the shadow ray is then traced). */
static inline uint32_t rgs_light_weights_q(uint32_t qw, uint32_t qh, uint32_t k, uint32_t *diff, uint32_t *spec)
{
    uint32_t s = qh;
phong_power:
    for (uint32_t j = 0; j < 8; j++)
        if (j < k)
            s = q_mul(s, s); /* cos^(2^k): k squarings */
    *diff = q_mul(qw, RGS_Q12_DIFFUSE);
    *spec = s;
    return (*diff | s) != 0;
}
/* The same from the cosines w and h. */
static inline uint32_t rgs_light_weights(f24w w, f24w h, uint32_t k, uint32_t *diff, uint32_t *spec)
{
    return rgs_light_weights_q(rgs_q_of_w(w), rgs_q_of_w(h), k, diff, spec);
}

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
/* rgs_spawn_children's rays from their geometry: the Q12 weights and active bits of ray i's
 * reflection ray (back, mirror) and transmission ray (t_o, t_d) into refl and trans. */
void rgs_child_rays(const uint32_t *m, const uint32_t weight[3], int i, const surface *sf, f24_vec3 back,
                    f24_vec3 mirror, f24_vec3 t_o, f24_vec3 t_d, rgs_task *refl, rgs_task *trans);

/* rgs_accumulate_ray's spawn bits: the packet's depth allows children; the image's
 * PROFILE_LIVE_CHILDREN (only a surface that spawns an active child takes T_R steps). */
enum { RGS_SPAWN_ON = 1, RGS_SPAWN_LIVE = 2 };

/* One active ray i of op_accumulate (hls/units/rgs_accum.c): its colour (the background for an
 * invalid surface sf, else emission + kd base diffuse + ks tint highlight, m: its material record)
 * times its Q12 weight added to acc; with RGS_SPAWN_ON in spawn and a valid surface its child rays
 * into refl and trans (rgs_spawn_children). Returns 1 if the ray's child rays take T_R steps on the
 * transformation unit (every spawning surface, or with RGS_SPAWN_LIVE one with an active child). */
int rgs_accumulate_ray(const uint32_t *m, const surface *sf, int i, const uint32_t weight[3], const uint32_t diffuse[3],
                       const uint32_t highlight[3], f24_t eps, uint32_t spawn, uint32_t acc[3], rgs_task *refl,
                       rgs_task *trans);
/* rgs_accumulate_ray's colour alone: the ray's colour times its weight added to acc. */
void rgs_ray_colour(const uint32_t *m, const surface *sf, const uint32_t weight[3], const uint32_t diffuse[3],
                    const uint32_t highlight[3], uint32_t acc[3]);
/* rgs_accumulate_ray's rule after a valid surface spawned (spawned: the tasks' active bits before):
 * its child rays take T_R steps unless RGS_SPAWN_LIVE and it spawned no active child. */
static inline int rgs_child_steps(uint32_t spawn, uint32_t spawned, const rgs_task *refl, const rgs_task *trans)
{
    return !(spawn & RGS_SPAWN_LIVE) || ((refl->rays.active | trans->rays.active) != spawned);
}
/* rgs_accumulate_ray of each ray of the packet in active (surfaces sf, their materials read from
 * mem); returns the number whose child rays take T_R steps (op_accumulate). */
uint32_t rgs_accumulate_rays(const uint32_t *mem, const surface sf[], uint32_t active, const uint32_t weight[][3],
                             const uint32_t diffuse[][3], const uint32_t highlight[][3], f24_t eps, uint32_t spawn,
                             uint32_t acc[][3], rgs_task *refl, rgs_task *trans);
#ifdef F24_SIM_LANES
/* A simulation build with vector packet values computes the child rays' geometry of the packet
 * side by side (tb/sim/rgs_accum_lanes.c, the same bits); the per-ray loop of rgs_accum.c, the
 * truth, then keeps this name, for the test that compares the two. */
uint32_t rgs_accumulate_rays_per_ray(const uint32_t *mem, const surface sf[], uint32_t active,
                                     const uint32_t weight[][3], const uint32_t diffuse[][3], const uint32_t highlight[][3],
                                     f24_t eps, uint32_t spawn, uint32_t acc[][3], rgs_task *refl, rgs_task *trans);
#endif

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
