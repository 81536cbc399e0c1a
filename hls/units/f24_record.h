/*
 * Densely packed fp24 records in the memory image (docs/memory-image.md, "Packed records").
 *
 * Value i of a record occupies bits [i W, (i + 1) W) of the record's bit string, W = F24_WIDTH;
 * word k of the record holds bits [32 k, 32 k + 32). n values take ceil(n W / 32) words (12 values
 * at e7m16: 9 words instead of 12), unused high bits of the last word are zero.
 *
 * Unpacking is the memory interface's wiring, not a datapath: a record is read whole, and i is a
 * constant at every use (unrolled loops), so each value is a fixed slice of one or two words.
 */
#ifndef SAARCOR_F24_RECORD_H
#define SAARCOR_F24_RECORD_H

#include <stdint.h>

#include "f24.h"

#define F24_RECORD_WORDS(n) (((n) * F24_WIDTH + 31) / 32)
/* Words from the one holding value first to the one holding value first + n - 1. */
#define F24_RECORD_SPAN(first, n) (((first + n) * F24_WIDTH - 1) / 32 - (first) * F24_WIDTH / 32 + 1)
/* A triangle record: M^-1 and the high word of the vertex C as a 3x4 matrix (12 values), then per
 * component C's low part as a signed F24_VERTEX_LO_BITS-bit multiple k of 2^-8 ulp(C.hi) (fields
 * from bit 12 W on): C to 8 bits beyond fp24's, which holds a binary32 vertex exactly, in 27 bits
 * instead of three more values (10 words at e7m16 instead of 12; f24_vertex_lo decodes). Then the
 * triangle's 3 shared-edge flags (TRI_SHARED_*, vec3.h), in what was the last word's
 * padding at every tested format (a format without 3 spare bits gets a word more). */
#define F24_TRIANGLE_VALUES 12
#define F24_VERTEX_LO_BITS 9
#define F24_VERTEX_LO_SHIFT 8
#define F24_EDGE_FLAG_BITS 3
#define F24_EDGE_FLAG_BIT (F24_TRIANGLE_VALUES * F24_WIDTH + 3 * F24_VERTEX_LO_BITS)
#define F24_TRIANGLE_BITS (F24_EDGE_FLAG_BIT + F24_EDGE_FLAG_BITS)
#define F24_TRIANGLE_RECORD_WORDS ((F24_TRIANGLE_BITS + 31) / 32)
/* An instance record (a 12-word matrix, the object index, flags and the translation's 3 low
 * words: 17 words read) takes whole triangle records, so that with cache lines of one triangle
 * record each instance starts on a line and costs 2 of them (24 words at e7m16 and e8m23). */
#define F24_INSTANCE_RECORD_WORDS \
    (F24_TRIANGLE_RECORD_WORDS * ((17 + F24_TRIANGLE_RECORD_WORDS - 1) / F24_TRIANGLE_RECORD_WORDS))

/* Bits [bit, bit + n) of the record at word address addr (n <= 32 - bit % 32 + 32). */
static inline uint32_t f24_record_field(const uint32_t *mem, uint32_t addr, uint32_t bit, uint32_t n)
{
    const uint32_t k = bit / 32, s = bit % 32;
    const uint32_t hi = s + n > 32 ? mem[addr + k + 1] << (32 - s) : 0u;
    return (mem[addr + k] >> s | hi) & (n == 32 ? 0xFFFFFFFFu : (1u << n) - 1u);
}

/* Value i of the record at word address addr. */
static inline f24_t f24_record_get(const uint32_t *mem, uint32_t addr, uint32_t i)
{
    return f24_record_field(mem, addr, i * F24_WIDTH, F24_WIDTH);
}

/* The low part of a vertex component whose high word is hi, from its record field: k 2^-8 ulp(hi)
 * exactly (|k| <= 256 fits fp24 for M >= 8), flushed to zero below the format's range. A small
 * int-to-float converter in the memory interface: a leading-zero count and an exponent add. */
static inline f24_t f24_vertex_lo(uint32_t field, f24_t hi)
{
    const int32_t k = (int32_t)(field << (32 - F24_VERTEX_LO_BITS)) >> (32 - F24_VERTEX_LO_BITS);
    if (k == 0 || f24_exp(hi) == 0 || f24_exp(hi) == F24_EXP_MAX)
        return 0;
    const f24_t f = f24_from_i32(k);
    const int32_t e = f24_exp(f) + f24_exp(hi) - F24_BIAS - F24_MAN_BITS - F24_VERTEX_LO_SHIFT;
    return e <= 0 ? (f & F24_SIGN_BIT) : f24_pack(f24_sign(f), (uint32_t)e, f24_frac(f));
}

/* ORs the n low bits of x into bits [bit, bit + n) of the record at w (the host's writer). */
static inline void f24_record_put_field(uint32_t *w, uint32_t bit, uint32_t n, uint32_t x)
{
    const uint32_t k = bit / 32, s = bit % 32;
    x &= n == 32 ? 0xFFFFFFFFu : (1u << n) - 1u;
    w[k] |= x << s;
    if (s + n > 32)
        w[k + 1] |= x >> (32 - s);
}

/* Writes n values as a record of F24_RECORD_WORDS(n) words at w (the host's writer). */
static inline void f24_record_put(uint32_t *w, const f24_t *v, uint32_t n)
{
record_clear:
    for (uint32_t k = 0; k < F24_RECORD_WORDS(n); k++)
        w[k] = 0;
record_put:
    for (uint32_t i = 0; i < n; i++)
        f24_record_put_field(w, i * F24_WIDTH, F24_WIDTH, v[i]);
}

#endif
