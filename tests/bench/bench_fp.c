/*
 * make bench-fp: throughput of the fp24 arithmetic paths against native binary32, per
 * operation: the host fast path (tb/fp/f24_fast.h, inlined, as simulation builds use it), the
 * integer hardware reference (hls/fp24, out-of-line calls) and native float. Each measurement
 * streams 2^16 operand pairs of normal values (1 + R passes); the median of 7 interleaved
 * repetitions is reported, and ratios are taken within the same run (the machine is noisy).
 * Writes JSON (--json) and a Markdown table (--markdown).
 */
#define _GNU_SOURCE
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "f24.h"
#include "f24_fast.h"
#include "f24_vec.h"

enum { N = 1 << 16, PASSES = 40, REPS = 7 };

static f24_t va[N], vb[N];
static float fa[N], fb[N];
static volatile uint32_t sink;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint32_t fbits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

typedef enum { OP_ADD, OP_MUL, OP_DIV, OP_SQRT, N_OPS } op_t;
typedef enum { PATH_NATIVE, PATH_FAST, PATH_INTEGER, N_PATHS } path_t;
static const char *op_names[N_OPS] = { "add", "mul", "div", "sqrt" };
static const char *path_names[N_PATHS] = { "native_float", "fast", "integer" };
static int passes = PASSES;

/* One timed stream per (path, op), each its own non-inlined function so that callgrind can
 * attribute instructions to it; the XOR of all results keeps the work from being dropped. */
#define BENCH(name, expr)                                      \
    static __attribute__((noinline)) double name(void)         \
    {                                                          \
        uint32_t acc = 0;                                      \
        const double t0 = now();                               \
        for (int p = 0; p < passes; p++)                       \
            for (int i = 0; i < N; i++)                        \
                acc ^= (expr);                                 \
        sink = acc;                                            \
        return (double)passes * N / (now() - t0);              \
    }

BENCH(bench_native_add, fbits(fa[i] + fb[i]))
BENCH(bench_native_mul, fbits(fa[i] * fb[i]))
BENCH(bench_native_div, fbits(fa[i] / fb[i]))
BENCH(bench_native_sqrt, fbits(__builtin_sqrtf(fa[i])))
BENCH(bench_fast_add, f24_fast_add(va[i], vb[i]))
BENCH(bench_fast_mul, f24_fast_mul(va[i], vb[i]))
BENCH(bench_fast_div, f24_fast_div(va[i], vb[i]))
BENCH(bench_fast_sqrt, f24_fast_sqrt(va[i]))
BENCH(bench_integer_add, f24_add(va[i], vb[i]))
BENCH(bench_integer_mul, f24_mul(va[i], vb[i]))
BENCH(bench_integer_div, f24_div(va[i], vb[i]))
BENCH(bench_integer_sqrt, f24_sqrt(va[i]))

static double (*const bench[N_PATHS][N_OPS])(void) = {
    { bench_native_add, bench_native_mul, bench_native_div, bench_native_sqrt },
    { bench_fast_add, bench_fast_mul, bench_fast_div, bench_fast_sqrt },
    { bench_integer_add, bench_integer_mul, bench_integer_div, bench_integer_sqrt },
};

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v)
{
    qsort(v, REPS, sizeof *v, cmp_double);
    return v[REPS / 2];
}

/* Instructions per operation from `callgrind_annotate --inclusive=yes` output of a --count run
 * (one pass over the stream per function, loop included); -1 where not found. */
static void read_instructions(const char *path, double ir[N_PATHS][N_OPS])
{
    for (int p = 0; p < N_PATHS; p++)
        for (int o = 0; o < N_OPS; o++)
            ir[p][o] = -1;
    FILE *f = path ? fopen(path, "r") : NULL;
    if (!f)
        return;
    char line[1024];
    while (fgets(line, sizeof line, f)) {
        for (int p = 0; p < N_PATHS; p++)
            for (int o = 0; o < N_OPS; o++) {
                char name[64];
                snprintf(name, sizeof name, ":bench_%s_%s ", p == PATH_NATIVE ? "native" : path_names[p], op_names[o]);
                if (!strstr(line, name))
                    continue;
                double v = 0;
                for (const char *c = line; *c && *c != '('; c++)
                    if (*c >= '0' && *c <= '9')
                        v = v * 10 + (*c - '0');
                ir[p][o] = v / N;
            }
    }
    fclose(f);
}

