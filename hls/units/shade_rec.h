/*
 * The compact shading record (docs/memory-image.md), one per triangle, read by the RGS at a hit:
 *
 *   normals  4 words if the object has vertex normals (object flag 1): the vertex normals of A,
 *            B, C as octahedral unit vectors of 2 x 21 bits each (normal k at bits 42k: x, then
 *            y, signed over [-SHADE_OCT_ONE, SHADE_OCT_ONE]; bits 126, 127 zero); x = -2^20,
 *            y = 0 (SHADE_NO_NORMAL) marks a missing normal.
 *   tail     bits 0..15 the material index, unless every triangle of the object has the same
 *            one (object flag 8: it is in the object's flags word, bits 16..31, and the records
 *            have none); then, with texture coordinates (object flag 2), sA tA sB tB sC tC as fp24
 *            fields of F24_WIDTH bits each (24-bit fp24: 160 bits = 5 words): the coordinates of
 *            the material's base-colour texture (of its emissive texture if it has no base
 *            colour texture), TEXCOORD_n set and KHR_texture_transform already applied by the
 *            host (an affine map commutes with the barycentric interpolation, so the device
 *            needs no transformation); then, with object flag 32, six more fields: the emissive
 *            texture's coordinates, for objects where some material maps its two textures
 *            differently; then, with vertex colours (object flag 16), the colours of A, B, C as
 *            R G B bytes (72 bits). Unused bits are zero.
 *
 * Fields are packed low bit first across the words. The stride is a function of the object's
 * flags (shade_rec_words): 24-bit fp24 gives 5 words with normals only, 9 with normals and
 * texture coordinates, 1 with neither; one word less for normals only or neither when the object
 * has one material (4 and 0 words). Objects without emission textures or vertex colours have the
 * records they had before these existed. Texture coordinates keep their fp24 bits, so texture
 * sampling is unchanged. Normals: 21 bits per component put the quantization (about 4
 * microradians) below fp24's own rounding of a unit vector's components (about 8); the decoded
 * normal is at most SHADE_OCT_MAX_ERR_URAD off the file's (tests/test_shade_rec.c).
 *
 * Decoding a vertex normal (shade_rec_normal): 21-bit integers |x|, |y|, z = 2^20 - 1 - |x| - |y|
 * and the fold of the lower hemisphere (4 adders, 2 sign muxes), 3 int-to-fp24 converters, then
 * normalization: 3 multipliers + 2 adders (squared length), 1 square root, 1 divider, 3
 * multipliers. A hit decodes 3 normals; texture coordinates and material are bit slices.
 */
#ifndef SAARCOR_SHADE_REC_H
#define SAARCOR_SHADE_REC_H

#include <stdint.h>

#include "vec3.h"

/* object descriptor flags (word 7; bit 4 is MI_OBJECT_DYNAMIC); with SHADE_ONE_MATERIAL the
 * word's bits 16..31 are the material of every triangle */
enum {
    SHADE_HAS_NORMALS = 1, SHADE_HAS_TEXCOORDS = 2, SHADE_ONE_MATERIAL = 8, SHADE_HAS_COLOURS = 16,
    SHADE_HAS_EMISSIVE_UV = 32 /* only with SHADE_HAS_TEXCOORDS */
};
#define SHADE_OBJ_MATERIAL_SHIFT 16
/* material words the shading model added after the record above (docs/memory-image.md): the
 * flags word's unlit bit (KHR_materials_unlit) and the emissive texture's index */
enum { SHADE_M_FLAGS = 8, SHADE_M_EMISSIVE_TEXTURE = 12, SHADE_MAT_UNLIT = 8 };
#define SHADE_OCT_BITS 21
#define SHADE_OCT_ONE ((1 << (SHADE_OCT_BITS - 1)) - 1)
#define SHADE_NO_NORMAL (1ull << (SHADE_OCT_BITS - 1)) /* the 42-bit code x = -2^20, y = 0 */
#define SHADE_NORMAL_WORDS 4                           /* 3 x 42 bits */
#define SHADE_MATERIAL_BITS 16
#define SHADE_COLOUR_BITS 72 /* R G B bytes of A, B, C */
#define SHADE_MAX_WORDS 19 /* normals (4) and the widest tail: 16 + 12 x 32 + 72 bits (15) */
#define SHADE_OCT_MAX_ERR_URAD 20 /* angle between a unit normal and its decoded encoding, microradians */

