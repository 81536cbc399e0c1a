/*
 * fp24 vectors and affine matrices as the units see them, and their layout in the memory image
 * (docs/memory-image.md: a matrix is 12 values, rows m0 m1 m2 t; an instance's are 12 words, a
 * triangle transformation's a packed record, f24_record.h).
 */
#ifndef SAARCOR_VEC3_H
#define SAARCOR_VEC3_H

#include <stdint.h>

#include "f24.h"
#include "f24_record.h"

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

/* Reads a matrix packed as a record of F24_AFFINE_RECORD_WORDS words (triangle transformations). */
static inline f24_affine f24_affine_load_record(const uint32_t *mem, uint32_t addr)
{
    f24_affine a;
load_record:
    for (uint32_t i = 0; i < 3; i++)
        for (uint32_t j = 0; j < 4; j++)
            a.m[i][j] = f24_record_get(mem, addr, 4 * i + j);
    return a;
}

#endif
