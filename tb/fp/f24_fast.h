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
#define F24_SIM_NOINLINE __attribute__((noinline)) /* f24.h: the rare operations out of line */
#define F24_SIM_WORKING /* f24.h then leaves the working values to this header */
#ifndef __clang__
#define F24_SIM_LANES /* and the packet values (the vectors below; clang keeps f24.h's lanes) */
#endif
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

#ifndef __clang__
#define F24_FAST_VECTORS
/* Four binary64 working values in one vector (the packet values of hls/fp24/f24.h in the
 * simulation build), each operation the f24w one below on all lanes at once, written with lane
 * masks (-1 or 0) and selects instead of branches. Functions using them (F24V_FN) are compiled
 * for AVX2 and for the baseline instruction set, one chosen at load time by the CPU (the baseline
 * one runs the vectors as pairs of SSE2 halves). Not with clang (the fuzz build): it rejects
 * 32-byte vectors passed by value in code compiled without AVX. */
#pragma GCC diagnostic ignored "-Wpsabi" /* static inline helpers: no ABI between them */
typedef double f24v __attribute__((vector_size(32)));
typedef int64_t f24v_i __attribute__((vector_size(32)));
typedef uint64_t f24v_l __attribute__((vector_size(32)));
typedef uint32_t f24v_u __attribute__((vector_size(16)));
#ifdef F24_SIM_BASELINE /* the build's SIM_LANES=baseline: only what machines without AVX2 run */
#define F24V_FN
#else
#define F24V_FN __attribute__((target_clones("avx2", "default")))
#endif
/* always inlined, also at -O0: a call would pass the vectors between code with and without AVX */
#define F24V_INLINE static inline __attribute__((always_inline))

typedef int32_t f24v_s __attribute__((vector_size(16)));
/* The lanes' constants, read from memory (tb/fp/f24_fast_lanes.c): gcc 12 builds a constant vector
 * it can see from an immediate in a general register and a broadcast, three instructions per
 * constant and function, where a memory operand costs none. In binary64 bit positions: the
 * magnitude mask, the rounding's half-ulp less one and its even bit, the kept bits, the smallest
 * normal and Inf of fp24, binary64's Inf, the sign, the default NaN decoded; as fp24 words in 64-bit
 * lanes (f24v_bits): the rebiasing, the smallest normal, Inf, the sign and the default NaN; in
 * 32-bit lanes (f24v_of): the magnitude mask, the rebiasing to binary32, the smallest normal and Inf
 * less one (for a greater-than), binary32's exponent field. */
typedef struct {
    f24v_i abs52, half52, one, keep52, min52, inf52, inf52_bits, sign52, nan52;
    f24v_i rebias, min_normal, pos_inf, sign_bit, default_nan;
    f24v_s abs24, rebias32, min_normal_m1, pos_inf_m1, exp32;
} f24v_consts;
extern const f24v_consts f24v_k;

F24V_INLINE f24v_i f24v_select(f24v_i mask, f24v_i a, f24v_i b) { return (a & mask) | (b & ~mask); }

/* lane i's bit at i: the halves or-ed together first (gcc: 6 instructions instead of 11) */
typedef int64_t f24v_i2 __attribute__((vector_size(16)));
F24V_INLINE uint32_t f24v_mask(f24v_i m)
{
    const f24v_i b = m & (f24v_i){ 1, 2, 4, 8 };
    const f24v_i2 o = (f24v_i2){ b[0], b[1] } | (f24v_i2){ b[2], b[3] };
    return (uint32_t)(o[0] | o[1]);
}

/* f24_fast_decode per lane, through binary32 (every fp24 value is one: E <= 8, M <= 23, f24.h):
 * the fields move within 32-bit lanes, then one exact conversion widens the lanes to binary64.
 * Inf and NaN keep their fraction bits (exponent all ones or-ed in): a NaN lane is a NaN with
 * its sign, whatever payload it carries, which no operation, comparison or encoding of a working
 * value can tell apart from f24_fast_decode's payload-free NaN (every NaN result is the default
 * NaN, f24w_bits writes F24_DEFAULT_NAN with the sign), and it saves the classification of NaN
 * against Inf. The widening is written per element, which gcc compiles to one vcvtps2pd
 * (__builtin_convertvector takes four). */
typedef float f24v_f __attribute__((vector_size(16)));
F24V_INLINE f24v f24v_of(const f24_t a[F24Q_LANES])
{
    const f24v_s x = { (int32_t)a[0], (int32_t)a[1], (int32_t)a[2], (int32_t)a[3] };
    const f24v_s mag = x & f24v_k.abs24; /* below 2^31: signed comparisons are exact */
    const f24v_s sign = (f24v_s)((f24v_u)x >> (F24_EXP_BITS + F24_MAN_BITS) << 31);
    const f24v_s normal = (mag << (23 - F24_MAN_BITS)) + f24v_k.rebias32;
    const f24v_s bits = sign | (normal & (mag > f24v_k.min_normal_m1)) | ((mag > f24v_k.pos_inf_m1) & f24v_k.exp32);
    f24v_f f;
    memcpy(&f, &bits, sizeof f);
    return (f24v){ f[0], f[1], f[2], f[3] };
}

