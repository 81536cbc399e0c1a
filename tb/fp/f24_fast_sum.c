/*
 * Host fast path of f24_sum_exact (hls/fp24/f24_sum_exact.c), bit-identical to it: the
 * simulation build maps f24_sum_exact here (tb/fp/f24_fast.h).
 *
 * The integer operator holds the exact sum S of the products in a 128-bit window whenever no
 * product falls below the window's last bit, and then returns hi = RN(S) and lo = RN(S - hi).
 * Here every product is exact in binary64 ((M+1)x(M+1) <= 48 bits), the products are summed
 * with error-free transformations (TwoSum) into a double-double s + e, and the partial errors are
 * accumulated with a check that their sum is exact, so s + e == S exactly. Rounding S to fp24
 * then is the rounding of s, except where s sits exactly on a midpoint between two fp24 values
 * and e breaks the tie; the remainder S - hi is again a double-double (s - hi is exact by
 * Sterbenz's lemma: s and hi are roundings of the same S). Everything this cannot decide
 * cheaply (a NaN or Inf operand, products too far apart for the window, an inexact error sum)
 * goes to the integer operator, which also keeps the rare paths' rules in one place.
 * tests/test_f24_sum.c compares both on random, cancelling, tie-breaking and special terms.
 */
#include <string.h>

#include "f24_fast.h"

typedef struct { double s, e; } f24_dd; /* s + e exactly */

/* Knuth's TwoSum: s = fl(a + b), e = a + b - s exactly (round to nearest, no FMA contraction). */
static inline f24_dd two_sum(double a, double b)
{
    const double s = a + b, bb = s - a;
    return (f24_dd){ s, (a - (s - bb)) + (b - bb) };
}

/* fp24 rounding of the exact r + rr (|rr| <= half an ulp of r in binary64, r != 0). Binary64
 * rounded once already, so only a tie of fp24 in r can be wrong: then rr says on which side of
 * it the exact value lies, and r moves one binary64 ulp that way. */
static f24_t round_dd(double r, double rr)
{
    enum { SHIFT = 52 - F24_MAN_BITS };
    uint64_t bits;
    memcpy(&bits, &r, sizeof bits);
    if ((bits & ((1ull << SHIFT) - 1u)) == 1ull << (SHIFT - 1) && rr != 0) {
        bits += (rr < 0) == (r < 0) ? 1 : (uint64_t)-1; /* away from or toward zero */
        memcpy(&r, &bits, sizeof r);
    }
    return f24_fast_encode(r);
}

/* The window of the integer operator holds the exact sum when the nonzero products a[k]*b[k]
 * are not too far apart (beyond, only its hi is exact and the integer operator decides).
 * Products of significands in [1, 2) lie in [2^e, 2^(e+2)) for the sum e of the exponents, so a
 * magnitude ratio below 2^(window - 2) keeps e within the window's reach. */
#define WINDOW_REACH_LOG2 (127 - 5 - (2 * F24_MAN_BITS + 1) - 2) /* f24_sum_exact.c: top - 2 (73 .. 103) */
/* 2^WINDOW_REACH_LOG2 as a product of two exact powers, so that it is a constant expression for
 * every compiler (clang does not fold __builtin_ldexp in an initializer) */
static const double window_reach =
    (double)(1ull << WINDOW_REACH_LOG2 / 2) * (double)(1ull << (WINDOW_REACH_LOG2 - WINDOW_REACH_LOG2 / 2));

/* 1 if the products p span no more than the window holds (the rare spreads between the
 * bounds go the slow way); Inf and NaN operands show up as a non-finite sum later. */
static int within_window(const double p[], uint32_t n)
{
    double largest = 0, smallest = __builtin_inf();
    for (uint32_t k = 0; k < n; k++) {
        const double m = __builtin_fabs(p[k]);
        largest = m > largest ? m : largest;
        smallest = m != 0 && m < smallest ? m : smallest;
    }
    return largest < smallest * window_reach || largest == __builtin_inf();
}

