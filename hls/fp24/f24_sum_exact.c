/*
 * fp24 exact dot product with a double-word result: hi + lo = a0*b0 + ... + a(n-1)*b(n-1),
 * where hi is the exact sum rounded (ties to even) and lo the exact remainder sum - hi rounded:
 * about 2(M+1) significant bits, what the positions of rays need where fp24 would cancel
 * (docs/fp24.md, "Double words"; docs/numerics.md). A single fp24 term x is passed as x * 1.
 *
 * Datapath (one accumulator, "Kulisch window"): the n products are exact ((M+1)x(M+1) bits, no
 * rounding), aligned to the largest product exponent in a 128-bit two's-complement window with
 * F24_SUM_HEAD bits of headroom; bits aligned below the window are ORed into its last bit
 * (sticky), so the window holds the exact sum whenever the products do not cancel by more than
 * about 128 - 2(2M+2) - F24_SUM_HEAD bits (80 at e7m16), and a correctly rounded hi otherwise.
 * Then one leading-one detector and two passes of the shared round-and-pack (hi, then the
 * remainder for lo). Special values: a NaN operand, Inf * 0 or Inf - Inf give (NaN, +0); an
 * Inf product gives (Inf, +0); a sum of zero products is -0 if all are -0, else +0, and an
 * exact cancellation is (+0, +0); lo is +0 when hi is Inf or was
 * flushed to zero. Hardware: n multipliers, n aligners and a 128-bit adder tree (or one
 * multiplier-accumulator iterated n times), one 128-bit leading-one detector and shifter.
 */
#include "f24_internal.h"

#define F24_SUM_HEAD 5 /* headroom bits: up to 2^(HEAD-1) terms without overflow */

typedef struct { uint64_t hi, lo; } f24_u128; /* two's complement */

static f24_u128 u128_add(f24_u128 a, f24_u128 b)
{
    const uint64_t lo = a.lo + b.lo;
    return (f24_u128){ a.hi + b.hi + (lo < a.lo), lo };
}

static f24_u128 u128_neg(f24_u128 a)
{
    return u128_add((f24_u128){ ~a.hi, ~a.lo }, (f24_u128){ 0, 1 });
}

/* v * 2^s for 0 <= s and v < 2^(128 - s). */
static f24_u128 u128_shl(uint64_t v, uint32_t s)
{
    if (s == 0)
        return (f24_u128){ 0, v };
    if (s >= 64)
        return (f24_u128){ v << (s - 64), 0 };
    return (f24_u128){ v >> (64 - s), v << s };
}

/* floor(a / 2^s) with the bits shifted out ORed into bit 0, as 32 bits (the caller keeps 31). */
static uint32_t u128_shr_jam(f24_u128 a, uint32_t s)
{
    uint64_t kept, lost;
    if (s >= 64) {
        kept = s >= 128 ? 0 : a.hi >> (s - 64);
        lost = a.lo | (s == 64 ? 0 : s >= 128 ? a.hi : a.hi << (128 - s));
    } else if (s > 0) {
        kept = (a.lo >> s) | (a.hi << (64 - s));
        lost = a.lo << (64 - s);
    } else {
        kept = a.lo;
        lost = 0;
    }
    return (uint32_t)kept | (lost != 0);
}

static uint32_t clz64(uint64_t v)
{
    return (v >> 32) ? f24_clz32((uint32_t)(v >> 32)) : 32u + f24_clz32((uint32_t)v);
}

/* Position of the leading one of a nonzero a. */
static uint32_t u128_lead(f24_u128 a) { return a.hi ? 127u - clz64(a.hi) : 63u - clz64(a.lo); }

/* Rounds |a| * 2^scale (a nonzero magnitude) with the shared rounder; sign is the result's. */
static f24_t round_window(uint32_t sign, f24_u128 a, int32_t scale)
{
    const uint32_t p = u128_lead(a);
    const uint32_t sig = p >= 30 ? u128_shr_jam(a, p - 30) : (uint32_t)a.lo << (30 - p);
    return f24_round_pack(sign, (int32_t)p + scale + F24_BIAS, sig);
}