/* Two working values are the same value: equal bits, or both NaN of one sign (a lane of f24v_of
 * keeps a NaN's fraction bits, which nothing reads; the tests compare decodings with it). */
static inline int f24_fast_same(double x, double y)
{
    return x != x ? y != y && __builtin_signbit(x) == __builtin_signbit(y) : memcmp(&x, &y, sizeof x) == 0;
}

F24V_INLINE f24v f24v_splat(f24_t a)
{
    const double d = f24_fast_decode(a);
    return (f24v){ d, d, d, d };
}

/* The rounding to nearest even of a binary64 magnitude's significand to M+1 bits (a carry
 * moves into the exponent field), in binary64 bit positions. */
F24V_INLINE f24v_i f24v_round_bits(f24v_i mag52)
{
    enum { SHIFT = 52 - F24_MAN_BITS };
    return mag52 + f24v_k.half52 + ((f24v_i)((f24v_l)mag52 >> SHIFT) & f24v_k.one);
}

/* f24_fast_round per lane */
F24V_INLINE f24v f24v_round(f24v d)
{
    const f24v_i bits = (f24v_i)d, mag52 = bits & f24v_k.abs52;
    const f24v_i r = f24v_round_bits(mag52) & f24v_k.keep52;
    const f24v_i ranged = f24v_select(r < f24v_k.min52, (f24v_i){ 0 }, f24v_select(r < f24v_k.inf52, r, f24v_k.inf52_bits));
    return (f24v)f24v_select(mag52 > f24v_k.inf52_bits, f24v_k.nan52, (bits & f24v_k.sign52) | ranged);
}

/* f24w_bits per lane */
F24V_INLINE void f24v_bits(f24v a, f24_t out[F24Q_LANES])
{
    enum { SHIFT = 52 - F24_MAN_BITS };
    const f24v_i bits = (f24v_i)a, mag52 = bits & f24v_k.abs52, sign = bits < 0;
    const f24v_i rebiased = (f24v_i)((f24v_l)f24v_round_bits(mag52) >> SHIFT) - f24v_k.rebias;
    const f24v_i ranged = f24v_select(rebiased < f24v_k.min_normal, (f24v_i){ 0 },
                                      f24v_select(rebiased < f24v_k.pos_inf, rebiased, f24v_k.pos_inf));
    const f24v_i nan = a != a, sign_bit = sign & f24v_k.sign_bit;
    const f24v_i w = f24v_select(nan, (nan & sign_bit) | f24v_k.default_nan, sign_bit | ranged);
    /* per element: gcc narrows with one shuffle of the two halves (__builtin_convertvector: five) */
    const f24v_u u = { (uint32_t)w[0], (uint32_t)w[1], (uint32_t)w[2], (uint32_t)w[3] };
    memcpy(out, &u, sizeof u);
}

/* f24_fast_minmax_w per lane */
F24V_INLINE f24v f24v_minmax(f24v x, f24v y, int want_max)
{
    const f24v_i xb = (f24v_i)x, yb = (f24v_i)y, x_nan = x != x, y_nan = y != y;
    const f24v_i x_first = (x < y) | ((x == y) & (xb < 0)); /* -0 before +0 */
    const f24v_i both = f24v_select(want_max ? ~x_first : x_first, xb, yb);
    const f24v_i one = f24v_select(y_nan, xb, both);
    return (f24v)f24v_select(x_nan, f24v_select(y_nan, f24v_k.nan52, yb), one);
}

F24V_INLINE f24v f24v_add(f24v a, f24v b) { return f24v_round(a + b); }
F24V_INLINE f24v f24v_mul(f24v a, f24v b) { return f24v_round(a * b); }
F24V_INLINE f24v f24v_sub(f24v a, f24v b) { return f24v_round(a - b); }
F24V_INLINE f24v f24v_div(f24v a, f24v b) { return f24v_round(a / b); }
F24V_INLINE f24v f24v_sqrt(f24v a)
{
    return f24v_round((f24v){ __builtin_sqrt(a[0]), __builtin_sqrt(a[1]), __builtin_sqrt(a[2]), __builtin_sqrt(a[3]) });
}
F24V_INLINE f24v f24v_from_i32(const int32_t a[F24Q_LANES]) /* exact in binary64, then rounded */
{
    const f24v_s x = { a[0], a[1], a[2], a[3] };
    return f24v_round((f24v){ x[0], x[1], x[2], x[3] }); /* one vcvtdq2pd, as f24v_of's widening */
}
F24V_INLINE f24v f24v_min(f24v a, f24v b) { return f24v_minmax(a, b, 0); }
F24V_INLINE f24v f24v_max(f24v a, f24v b) { return f24v_minmax(a, b, 1); }
/* f24q_columns: the three rows decoded (a row's words lie side by side), then transposed, instead
 * of four columns gathered word by word and decoded */
