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

/* The products a[k]*b[k] into p; 0 if the nonzero ones may span more than the window holds
 * exactly (the integer operator decides those). Products of significands in [1, 2) lie in
 * [2^e, 2^(e+2)) for the sum e of the exponents, so a magnitude ratio below 2^(window - 2)
 * keeps e within the window's reach; the rare spreads between the two bounds go the slow way.
 * Inf and NaN operands show up as a non-finite sum later. */
static int exact_products(const f24_t a[], const f24_t b[], uint32_t n, double p[])
{
    const double reach = __builtin_ldexp(1.0, 127 - 5 - (2 * F24_MAN_BITS + 1) - 2); /* f24_sum_exact.c: top - 2 */
    double largest = 0, smallest = __builtin_inf();
    for (uint32_t k = 0; k < n; k++) {
        p[k] = f24_fast_decode(a[k]) * f24_fast_decode(b[k]);
        const double m = __builtin_fabs(p[k]);
        largest = m > largest ? m : largest;
        smallest = m != 0 && m < smallest ? m : smallest;
    }
    return largest < smallest * reach || largest == __builtin_inf();
}

f24x2 f24_fast_sum_exact(const f24_t a[], const f24_t b[], uint32_t n)
{
    double p[F24_SUM_TERMS];
    if (n == 0 || n > F24_SUM_TERMS || !exact_products(a, b, n, p))
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
