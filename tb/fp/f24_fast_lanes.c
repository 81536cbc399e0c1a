/* The constants of the lanes' operations in tb/fp/f24_fast.h (f24v_k): see there. */
#include "f24_fast.h"

#ifdef F24_FAST_VECTORS
#define K4(x) { (x), (x), (x), (x) }
enum { SHIFT = 52 - F24_MAN_BITS };

__attribute__((aligned(32))) const f24v_consts f24v_k = {
    .abs52 = K4(0x7FFFFFFFFFFFFFFFll),
    .half52 = K4((1ll << (SHIFT - 1)) - 1),
    .one = K4(1),
    .keep52 = K4(~((1ll << SHIFT) - 1)),
    .min52 = K4((int64_t)(1023 - F24_BIAS + 1) << 52),
    .inf52 = K4((int64_t)(1023 - F24_BIAS + F24_EXP_MAX) << 52),
    .inf52_bits = K4(0x7FF0000000000000ll),
    .sign52 = K4((int64_t)0x8000000000000000ull),
    /* f24_fast_decode(F24_DEFAULT_NAN): its sign, binary64's exponent field, the quiet bit */
    .nan52 = K4((int64_t)((uint64_t)(F24_DEFAULT_NAN >> (F24_EXP_BITS + F24_MAN_BITS)) << 63 | 0x7FF8000000000000ull)),
    .rebias = K4((int64_t)F24_FAST_REBIAS),
    .min_normal = K4((int64_t)F24_MIN_NORMAL),
    .pos_inf = K4((int64_t)F24_POS_INF),
    .sign_bit = K4((int64_t)F24_SIGN_BIT),
    .default_nan = K4((int64_t)F24_DEFAULT_NAN),
    .abs24 = K4((int32_t)F24_ABS_MASK),
    .rebias32 = K4((int32_t)((127u - F24_BIAS) << 23)),
    .min_normal_m1 = K4((int32_t)F24_MIN_NORMAL - 1),
    .pos_inf_m1 = K4((int32_t)F24_POS_INF - 1),
    .exp32 = K4(0x7F800000),
};
#endif
