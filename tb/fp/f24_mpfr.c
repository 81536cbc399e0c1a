/*
 * Correctly rounded reference for every fp24 operation, computed with GNU MPFR at precision
 * M+1 and with MPFR's exponent range set to the format's. MPFR signals underflow after rounding
 * with an unbounded exponent, which is exactly fp24's tininess rule; an underflowing result is
 * flushed to zero of its sign, an overflowing one is Inf (MPFR already rounds it so in RNDN).
 */
#include <mpfr.h>
#include <string.h>

#include "f24.h"
#include "f24_ops.h"

#define PREC (F24_MAN_BITS + 1)

/* Exact decode with DAZ; x must have precision >= PREC. */
static void ref_decode(mpfr_t x, f24_t a)
{
    const int sign = f24_sign(a) ? -1 : 1;
    const int32_t e = f24_exp(a);
    if (e == F24_EXP_MAX) {
        if (f24_frac(a))
            mpfr_set_nan(x);
        else
            mpfr_set_inf(x, sign);
    } else if (e == 0) {
        mpfr_set_zero(x, sign);
    } else {
        mpfr_set_ui_2exp(x, (1ul << F24_MAN_BITS) | f24_frac(a), e - F24_BIAS - F24_MAN_BITS, MPFR_RNDN);
        if (sign < 0)
            mpfr_neg(x, x, MPFR_RNDN);
    }
}

/* Encode a value already rounded to PREC bits within the format's exponent range. */
static f24_t ref_encode(mpfr_t r)
{
    const uint32_t sign = mpfr_signbit(r) ? 1u : 0u;
    if (mpfr_nan_p(r))
        return F24_DEFAULT_NAN;
    if (mpfr_inf_p(r))
        return f24_pack(sign, F24_EXP_MAX, 0u);
    if (mpfr_zero_p(r) || mpfr_underflow_p())
        return f24_pack(sign, 0u, 0u);
    const mpfr_exp_t e = mpfr_get_exp(r); /* r = m * 2^e, 1/2 <= m < 1 */
    mpfr_t s;
    mpfr_init2(s, PREC);
    mpfr_abs(s, r, MPFR_RNDN);
    mpfr_mul_2si(s, s, PREC - e, MPFR_RNDN); /* integer in [2^M, 2^(M+1)) */
    const uint32_t sig = (uint32_t)mpfr_get_ui(s, MPFR_RNDN);
    mpfr_clear(s);
    return f24_pack(sign, (uint32_t)(e - 1 + F24_BIAS), sig & F24_FRAC_MASK);
}

static uint32_t f32_bits_of(mpfr_t x)
{
    if (mpfr_nan_p(x))
        return 0x7FC00000u;
    float f = mpfr_get_flt(x, MPFR_RNDN);
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    return bits;
}

int f24_mpfr_parse(const char *text, uint32_t *out)
{
    const mpfr_exp_t old_emin = mpfr_get_emin(), old_emax = mpfr_get_emax();
    mpfr_t r;
    mpfr_init2(r, PREC);
    mpfr_set_emin(2 - F24_BIAS);
    mpfr_set_emax(F24_BIAS + 1);
    mpfr_clear_flags();
    char *end = NULL;
    const int t = mpfr_strtofr(r, text, &end, 10, MPFR_RNDN);
    mpfr_check_range(r, t, MPFR_RNDN);
    const int ok = end != text && *end == '\0';
    if (ok)
        *out = ref_encode(r);
    mpfr_set_emin(old_emin);
    mpfr_set_emax(old_emax);
    mpfr_clear(r);
    return ok;
}

