/*
 * Tests of f24_sum_exact (hls/fp24/f24_sum_exact.c), the exact dot product with a double-word
 * result, against MPFR: hi is the exact sum rounded to fp24 and lo the exact remainder rounded,
 * on random terms, on terms built to cancel, and on the special values.
 */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>
#include <mpfr.h>

#include "f24.h"
#include "f24_fast.h"

/* A random finite nonzero fp24 with an unbiased exponent in [-span, span]. */
static f24_t random_value(unsigned *seed, int span)
{
    const uint32_t e = (uint32_t)(F24_BIAS - span + rand_r(seed) % (2 * span + 1));
    return f24_pack((uint32_t)rand_r(seed) & 1u, e, (uint32_t)rand_r(seed) & F24_FRAC_MASK);
}

/* The exact value x rounded to fp24 (no underflow or overflow in these tests). */
static f24_t round_f24(const mpfr_t x)
{
    mpfr_t r;
    mpfr_init2(r, F24_MAN_BITS + 1);
    mpfr_set(r, x, MPFR_RNDN);
    const f24_t v = f24_fast_encode(mpfr_get_d(r, MPFR_RNDN));
    mpfr_clear(r);
    return v;
}

/* 1 if f24_sum_exact gives the correctly rounded hi and lo of the n terms. */
static int agrees(const f24_t a[], const f24_t b[], uint32_t n)
{
    mpfr_t sum, p, hi;
    mpfr_inits2(1024, sum, p, hi, (mpfr_ptr)0);
    mpfr_set_zero(sum, 1);
    for (uint32_t k = 0; k < n; k++) {
        mpfr_set_d(p, f24_fast_decode(a[k]), MPFR_RNDN);
        mpfr_mul_d(p, p, f24_fast_decode(b[k]), MPFR_RNDN); /* exact at 1024 bits */
        mpfr_add(sum, sum, p, MPFR_RNDN);
    }
    const f24x2 got = f24_sum_exact(a, b, n);
    const f24_t want_hi = mpfr_zero_p(sum) ? 0 : round_f24(sum);
    mpfr_set_d(hi, f24_fast_decode(want_hi), MPFR_RNDN);
    mpfr_sub(sum, sum, hi, MPFR_RNDN);
    const f24_t want_lo = mpfr_zero_p(sum) ? 0 : round_f24(sum);
    mpfr_clears(sum, p, hi, (mpfr_ptr)0);
    if (got.hi == want_hi && got.lo == want_lo)
        return 1;
    print_message("n %u: got %06x %06x, want %06x %06x\n", n, got.hi, got.lo, want_hi, want_lo);
    return 0;
}

static void random_terms(void **state)
{
    (void)state;
    unsigned seed = 1;
    int bad = 0;
    for (int i = 0; i < 20000 && bad < 5; i++) {
        f24_t a[F24_SUM_TERMS], b[F24_SUM_TERMS];
        const uint32_t n = 1 + (uint32_t)rand_r(&seed) % F24_SUM_TERMS;
        for (uint32_t k = 0; k < n; k++) {
            a[k] = random_value(&seed, 20);
            b[k] = rand_r(&seed) % 3 ? random_value(&seed, 20) : F24_ONE; /* single terms too */
        }
        bad += !agrees(a, b, n);
    }
    assert_int_equal(bad, 0);
}

/* A ray origin moved along its direction to near the geometry: o + t d with o and t d nearly
 * opposite, the case the operator is for; and exact cancellation to zero. */
static void cancelling_terms(void **state)
{
    (void)state;
    unsigned seed = 2;
    int bad = 0;
    for (int i = 0; i < 20000 && bad < 5; i++) {
        const f24_t t = random_value(&seed, 8), d = random_value(&seed, 8);
        const f24_t o = f24_neg(f24_mul(t, d)); /* the rounded product: cancels all but its error */
        const f24_t nudge = f24_pack(0, f24_exp(o) > 30 ? (uint32_t)f24_exp(o) - 30 : 1u, (uint32_t)i & F24_FRAC_MASK);
        const f24_t a[4] = { o, t, nudge, o }, b[4] = { F24_ONE, d, F24_ONE, 0 };
        bad += !agrees(a, b, 2 + (uint32_t)(i & 1)) + !agrees(a, b, 4);
    }
    const f24_t x = random_value(&seed, 4), a[2] = { x, f24_neg(x) }, b[2] = { F24_ONE, F24_ONE };
    const f24x2 zero = f24_sum_exact(a, b, 2);
    assert_int_equal(zero.hi, 0);
    assert_int_equal(zero.lo, 0);
    assert_int_equal(bad, 0);
}

static void special_values(void **state)
{
    (void)state;
    const f24_t one = F24_ONE, inf = F24_POS_INF, ninf = f24_neg(F24_POS_INF);
    const f24_t nan_in[2] = { F24_DEFAULT_NAN, one }, ones[2] = { one, one };
    assert_int_equal(f24_sum_exact(nan_in, ones, 2).hi, F24_DEFAULT_NAN);
    const f24_t inf_zero[2] = { inf, one }, zero_b[2] = { 0, one };
    assert_int_equal(f24_sum_exact(inf_zero, zero_b, 2).hi, F24_DEFAULT_NAN); /* Inf * 0 */
    const f24_t inf_minus_inf[2] = { inf, ninf };
    assert_int_equal(f24_sum_exact(inf_minus_inf, ones, 2).hi, F24_DEFAULT_NAN);
    const f24_t inf_plus_one[2] = { ninf, one };
    const f24x2 r = f24_sum_exact(inf_plus_one, ones, 2);
    assert_int_equal(r.hi, ninf);
    assert_int_equal(r.lo, 0);
    assert_int_equal(f24_sum_exact(ones, ones, 0).hi, 0); /* the empty sum */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(random_terms),
        cmocka_unit_test(cancelling_terms),
        cmocka_unit_test(special_values),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
