/*
 * Host side of the compact shading record (hls/units/shade_rec.h, docs/memory-image.md): the
 * octahedral encoding of vertex normals and the packing of a triangle's record.
 */
#ifndef SAARCOR_SHADE_ENCODE_H
#define SAARCOR_SHADE_ENCODE_H

#include <stdint.h>

#include "shade_rec.h"

/* The 42-bit octahedral code (x | y << 21) of direction n (any length); SHADE_NO_NORMAL if n is
 * zero or not finite. */
uint64_t shade_encode_normal(const double n[3]);

/* Sets normal k of a normal block to a code of shade_encode_normal. */
void shade_encode_set_normal(uint32_t *normals, uint32_t k, uint64_t code);

/* Sets texture coordinate i (sA tA sB tB sC tC) of a tail with texture coordinates (of an object
 * with these flags) to fp24 value. */
void shade_encode_texcoord(uint32_t *tail, uint32_t flags, uint32_t i, uint32_t value);

/* The record (shade_rec_words(flags) words) of a triangle: normals[k] (the shade_encode_normal
 * code of vertex k's normal: a mesh encodes each vertex once) and texcoords[k] (2 floats) of
 * vertex k, each used only if flags has them, and the material unless flags has
 * SHADE_ONE_MATERIAL. */
void shade_encode_record(uint32_t *w, uint32_t flags, const uint64_t normals[3], const float *const texcoords[3],
                         uint32_t material);

#endif
