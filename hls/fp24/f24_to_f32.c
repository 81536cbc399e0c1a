/*
 * fp24 to binary32: exact (E <= 8, M <= 23), a rebias and a shift. Subnormal encodings give a
 * signed zero, NaN gives the binary32 default NaN 0x7FC00000.
 */
#include "f24_internal.h"

#define F32_DEFAULT_NAN 0x7FC00000u

uint32_t f24_to_f32(f24_t a)
{
    const uint32_t sign = f24_sign(a) << 31;
    const int32_t exp = f24_exp(a);

    if (exp == F24_EXP_MAX)
        return f24_frac(a) ? F32_DEFAULT_NAN : (sign | 0x7F800000u);
    if (exp == 0)
        return sign;
    return sign | ((uint32_t)(exp - F24_BIAS + 127) << 23) | (f24_frac(a) << (23 - F24_MAN_BITS));
}
