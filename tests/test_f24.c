/*
 * Tests of the fp24 library (hls/fp24) and its fast path (tb/fp/f24_fast.h), built once per
 * tested format. Every operation is checked three ways (MPFR reference, integer path, fast path)
 * on its edge set and on random vectors; unary operations exhaustively for formats of at most
 * 20 bits; the committed golden vectors (tests/golden/f24, format e7m16) are replayed; and a
 * negative control shows that the vectors catch double rounding at insufficient precision.
 * F24_TEST_N (environment) sets the random vectors per operation (default 100000).
 */
#define _GNU_SOURCE /* open_memstream */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "f24.h"
#include "f24_check.h"
#include "f24_fast.h"
#include "f24_ops.h"
#include "f24_vec.h"

#ifndef SAARCOR_SRC_DIR
#define SAARCOR_SRC_DIR "."
#endif

static uint64_t test_n(void)
{
    const char *s = getenv("F24_TEST_N");
    return s ? strtoull(s, NULL, 10) : 100000u;
}

static void expect_no_mismatch(f24_check_stats st)
{
    assert_true(st.vectors > 0);
    assert_int_equal(st.hw_mismatches, 0);
    assert_int_equal(st.fast_mismatches, 0);
}

/* ---- three-way checks -------------------------------------------------------------------- */

static void check_op(void **state)
{
    const f24_op op = (f24_op)(intptr_t)*state;
    expect_no_mismatch(f24_check_op(op, test_n(), 1000u + (uint64_t)op, stdout, 10));
}

static void edge_sets_fit(void **state)
{
    (void)state;
    for (int op = 0; op < F24_OP_COUNT; op++) {
        const size_t n = f24_vec_edges((f24_op)op, NULL, 0);
        assert_true(n > 0);
        assert_true(n <= F24_VEC_MAX_EDGES);
    }
}

static void exhaustive_unary(void **state)
{
    (void)state;
    if (F24_WIDTH > 20)
        skip();
    const f24_op ops[] = { F24_OP_SQRT, F24_OP_NEG, F24_OP_ABS, F24_OP_TO_F32, F24_OP_TO_I32 };
    for (size_t i = 0; i < sizeof ops / sizeof ops[0]; i++)
        expect_no_mismatch(f24_check_exhaustive(ops[i], stdout, 10));
}

/* ---- semantics spelled out in docs/fp24.md ----------------------------------------------- */

static f24_t val(int32_t i) { return f24_from_i32(i); }

static void documented_semantics(void **state)
{
    (void)state;
    const f24_t pz = 0, nz = F24_SIGN_BIT, one = F24_ONE, inf = F24_POS_INF, nan = F24_DEFAULT_NAN;
    const f24_t sub = 1u; /* a subnormal encoding: read as +0 */
    assert_int_equal(f24_add(one, one), val(2));
    assert_int_equal(f24_sub(one, one), pz);             /* exact cancellation: +0 */
    assert_int_equal(f24_add(nz, nz), nz);
    assert_int_equal(f24_add(pz, nz), pz);
    assert_int_equal(f24_add(sub, nz), pz);             /* subnormal input is +0 */
    assert_int_equal(f24_mul(f24_neg(one), pz), nz);
    assert_int_equal(f24_mul(inf, pz), nan);
    assert_int_equal(f24_sub(inf, inf), nan);
    assert_int_equal(f24_div(one, nz), f24_neg(inf));
    assert_int_equal(f24_div(pz, pz), nan);
    assert_int_equal(f24_sqrt(nz), nz);
    assert_int_equal(f24_sqrt(f24_neg(one)), nan);
    assert_int_equal(f24_add(nan | 1u, one), nan);        /* every NaN result is the default NaN */
    assert_int_equal(f24_mul(F24_MAX_NORMAL, val(2)), inf); /* overflow */
    assert_int_equal(f24_mul(F24_MIN_NORMAL, f24_from_f32(0x3F000000u)), pz); /* smallest normal / 2 */
    assert_true(f24_eq(pz, nz) && !f24_lt(nz, pz) && f24_le(nz, pz));
    assert_true(!f24_eq(nan, nan) && !f24_lt(nan, one) && !f24_le(one, nan) && f24_unordered(nan, one));
    assert_true(f24_eq(sub, pz));
    assert_int_equal(f24_min(pz, nz), nz);
    assert_int_equal(f24_max(nz, pz), pz);
    assert_int_equal(f24_min(nan, one), one);
    assert_int_equal(f24_max(sub, nz), pz);
    assert_int_equal(f24_neg(nan), nan | F24_SIGN_BIT);  /* sign operations are bit operations */
    assert_int_equal(f24_abs(f24_neg(sub)), sub);
    assert_int_equal(f24_to_f32(nan), 0x7FC00000u);
    assert_int_equal(f24_to_f32(one), 0x3F800000u);
    assert_int_equal(f24_from_i32(-3), f24_neg(f24_add(one, val(2))));
    /* tininess after rounding: (1 - 2^-2M) * 2^emin rounds up to the smallest normal and is kept;
     * (1 - 2^-(M+1)) * 2^emin is exact, below the smallest normal, and flushed */
    const f24_t below_one = f24_pack(0, F24_BIAS - 1, F24_FRAC_MASK); /* 1 - 2^-(M+1) */
    assert_int_equal(f24_mul(F24_MIN_NORMAL, below_one), pz);
    assert_int_equal(f24_mul(f24_pack(0, 1, F24_FRAC_MASK - 1), f24_pack(0, F24_BIAS - 1, 1)), F24_MIN_NORMAL);
}

