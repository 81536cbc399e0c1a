/*
 * fp24 multiplier: (M+1)x(M+1)-bit significand product, exponent add, normalize by at most one
 * bit, then f24_round_pack. Hardware: one (M+1)x(M+1) multiplier (one DSP block at M=16), one
 * exponent adder, a 1-bit normalize mux and the shared rounder.
 */
#include "f24_internal.h"

f24_t f24_mul(f24_t a, f24_t b)
{
    const uint32_t sign = f24_sign(a) ^ f24_sign(b);
    const int32_t ea = f24_exp(a), eb = f24_exp(b);

    if (f24_is_nan(a) || f24_is_nan(b))
        return F24_DEFAULT_NAN;
    if (ea == F24_EXP_MAX || eb == F24_EXP_MAX)
        return (ea == 0 || eb == 0) ? F24_DEFAULT_NAN : f24_inf(sign); /* Inf * 0 is NaN */
    if (ea == 0 || eb == 0)
        return f24_zero(sign);

    const uint64_t prod = (uint64_t)f24_sig(a) * f24_sig(b); /* in [2^2M, 2^(2M+2)) */
    const uint32_t carry = (uint32_t)(prod >> (2 * F24_MAN_BITS + 1)) & 1u;
    const uint32_t lead = 2u * F24_MAN_BITS + carry; /* position of the leading one */
    const uint32_t sig = lead >= 30u ? f24_shift_right_jam64(prod, lead - 30u)
                                     : (uint32_t)prod << (30u - lead);
    return f24_round_pack(sign, ea + eb - F24_BIAS + (int32_t)carry, sig);
}
