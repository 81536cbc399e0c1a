/* The surface the RGS shades at a hit (surface_at) and the packet's: see rgs_ops.h and
 * docs/shading.md. Outside rgs.c so that the unit capture can wrap rgs_surface_at
 * (rtl/rgs_surface.sv is checked against it) and rgs_surfaces. */
#include "rgs_ops.h"

#include "shade_rec.h"

#ifdef F24_SIM_LANES
#define rgs_surfaces rgs_surfaces_per_ray /* the simulation build's frames are side by side (rgs_ops.h) */
#endif

/* Ray i of packet rp is active and hit something: the RGS shades it. */
static int shaded(const ray_packet *rp, int i, const hit_record *h)
{
    return h->instance != TRACE_NO_HIT && (rp->active >> i & 1u);
}

/* The hit's instance (into ia), object descriptor (into obj) and shading record addresses. */
static uint32_t record_address(const uint32_t *mem, const hit_record *h, uint32_t *ia, uint32_t *obj)
{
    *ia = region_start(mem, R_INSTANCES) + INST_WORDS * h->instance;
    *obj = region_start(mem, R_OBJECTS) + OBJ_WORDS * mem[*ia + 12];
    return mem[*obj + O_SHADING] + shade_rec_words(mem[*obj + O_FLAGS]) * h->triangle;
}

int rgs_vertex_normals(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h,
                       f24_t normals[3][F24Q_LANES])
{
    uint32_t ia, obj;
    if (!shaded(rp, i, h))
        return 0;
    const uint32_t shade = record_address(mem, h, &ia, &obj);
    if (!(mem[obj + O_FLAGS] & SHADE_HAS_NORMALS))
        return 0;
    shade_rec_normals(&mem[shade], normals); /* the three side by side, decoded once */
    return 1;
}

#if SAARCOR_CFG_TEXTURES
/* Multiplies out (Q12) by the bilinear sample of texture t at the hit's coordinates of set uv
 * (hls/units/shade_rec.h), if t names a texture and the object has texture coordinates. */
static void modulate_texture(const uint32_t *mem, uint32_t t, uint32_t flags, const uint32_t *tail, uint32_t uv,
                             const hit_record *h, uint32_t out[3], unit_op *op, trace_counters *c)
{
    if (t >= mem[H_TEXTURES] || !(flags & SHADE_HAS_TEXCOORDS))
        return;
    f24_t st[2];
texcoords:
    for (uint32_t k = 0; k < 2; k++)
        st[k] = rgs_lerp(shade_rec_texcoord(flags, tail, uv, k), shade_rec_texcoord(flags, tail, uv, 2 + k),
                     shade_rec_texcoord(flags, tail, uv, 4 + k), h->u, h->v);
    const uint32_t entry = region_start(mem, R_TEXTURES) + TEX_WORDS * t;
    uint32_t tex[3];
    shade_read(op, c, entry, TEX_WORDS);
    rgs_sample_bilinear(mem, &mem[entry], st[0], st[1], tex, op, c);
texture_modulate:
    for (int k = 0; k < 3; k++)
        out[k] = q_mul(out[k], tex[k]);
}
#endif

/* Multiplies out (Q12) by the vertex colours interpolated at the hit, if the object has them:
 * bytes widened as texels, weights u, v, 1 - u - v in Q12. */
static void modulate_colours(uint32_t flags, const uint32_t *tail, const hit_record *h, uint32_t out[3])
{
    if (!(flags & SHADE_HAS_COLOURS))
        return;
    const uint32_t wa = rgs_q_of(h->u), wb = rgs_q_of(h->v), wc = wa + wb < RGS_Q12_ONE ? RGS_Q12_ONE - wa - wb : 0u;
vertex_colours:
    for (uint32_t k = 0; k < 3; k++) {
        const uint32_t sum = wa * q_byte(shade_rec_colour(flags, tail, 0, k)) +
                             wb * q_byte(shade_rec_colour(flags, tail, 1, k)) + wc * q_byte(shade_rec_colour(flags, tail, 2, k));
        out[k] = q_mul(out[k], (sum + 2048u) >> 12);
    }
}

/* Base colour and emission at the hit (tail: the shading record's tail): the material's
 * factors, the base colour times the vertex colours and its texture, the emission times its
 * texture (through the emissive coordinates if the object has them). */
