/*
 * fp24 from binary32: rebias and round through f24_round_pack. binary32 subnormals read as zero,
 * as fp24 subnormal encodings do; with E=8, M=23 the conversion is exact apart from that.
 */
#include "f24_internal.h"

f24_t f24_from_f32(uint32_t bits)
{
    const uint32_t sign = bits >> 31;
    const int32_t exp = (int32_t)((bits >> 23) & 0xFFu);
    const uint32_t frac = bits & 0x7FFFFFu;

    if (exp == 0xFF)
        return frac ? F24_DEFAULT_NAN : f24_inf(sign);
    if (exp == 0)
        return f24_zero(sign);
    return f24_round_pack(sign, exp - 127 + F24_BIAS, (frac | 0x800000u) << 7);
}