#if F24_EXP_BITS == 7 && F24_MAN_BITS == 16
/* Values worked out by hand for the default format (bias 63). */
static void hand_values_e7m16(void **state)
{
    (void)state;
    assert_int_equal(F24_ONE, 0x3F0000u);
    assert_int_equal(f24_div(F24_ONE, val(3)), 0x3D5555u);  /* 1/3 = 1.0101...b * 2^-2, rounds down */
    assert_int_equal(f24_sqrt(val(2)), 0x3F6A0Au);           /* 1.0110101000001001|111... rounds up */
    assert_int_equal(f24_add(0x3F0000u, 0x2E0000u), 0x3F0000u); /* 1 + 2^-17: tie, stays even */
    assert_int_equal(f24_add(0x3F0001u, 0x2E0000u), 0x3F0002u); /* odd + tie: rounds up to even */
    assert_int_equal(f24_add(0x3FFFFFu, 0x2E0000u), 0x400000u); /* tie carries into the next binade */
    assert_int_equal(f24_from_f32(0x3F800040u), 0x3F0000u);  /* 1 + 2^-17 in f32: tie to even */
    assert_int_equal(f24_from_f32(0x3F800080u), 0x3F0001u);  /* 1 + 2^-16 in f32: exact */
}
#endif

/* ---- golden vectors ---------------------------------------------------------------------- */

/* Replays tests/golden/f24/<op>.hex (made by `saarcor f24gen OP 1000 --seed 1` at e7m16) through
 * both paths, and checks that regenerating the file gives the same bytes. */
static void golden_vectors(void **state)
{
    (void)state;
    if (!(F24_EXP_BITS == 7 && F24_MAN_BITS == 16))
        skip();
    for (int op = 0; op < F24_OP_COUNT; op++) {
        const f24_op_info *info = &f24_ops[op];
        char path[512];
        snprintf(path, sizeof path, "%s/tests/golden/f24/%s.hex", SAARCOR_SRC_DIR, info->name);
        FILE *f = fopen(path, "r");
        if (!f)
            fail_msg("missing golden file %s", path);
        unsigned a = 0, b = 0, r = 0;
        uint64_t lines = 0;
        char line[128];
        while (fgets(line, sizeof line, f)) {
            const int n = info->arity == 2 ? sscanf(line, "%x %x %x", &a, &b, &r) : sscanf(line, "%x %x", &a, &r);
            assert_int_equal(n, info->arity + 1);
            if (info->hw(a, b) != r || info->fast(a, b) != r)
                fail_msg("%s line %llu: %s", path, (unsigned long long)lines + 1, line);
            lines++;
        }
        assert_true(lines > 1000);
        /* the generator must reproduce the file exactly */
        char *buf = NULL;
        size_t len = 0;
        FILE *mem = open_memstream(&buf, &len);
        f24_gen_vectors(mem, (f24_op)op, 1000, 1, 1);
        fclose(mem);
        rewind(f);
        char *file = calloc(1, len + 2);
        const size_t got = fread(file, 1, len + 1, f);
        fclose(f);
        assert_int_equal(got, len);
        assert_memory_equal(file, buf, len);
        free(file);
        free(buf);
    }
}