/* The fp24 rounding of x's magnitude as an integer (the kept bits, a carry into the exponent
 * included): monotone in |x|, so two values of one sign with equal keys bound an interval that
 * rounds to one fp24 value, range rules included (they depend on the rounded value only). */
static inline uint64_t round_key(double x)
{
    enum { SHIFT = 52 - F24_MAN_BITS };
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    bits &= 0x7FFFFFFFFFFFFFFFull;
    return (bits + ((1ull << (SHIFT - 1)) - 1u) + ((bits >> SHIFT) & 1u)) >> SHIFT;
}

/* 1 if every value within w of x (w >= 0) has x's sign and rounds to fp24 as x does; w = 0 is
 * exact. x +- w are computed rounded; the callers' w hold the margin for that. */
static inline int rounds_alike(double x, double w)
{
    const double ax = __builtin_fabs(x);
    return w == 0 || (w < ax && round_key(ax - w) == round_key(ax + w));
}

/* A bound on |s - S| for the recursive binary64 sum s of the n products p and their exact sum
 * S, 0 where s is exact; NaN where the products are not finite or spread wider than the window
 * (sum|p| bounds the largest one). Every product has at most 2(M+1) significant bits, so all
 * are multiples of 2^(e - 2M - 1) for the exponent e of the smallest nonzero one, and partial
 * sums below 2^(e + 52 - 2M) are exact: mass = sum|p| < smallest 2^(50 - 2M) guarantees that
 * with room for mass's own rounding. Otherwise recursive summation errs by at most
 * (n-1)u/(1-(n-1)u) mass <= n u mass (u = 2^-53); n 2^-50 mass leaves room for the bound's own
 * roundings. */
static double sum_error(const double p[], uint32_t n, double *s)
{
    double sum = -0.0, mass = 0, smallest = __builtin_inf(); /* -0: -0 only if all products are -0 */
    for (uint32_t k = 0; k < n; k++) {
        const double m = __builtin_fabs(p[k]);
        sum += p[k];
        mass += m;
        smallest = m != 0 && m < smallest ? m : smallest;
    }
    *s = sum;
    if (!(mass < smallest * window_reach))
        return __builtin_nan("");
    return mass < smallest * __builtin_ldexp(1.0, 50 - 2 * F24_MAN_BITS) ? 0 : mass * (double)n * 0x1p-50;
}

int f24_fast_sum_filter(const double p[], uint32_t n, f24x2 *r)
{
    double s;
    const double err = sum_error(p, n, &s);
    /* 2 err and 2^-50 |x| cover the error of s and the roundings of x +- w (|x| u each) */
    if (err != err || !rounds_alike(s, 2 * err + __builtin_fabs(s) * 0x1p-50 * (err != 0)))
        return 0;
    const f24_t hi = f24_fast_encode(s);
    if (f24_exp(hi) == 0 || f24_exp(hi) == F24_EXP_MAX) { /* flushed (or zero) or overflowed */
        *r = (f24x2){ hi, 0 };
        return 1;
    }
    const double rest = s - f24_fast_decode(hi); /* exact: |s - hi| <= ulp(hi) / 2 */
    if (!rounds_alike(rest, 2 * err + __builtin_fabs(rest) * 0x1p-50 * (err != 0)))
        return 0;
    *r = (f24x2){ hi, rest == 0 ? 0 : f24_fast_encode(rest) };
    return 1;
}

#ifdef F24_FAST_VECTORS
#define F24V_PRODUCTS_FN F24V_FN
#else
#define F24V_PRODUCTS_FN
#endif

/* The products a[k] b[k] into p, exact in binary64 (at most 2(M+1) significant bits); four at a
 * time where the build has the vectors of tb/fp/f24_fast.h. */
