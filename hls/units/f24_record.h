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
/* A triangle record: M^-1 and the vertex C as a 3x4 matrix (12 values), then C's low words (3). */
#define F24_TRIANGLE_VALUES 15
#define F24_TRIANGLE_RECORD_WORDS F24_RECORD_WORDS(F24_TRIANGLE_VALUES)
/* An instance record (a 12-word matrix, the object index, flags and the translation's 3 low
 * words: 17 words read) takes whole triangle records, so that with cache lines of one triangle
 * record each instance starts on a line and costs 2 of them (24 words at e7m16 and e8m23). */
#define F24_INSTANCE_RECORD_WORDS (F24_TRIANGLE_RECORD_WORDS * ((17 + F24_TRIANGLE_RECORD_WORDS - 1) / F24_TRIANGLE_RECORD_WORDS))

/* Value i of the record at word address addr. */
static inline f24_t f24_record_get(const uint32_t *mem, uint32_t addr, uint32_t i)
{
    const uint32_t bit = i * F24_WIDTH, k = bit / 32, s = bit % 32;
    const uint32_t hi = s + F24_WIDTH > 32 ? mem[addr + k + 1] << (32 - s) : 0u;
    return (mem[addr + k] >> s | hi) & F24_MASK;
}

/* Writes n values as a record of F24_RECORD_WORDS(n) words at w (the host's writer). */
static inline void f24_record_put(uint32_t *w, const f24_t *v, uint32_t n)
{
record_clear:
    for (uint32_t k = 0; k < F24_RECORD_WORDS(n); k++)
        w[k] = 0;
record_put:
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t bit = i * F24_WIDTH, k = bit / 32, s = bit % 32, x = v[i] & F24_MASK;
        w[k] |= x << s;
        if (s + F24_WIDTH > 32)
            w[k + 1] |= x >> (32 - s);
    }
}

#endif
