/*
 * Host-only fast path of the fp24 arithmetic, bit-identical to hls/fp24 (HLS_HOST_ONLY).
 *
 * Each operation computes in binary64 and rounds the binary64 result once to fp24. The binary64
 * result is the exact result rounded to 53 bits; rounding that again to p = M+1 <= 24 bits gives
 * the correctly rounded result because 53 >= 2p + 2 (Figueroa, "When is double rounding
 * innocuous?", SIGNUM 1995) for +, -, *, / and sqrt. No fp24 result comes near binary64's
 * exponent limits (|exponent| <= 2*128), so binary64 never over- or underflows here, and the
 * fp24 range checks (tininess after rounding, flush to zero, overflow to Inf) are applied to the
 * once-rounded value exactly as f24_round_pack does. tests/test_f24.c checks all of this against
 * the integer path and MPFR at every tested width instead of relying on the argument.
 *
 * Build with -ffp-contract=off (no fused multiply-add) and without -ffast-math.
 * With -DF24_FAST_SIM, f24.h maps f24_add ... f24_from_i32 onto these functions; the
 * comparisons, min/max and sign operations stay the integer ones (they are already cheap).
 */
#ifndef SAARCOR_F24_FAST_H
#define SAARCOR_F24_FAST_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "f24.h"

static inline double f24_fast_decode(f24_t a)
{
    const uint64_t sign = (uint64_t)f24_sign(a) << 63;
    const int32_t exp = f24_exp(a);
    uint64_t bits;
    if (exp == 0)
        bits = sign;
    else if (exp == F24_EXP_MAX)
        bits = sign | 0x7FF0000000000000ull | ((uint64_t)(f24_frac(a) != 0) << 51);
    else
        bits = sign | ((uint64_t)(exp - F24_BIAS + 1023) << 52) |
               ((uint64_t)f24_frac(a) << (52 - F24_MAN_BITS));
    double d;
    memcpy(&d, &bits, sizeof d);
    return d;
}

static inline f24_t f24_fast_encode(double d)
{
    enum { SHIFT = 52 - F24_MAN_BITS };
    uint64_t bits;
    memcpy(&bits, &d, sizeof bits);
    const uint32_t sign = (uint32_t)(bits >> 63);
    uint64_t mag = bits & 0x7FFFFFFFFFFFFFFFull;

    if (mag >= 0x7FF0000000000000ull)
        return mag > 0x7FF0000000000000ull ? F24_DEFAULT_NAN : f24_pack(sign, F24_EXP_MAX, 0u);
    if (mag == 0)
        return f24_pack(sign, 0u, 0u);
    /* round to nearest even on the magnitude; a carry moves into the exponent field */
    mag += ((1ull << (SHIFT - 1)) - 1u) + ((mag >> SHIFT) & 1u);
    mag >>= SHIFT;
    const int64_t exp = (int64_t)(mag >> F24_MAN_BITS) - 1023 + F24_BIAS;
    if (exp <= 0)
        return f24_pack(sign, 0u, 0u);
    if (exp >= F24_EXP_MAX)
        return f24_pack(sign, F24_EXP_MAX, 0u);
    return f24_pack(sign, (uint32_t)exp, (uint32_t)mag & F24_FRAC_MASK);
}

static inline f24_t f24_fast_add(f24_t a, f24_t b) { return f24_fast_encode(f24_fast_decode(a) + f24_fast_decode(b)); }
static inline f24_t f24_fast_sub(f24_t a, f24_t b) { return f24_fast_encode(f24_fast_decode(a) - f24_fast_decode(b)); }
static inline f24_t f24_fast_mul(f24_t a, f24_t b) { return f24_fast_encode(f24_fast_decode(a) * f24_fast_decode(b)); }
static inline f24_t f24_fast_div(f24_t a, f24_t b) { return f24_fast_encode(f24_fast_decode(a) / f24_fast_decode(b)); }
static inline f24_t f24_fast_sqrt(f24_t a) { return f24_fast_encode(__builtin_sqrt(f24_fast_decode(a))); }
static inline f24_t f24_fast_from_i32(int32_t i) { return f24_fast_encode((double)i); }

static inline f24_t f24_fast_from_f32(uint32_t bits)
{
    if ((bits & 0x7F800000u) == 0)
        bits &= 0x80000000u; /* binary32 subnormals read as zero */
    float f;
    memcpy(&f, &bits, sizeof f);
    return f24_fast_encode((double)f);
}

#ifdef F24_FAST_SIM
#define f24_add f24_fast_add
#define f24_sub f24_fast_sub
#define f24_mul f24_fast_mul
#define f24_div f24_fast_div
#define f24_sqrt f24_fast_sqrt
#define f24_from_i32 f24_fast_from_i32
#define f24_from_f32 f24_fast_from_f32
#endif

#endif
