/*
 * Three-way check of fp24 operations: MPFR reference vs integer hardware path vs fast path,
 * on the edge set, on random vectors and exhaustively over small unary input spaces.
 * Mismatches are printed (up to a limit) as hex vectors with all three results.
 */
#ifndef SAARCOR_F24_CHECK_H
#define SAARCOR_F24_CHECK_H

#include <stdint.h>
#include <stdio.h>

#include "f24_ops.h"
#include "f24_vec.h"

typedef struct {
    uint64_t vectors;
    uint64_t hw_mismatches;   /* integer path != MPFR */
    uint64_t fast_mismatches; /* fast path != MPFR */
} f24_check_stats;

/* Checks one vector; returns 0 if all three agree. Mismatches are logged to log while
 * *budget > 0 (log may be NULL). */
int f24_check_vector(f24_op op, f24_pair v, f24_check_stats *st, FILE *log, int *budget);

/* Polled every 4096 vectors by the checks and the generator below: non-zero stops them early,
 * with the counts or vectors so far (f24verify's and f24gen's Ctrl-C). NULL: never. */
extern int (*f24_check_stop)(void);

/* Edge set, then n_random random vectors from seed. */
f24_check_stats f24_check_op(f24_op op, uint64_t n_random, uint64_t seed, FILE *log, int max_log);

/* Every operand of a unary operation on fp24 inputs (2^F24_WIDTH vectors). */
f24_check_stats f24_check_exhaustive(f24_op op, FILE *log, int max_log);

/* Writes "a [b] result" hex lines (TestFloat style; result from MPFR): edges then n random (fewer
 * if f24_check_stop stopped it). */
void f24_gen_vectors(FILE *out, f24_op op, uint64_t n_random, uint64_t seed, int with_edges);

/* Format name, e.g. "e7m16". */
const char *f24_format_name(void);

#endif
