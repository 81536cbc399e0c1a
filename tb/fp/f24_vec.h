/*
 * Test-vector generation for fp24 operations, TestFloat style: a deterministic edge set per
 * operation (special values of every class and both signs, exact ties, carries into the next
 * binade, near-overflow and near-underflow results), then random operands weighted towards
 * the interesting exponents and bit patterns. Shared by `saarcor f24gen`, `saarcor f24verify`
 * and the tests, so the C tests and the Verilator benches read the same vectors.
 */
#ifndef SAARCOR_F24_VEC_H
#define SAARCOR_F24_VEC_H

#include <stddef.h>
#include <stdint.h>

#include "f24_ops.h"

typedef struct { uint64_t s[4]; } f24_rng; /* xoshiro256** */

void f24_rng_seed(f24_rng *rng, uint64_t seed);
uint64_t f24_rng_next(f24_rng *rng);

typedef struct { uint32_t a, b; } f24_pair;

/* Upper bound of the edge-set size of any operation (checked by tests/test_f24.c). */
#define F24_VEC_MAX_EDGES 4096

/* Writes the edge vectors of op into out (at most cap of them); returns how many the set has,
 * which callers compare with cap. */
size_t f24_vec_edges(f24_op op, f24_pair *out, size_t cap);

/* One random operand pair for op. */
f24_pair f24_vec_random(f24_op op, f24_rng *rng);

#endif
