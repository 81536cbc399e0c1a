/*
 * fp24 minimum/maximum (IEEE 754-2019 minimumNumber/maximumNumber): the comparator plus a mux.
 * A NaN operand yields the other operand (NaN only if both are NaN), -0 orders below +0, and
 * the result is canonical (subnormal encodings become signed zero). The traversal unit relies on
 * "NaN yields the other operand" to keep ray intervals finite for axis-parallel rays.
 */
#include "f24_internal.h"

static f24_t f24_canonical(f24_t a)
{
    return f24_is_zero(a) ? f24_zero(f24_sign(a)) : (a & F24_MASK);
}

static f24_t f24_minmax(f24_t a, f24_t b, int want_max)
{
    if (f24_is_nan(a))
        return f24_is_nan(b) ? F24_DEFAULT_NAN : f24_canonical(b);
    if (f24_is_nan(b))
        return f24_canonical(a);
    a = f24_canonical(a);
    b = f24_canonical(b);
    int a_first = f24_lt(a, b) || (f24_eq(a, b) && f24_sign(a)); /* -0 before +0 */
    return (a_first != want_max) ? a : b;
}

f24_t f24_min(f24_t a, f24_t b) { return f24_minmax(a, b, 0); }

f24_t f24_max(f24_t a, f24_t b) { return f24_minmax(a, b, 1); }
