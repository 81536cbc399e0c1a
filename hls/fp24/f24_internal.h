/*
 * Internal datapath helpers of the fp24 library (not part of the unit interface).
 *
 * Datapath convention: an unrounded result is (sign, exp, sig) with value
 *   sig * 2^(exp - F24_BIAS - 30),
 * where sig has its leading one at bit 30 and F24_ROUND_BITS = 30 - M bits below the kept
 * significand; bit 0 is sticky (the OR of everything shifted out). Keeping the leading bit at a
 * fixed position makes one round-and-pack routine serve every operation and every width.
 */
#ifndef SAARCOR_F24_INTERNAL_H
#define SAARCOR_F24_INTERNAL_H

#include "f24.h"

#define F24_ROUND_BITS (30 - F24_MAN_BITS)
#define F24_SIG_LEAD   (1u << 30)

/* Rounds (ties to even), flushes tiny results to signed zero, overflows to Inf, packs.
 * Precondition: sig has bit 30 set (exact zeros are handled by the caller). */
f24_t f24_round_pack(uint32_t sign, int32_t exp, uint32_t sig);

/* Leading-zero count of a nonzero word: a 5-level priority encoder. */
static inline uint32_t f24_clz32(uint32_t a)
{
    uint32_t n = 0;
    if (!(a & 0xFFFF0000u)) { n += 16; a <<= 16; }
    if (!(a & 0xFF000000u)) { n += 8; a <<= 8; }
    if (!(a & 0xF0000000u)) { n += 4; a <<= 4; }
    if (!(a & 0xC0000000u)) { n += 2; a <<= 2; }
    if (!(a & 0x80000000u)) { n += 1; }
    return n;
}

/* Right shift that ORs every bit shifted out into bit 0 ("jamming"). */
static inline uint32_t f24_shift_right_jam32(uint32_t a, uint32_t dist)
{
    if (dist >= 31u)
        return a != 0u;
    return (a >> dist) | ((a & ((1u << dist) - 1u)) != 0u);
}

static inline uint32_t f24_shift_right_jam64(uint64_t a, uint32_t dist)
{
    return (uint32_t)((a >> dist) | ((a & ((1ull << dist) - 1u)) != 0u));
}

/* Significand with the hidden bit: M+1 bits. */
static inline uint32_t f24_sig(f24_t a) { return f24_frac(a) | (1u << F24_MAN_BITS); }

static inline f24_t f24_zero(uint32_t sign) { return f24_pack(sign, 0u, 0u); }
static inline f24_t f24_inf(uint32_t sign) { return f24_pack(sign, (uint32_t)F24_EXP_MAX, 0u); }

#endif
