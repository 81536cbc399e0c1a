/*
 * fp24 to a 32-bit signed integer, rounding toward zero (the shader's colour quantizer and any
 * index computation need it). Saturates to INT32_MIN / INT32_MAX; NaN gives 0.
 * Hardware: one right shifter of the significand by (bias + M - exponent) and a negation.
 */
#include "f24_internal.h"

int32_t f24_to_i32(f24_t a)
{
    const int32_t e = f24_exp(a) - F24_BIAS; /* value = 1.f x 2^e */
    const uint32_t sign = f24_sign(a);
    if (f24_is_nan(a))
        return 0;
    if (f24_exp(a) == 0 || e < 0)
        return 0;
    if (e >= 31) /* includes Inf */
        return sign ? INT32_MIN : INT32_MAX;
    const uint32_t sig = f24_sig(a);
    const uint32_t mag = e >= F24_MAN_BITS ? sig << (e - F24_MAN_BITS) : sig >> (F24_MAN_BITS - e);
    return sign ? (int32_t)(0u - mag) : (int32_t)mag;
}