static F24V_PRODUCTS_FN void products(const f24_t a[], const f24_t b[], uint32_t n, double p[F24_SUM_TERMS])
{
#ifdef F24_FAST_VECTORS
    f24_t ap[F24_SUM_TERMS] = { 0 }, bp[F24_SUM_TERMS] = { 0 };
    memcpy(ap, a, n * sizeof a[0]);
    memcpy(bp, b, n * sizeof b[0]);
    for (uint32_t k = 0; k < n; k += F24Q_LANES) {
        const f24v v = f24v_of(ap + k) * f24v_of(bp + k); /* lanes past n: zeros, unused */
        memcpy(p + k, &v, sizeof v);
    }
#else
    for (uint32_t k = 0; k < n; k++)
        p[k] = f24_fast_decode(a[k]) * f24_fast_decode(b[k]);
#endif
}

f24x2 f24_fast_sum_exact(const f24_t a[], const f24_t b[], uint32_t n)
{
    double p[F24_SUM_TERMS] = { 0 }; /* (products writes p[0 .. n-1]: for the compiler's flow analysis) */
    if (n == 0 || n > F24_SUM_TERMS)
        return f24_sum_exact(a, b, n);
    products(a, b, n, p);
    f24x2 r;
    if (f24_fast_sum_filter(p, n, &r))
        return r;
    if (!within_window(p, n))
        return f24_sum_exact(a, b, n);
    /* p[0] first: a sum of zero products keeps binary64's sign rule, -0 only if all are -0 */
    double s = p[0], e = 0;
    int exact = 1;
    for (uint32_t k = 1; k < n; k++) {
        const f24_dd t = two_sum(s, p[k]), u = two_sum(e, t.e);
        s = t.s;
        e = u.s;
        exact &= u.e == 0;
    }
    if (!exact || s - s != 0) /* or an Inf or NaN operand */
        return f24_sum_exact(a, b, n);
    const f24_dd sum = two_sum(s, e);
    if (sum.s == 0) /* all products zero (signed zero) or an exact cancellation (+0) */
        return (f24x2){ f24_fast_encode(s == 0 ? s : 0.0), 0 };
    const f24_t hi = round_dd(sum.s, sum.e);
    if (f24_exp(hi) == 0 || f24_exp(hi) == F24_EXP_MAX)
        return (f24x2){ hi, 0 };
    const f24_dd rest = two_sum(sum.s - f24_fast_decode(hi), sum.e);
    return (f24x2){ hi, rest.s == 0 ? 0 : round_dd(rest.s, rest.e) };
}

#ifdef F24_FAST_VECTORS
static inline __attribute__((always_inline)) f24v abs_lanes(f24v x) { return (f24v)((f24v_i)x & 0x7FFFFFFFFFFFFFFFll); }

/* rounds_alike per lane, as a lane mask */
static inline __attribute__((always_inline)) f24v_i rounds_alike_lanes(f24v x, f24v w)
{
    enum { SHIFT = 52 - F24_MAN_BITS };
    const f24v ax = abs_lanes(x);
    const f24v_l key_lo = (f24v_l)f24v_round_bits((f24v_i)(ax - w)) >> SHIFT,
                 key_hi = (f24v_l)f24v_round_bits((f24v_i)(ax + w)) >> SHIFT;
    return (w == 0) | ((w < ax) & ((f24v_i)key_lo == (f24v_i)key_hi));
}

/* The margin of f24_fast_sum_filter around x: 2 err, and 2^-50 |x| where err != 0. */
static inline __attribute__((always_inline)) f24v margin_lanes(f24v x, f24v err, f24v_i inexact)
{
    return 2 * err + (f24v)((f24v_i)(abs_lanes(x) * 0x1p-50) & inexact);
}

typedef struct { f24v s, e; } f24v_dd;

/* two_sum per lane */
static inline __attribute__((always_inline)) f24v_dd two_sum_lanes(f24v a, f24v b)
{
    const f24v s = a + b, bb = s - a;
    return (f24v_dd){ s, (a - (s - bb)) + (b - bb) };
}