F24V_INLINE void f24v_columns(const f24_t m[3][4], f24v col[4])
{
    const f24v r0 = f24v_of(m[0]), r1 = f24v_of(m[1]), r2 = f24v_of(m[2]), zero = { 0, 0, 0, 0 };
    const f24v_i even = { 0, 4, 2, 6 }, odd = { 1, 5, 3, 7 }, low = { 0, 1, 4, 5 }, high = { 2, 3, 6, 7 };
    const f24v t0 = __builtin_shuffle(r0, r1, even), t1 = __builtin_shuffle(r0, r1, odd);
    const f24v t2 = __builtin_shuffle(r2, zero, even), t3 = __builtin_shuffle(r2, zero, odd);
    col[0] = __builtin_shuffle(t0, t2, low);
    col[1] = __builtin_shuffle(t1, t3, low);
    col[2] = __builtin_shuffle(t0, t2, high);
    col[3] = __builtin_shuffle(t1, t3, high);
}
F24V_INLINE double f24v_lane(f24v a, int i) { return a[i]; }
/* one permutation, where a splat of an fp24 word decodes it alone */
F24V_INLINE f24v f24v_broadcast(f24v a, int i) { return (f24v){ a[i], a[i], a[i], a[i] }; }
F24V_INLINE f24v f24v_pick(uint32_t mask, f24v a, f24v b) /* lane i of a where mask bit i */
{
    const f24v_i m = ((f24v_i){ 1, 2, 4, 8 } & (int64_t)mask) != 0;
    return (f24v)f24v_select(m, (f24v_i)a, (f24v_i)b);
}
F24V_INLINE uint32_t f24v_le(f24v a, f24v b) { return f24v_mask(a <= b); }
F24V_INLINE uint32_t f24v_lt(f24v a, f24v b) { return f24v_mask(a < b); }
F24V_INLINE uint32_t f24v_sign(f24v a) { return f24v_mask((f24v_i)a < 0); }

/* f24q_sum_exact (hls/fp24/f24.h) on vectors (tb/fp/f24_fast_sum.c): the terms' lanes are
 * working values, so that a unit passes the ones it holds decoded and decodes a repeated term once */
void f24_fast_sum_exact_lanes(const f24v a[], const f24v b[], uint32_t n, f24_t hi[F24Q_LANES], f24_t lo[F24Q_LANES]);
/* its hi alone (f24q_sum_exact_hi): the filter then needs no bound on the remainder, so that a sum
 * cancelling down to its last bits is decided by its rounding alone more often */
void f24_fast_sum_exact_hi_lanes(const f24v a[], const f24v b[], uint32_t n, f24_t hi[F24Q_LANES]);
#endif

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
static inline f24w f24w_sqrt(f24w a) { return f24_fast_round(__builtin_sqrt(a)); }
static inline f24w f24w_from_i32(int32_t i) { return f24_fast_round((double)i); }
/* f24_to_i32 (hls/fp24/f24_to_i32.c): toward zero, saturating, NaN -> 0 */
static inline int32_t f24w_to_i32(f24w a)
{
    return a != a ? 0 : a >= 0x1p31 ? INT32_MAX : a <= -0x1p31 ? INT32_MIN : (int32_t)a;
}
static inline f24w f24w_min(f24w a, f24w b) { return f24_fast_minmax_w(a, b, 0); }
static inline f24w f24w_max(f24w a, f24w b) { return f24_fast_minmax_w(a, b, 1); }
static inline f24w f24w_neg(f24w a) { return -a; }
static inline int f24w_lt(f24w a, f24w b) { return a < b; }
static inline int f24w_le(f24w a, f24w b) { return a <= b; }
static inline uint32_t f24w_sign(f24w a) { return __builtin_signbit(a) != 0; }

#ifdef F24_SIM_LANES /* the packet values of hls/fp24/f24.h are the vectors above */
typedef f24v f24q;
#define F24Q_FN F24V_FN
#define F24Q_INLINE F24V_INLINE
/* held in the units' state (f24h): at 8-byte alignment, as the words were, so that the states'
 * layout needs no 32-byte alignment (their memory may come from malloc) */
#define F24_SIM_HELD
typedef f24v f24h __attribute__((aligned(8)));
#define f24q_of f24v_of
#define f24q_splat f24v_splat
#define f24q_bits f24v_bits
#define f24q_add f24v_add
#define f24q_mul f24v_mul
#define f24q_sub f24v_sub
#define f24q_div f24v_div
#define f24q_min f24v_min
#define f24q_max f24v_max
#define f24q_sqrt f24v_sqrt
#define f24q_from_i32 f24v_from_i32
#define f24q_lane f24v_lane
#define f24q_columns f24v_columns
#define f24q_broadcast f24v_broadcast
#define f24q_select f24v_pick
#define f24q_le f24v_le
#define f24q_lt f24v_lt
#define f24q_sign f24v_sign
#define f24q_sum_exact f24_fast_sum_exact_lanes
#define f24q_sum_exact_hi f24_fast_sum_exact_hi_lanes
#endif


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
