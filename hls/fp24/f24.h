/*
 * fp24: the number format of the saarcor pipeline (paper section 4.2).
 *
 * A binary floating-point format with 1 sign bit, F24_EXP_BITS exponent bits and F24_MAN_BITS
 * fraction bits, stored in the low 1+E+M bits of a uint32_t (default E=7, M=16: 24 bits).
 * Semantics (exact rules in docs/fp24.md, which the RTL matches bit for bit):
 *   - round to nearest, ties to even; tininess detected after rounding;
 *   - subnormal inputs are read as zero of the same sign, results below the smallest normal
 *     are flushed to zero of the result's sign;
 *   - exponent all ones: Inf (fraction 0) or NaN; every NaN result is F24_DEFAULT_NAN;
 *   - overflow gives Inf.
 * This is the hardware reference: integer-only C, no libc, no floating-point types, bounded
 * loops, usable unchanged by HLS. One file per operation, one shared round-and-pack routine
 * (f24_round_pack.c), as in Berkeley SoftFloat.
 */
#ifndef SAARCOR_F24_H
#define SAARCOR_F24_H

#include <stdint.h>

#ifndef F24_EXP_BITS
#define F24_EXP_BITS 7
#endif
#ifndef F24_MAN_BITS
#define F24_MAN_BITS 16
#endif
#if F24_EXP_BITS < 3 || F24_EXP_BITS > 8
#error "F24_EXP_BITS must be in 3..8 (every value must be exactly representable in binary32)"
#endif
#if F24_MAN_BITS < 2 || F24_MAN_BITS > 23
#error "F24_MAN_BITS must be in 2..23 (binary32 conversions; 7 round bits in the datapath)"
#endif

typedef uint32_t f24_t;

#define F24_WIDTH      (1 + F24_EXP_BITS + F24_MAN_BITS)
#define F24_BIAS       ((1 << (F24_EXP_BITS - 1)) - 1)
#define F24_EXP_MAX    ((1 << F24_EXP_BITS) - 1) /* biased exponent of Inf and NaN */
#define F24_FRAC_MASK  ((1u << F24_MAN_BITS) - 1u)
#define F24_SIGN_BIT   (1u << (F24_EXP_BITS + F24_MAN_BITS))
#define F24_ABS_MASK   (F24_SIGN_BIT - 1u)
#define F24_MASK       (F24_SIGN_BIT | F24_ABS_MASK)
#define F24_POS_INF    ((uint32_t)F24_EXP_MAX << F24_MAN_BITS)
#define F24_DEFAULT_NAN (F24_POS_INF | (1u << (F24_MAN_BITS - 1)))
#define F24_ONE        ((uint32_t)F24_BIAS << F24_MAN_BITS)
#define F24_MIN_NORMAL (1u << F24_MAN_BITS)
#define F24_MAX_NORMAL (F24_POS_INF - 1u)

/* Field access. Bits above F24_WIDTH are ignored by every operation. */
static inline uint32_t f24_sign(f24_t a) { return (a >> (F24_EXP_BITS + F24_MAN_BITS)) & 1u; }
static inline int32_t f24_exp(f24_t a) { return (int32_t)((a >> F24_MAN_BITS) & (uint32_t)F24_EXP_MAX); }
static inline uint32_t f24_frac(f24_t a) { return a & F24_FRAC_MASK; }
static inline f24_t f24_pack(uint32_t sign, uint32_t exp, uint32_t frac)
{
    return (sign << (F24_EXP_BITS + F24_MAN_BITS)) | (exp << F24_MAN_BITS) | frac;
}

/* Classification. Zero includes the subnormal encodings, which every operation reads as zero. */
static inline int f24_is_nan(f24_t a) { return f24_exp(a) == F24_EXP_MAX && f24_frac(a) != 0; }
static inline int f24_is_inf(f24_t a) { return f24_exp(a) == F24_EXP_MAX && f24_frac(a) == 0; }
static inline int f24_is_zero(f24_t a) { return f24_exp(a) == 0; }

/* Sign operations: pure bit operations (IEEE 754 "quiet-computational"), no rounding, no DAZ. */
static inline f24_t f24_neg(f24_t a) { return (a ^ F24_SIGN_BIT) & F24_MASK; }
static inline f24_t f24_abs(f24_t a) { return a & F24_ABS_MASK; }

/* Arithmetic (correctly rounded, f24_add.c ... f24_sqrt.c). */
f24_t f24_add(f24_t a, f24_t b);
f24_t f24_sub(f24_t a, f24_t b);
f24_t f24_mul(f24_t a, f24_t b);
f24_t f24_div(f24_t a, f24_t b);
f24_t f24_sqrt(f24_t a);

/* Double words (f24_sum_exact.c): hi + lo with |lo| <= ulp(hi) / 2, about 2(M+1) significant
 * bits, for the positions of rays where one fp24 would cancel (docs/fp24.md). */