/* Bits of the material index in a record of an object with these flags. */
static inline uint32_t shade_rec_material_bits(uint32_t flags)
{
    return (flags & SHADE_ONE_MATERIAL) ? 0u : SHADE_MATERIAL_BITS;
}

/* Bit offset of the texture coordinates of set uv (0: base colour, 1: emissive) in a tail. */
static inline uint32_t shade_rec_uv_at(uint32_t flags, uint32_t uv)
{
    return shade_rec_material_bits(flags) + ((flags & SHADE_HAS_EMISSIVE_UV) ? 6u * F24_WIDTH * uv : 0u);
}

/* Bit offset of the vertex colours in a tail (and the end of the texture coordinates). */
static inline uint32_t shade_rec_colour_at(uint32_t flags)
{
    const uint32_t sets = ((flags & SHADE_HAS_TEXCOORDS) ? 1u : 0u) + ((flags & SHADE_HAS_EMISSIVE_UV) ? 1u : 0u);
    return shade_rec_material_bits(flags) + 6u * F24_WIDTH * sets;
}

/* Bits of a tail that hold data. */
static inline uint32_t shade_rec_tail_bits(uint32_t flags)
{
    return shade_rec_colour_at(flags) + ((flags & SHADE_HAS_COLOURS) ? (uint32_t)SHADE_COLOUR_BITS : 0u);
}

/* Words of a record of an object with these flags. */
static inline uint32_t shade_rec_words(uint32_t flags)
{
    return ((flags & SHADE_HAS_NORMALS) ? SHADE_NORMAL_WORDS : 0u) + (shade_rec_tail_bits(flags) + 31u) / 32u;
}

/* Offset of the tail in a record. */
static inline uint32_t shade_rec_tail(uint32_t flags) { return (flags & SHADE_HAS_NORMALS) ? SHADE_NORMAL_WORDS : 0u; }

/* The width (1..32) bits of w from bit at on: a slice of one word or of two neighbours. */
static inline uint32_t shade_rec_bits(const uint32_t *w, uint32_t at, uint32_t width)
{
    uint64_t bits = w[at / 32u] >> (at % 32u);
    if (at % 32u + width > 32u)
        bits |= (uint64_t)w[at / 32u + 1] << (32u - at % 32u);
    return (uint32_t)(bits & ((1ull << width) - 1u));
}

/* The material of a triangle: the object's (flags: its descriptor's flags word), or its tail's. */
static inline uint32_t shade_rec_material(uint32_t flags, const uint32_t *tail)
{
    return (flags & SHADE_ONE_MATERIAL) ? flags >> SHADE_OBJ_MATERIAL_SHIFT : tail[0] & 0xFFFFu;
}

/* Texture coordinate i (sA tA sB tB sC tC) of set uv (0: base colour, 1: emissive; the emissive
 * texture uses set 0 when the object has no SHADE_HAS_EMISSIVE_UV) of a tail with texture
 * coordinates. */
static inline f24_t shade_rec_texcoord(uint32_t flags, const uint32_t *tail, uint32_t uv, uint32_t i)
{
    return shade_rec_bits(tail, shade_rec_uv_at(flags, uv) + F24_WIDTH * i, F24_WIDTH);
}

/* Bit offset of channel k (R, G, B) of the colour of vertex v (A, B, C) in a tail. */
static inline uint32_t shade_rec_colour_bit(uint32_t flags, uint32_t v, uint32_t k)
{
    return shade_rec_colour_at(flags) + 24u * v + 8u * k;
}

/* Channel k of the colour of vertex v of a tail with vertex colours: a byte. */
static inline uint32_t shade_rec_colour(uint32_t flags, const uint32_t *tail, uint32_t v, uint32_t k)
{
    return shade_rec_bits(tail, shade_rec_colour_bit(flags, v, k), 8u);
}

/* The octahedral components x (c = 0) and y (c = 1) of normal k of a normal block. */
int32_t shade_rec_oct(const uint32_t *normals, uint32_t k, uint32_t c);

/* Unit vertex normal k (A, B, C) of a normal block; (0, 0, 0) for a missing normal. */
f24_vec3 shade_rec_normal(const uint32_t *normals, uint32_t k);
/* All three of a block side by side, as the shading datapath decodes them: out[c][k] is
 * component c (x, y, z) of normal k (lane 3 unused, zero). */
void shade_rec_normals(const uint32_t *normals, f24_t out[3][F24Q_LANES]);

#endif