uint32_t f24_mpfr(f24_op op, uint32_t a, uint32_t b)
{
    const mpfr_exp_t old_emin = mpfr_get_emin(), old_emax = mpfr_get_emax();
    mpfr_t x, y, r;
    mpfr_inits2(PREC, x, y, r, (mpfr_ptr)0);
    ref_decode(x, a);
    ref_decode(y, b);

    mpfr_set_emin(2 - F24_BIAS); /* smallest normal 2^(1-bias) = 0.5 * 2^(2-bias) */
    mpfr_set_emax(F24_BIAS + 1);
    mpfr_clear_flags();

    uint32_t out = 0;
    int rounded = 1; /* result is in r and goes through ref_encode */
    switch (op) {
    case F24_OP_ADD: mpfr_add(r, x, y, MPFR_RNDN); break;
    case F24_OP_SUB: mpfr_sub(r, x, y, MPFR_RNDN); break;
    case F24_OP_MUL: mpfr_mul(r, x, y, MPFR_RNDN); break;
    case F24_OP_DIV: mpfr_div(r, x, y, MPFR_RNDN); break;
    case F24_OP_SQRT: mpfr_sqrt(r, x, MPFR_RNDN); break;
    case F24_OP_MIN: mpfr_min(r, x, y, MPFR_RNDN); break;
    case F24_OP_MAX: mpfr_max(r, x, y, MPFR_RNDN); break;
    case F24_OP_NEG:
    case F24_OP_ABS:
        if (op == F24_OP_NEG)
            mpfr_neg(r, x, MPFR_RNDN);
        else
            mpfr_abs(r, x, MPFR_RNDN);
        /* sign operations are bit operations: NaN payloads and subnormal encodings, which have
         * no value of their own, keep their bits apart from the sign */
        if (f24_exp(a) == 0 || f24_is_nan(a)) {
            out = (a & F24_ABS_MASK) | (op == F24_OP_NEG ? ~a & F24_SIGN_BIT : 0u);
            rounded = 0;
        }
        break;
    case F24_OP_LT: out = (uint32_t)mpfr_less_p(x, y); rounded = 0; break;
    case F24_OP_LE: out = (uint32_t)mpfr_lessequal_p(x, y); rounded = 0; break;
    case F24_OP_EQ: out = (uint32_t)mpfr_equal_p(x, y); rounded = 0; break;
    case F24_OP_UNORDERED: out = (uint32_t)mpfr_unordered_p(x, y); rounded = 0; break;
    case F24_OP_FROM_F32: {
        const uint32_t e32 = (a >> 23) & 0xFFu, f32 = a & 0x7FFFFFu;
        const int neg = (int)(a >> 31);
        if (e32 == 0xFF && f32)
            mpfr_set_nan(r);
        else if (e32 == 0xFF)
            mpfr_set_inf(r, neg ? -1 : 1);
        else if (e32 == 0)
            mpfr_set_zero(r, neg ? -1 : 1);
        else {
            mpfr_set_ui_2exp(r, f32 | 0x800000u, (mpfr_exp_t)e32 - 127 - 23, MPFR_RNDN);
            if (neg)
                mpfr_neg(r, r, MPFR_RNDN);
        }
        break;
    }
    case F24_OP_FROM_I32: mpfr_set_si(r, (int32_t)a, MPFR_RNDN); break;
    case F24_OP_TO_I32: /* toward zero, saturating, NaN -> 0 */
        if (mpfr_nan_p(x))
            out = 0;
        else if (mpfr_cmp_si(x, INT32_MAX) > 0)
            out = (uint32_t)INT32_MAX;
        else if (mpfr_cmp_si(x, INT32_MIN) < 0)
            out = (uint32_t)INT32_MIN;
        else
            out = (uint32_t)(int32_t)mpfr_get_si(x, MPFR_RNDZ);
        rounded = 0;
        break;
    case F24_OP_TO_F32:
        mpfr_set_emin(old_emin);
        mpfr_set_emax(old_emax);
        out = f32_bits_of(x);
        rounded = 0;
        break;
    case F24_OP_COUNT: break;
    }
    if (rounded)
        out = ref_encode(r);

    mpfr_set_emin(old_emin);
    mpfr_set_emax(old_emax);
    mpfr_clears(x, y, r, (mpfr_ptr)0);
    return out;
}
