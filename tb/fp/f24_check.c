/* Three-way fp24 checks and vector writing (see f24_check.h). */
#include "f24_check.h"

#include "f24.h"

#define STR2(x) #x
#define STR(x) STR2(x)

const char *f24_format_name(void) { return "e" STR(F24_EXP_BITS) "m" STR(F24_MAN_BITS); }

static void put_word(FILE *out, f24_kind kind, uint32_t w)
{
    fprintf(out, "%0*X", f24_kind_hex_digits(kind), (unsigned)w);
}

int f24_check_vector(f24_op op, f24_pair v, f24_check_stats *st, FILE *log, int *budget)
{
    const f24_op_info *info = &f24_ops[op];
    const uint32_t ref = f24_mpfr(op, v.a, v.b);
    const uint32_t hw = info->hw(v.a, v.b), fast = info->fast(v.a, v.b);
    st->vectors++;
    st->hw_mismatches += hw != ref;
    st->fast_mismatches += fast != ref;
    if (hw == ref && fast == ref)
        return 0;
    if (log && *budget > 0) {
        (*budget)--;
        fprintf(log, "mismatch %s %s: a=", f24_format_name(), info->name);
        put_word(log, info->arg, v.a);
        if (info->arity == 2) {
            fputs(" b=", log);
            put_word(log, info->arg, v.b);
        }
        fputs(" mpfr=", log);
        put_word(log, info->result, ref);
        fputs(" hw=", log);
        put_word(log, info->result, hw);
        fputs(" fast=", log);
        put_word(log, info->result, fast);
        fputc('\n', log);
    }
    return 1;
}

int (*f24_check_stop)(void);

/* True when vector i is a polling point and the caller asked to stop. */
static int stopped(uint64_t i) { return (i & 4095) == 4095 && f24_check_stop && f24_check_stop(); }

f24_check_stats f24_check_op(f24_op op, uint64_t n_random, uint64_t seed, FILE *log, int max_log)
{
    f24_check_stats st = { 0, 0, 0 };
    int budget = max_log;
    static f24_pair edges[F24_VEC_MAX_EDGES];
    const size_t n_edges = f24_vec_edges(op, edges, F24_VEC_MAX_EDGES);
    for (size_t i = 0; i < n_edges; i++)
        f24_check_vector(op, edges[i], &st, log, &budget);

    f24_rng rng;
    f24_rng_seed(&rng, seed);
    for (uint64_t i = 0; i < n_random && !stopped(i); i++)
        f24_check_vector(op, f24_vec_random(op, &rng), &st, log, &budget);
    return st;
}

f24_check_stats f24_check_exhaustive(f24_op op, FILE *log, int max_log)
{
    f24_check_stats st = { 0, 0, 0 };
    int budget = max_log;
    const uint64_t n = 1ull << F24_WIDTH;
    for (uint64_t a = 0; a < n && !stopped(a); a++)
        f24_check_vector(op, (f24_pair){ (uint32_t)a, 0 }, &st, log, &budget);
    return st;
}

static void write_vector(FILE *out, const f24_op_info *info, f24_op op, f24_pair v)
{
    put_word(out, info->arg, v.a);
    if (info->arity == 2) {
        fputc(' ', out);
        put_word(out, info->arg, v.b);
    }
    fputc(' ', out);
    put_word(out, info->result, f24_mpfr(op, v.a, v.b));
    fputc('\n', out);
}

void f24_gen_vectors(FILE *out, f24_op op, uint64_t n_random, uint64_t seed, int with_edges)
{
    const f24_op_info *info = &f24_ops[op];
    if (with_edges) {
        static f24_pair edges[F24_VEC_MAX_EDGES];
        const size_t n_edges = f24_vec_edges(op, edges, F24_VEC_MAX_EDGES);
        for (size_t i = 0; i < n_edges; i++)
            write_vector(out, info, op, edges[i]);
    }
    f24_rng rng;
    f24_rng_seed(&rng, seed);
    for (uint64_t i = 0; i < n_random && !stopped(i); i++)
        write_vector(out, info, op, f24_vec_random(op, &rng));
}