typedef struct { f24_t hi, lo; } f24x2;
#define F24_SUM_TERMS 12
/* hi + lo = a[0]*b[0] + ... + a[n-1]*b[n-1] (n <= F24_SUM_TERMS), from exact products. */
f24x2 f24_sum_exact(const f24_t a[], const f24_t b[], uint32_t n);

/* Comparisons: 1 or 0. lt/le/eq are false when either operand is NaN; -0 == +0. */
int f24_lt(f24_t a, f24_t b);
int f24_le(f24_t a, f24_t b);
int f24_eq(f24_t a, f24_t b);
int f24_unordered(f24_t a, f24_t b);

/* IEEE 754-2019 minimumNumber/maximumNumber: a NaN operand yields the other operand,
 * -0 < +0, subnormal inputs come back as signed zero. */
f24_t f24_min(f24_t a, f24_t b);
f24_t f24_max(f24_t a, f24_t b);

/* Conversions. binary32 values are passed as their bit patterns (uint32_t). */
f24_t f24_from_f32(uint32_t bits);
uint32_t f24_to_f32(f24_t a); /* exact: every fp24 value is a binary32 value */
f24_t f24_from_i32(int32_t i);
int32_t f24_to_i32(f24_t a); /* toward zero, saturating, NaN -> 0 */

#define F24Q_LANES 4 /* lanes of the packet values below: the rays of a packet */

/* Host simulation builds may swap in a bit-identical fast path for these operations at build
 * time: the build names its header in F24_SIM_HEADER (tb/fp/f24_fast.h, Makefile SIM_FLAGS), so
 * that nothing here depends on the simulator; hardware and reference builds define none. */
#ifdef F24_SIM_HEADER
#include F24_SIM_HEADER
#endif
/* Functions a simulation build keeps out of line (its F24_SIM_HEADER may define this as a
 * compiler attribute): a unit's rare operations beside its frequent one. Nothing in the C an HLS
 * tool reads. */
#ifndef F24_SIM_NOINLINE
#define F24_SIM_NOINLINE
#endif

/* Working values. A chain of operations inside a unit (a row of a matrix, a ray against a
 * plane) reads its fp24 inputs with f24w_of, computes with the f24w_ operations (the f24_ ones,
 * the same roundings) and stores its results with f24w_bits. In the hardware build a working value
 * is the fp24 word itself and these are the operations above; a simulation build may hold it
 * decoded (its F24_SIM_HEADER defines F24_SIM_WORKING), so that a chain decodes and encodes once
 * instead of around every operation. Only results of operations pass through f24w_bits: a value
 * copied from one register to another stays an f24_t, so its bits are never normalized. */
#ifndef F24_SIM_WORKING
typedef f24_t f24w;
static inline f24w f24w_of(f24_t a) { return a; }
static inline f24_t f24w_bits(f24w a) { return a; }
static inline f24w f24w_add(f24w a, f24w b) { return f24_add(a, b); }
static inline f24w f24w_sub(f24w a, f24w b) { return f24_sub(a, b); }
static inline f24w f24w_mul(f24w a, f24w b) { return f24_mul(a, b); }
static inline f24w f24w_div(f24w a, f24w b) { return f24_div(a, b); }
static inline f24w f24w_sqrt(f24w a) { return f24_sqrt(a); }
static inline f24w f24w_from_i32(int32_t i) { return f24_from_i32(i); }
static inline int32_t f24w_to_i32(f24w a) { return f24_to_i32(a); }
static inline f24w f24w_min(f24w a, f24w b) { return f24_min(a, b); }
static inline f24w f24w_max(f24w a, f24w b) { return f24_max(a, b); }
static inline f24w f24w_neg(f24w a) { return f24_neg(a); }
static inline int f24w_lt(f24w a, f24w b) { return f24_lt(a, b); }
static inline int f24w_le(f24w a, f24w b) { return f24_le(a, b); }
static inline uint32_t f24w_sign(f24w a) { return f24_sign(a); }
#endif

/* Packet values: the working values of the F24Q_LANES rays of a packet side by side, one lane
 * per ray, as a unit's per-ray datapaths compute them in parallel. Comparisons and the sign give
 * lane masks (bit i: lane i). Here each lane is an f24w and each operation the f24w one; a
 * simulation build may hold the lanes in one vector register (its F24_SIM_HEADER defines
 * F24_SIM_LANES) and compile the functions that use them for several instruction sets (F24Q_FN
 * on their definitions), so that the lanes compute together; the roundings stay the same. */
