/*
 * Shared round-and-pack stage of every fp24 operator (docs/fp24.md, "Rounding").
 * Hardware: one incrementer of M+2 bits, a tie detector on the round bits, and range checks on
 * the exponent. Tininess is detected after rounding: a result that rounds up to the smallest
 * normal is kept, anything smaller is flushed to a zero with the result's sign.
 */
#include "f24_internal.h"

f24_t f24_round_pack(uint32_t sign, int32_t exp, uint32_t sig)
{
    const uint32_t half = 1u << (F24_ROUND_BITS - 1);
    const uint32_t round_bits = sig & ((1u << F24_ROUND_BITS) - 1u);
    uint32_t kept = (sig + half) >> F24_ROUND_BITS;

    if (round_bits == half) /* exact tie: back to even */
        kept &= ~1u;
    if (kept >> (F24_MAN_BITS + 1)) {        /* carried into the next binade */
        kept >>= 1;
        exp += 1;
    }
    if (exp <= 0)
        return f24_zero(sign);
    if (exp >= F24_EXP_MAX)
        return f24_inf(sign);
    return f24_pack(sign, (uint32_t)exp, kept & F24_FRAC_MASK);
}
