/*
 * fp24 adder/subtractor: one datapath, the operation bit flips the sign of b.
 * Stages: special cases -> swap so |a| >= |b| -> align b (shift right with sticky) ->
 * add or subtract significands -> normalize (leading-zero count) -> f24_round_pack.
 * Significands sit with their leading one at bit 29, one bit of headroom for the carry;
 * a's low bits are zero, so the jammed sticky bit of b never lands on a rounding boundary.
 * Hardware: one exponent subtractor, one 31-bit aligner, one 31-bit adder, one LZC, one shifter.
 */
#include "f24_internal.h"

static f24_t f24_addsub(f24_t a, f24_t b, uint32_t negate_b)
{
    uint32_t sa = f24_sign(a), sb = f24_sign(b) ^ negate_b;
    int32_t ea = f24_exp(a), eb = f24_exp(b);

    if (ea == F24_EXP_MAX || eb == F24_EXP_MAX) {
        if (f24_is_nan(a) || f24_is_nan(b) || (ea == eb && sa != sb))
            return F24_DEFAULT_NAN; /* NaN in, or Inf - Inf */
        return f24_inf(ea == F24_EXP_MAX ? sa : sb);
    }
    if (ea == 0)
        return eb == 0 ? f24_zero(sa & sb) : f24_pack(sb, (uint32_t)eb, f24_frac(b));
    if (eb == 0)
        return f24_pack(sa, (uint32_t)ea, f24_frac(a));

    uint32_t siga = f24_sig(a) << (29 - F24_MAN_BITS);
    uint32_t sigb = f24_sig(b) << (29 - F24_MAN_BITS);
    if (ea < eb || (ea == eb && siga < sigb)) {
        uint32_t ts = sa; sa = sb; sb = ts;
        int32_t te = ea; ea = eb; eb = te;
        uint32_t tg = siga; siga = sigb; sigb = tg;
    }
    sigb = f24_shift_right_jam32(sigb, (uint32_t)(ea - eb));

    if (sa == sb) {
        uint32_t sum = siga + sigb; /* leading one at bit 30 or 29 */
        if (sum & F24_SIG_LEAD)
            return f24_round_pack(sa, ea + 1, sum);
        return f24_round_pack(sa, ea, sum << 1);
    }
    uint32_t diff = siga - sigb;
    if (diff == 0)
        return f24_zero(0); /* exact cancellation is +0 when rounding to nearest */
    uint32_t shift = f24_clz32(diff) - 1u;
    return f24_round_pack(sa, ea + 1 - (int32_t)shift, diff << shift);
}

f24_t f24_add(f24_t a, f24_t b) { return f24_addsub(a, b, 0u); }

f24_t f24_sub(f24_t a, f24_t b) { return f24_addsub(a, b, 1u); }
