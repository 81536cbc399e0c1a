/*
 * fp24 vectors and affine matrices as the units see them, and their layout in the memory image
 * (docs/memory-image.md: a matrix is 12 words, rows m0 m1 m2 t).
 */
#ifndef SAARCOR_VEC3_H
#define SAARCOR_VEC3_H

#include <stdint.h>

#include "f24.h"

typedef struct { f24_t x, y, z; } f24_vec3;

typedef struct { f24_t m[3][4]; } f24_affine; /* x' = m0 x + m1 y + m2 z + t, per row */

/* Reads a 12-word matrix at word address addr of the memory image. */
static inline f24_affine f24_affine_load(const uint32_t *mem, uint32_t addr)
{
    f24_affine a;
load_rows:
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            a.m[i][j] = mem[addr + (uint32_t)(4 * i + j)] & F24_MASK;
    return a;
}

#endif
