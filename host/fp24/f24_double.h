/*
 * binary64 <-> fp24 conversions for the host (host/memimage writes the device's numbers with
 * them) and the simulator (tb/fp/f24_fast.h computes with them): f24_fast_decode is exact (every
 * fp24 value is a binary64 value), f24_fast_encode rounds to nearest even once, with fp24's
 * range rules (flush to zero, overflow to Inf, one NaN), as hls/fp24's f24_round_pack does.
 * Host-only: hls/ stays integer-only and never includes this.
 */
#ifndef SAARCOR_F24_DOUBLE_H
#define SAARCOR_F24_DOUBLE_H

#include <stdint.h>
#include <string.h>

#include "f24.h"

/* binary64 exponent field minus fp24 bias, in the fp24 exponent position */
#define F24_FAST_REBIAS ((uint64_t)(1023 - F24_BIAS) << F24_MAN_BITS)

static inline double f24_fast_decode(f24_t a)
{
    const uint64_t sign = (uint64_t)f24_sign(a) << 63;
    const uint64_t mag = a & F24_ABS_MASK;
    uint64_t bits;
    if (mag - F24_MIN_NORMAL < (uint64_t)(F24_POS_INF - F24_MIN_NORMAL)) /* normal: one range check */
        bits = sign | ((mag + F24_FAST_REBIAS) << (52 - F24_MAN_BITS));
    else if (mag < F24_MIN_NORMAL)
        bits = sign; /* zero or subnormal encoding */
    else
        bits = sign | 0x7FF0000000000000ull | ((uint64_t)(mag != F24_POS_INF) << 51);
    double d;
    memcpy(&d, &bits, sizeof d);
    return d;
}

/* Rare results of f24_fast_encode: zero, flushed, overflowed, Inf and NaN. */
static inline f24_t f24_fast_encode_special(uint32_t sign, uint64_t mag52, uint64_t rebiased)
{
    if (mag52 > 0x7FF0000000000000ull)
        return F24_DEFAULT_NAN;
    if ((int64_t)rebiased >= (int64_t)F24_POS_INF)
        return f24_pack(sign, F24_EXP_MAX, 0u); /* Inf, or overflow after rounding */
    return f24_pack(sign, 0u, 0u);              /* zero, or tiny after rounding (negative): flush */
}

static inline f24_t f24_fast_encode(double d)
{
    enum { SHIFT = 52 - F24_MAN_BITS };
    uint64_t bits;
    memcpy(&bits, &d, sizeof bits);
    const uint32_t sign = (uint32_t)(bits >> 63);
    const uint64_t mag52 = bits & 0x7FFFFFFFFFFFFFFFull;
    /* round to nearest even on the magnitude; a carry moves into the exponent field */
    const uint64_t mag = (mag52 + ((1ull << (SHIFT - 1)) - 1u) + ((mag52 >> SHIFT) & 1u)) >> SHIFT;
    const uint64_t rebiased = mag - F24_FAST_REBIAS; /* fp24 exponent and fraction fields */
    if (rebiased - F24_MIN_NORMAL < (uint64_t)(F24_POS_INF - F24_MIN_NORMAL)) /* normal result */
        return (sign << (F24_EXP_BITS + F24_MAN_BITS)) | (uint32_t)rebiased;
    return f24_fast_encode_special(sign, mag52, rebiased);
}

/* d rounded to fp24 with fp24's range rules, kept as a binary64 value: the value of
 * f24_fast_encode(d) without the trip through the fp24 bits (the simulator's working values,
 * tb/fp/f24_fast.h). Every NaN becomes the default NaN. */
static inline double f24_fast_round(double d)
{
    enum { SHIFT = 52 - F24_MAN_BITS };
    const uint64_t min52 = (uint64_t)(1023 - F24_BIAS + 1) << 52, inf52 = (uint64_t)(1023 - F24_BIAS + F24_EXP_MAX) << 52;
    uint64_t bits;
    memcpy(&bits, &d, sizeof bits);
    const uint64_t sign = bits & 0x8000000000000000ull, mag52 = bits & 0x7FFFFFFFFFFFFFFFull;
    uint64_t r = (mag52 + ((1ull << (SHIFT - 1)) - 1u) + ((mag52 >> SHIFT) & 1u)) & ~((1ull << SHIFT) - 1u);
    if (r - min52 >= inf52 - min52) { /* not a normal number after rounding */
        if (mag52 > 0x7FF0000000000000ull)
            return f24_fast_decode(F24_DEFAULT_NAN);
        r = r >= inf52 ? 0x7FF0000000000000ull : 0; /* overflow to Inf, flush to zero */
    }
    bits = sign | r;
    memcpy(&d, &bits, sizeof d);
    return d;
}

#endif
