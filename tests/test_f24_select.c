/*
 * Test of the build-time arithmetic selection: compiled with -DF24_FAST_SIM, so f24_add ...
 * f24_from_f32 below are the host fast path (tb/fp/f24_fast.h), while the operation table
 * (compiled without the switch) still holds the integer hardware path. They must agree.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "f24.h"
#include "f24_ops.h"
#include "f24_vec.h"

#ifndef f24_add
#error "F24_FAST_SIM must map f24_add onto the fast path"
#endif

static void selected_path_is_fast_and_identical(void **state)
{
    (void)state;
    assert_ptr_equal((void *)&f24_add, (void *)&f24_fast_add);
    f24_rng rng;
    f24_rng_seed(&rng, 3);
    for (int i = 0; i < 50000; i++) {
        const f24_pair v = f24_vec_random(F24_OP_MUL, &rng);
        assert_int_equal(f24_add(v.a, v.b), f24_ops[F24_OP_ADD].hw(v.a, v.b));
        assert_int_equal(f24_sub(v.a, v.b), f24_ops[F24_OP_SUB].hw(v.a, v.b));
        assert_int_equal(f24_mul(v.a, v.b), f24_ops[F24_OP_MUL].hw(v.a, v.b));
        assert_int_equal(f24_div(v.a, v.b), f24_ops[F24_OP_DIV].hw(v.a, v.b));
        assert_int_equal(f24_sqrt(v.a), f24_ops[F24_OP_SQRT].hw(v.a, 0));
        assert_int_equal(f24_from_i32((int32_t)v.a), f24_ops[F24_OP_FROM_I32].hw(v.a, 0));
        assert_int_equal(f24_lt(v.a, v.b), f24_ops[F24_OP_LT].hw(v.a, v.b));
        assert_int_equal(f24_le(v.a, v.b), f24_ops[F24_OP_LE].hw(v.a, v.b));
        assert_int_equal(f24_eq(v.a, v.b), f24_ops[F24_OP_EQ].hw(v.a, v.b));
        assert_int_equal(f24_min(v.a, v.b), f24_ops[F24_OP_MIN].hw(v.a, v.b));
        assert_int_equal(f24_max(v.a, v.b), f24_ops[F24_OP_MAX].hw(v.a, v.b));
    }
}

/* The edge sets (zeros of both signs, subnormal encodings, Inf, NaN, extremes) of the mapped
 * comparisons and min/max. */
static void mapped_comparisons_on_edges(void **state)
{
    (void)state;
    static f24_pair e[F24_VEC_MAX_EDGES];
    const f24_op ops[] = { F24_OP_LT, F24_OP_MIN };
    for (size_t k = 0; k < 2; k++) {
        const size_t n = f24_vec_edges(ops[k], e, F24_VEC_MAX_EDGES);
        for (size_t i = 0; i < n; i++) {
            assert_int_equal(f24_lt(e[i].a, e[i].b), f24_ops[F24_OP_LT].hw(e[i].a, e[i].b));
            assert_int_equal(f24_le(e[i].a, e[i].b), f24_ops[F24_OP_LE].hw(e[i].a, e[i].b));
            assert_int_equal(f24_eq(e[i].a, e[i].b), f24_ops[F24_OP_EQ].hw(e[i].a, e[i].b));
            assert_int_equal(f24_min(e[i].a, e[i].b), f24_ops[F24_OP_MIN].hw(e[i].a, e[i].b));
            assert_int_equal(f24_max(e[i].a, e[i].b), f24_ops[F24_OP_MAX].hw(e[i].a, e[i].b));
        }
    }
}

/* The working values' operations the shading chains use beyond the mapped ones (f24w_sqrt,
 * f24w_from_i32, f24w_to_i32) against the integer operators, the packet values' decoding (f24v_of,
 * through binary32 lanes) against the scalar decoding bit for bit (a NaN: a NaN of its sign), and their sqrt and from_i32
 * (the vertex normals' datapath) against the integer operators, on the edge sets
 * (subnormal encodings, Inf, NaN of both signs, bits above the format) and random operands; and a
 * matrix's columns as vectors (f24v_columns) against the decoded words. */
static void working_values_and_lanes(void **state)
{
    (void)state;
    static f24_pair e[F24_VEC_MAX_EDGES];
    const size_t n = f24_vec_edges(F24_OP_SQRT, e, F24_VEC_MAX_EDGES);
    f24_rng rng;
    f24_rng_seed(&rng, 5);
    for (size_t i = 0; i < n + 50000; i++) {
        const f24_pair v = i < n ? e[i] : f24_vec_random(F24_OP_MUL, &rng);
        assert_int_equal(f24w_bits(f24w_sqrt(f24w_of(v.a))), f24_ops[F24_OP_SQRT].hw(v.a, 0));
        assert_int_equal(f24w_bits(f24w_from_i32((int32_t)v.b)), f24_ops[F24_OP_FROM_I32].hw(v.b, 0));
        assert_int_equal((uint32_t)f24w_to_i32(f24w_of(v.a)), f24_ops[F24_OP_TO_I32].hw(v.a, 0));
        /* large products: the saturation of f24w_to_i32 */
        const f24w big = f24w_mul(f24w_of(v.a), f24w_of(v.b));
        assert_int_equal((uint32_t)f24w_to_i32(big), f24_ops[F24_OP_TO_I32].hw(f24w_bits(big), 0));
#ifdef F24_FAST_VECTORS
        const f24_t lanes[F24Q_LANES] = { v.a, v.b, v.a | ~F24_MASK, f24_neg(v.b) };
        const int32_t ints[F24Q_LANES] = { (int32_t)v.a, (int32_t)v.b, (int32_t)(0u - v.a), (int32_t)(v.a << 8) };
        /* the lanes' values themselves: the next operation of a chain reads them unencoded */
        const f24v d = f24v_of(lanes), roots = f24v_sqrt(d), from_ints = f24v_from_i32(ints);
        for (int k = 0; k < F24Q_LANES; k++) {
            const double want = f24_fast_decode(lanes[k]),
                         root = f24_fast_decode(f24_ops[F24_OP_SQRT].hw(lanes[k], 0)),
                         from_int = f24_fast_decode(f24_ops[F24_OP_FROM_I32].hw((uint32_t)ints[k], 0));
            assert_true(f24_fast_same(d[k], want));
            assert_memory_equal(&roots[k], &root, sizeof root);
            assert_memory_equal(&from_ints[k], &from_int, sizeof from_int);
        }
        /* a matrix's columns (f24q_columns: rows decoded, then transposed): lane r of column k is
         * m[r][k], lane 3 +0 */
        const f24_t m[3][4] = { { v.a, v.b, f24_neg(v.a), v.a ^ v.b }, { v.b, v.a | ~F24_MASK, F24_ONE, f24_neg(v.b) },
                                { v.a + 1u, v.b - 1u, 0u, F24_SIGN_BIT } };
        f24v col[4];
        f24v_columns(m, col);
        for (int k = 0; k < 4; k++) {
            for (int r = 0; r < 3; r++)
                assert_true(f24_fast_same(col[k][r], f24_fast_decode(m[r][k])));
            assert_true(f24_fast_same(col[k][3], 0.0));
        }
#endif
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = { cmocka_unit_test(selected_path_is_fast_and_identical),
                                        cmocka_unit_test(mapped_comparisons_on_edges),
                                        cmocka_unit_test(working_values_and_lanes) };
    return cmocka_run_group_tests_name("fp24 build-time path selection", tests, NULL, NULL);
}
