/*
 * fp24 comparator: maps each operand to a two's-complement key that orders like the value
 * (zero and subnormal encodings to 0, so -0 == +0), then one integer compare. NaN makes every
 * ordered predicate false. Hardware: two conditional negations and one (W)-bit comparator.
 */
#include "f24_internal.h"

static int32_t f24_order_key(f24_t a)
{
    const int32_t mag = f24_exp(a) == 0 ? 0 : (int32_t)(a & F24_ABS_MASK);
    return f24_sign(a) ? -mag : mag;
}

int f24_unordered(f24_t a, f24_t b) { return f24_is_nan(a) || f24_is_nan(b); }

int f24_lt(f24_t a, f24_t b) { return !f24_unordered(a, b) && f24_order_key(a) < f24_order_key(b); }

int f24_le(f24_t a, f24_t b) { return !f24_unordered(a, b) && f24_order_key(a) <= f24_order_key(b); }

int f24_eq(f24_t a, f24_t b) { return !f24_unordered(a, b) && f24_order_key(a) == f24_order_key(b); }
