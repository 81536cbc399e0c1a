/*
 * fp24 square root: restoring digit-by-digit integer square root of the significand scaled to
 * an even exponent, M+3 result bits, the remainder gives the sticky bit (an exact tie cannot
 * occur). Hardware: iterative, one (2M+6)-bit subtractor per step; latency M+3 cycles plus
 * rounding. Never overflows or underflows.
 */
#include "f24_internal.h"

#define F24_SQRT_STEPS (F24_MAN_BITS + 3)

f24_t f24_sqrt(f24_t a)
{
    const uint32_t sign = f24_sign(a);
    const int32_t ea = f24_exp(a);

    if (f24_is_nan(a) || (sign && ea != 0))
        return F24_DEFAULT_NAN; /* NaN, or a negative nonzero (including -Inf) */
    if (ea == 0 || ea == F24_EXP_MAX)
        return a & (F24_SIGN_BIT | F24_POS_INF); /* +-0 and +Inf are their own root */

    int32_t e = ea - F24_BIAS;
    uint64_t rad = f24_sig(a);
    if (e & 1) { /* make the exponent even */
        rad <<= 1;
        e -= 1;
    }
    rad <<= F24_MAN_BITS + 4; /* root gets M+3 bits, leading one at bit M+2 */

    uint64_t root = 0, bit = 1ull << (2 * (F24_SQRT_STEPS - 1));
sqrt_digits:
    for (int i = 0; i < F24_SQRT_STEPS; i++) {
        if (rad >= root + bit) {
            rad -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    const uint32_t sig = ((uint32_t)root | (rad != 0u)) << (30 - (F24_SQRT_STEPS - 1));
    return f24_round_pack(0u, e / 2 + F24_BIAS, sig);
}