/* ---- double rounding: the argument behind the fast path, and a negative control ---------- */

/* The fast path with the binary64 result first rounded to q bits (q < 53). */
static f24_t rounded_via(double x, int q)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    const int shift = 52 - (q - 1);
    if ((bits & 0x7FF0000000000000ull) != 0x7FF0000000000000ull && (bits << 1) != 0) {
        bits += ((1ull << (shift - 1)) - 1u) + ((bits >> shift) & 1u);
        bits &= ~((1ull << shift) - 1u);
    }
    memcpy(&x, &bits, sizeof x);
    return f24_fast_encode(x);
}

static uint64_t double_rounding_errors(int q)
{
    uint64_t errors = 0;
    const f24_op ops[] = { F24_OP_ADD, F24_OP_MUL };
    f24_pair edges[F24_VEC_MAX_EDGES];
    for (size_t k = 0; k < 2; k++) {
        const size_t n = f24_vec_edges(ops[k], edges, F24_VEC_MAX_EDGES);
        for (size_t i = 0; i < n; i++) {
            const double x = f24_fast_decode(edges[i].a), y = f24_fast_decode(edges[i].b);
            const double exact = ops[k] == F24_OP_ADD ? x + y : x * y;
            errors += rounded_via(exact, q) != f24_mpfr(ops[k], edges[i].a, edges[i].b);
        }
    }
    return errors;
}

static void double_rounding(void **state)
{
    (void)state;
    const int p = F24_MAN_BITS + 1;
    /* q = p + 1 is far below 2p + 2: the tie-plus-one-bit edge vectors must expose it */
    assert_true(double_rounding_errors(p + 1) > 0);
    /* q = 2p + 2 is enough (Figueroa); the fast path uses q = 53 >= 2p + 2 */
    assert_int_equal(double_rounding_errors(2 * p + 2), 0);
    assert_true(53 >= 2 * p + 2);
}

/* ---- algebraic properties ---------------------------------------------------------------- */

static void properties(void **state)
{
    (void)state;
    f24_rng rng;
    f24_rng_seed(&rng, 7);
    for (int i = 0; i < 20000; i++) {
        const f24_pair v = f24_vec_random(F24_OP_ADD, &rng);
        assert_int_equal(f24_add(v.a, v.b), f24_add(v.b, v.a));
        assert_int_equal(f24_mul(v.a, v.b), f24_mul(v.b, v.a));
        assert_int_equal(f24_sub(v.a, v.b), f24_add(v.a, f24_neg(v.b)));
        assert_int_equal(f24_lt(v.a, v.b), f24_lt(f24_neg(v.b), f24_neg(v.a)));
        assert_int_equal(f24_from_f32(f24_to_f32(v.a)), f24_is_zero(v.a) ? (v.a & F24_SIGN_BIT)
                                                         : f24_is_nan(v.a) ? F24_DEFAULT_NAN : (v.a & F24_MASK));
    }
}

int main(void)
{
    char group[64];
    snprintf(group, sizeof group, "fp24 %s", f24_format_name());
    struct CMUnitTest tests[F24_OP_COUNT + 8];
    size_t n = 0;
    for (int op = 0; op < F24_OP_COUNT; op++) {
        tests[n] = (struct CMUnitTest)cmocka_unit_test_prestate(check_op, (void *)(intptr_t)op);
        tests[n++].name = f24_ops[op].name;
    }
    tests[n++] = (struct CMUnitTest)cmocka_unit_test(edge_sets_fit);
    tests[n++] = (struct CMUnitTest)cmocka_unit_test(exhaustive_unary);
    tests[n++] = (struct CMUnitTest)cmocka_unit_test(documented_semantics);
#if F24_EXP_BITS == 7 && F24_MAN_BITS == 16
    tests[n++] = (struct CMUnitTest)cmocka_unit_test(hand_values_e7m16);
#endif
    tests[n++] = (struct CMUnitTest)cmocka_unit_test(golden_vectors);
    tests[n++] = (struct CMUnitTest)cmocka_unit_test(double_rounding);
    tests[n++] = (struct CMUnitTest)cmocka_unit_test(properties);
    return _cmocka_run_group_tests(group, tests, n, NULL, NULL);
}