static void init_operands(void)
{
    /* positive normal operands in [2^-8, 2^8): no special-case shortcuts in any path */
    f24_rng rng;
    f24_rng_seed(&rng, 42);
    for (int i = 0; i < N; i++) {
        const uint64_t r = f24_rng_next(&rng);
        va[i] = f24_pack(0, (uint32_t)(F24_BIAS - 8 + (int)(r % 16)), (uint32_t)(r >> 8) & F24_FRAC_MASK);
        vb[i] = f24_pack(0, (uint32_t)(F24_BIAS - 8 + (int)((r >> 40) % 16)), (uint32_t)(r >> 20) & F24_FRAC_MASK);
        const uint32_t a32 = f24_to_f32(va[i]), b32 = f24_to_f32(vb[i]);
        memcpy(&fa[i], &a32, sizeof a32);
        memcpy(&fb[i], &b32, sizeof b32);
    }
}

static void write_reports(const char *json, const char *md, double mops[N_PATHS][N_OPS], double ir[N_PATHS][N_OPS])
{
    FILE *j = json ? fopen(json, "w") : NULL, *m = md ? fopen(md, "w") : NULL;
    if ((json && !j) || (md && !m)) {
        fprintf(stderr, "bench_fp: error: cannot write the report files\n");
        exit(3);
    }
    if (j) {
        fprintf(j, "{\n  \"format\": \"e%dm%d\", \"stream\": %d, \"passes\": %d, \"repetitions\": %d,\n  \"results\": [\n",
                F24_EXP_BITS, F24_MAN_BITS, N, PASSES, REPS);
        for (int o = 0; o < N_OPS; o++)
            for (int p = 0; p < N_PATHS; p++)
                fprintf(j, "    {\"op\": \"%s\", \"path\": \"%s\", \"mops_per_s\": %.2f, \"instructions_per_op\": %.1f}%s\n",
                        op_names[o], path_names[p], mops[p][o], ir[p][o], o + 1 < N_OPS || p + 1 < N_PATHS ? "," : "");
        fprintf(j, "  ]\n}\n");
        fclose(j);
    }
    if (m) {
        fprintf(m, "# fp24 arithmetic throughput (format e%dm%d)\n\n"
                   "`make bench-fp`: Mops/s = median of %d interleaved repetitions of %d passes over %d operand\n"
                   "pairs on one core; instructions/op from callgrind (repeatable; loop included).\n\n"
                   "| op | native float Mops/s | fast path Mops/s | integer path Mops/s | fast / native | "
                   "fast / integer | instr/op native | instr/op fast | instr/op integer |\n"
                   "|---|---|---|---|---|---|---|---|---|\n",
                F24_EXP_BITS, F24_MAN_BITS, REPS, PASSES, N);
        for (int o = 0; o < N_OPS; o++)
            fprintf(m, "| %s | %.0f | %.0f | %.0f | %.2f | %.1fx | %.1f | %.1f | %.1f |\n", op_names[o],
                    mops[PATH_NATIVE][o], mops[PATH_FAST][o], mops[PATH_INTEGER][o],
                    mops[PATH_FAST][o] / mops[PATH_NATIVE][o], mops[PATH_FAST][o] / mops[PATH_INTEGER][o],
                    ir[PATH_NATIVE][o], ir[PATH_FAST][o], ir[PATH_INTEGER][o]);
        fclose(m);
    }
}

int main(int argc, char **argv)
{
    const char *json = NULL, *md = NULL, *instr = NULL;
    int count_only = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--count"))
            count_only = 1;
        else if (i + 1 < argc && !strcmp(argv[i], "--json"))
            json = argv[++i];
        else if (i + 1 < argc && !strcmp(argv[i], "--markdown"))
            md = argv[++i];
        else if (i + 1 < argc && !strcmp(argv[i], "--instructions"))
            instr = argv[++i];
        else {
            fprintf(stderr, "usage: bench_fp [--count] [--json F] [--markdown F] [--instructions CALLGRIND_ANNOTATE_OUT]\n");
            return 2;
        }
    }
    init_operands();
    if (count_only) { /* one pass per function, for callgrind */
        passes = 1;
        for (int p = 0; p < N_PATHS; p++)
            for (int o = 0; o < N_OPS; o++)
                bench[p][o]();
        return 0;
    }
    double mops[N_PATHS][N_OPS], ir[N_PATHS][N_OPS];
    for (int o = 0; o < N_OPS; o++) {
        double t[N_PATHS][REPS];
        for (int r = 0; r < REPS; r++)
            for (int p = 0; p < N_PATHS; p++)
                t[p][r] = bench[p][o]();
        for (int p = 0; p < N_PATHS; p++)
            mops[p][o] = median(t[p]) / 1e6;
        fprintf(stderr, "bench-fp: %s done\n", op_names[o]);
    }
    read_instructions(instr, ir);
    write_reports(json, md, mops, ir);
    return 0;
}