/* round_dd per lane, before the encoding: r moved one binary64 ulp toward rr where r is an fp24
 * tie and rr != 0 */
static inline __attribute__((always_inline)) f24v tie_lanes(f24v r, f24v rr)
{
    enum { SHIFT = 52 - F24_MAN_BITS };
    const f24v_i bits = (f24v_i)r, tie = ((bits & ((1ll << SHIFT) - 1)) == (1ll << (SHIFT - 1))) & (rr != 0);
    const f24v_i away = (rr < 0) == (r < 0); /* away from zero: +1 on the magnitude, else -1 */
    return (f24v)(bits + (tie & ((away & 1) | ~away)));
}

/* f24_fast_sum_exact's double-double path per lane on the products p (their magnitudes' sum mass
 * within the window): hi and lo where the error sum is exact and the sum finite, as a lane mask. */
static inline __attribute__((always_inline)) f24v_i dd_lanes(const f24v p[], uint32_t n, f24_t hi[F24Q_LANES],
                                                             f24_t lo[F24Q_LANES])
{
    f24v s = p[0], e = { 0, 0, 0, 0 };
    f24v_i exact = e == e;
    for (uint32_t k = 1; k < n; k++) {
        const f24v_dd t = two_sum_lanes(s, p[k]), u = two_sum_lanes(e, t.e);
        s = t.s;
        e = u.s;
        exact &= u.e == 0;
    }
    const f24v_dd sum = two_sum_lanes(s, e);
    const f24v_i zero = sum.s == 0; /* all products zero (signed zero) or an exact cancellation (+0) */
    const f24v hi_d = f24v_round(tie_lanes(sum.s, sum.e));
    const f24v_i hi_special = (hi_d == 0) | (abs_lanes(hi_d) == e + __builtin_inf());
    const f24v_dd rest = two_sum_lanes(sum.s - hi_d, sum.e);
    f24v_bits((f24v)f24v_select(zero, (f24v_i)s & (f24v_i)(s == 0), (f24v_i)hi_d), hi);
    f24v_bits((f24v)((f24v_i)tie_lanes(rest.s, rest.e) & ~(zero | hi_special | (rest.s == 0))), lo);
    return exact & (s - s == 0);
}

/* The lanes the filter of sum_lanes left undecided (ok 0): the double-double path on vectors, a
 * lane it cannot decide either f24_fast_sum_exact alone. Out of line, its vectors passed by
 * address: the common case needs none of its stack. */
static F24V_FN __attribute__((noinline)) void undecided_lanes(const f24v a[], const f24v b[], uint32_t n,
                                                              const f24v_i *window, const f24v_i *ok,
                                                              f24_t hi[F24Q_LANES], f24_t lo[F24Q_LANES])
{
    f24v p[F24_SUM_TERMS];
    for (uint32_t k = 0; k < n; k++)
        p[k] = a[k] * b[k]; /* exact */
    f24v_i dd = { 0, 0, 0, 0 };
    f24_t dd_hi[F24Q_LANES], dd_lo[F24Q_LANES];
    if (n > 0)
        dd = *window & dd_lanes(p, n, dd_hi, dd_lo);
    for (int i = 0; i < F24Q_LANES; i++) {
        if ((*ok)[i])
            continue;
        if (dd[i]) {
            hi[i] = dd_hi[i];
            lo[i] = dd_lo[i];
            continue;
        }
        f24_t ai[F24_SUM_TERMS], bi[F24_SUM_TERMS];
        for (uint32_t k = 0; k < n; k++) { /* the lane's terms as fp24 words (exact: fp24 values) */
            ai[k] = f24_fast_encode(a[k][i]);
            bi[k] = f24_fast_encode(b[k][i]);
        }
        const f24x2 r = f24_fast_sum_exact(ai, bi, n);
        hi[i] = r.hi;
        lo[i] = r.lo;
    }
}

