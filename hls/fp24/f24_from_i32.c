/*
 * fp24 from a 32-bit signed integer: magnitude, leading-zero count, normalize, round.
 */
#include "f24_internal.h"

f24_t f24_from_i32(int32_t i)
{
    if (i == 0)
        return f24_zero(0u);
    const uint32_t sign = i < 0;
    const uint32_t mag = sign ? 0u - (uint32_t)i : (uint32_t)i;
    const uint32_t lz = f24_clz32(mag);
    const uint32_t sig = f24_shift_right_jam32(mag << lz, 1u); /* leading one to bit 30 */
    return f24_round_pack(sign, 31 - (int32_t)lz + F24_BIAS, sig);
}