f24x2 f24_sum_exact(const f24_t a[], const f24_t b[], uint32_t n)
{
    const f24x2 nan = { F24_DEFAULT_NAN, 0 };
    int32_t emax = -1;
    uint32_t inf = 0, inf_sign = 0, zero_sign = 1;
scan_terms:
    for (uint32_t k = 0; k < F24_SUM_TERMS; k++) {
        if (k >= n)
            break;
        const int32_t ea = f24_exp(a[k]), eb = f24_exp(b[k]);
        const uint32_t sign = f24_sign(a[k]) ^ f24_sign(b[k]);
        zero_sign &= sign;
        if (f24_is_nan(a[k]) || f24_is_nan(b[k]))
            return nan;
        if (ea == F24_EXP_MAX || eb == F24_EXP_MAX) {
            if (ea == 0 || eb == 0 || (inf && inf_sign != sign))
                return nan; /* Inf * 0, or Inf - Inf */
            inf = 1;
            inf_sign = sign;
        } else if (ea != 0 && eb != 0 && ea + eb > emax) {
            emax = ea + eb;
        }
    }
    if (inf)
        return (f24x2){ f24_inf(inf_sign), 0 };
    if (emax < 0) /* a sum of zeros: -0 only if every one is -0, as an fp24 adder chain gives */
        return (f24x2){ f24_zero(n ? zero_sign : 0u), 0 };

    const uint32_t top = 127 - F24_SUM_HEAD - (2 * F24_MAN_BITS + 1); /* where the largest product's LSB sits */
    f24_u128 acc = { 0, 0 };
accumulate:
    for (uint32_t k = 0; k < F24_SUM_TERMS; k++) {
        const int32_t ea = k < n ? f24_exp(a[k]) : 0, eb = k < n ? f24_exp(b[k]) : 0;
        if (ea == 0 || eb == 0)
            continue;
        const uint64_t prod = (uint64_t)f24_sig(a[k]) * f24_sig(b[k]);
        const uint32_t down = (uint32_t)(emax - ea - eb);
        const uint32_t below = down > top ? down - top : 0; /* bits of prod under the window's last */
        const uint64_t lost = below == 0 ? 0 : below >= 64 ? prod : prod << (64 - below);
        const f24_u128 term = below == 0 ? u128_shl(prod, top - down)
                                         : (f24_u128){ 0, (below >= 64 ? 0 : prod >> below) | (lost != 0) };
        acc = u128_add(acc, f24_sign(a[k]) ^ f24_sign(b[k]) ? u128_neg(term) : term);
    }
    const uint32_t sign = (uint32_t)(acc.hi >> 63);
    const f24_u128 mag = sign ? u128_neg(acc) : acc;
    if (!mag.hi && !mag.lo)
        return (f24x2){ 0, 0 };

    /* bit 0 of the window weighs 2^scale */
    const int32_t scale = emax - 2 * F24_BIAS - 2 * F24_MAN_BITS - (int32_t)top;
    const f24_t hi = round_window(sign, mag, scale);
    if (f24_exp(hi) == 0 || f24_exp(hi) == F24_EXP_MAX)
        return (f24x2){ hi, 0 };
    const int32_t at = f24_exp(hi) - F24_BIAS - F24_MAN_BITS - scale; /* hi's last bit in the window */
    if (at < 0)
        return (f24x2){ hi, 0 }; /* hi holds every bit of the window: exact */
    const f24_u128 rest = u128_add(mag, u128_neg(u128_shl(f24_sig(hi), (uint32_t)at)));
    const uint32_t rest_neg = (uint32_t)(rest.hi >> 63);
    const f24_u128 rmag = rest_neg ? u128_neg(rest) : rest;
    if (!rmag.hi && !rmag.lo)
        return (f24x2){ hi, 0 };
    return (f24x2){ hi, round_window(sign ^ rest_neg, rmag, scale) };
}
