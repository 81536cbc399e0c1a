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
 * The simulation build names this header to hls/fp24/f24.h (-DF24_SIM_HEADER='"f24_fast.h"' with
 * -DF24_FAST_SIM, the Makefile's SIM_FLAGS), which then maps f24_add ... f24_from_f32, the
 * comparisons lt/le/eq, min/max and the exact dot product onto these functions, so that hls/
 * names nothing of tb/; the sign operations and conversions to integers stay the integer ones.
 */
#ifndef SAARCOR_F24_FAST_H
#define SAARCOR_F24_FAST_H

#include <stdint.h>

#ifdef F24_FAST_SIM
#define F24_SIM_WORKING /* f24.h then leaves the working values to this header */
#endif
#include "f24.h"
#include "f24_double.h" /* host/fp24: f24_fast_decode, f24_fast_encode */

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

/* Comparisons and minimumNumber/maximumNumber on the decoded values: binary64 comparisons are
 * false for NaN and treat -0 == +0, and decoding reads subnormal encodings as zero, as
 * f24_compare.c and f24_minmax.c do. */
static inline int f24_fast_lt(f24_t a, f24_t b) { return f24_fast_decode(a) < f24_fast_decode(b); }
static inline int f24_fast_le(f24_t a, f24_t b) { return f24_fast_decode(a) <= f24_fast_decode(b); }
static inline int f24_fast_eq(f24_t a, f24_t b) { return f24_fast_decode(a) == f24_fast_decode(b); }

/* f24_sum_exact from exact binary64 products and double-doubles (tb/fp/f24_fast_sum.c). */
f24x2 f24_fast_sum_exact(const f24_t a[], const f24_t b[], uint32_t n);
/* Its common case: r from the plain binary64 sum of the n exact products p and a bound on its
 * error, where no fp24 rounding boundary lies within the bound of hi or lo; 0 otherwise. */
int f24_fast_sum_filter(const double p[], uint32_t n, f24x2 *r);

/* The working values of hls/fp24/f24.h held decoded: each operation rounds its binary64 result
 * with f24_fast_round and stays binary64, the comparisons and minimum/maximum are those above on
 * decoded values; f24w_bits encodes (exactly: every working value is an fp24 value) and keeps the
 * sign of a NaN that f24w_neg gave, as the integer f24_neg does. */
static inline double f24_fast_minmax_w(double x, double y, int want_max)
{
    if (x != x)
        return y != y ? f24_fast_decode(F24_DEFAULT_NAN) : y;
    if (y != y)
        return x;
    const int x_first = x < y || (x == y && __builtin_signbit(x)); /* -0 before +0 */
    return x_first != want_max ? x : y;
}

static inline f24_t f24_fast_min(f24_t a, f24_t b)
{
    return f24_fast_encode(f24_fast_minmax_w(f24_fast_decode(a), f24_fast_decode(b), 0));
}
static inline f24_t f24_fast_max(f24_t a, f24_t b)
{
    return f24_fast_encode(f24_fast_minmax_w(f24_fast_decode(a), f24_fast_decode(b), 1));
}

#ifdef F24_FAST_SIM
typedef double f24w;
static inline f24w f24w_of(f24_t a) { return f24_fast_decode(a); }
static inline f24_t f24w_bits(f24w a)
{
    return f24_fast_encode(a) | (a != a && __builtin_signbit(a) ? F24_SIGN_BIT : 0u);
}
static inline f24w f24w_add(f24w a, f24w b) { return f24_fast_round(a + b); }
static inline f24w f24w_sub(f24w a, f24w b) { return f24_fast_round(a - b); }
static inline f24w f24w_mul(f24w a, f24w b) { return f24_fast_round(a * b); }
static inline f24w f24w_div(f24w a, f24w b) { return f24_fast_round(a / b); }
static inline f24w f24w_min(f24w a, f24w b) { return f24_fast_minmax_w(a, b, 0); }
static inline f24w f24w_max(f24w a, f24w b) { return f24_fast_minmax_w(a, b, 1); }
static inline f24w f24w_neg(f24w a) { return -a; }
static inline int f24w_lt(f24w a, f24w b) { return a < b; }
static inline int f24w_le(f24w a, f24w b) { return a <= b; }
static inline uint32_t f24w_sign(f24w a) { return __builtin_signbit(a) != 0; }

#define f24_lt f24_fast_lt
#define f24_le f24_fast_le
#define f24_eq f24_fast_eq
#define f24_min f24_fast_min
#define f24_max f24_fast_max
#define f24_add f24_fast_add
#define f24_sub f24_fast_sub
#define f24_mul f24_fast_mul
#define f24_div f24_fast_div
#define f24_sqrt f24_fast_sqrt
#define f24_sum_exact f24_fast_sum_exact
#define f24_from_i32 f24_fast_from_i32
#define f24_from_f32 f24_fast_from_f32
#endif

#endif
