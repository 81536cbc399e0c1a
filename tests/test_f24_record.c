/*
 * Packed fp24 records (hls/units/f24_record.h), built and run at every number format (make
 * widths): a record of n values round-trips, takes ceil(n W / 32) words, keeps its padding bits
 * zero, and every value lives in its own slice of bits; a triangle record's vertex low parts
 * decode to their multiples of the high word's ulp.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <math.h>

#include <cmocka.h>

#include "f24_record.h"
#include "vec3.h"

enum { MAX_VALUES = 16, GUARD = 0x5A5A5A5Au };

static double f24_to_double(f24_t a)
{
    const double m = f24_exp(a) ? 1 + ldexp(f24_frac(a), -F24_MAN_BITS) : 0;
    return (f24_sign(a) ? -1 : 1) * ldexp(m, (int)f24_exp(a) - F24_BIAS);
}

static uint32_t rng_next(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static void size_is_the_bits_rounded_up_to_words(void **state)
{
    (void)state;
    for (uint32_t n = 1; n <= MAX_VALUES; n++) {
        assert_true(32u * F24_RECORD_WORDS(n) >= n * F24_WIDTH);
        assert_true(32u * F24_RECORD_WORDS(n) < n * F24_WIDTH + 32u);
    }
    assert_int_equal(32 * F24_TRIANGLE_RECORD_WORDS - F24_TRIANGLE_BITS < 32, 1);
    assert_true(32 * F24_TRIANGLE_RECORD_WORDS >= F24_TRIANGLE_BITS);
    assert_int_equal(F24_INSTANCE_RECORD_WORDS % F24_TRIANGLE_RECORD_WORDS, 0);
    assert_true(F24_INSTANCE_RECORD_WORDS >= 17);
}

/* Random values (with junk above the format's width, which the writer must drop) round-trip;
 * the words after the record and the padding bits of its last word stay as they must. */
static void round_trip(void **state)
{
    (void)state;
    uint32_t seed = 12345;
    for (int iter = 0; iter < 2000; iter++) {
        const uint32_t n = 1 + rng_next(&seed) % MAX_VALUES;
        f24_t v[MAX_VALUES];
        uint32_t w[MAX_VALUES + 2];
        for (uint32_t i = 0; i < n; i++)
            v[i] = rng_next(&seed);
        for (uint32_t k = 0; k < MAX_VALUES + 2; k++)
            w[k] = GUARD;
        f24_record_put(w + 1, v, n);
        for (uint32_t i = 0; i < n; i++)
            assert_int_equal(f24_record_get(w, 1, i), v[i] & F24_MASK);
        assert_int_equal(w[0], GUARD);
        assert_int_equal(w[1 + F24_RECORD_WORDS(n)], GUARD);
        const uint32_t used = n * F24_WIDTH % 32;
        if (used)
            assert_int_equal(w[F24_RECORD_WORDS(n)] >> used, 0);
    }
}

/* A value of all ones among zeros: only its own slice reads back nonzero, and the words that
 * F24_RECORD_SPAN counts for it are exactly the nonzero ones. */
static void values_have_disjoint_slices(void **state)
{
    (void)state;
    for (uint32_t j = 0; j < F24_TRIANGLE_VALUES; j++) {
        f24_t v[F24_TRIANGLE_VALUES] = { 0 };
        uint32_t w[F24_RECORD_WORDS(F24_TRIANGLE_VALUES)];
        v[j] = F24_MASK;
        f24_record_put(w, v, F24_TRIANGLE_VALUES);
        uint32_t nonzero = 0;
        for (uint32_t k = 0; k < F24_RECORD_WORDS(F24_TRIANGLE_VALUES); k++)
            nonzero += w[k] != 0;
        assert_int_equal(nonzero, F24_RECORD_SPAN(j, 1));
        for (uint32_t i = 0; i < F24_TRIANGLE_VALUES; i++)
            assert_int_equal(f24_record_get(w, 0, i), i == j ? F24_MASK : 0u);
    }
}

/* The rows come back in order, and each vertex component's low field k decodes to k 2^-8 of the
 * ulp of its high word: exactly, with its sign, and zero where that falls below the format. */
static void triangle_loads_rows_then_low_parts(void **state)
{
    (void)state;
    f24_t v[F24_TRIANGLE_VALUES];
    uint32_t w[F24_TRIANGLE_RECORD_WORDS + 1];
    for (uint32_t i = 0; i < F24_TRIANGLE_VALUES; i++)
        v[i] = (F24_ONE + 977u * i) & F24_MASK;
    v[11] = F24_MIN_NORMAL; /* C.z so small that its low part underflows */
    memset(w, 0, sizeof w);
    f24_record_put(w, v, F24_TRIANGLE_VALUES);
    const int32_t k[3] = { -128, 77, 1 };
    for (uint32_t i = 0; i < 3; i++)
        f24_record_put_field(w, F24_TRIANGLE_VALUES * F24_WIDTH + i * F24_VERTEX_LO_BITS, F24_VERTEX_LO_BITS, (uint32_t)k[i]);
    const f24_triangle t = f24_triangle_load(w, 0);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            assert_int_equal(t.m.m[r][c], v[4 * r + c]);
    const double ulp_x = ldexp(1.0, (int)f24_exp(v[3]) - F24_BIAS - F24_MAN_BITS);
    assert_true(f24_to_double(t.c_lo.x) == -128 * ldexp(ulp_x, -F24_VERTEX_LO_SHIFT));
    const double ulp_y = ldexp(1.0, (int)f24_exp(v[7]) - F24_BIAS - F24_MAN_BITS);
    assert_true(f24_to_double(t.c_lo.y) == 77 * ldexp(ulp_y, -F24_VERTEX_LO_SHIFT));
    assert_int_equal(t.c_lo.z, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(size_is_the_bits_rounded_up_to_words),
        cmocka_unit_test(round_trip),
        cmocka_unit_test(values_have_disjoint_slices),
        cmocka_unit_test(triangle_loads_rows_then_low_parts),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
