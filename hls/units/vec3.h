/*
 * fp24 vectors and affine matrices as the units see them, and their layout in the memory image
 * (docs/memory-image.md: a matrix is 12 values, rows m0 m1 m2 t; an instance's are 12 words, a
 * triangle's a packed record with its vertex, f24_record.h).
 */
#ifndef SAARCOR_VEC3_H
#define SAARCOR_VEC3_H

#include <stdint.h>

#include "f24.h"
#include "f24_record.h"

typedef struct { f24_t x, y, z; } f24_vec3;

/* A vector of working values (f24.h): a chain of vector operations (shading's normals, cosines,
 * directions) reads its fp24 inputs once with f24w_vec3_of and stores only its results. */
typedef struct { f24w x, y, z; } f24w_vec3;

static inline f24w_vec3 f24w_vec3_of(f24_vec3 a) { return (f24w_vec3){ f24w_of(a.x), f24w_of(a.y), f24w_of(a.z) }; }
static inline f24_vec3 f24w_vec3_bits(f24w_vec3 a) { return (f24_vec3){ f24w_bits(a.x), f24w_bits(a.y), f24w_bits(a.z) }; }
/* ((a.x b.x + a.y b.y) + a.z b.z), the order of every dot product of the units */
static inline f24w f24w_dot3(f24w_vec3 a, f24w_vec3 b)
{
    return f24w_add(f24w_add(f24w_mul(a.x, b.x), f24w_mul(a.y, b.y)), f24w_mul(a.z, b.z));
}
static inline f24w_vec3 f24w_scale3(f24w_vec3 a, f24w s)
{
    return (f24w_vec3){ f24w_mul(a.x, s), f24w_mul(a.y, s), f24w_mul(a.z, s) };
}

/* A vector of double words (f24.h): ray positions and directions in object space, where one fp24
 * would lose the bits that tell small neighbouring triangles apart (docs/numerics.md). */
typedef struct { f24_vec3 hi, lo; } f24_vec3x2;

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

/* Shared-edge flags of a triangle: the bound of the unit-triangle test that lies on an edge the
 * triangle shares with another triangle of its object (the host finds them, docs/memory-image.md);
 * the intersection unit widens only these bounds (isect_unit.h). */
#define TRI_SHARED_U 1u /* u >= 0: the edge B C */
#define TRI_SHARED_V 2u /* v >= 0: the edge A C */
#define TRI_SHARED_W 4u /* u + v <= 1: the edge A B */

/* A triangle as the intersection path sees it: M^-1 in columns 0..2 of m, its vertex C in column 3
 * (high words) and c_lo (low words, decoded from the record's fields), its shared-edge flags: the
 * record of F24_TRIANGLE_RECORD_WORDS words (docs/memory-image.md). */
typedef struct {
    f24_affine m;
    f24_vec3 c_lo;
    uint32_t shared;
} f24_triangle;

static inline f24_triangle f24_triangle_load(const uint32_t *mem, uint32_t addr)
{
    f24_triangle t;
load_record:
    for (uint32_t i = 0; i < 3; i++)
        for (uint32_t j = 0; j < 4; j++)
            t.m.m[i][j] = f24_record_get(mem, addr, 4 * i + j);
    const uint32_t lo = F24_TRIANGLE_VALUES * F24_WIDTH;
    t.c_lo.x = f24_vertex_lo(f24_record_field(mem, addr, lo, F24_VERTEX_LO_BITS), t.m.m[0][3]);
    t.c_lo.y = f24_vertex_lo(f24_record_field(mem, addr, lo + F24_VERTEX_LO_BITS, F24_VERTEX_LO_BITS), t.m.m[1][3]);
    t.c_lo.z = f24_vertex_lo(f24_record_field(mem, addr, lo + 2 * F24_VERTEX_LO_BITS, F24_VERTEX_LO_BITS), t.m.m[2][3]);
    t.shared = f24_record_field(mem, addr, F24_EDGE_FLAG_BIT, F24_EDGE_FLAG_BITS);
    return t;
}

#endif