#ifndef F24_SIM_LANES
#define F24Q_FN
#define F24Q_INLINE static inline /* helpers on packet values (f24_held.h); vector lanes inline them always */
typedef struct { f24w l[F24Q_LANES]; } f24q;
static inline f24q f24q_of(const f24_t a[F24Q_LANES])
{
    f24q q;
lanes_of:
    for (int i = 0; i < F24Q_LANES; i++)
        q.l[i] = f24w_of(a[i]);
    return q;
}
static inline f24q f24q_splat(f24_t a)
{
    const f24_t s[F24Q_LANES] = { a, a, a, a };
    return f24q_of(s);
}
static inline void f24q_bits(f24q a, f24_t out[F24Q_LANES])
{
lanes_bits:
    for (int i = 0; i < F24Q_LANES; i++)
        out[i] = f24w_bits(a.l[i]);
}
#define F24Q_BINARY(name)                                                                          \
    static inline f24q f24q_##name(f24q a, f24q b)                                                 \
    {                                                                                              \
        f24q q;                                                                                    \
        for (int i = 0; i < F24Q_LANES; i++)                                                       \
            q.l[i] = f24w_##name(a.l[i], b.l[i]);                                                  \
        return q;                                                                                  \
    }
F24Q_BINARY(add)
F24Q_BINARY(mul)
F24Q_BINARY(sub)
F24Q_BINARY(div)
F24Q_BINARY(min)
F24Q_BINARY(max)
static inline f24q f24q_sqrt(f24q a)
{
lanes_sqrt:
    for (int i = 0; i < F24Q_LANES; i++)
        a.l[i] = f24w_sqrt(a.l[i]);
    return a;
}
static inline f24q f24q_from_i32(const int32_t a[F24Q_LANES])
{
    f24q q;
lanes_from_i32:
    for (int i = 0; i < F24Q_LANES; i++)
        q.l[i] = f24w_from_i32(a[i]);
    return q;
}
/* The columns of a matrix of 3 rows and 4 columns: lane r of col[k] is m[r][k], lane 3 zero (the
 * rows side by side, as the transformation unit's per-row datapaths read them). */
static inline void f24q_columns(const f24_t m[3][4], f24q col[4])
{
lanes_columns:
    for (int k = 0; k < 4; k++) {
        const f24_t c[F24Q_LANES] = { m[0][k], m[1][k], m[2][k], 0u };
        col[k] = f24q_of(c);
    }
}
static inline f24w f24q_lane(f24q a, int i) { return a.l[i]; }
static inline f24q f24q_broadcast(f24q a, int i) /* lane i in every lane */
{
    f24q q;
lanes_broadcast:
    for (int j = 0; j < F24Q_LANES; j++)
        q.l[j] = a.l[i];
    return q;
}
static inline f24q f24q_select(uint32_t mask, f24q a, f24q b) /* lane i of a where mask bit i */
{
lanes_select:
    for (int i = 0; i < F24Q_LANES; i++)
        a.l[i] = mask >> i & 1u ? a.l[i] : b.l[i];
    return a;
}
static inline uint32_t f24q_le(f24q a, f24q b)
{
    uint32_t m = 0;
lanes_le:
    for (int i = 0; i < F24Q_LANES; i++)
        m |= (uint32_t)f24w_le(a.l[i], b.l[i]) << i;
    return m;
}
static inline uint32_t f24q_lt(f24q a, f24q b)
{
    uint32_t m = 0;
lanes_lt:
    for (int i = 0; i < F24Q_LANES; i++)
        m |= (uint32_t)f24w_lt(a.l[i], b.l[i]) << i;
    return m;
}
static inline uint32_t f24q_sign(f24q a)
{
    uint32_t m = 0;
lanes_sign:
    for (int i = 0; i < F24Q_LANES; i++)
        m |= f24w_sign(a.l[i]) << i;
    return m;
}
/* Exact dot products side by side: lane i is f24_sum_exact of the n terms a[k] * b[k] of lane i
 * (each lane's terms its working values' bits: the same values). */
static inline void f24q_sum_exact(const f24q a[], const f24q b[], uint32_t n, f24_t hi[F24Q_LANES], f24_t lo[F24Q_LANES])
{
lanes_sum:
    for (int i = 0; i < F24Q_LANES; i++) {
        f24_t ai[F24_SUM_TERMS], bi[F24_SUM_TERMS];
    lanes_sum_terms:
        for (uint32_t k = 0; k < F24_SUM_TERMS; k++) {
            ai[k] = k < n ? f24w_bits(a[k].l[i]) : 0u;
            bi[k] = k < n ? f24w_bits(b[k].l[i]) : 0u;
        }
        const f24x2 r = f24_sum_exact(ai, bi, n);
        hi[i] = r.hi;
        lo[i] = r.lo;
    }
}
/* Their high words alone (the intersection's plane distance): the same hi bits. */
static inline void f24q_sum_exact_hi(const f24q a[], const f24q b[], uint32_t n, f24_t hi[F24Q_LANES])
{
    f24_t lo[F24Q_LANES];
    f24q_sum_exact(a, b, n, hi, lo);
}
#endif

#endif
