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

/* Sets texture coordinate i (sA tA sB tB sC tC) of set uv of a tail with texture coordinates (of
 * an object with these flags) to fp24 value. */
void shade_encode_texcoord(uint32_t *tail, uint32_t flags, uint32_t uv, uint32_t i, uint32_t value);

/* What a triangle's record holds, per vertex k; each part is used only if the flags have it. */
typedef struct {
    uint64_t normal[3];      /* shade_encode_normal codes (a mesh encodes each vertex once) */
    double uv[2][3][2];      /* coordinate sets 0 and 1 (hls/units/shade_rec.h), mapped already */
    const float *colour[3];  /* R G B in [0, 1] */
    uint32_t material;       /* unless SHADE_ONE_MATERIAL */
} shade_triangle;

/* The record (shade_rec_words(flags) words) of a triangle. */
void shade_encode_record(uint32_t *w, uint32_t flags, const shade_triangle *t);

#endif