/* f24_fast_sum_exact of the four lanes at once (n <= F24_SUM_TERMS): f24_fast_sum_filter on
 * vectors, the products summed in order, then for the lanes it cannot decide (cancellation: the
 * plane distance of isect_unit.c) the double-double path on vectors; a lane neither decides goes
 * to f24_fast_sum_exact alone (undecided_lanes). Inlined into f24_fast_sum_exact_lanes once per term
 * count of the units, so that the loops over the terms unroll and the products stay in registers. */
static inline __attribute__((always_inline)) void sum_lanes(const f24v a[], const f24v b[], uint32_t n,
                                                            f24_t hi[F24Q_LANES], f24_t lo[F24Q_LANES], int want_lo)
{
    const f24v zero = { 0, 0, 0, 0 }, inf = zero + __builtin_inf();
    f24v sum = -zero, mass = zero, least = inf; /* -0: -0 only if all products are -0 */
    for (uint32_t k = 0; k < n; k++) {
        const f24v p = a[k] * b[k]; /* exact */
        const f24v m = abs_lanes(p);
        sum += p;
        mass += m;
        least = (f24v)f24v_select((m != 0) & (m < least), (f24v_i)m, (f24v_i)least);
    }
    const f24v_i window = mass < least * window_reach, exact = mass < least * __builtin_ldexp(1.0, 50 - 2 * F24_MAN_BITS);
    const f24v err = (f24v)((f24v_i)(mass * (double)n * 0x1p-50) & ~exact);
    const f24v hi_d = f24v_round(sum), rest = sum - hi_d; /* exact: |s - hi| <= ulp(hi) / 2 */
    const f24v_i hi_special = (hi_d == 0) | (abs_lanes(hi_d) == inf); /* flushed (or zero) or overflowed: lo = 0 */
    /* hi alone: every value within the bound of s rounds as s does, whatever lo would be */
    const f24v_i lo_ok = want_lo ? hi_special | rounds_alike_lanes(rest, margin_lanes(rest, err, ~exact)) : (f24v_i){ 0 } - 1;
    const f24v_i ok = window & rounds_alike_lanes(sum, margin_lanes(sum, err, ~exact)) & lo_ok & (n > 0 ? -1ll : 0);
    f24v_bits(sum, hi);
    if (want_lo)
        f24v_bits((f24v)((f24v_i)rest & ~(hi_special | (rest == 0))), lo);
    if (n > 0 && (ok[0] & ok[1] & ok[2] & ok[3]) != 0)
        return; /* the common case: every lane decided */
    undecided_lanes(a, b, n, &window, &ok, hi, lo);
}

/* the term counts of the units: a vector's 3 and a point's 8 (xform_unit.c), the rebase's 4
 * (rebase_unit.c), the plane distance's 9 (isect_unit.c) */
F24V_FN void f24_fast_sum_exact_lanes(const f24v a[], const f24v b[], uint32_t n, f24_t hi[F24Q_LANES], f24_t lo[F24Q_LANES])
{
    switch (n) {
    case 3: sum_lanes(a, b, 3, hi, lo, 1); break;
    case 4: sum_lanes(a, b, 4, hi, lo, 1); break;
    case 8: sum_lanes(a, b, 8, hi, lo, 1); break;
    case 9: sum_lanes(a, b, 9, hi, lo, 1); break;
    default: sum_lanes(a, b, n, hi, lo, 1); break;
    }
}

/* the plane distance's 9 terms (isect_unit.c) */
F24V_FN void f24_fast_sum_exact_hi_lanes(const f24v a[], const f24v b[], uint32_t n, f24_t hi[F24Q_LANES])
{
    f24_t lo[F24Q_LANES]; /* the undecided lanes' (undecided_lanes), not read */
    if (n == 9)
        sum_lanes(a, b, 9, hi, lo, 0);
    else
        sum_lanes(a, b, n, hi, lo, 0);
}
#endif
