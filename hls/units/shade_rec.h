/*
 * The compact shading record (docs/memory-image.md), one per triangle, read by the RGS at a hit:
 *
 *   normals  3 words if the object has vertex normals (object flag 1): A, B, C, each an
 *            octahedral unit vector, bits 0..15 x and 16..31 y as signed 16-bit integers over
 *            [-SHADE_OCT_ONE, SHADE_OCT_ONE]; x = -32768 (SHADE_NO_NORMAL) marks a missing normal.
 *   tail     bits 0..15 the material index; with texture coordinates (object flag 2) bits 16 on
 *            hold sA tA sB tB sC tC as fp24 fields of F24_WIDTH bits each, packed low bit first
 *            across the words (24-bit fp24: 160 bits = 5 words).
 *
 * The stride is a function of the object's flags (shade_rec_words): 4 words with normals only,
 * 8 with normals and texture coordinates, 1 with neither. Texture coordinates keep their fp24
 * bits, so texture sampling is unchanged; normals lose at most SHADE_OCT_MAX_ERR_URAD of angle
 * (tests/test_shade_rec.c).
 *
 * Decoding a vertex normal (shade_rec_normal): integers |x|, |y|, z = 32767 - |x| - |y| and the
 * fold of the lower hemisphere (4 adders, 2 sign muxes), 3 int-to-fp24 converters (exact: below
 * 2^17), then normalization: 3 multipliers + 2 adders (squared length), 1 square root, 1 divider,
 * 3 multipliers. A hit decodes 3 normals; the texture coordinates and material index are wiring
 * (bit slices).
 */
#ifndef SAARCOR_SHADE_REC_H
#define SAARCOR_SHADE_REC_H

#include <stdint.h>

#include "vec3.h"

enum { SHADE_HAS_NORMALS = 1, SHADE_HAS_TEXCOORDS = 2 }; /* object descriptor flags (word 7) */
#define SHADE_OCT_ONE 32767
#define SHADE_NO_NORMAL 0x8000u
#define SHADE_MATERIAL_BITS 16
#define SHADE_MAX_WORDS 11 /* normals (3) and the widest tail: 16 + 6 x 32 bits */
#define SHADE_OCT_MAX_ERR_URAD 140 /* angle between a unit normal and its encoding, microradians */

/* Words of a record of an object with these flags. */
static inline uint32_t shade_rec_words(uint32_t flags)
{
    const uint32_t tail_bits = SHADE_MATERIAL_BITS + ((flags & SHADE_HAS_TEXCOORDS) ? 6u * F24_WIDTH : 0u);
    return ((flags & SHADE_HAS_NORMALS) ? 3u : 0u) + (tail_bits + 31u) / 32u;
}

/* Offset of the tail in a record. */
static inline uint32_t shade_rec_tail(uint32_t flags) { return (flags & SHADE_HAS_NORMALS) ? 3u : 0u; }

static inline uint32_t shade_rec_material(const uint32_t *tail) { return tail[0] & 0xFFFFu; }

/* Texture coordinate i (sA tA sB tB sC tC) of a tail with texture coordinates. */
f24_t shade_rec_texcoord(const uint32_t *tail, uint32_t i);

/* Unit vertex normal of an octahedral word; (0, 0, 0) for SHADE_NO_NORMAL. */
f24_vec3 shade_rec_normal(uint32_t word);

#endif