static void surface_colours(const uint32_t *mem, uint32_t mat, uint32_t flags, const uint32_t *tail,
                            const hit_record *h, surface *sf, unit_op *op, trace_counters *c)
{
material_factors:
    for (uint32_t k = 0; k < 3; k++) {
        sf->base[k] = rgs_q_of(mem[mat + k]);
        sf->emission[k] = rgs_q_of(mem[mat + M_EMISSIVE + k]);
    }
    modulate_colours(flags, tail, h, sf->base);
#if SAARCOR_CFG_TEXTURES
    modulate_texture(mem, mem[mat + M_TEXTURE], flags, tail, 0, h, sf->base, op, c);
    modulate_texture(mem, mem[mat + SHADE_M_EMISSIVE_TEXTURE], flags, tail, (flags & SHADE_HAS_EMISSIVE_UV) ? 1u : 0u,
                     h, sf->emission, op, c);
#else
    (void)op, (void)c;
#endif
}

/* rgs_surface_at but the frame: the reads (instance, object descriptor (words 2..7), shading
 * record, geometric normal if needed, material, and per texture sampled (base colour, emissive) its
 * entry and 4 texels: at most 15, UNIT_OP_READS), the object-space normal n (vn, or the geometric
 * normal, row 2 of the triangle transformation, if flat) and the instance's world-to-object matrix
 * w2o for the frame, the material, colours and tint. */
surface rgs_surface_material(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h, f24_vec3 vn,
                             int flat, f24_vec3 *n, f24_affine *w2o, unit_op *op, trace_counters *c)
{
    surface sf = { 0 };
    if (!shaded(rp, i, h))
        return sf;
    uint32_t ia, obj;
    const uint32_t shade = record_address(mem, h, &ia, &obj), flags = mem[obj + O_FLAGS];
    const uint32_t *tail = &mem[shade + shade_rec_tail(flags)];
    shade_read(op, c, ia, 13);
    shade_read(op, c, obj + O_TRIANGLES, O_FLAGS - O_TRIANGLES + 1);
    shade_read(op, c, shade, shade_rec_words(flags));
    sf.valid = 1;
    *w2o = f24_affine_load(mem, ia);
    *n = vn;
    if (flat) {
        const uint32_t tri = mem[obj + O_TRIANGLES] + TRI_WORDS * h->triangle;
        *n = (f24_vec3){ f24_record_get(mem, tri, 8), f24_record_get(mem, tri, 9), f24_record_get(mem, tri, 10) };
        shade_read(op, c, tri + 8 * F24_WIDTH / 32, F24_RECORD_SPAN(8, 3));
    }
    sf.mat = region_start(mem, R_MATERIALS) + MAT_WORDS * shade_rec_material(flags, tail);
    shade_read(op, c, sf.mat, MAT_WORDS);
    sf.unlit = (mem[sf.mat + SHADE_M_FLAGS] & SHADE_MAT_UNLIT) != 0;
    surface_colours(mem, sf.mat, flags, tail, h, &sf, op, c);
    const uint32_t metal = rgs_q_of(mem[sf.mat + M_METALLIC]);
tint:
    for (int k = 0; k < 3; k++) /* 1 + m (b - 1) = (1 - m) + m b */
        sf.tint[k] = q_add(RGS_Q12_ONE - (metal < RGS_Q12_ONE ? metal : RGS_Q12_ONE), q_mul(metal, sf.base[k]));
    return sf;
}

/* The normal's chain and the frame read nothing: computed before and after the material's reads,
 * the reads keep their order. */
surface rgs_surface_at(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h, unit_op *op,
                       trace_counters *c)
{
    f24_t normals[3][F24Q_LANES];
    f24_vec3 vn = { 0, 0, 0 }, n;
    f24_affine w2o;
    if (rgs_vertex_normals(mem, rp, i, h, normals))
        vn = rgs_lerp_normal(normals, h->u, h->v);
    surface sf = rgs_surface_material(mem, rp, i, h, vn, f24_is_zero(rgs_dot3(vn, vn)), &n, &w2o, op, c);
    if (sf.valid)
        rgs_surface_frame(rp->o[i], rp->d[i], h->t, h->cos_n, n, &w2o, &sf);
    return sf;
}

void rgs_surfaces(const uint32_t *mem, const ray_packet *rp, const hit_record h[], surface sf[], unit_op *op,
                  trace_counters *c)
{
surfaces:
    for (int i = 0; i < TRACE_PACKET; i++)
        sf[i] = rgs_surface_at(mem, rp, i, &h[i], op, c);
}
