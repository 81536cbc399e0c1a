/*
 * fp24 divider: restoring radix-2 digit recurrence, one quotient bit per step, M+3 steps
 * (M+1 result bits, a guard bit, a round bit), the final remainder gives the sticky bit.
 * Hardware: iterative, one (M+3)-bit subtractor and a quotient shift register; latency M+3
 * cycles plus rounding (docs/fp24.md). Correct rounding does not depend on the algorithm, so a
 * pipelined or SRT divider in rtl/ produces the same bits.
 */
#include "f24_internal.h"

#define F24_DIV_STEPS (F24_MAN_BITS + 3)

f24_t f24_div(f24_t a, f24_t b)
{
    const uint32_t sign = f24_sign(a) ^ f24_sign(b);
    const int32_t ea = f24_exp(a), eb = f24_exp(b);

    if (f24_is_nan(a) || f24_is_nan(b))
        return F24_DEFAULT_NAN;
    if (ea == F24_EXP_MAX)
        return eb == F24_EXP_MAX ? F24_DEFAULT_NAN : f24_inf(sign); /* Inf / Inf is NaN */
    if (eb == F24_EXP_MAX)
        return f24_zero(sign);
    if (eb == 0)
        return ea == 0 ? F24_DEFAULT_NAN : f24_inf(sign); /* 0 / 0 is NaN */
    if (ea == 0)
        return f24_zero(sign);

    uint32_t rem = f24_sig(a);
    const uint32_t divisor = f24_sig(b);
    int32_t exp = ea - eb + F24_BIAS;
    if (rem < divisor) { /* quotient below one: take one more dividend bit */
        rem <<= 1;
        exp -= 1;
    }
    uint32_t quot = 0;
div_digits:
    for (int i = 0; i < F24_DIV_STEPS; i++) {
        const uint32_t take = rem >= divisor;
        quot = (quot << 1) | take;
        rem = (rem - (take ? divisor : 0u)) << 1;
    }
    const uint32_t sig = (quot | (rem != 0u)) << (30 - (F24_DIV_STEPS - 1));
    return f24_round_pack(sign, exp, sig);
}
