/*
 * fp24 subcommands: `f24` (evaluate one operation), `f24gen` (test vectors) and `f24verify`
 * (three-way check against MPFR).
 */
#define _GNU_SOURCE
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "f24.h"
#include "f24_check.h"
#include "f24_ops.h"
#include "interrupt.h"

static void list_ops(FILE *out)
{
    fputs("operations:", out);
    for (int i = 0; i < F24_OP_COUNT; i++)
        fprintf(out, " %s", f24_ops[i].name);
    fputc('\n', out);
}

static int find_op(const char *cmd, const char *name, f24_op *op)
{
    const int i = f24_op_find(name);
    if (i < 0) {
        cli_usage_error(cmd, "unknown operation '%s'", name);
        return 0;
    }
    *op = (f24_op)i;
    return 1;
}

/* ---- saarcor f24 OP A [B] --------------------------------------------------------------- */

static int parse_operand(f24_kind kind, const char *text, uint32_t *out)
{
    if (text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
        uint64_t v;
        const uint64_t max = kind == F24_KIND_F24 ? F24_MASK : 0xFFFFFFFFu;
        return cli_parse_u64(text, 0, max, &v) && ((*out = (uint32_t)v), 1);
    }
    if (kind == F24_KIND_F24)
        return f24_mpfr_parse(text, out);
    if (kind == F24_KIND_F32) {
        char *end = NULL;
        float f = strtof(text, &end);
        if (end == text || *end != '\0')
            return 0;
        memcpy(out, &f, sizeof f);
        return 1;
    }
    char *end = NULL;
    long long v = strtoll(text, &end, 10);
    if (end == text || *end != '\0' || v < INT32_MIN || v > INT32_MAX)
        return 0;
    *out = (uint32_t)(int32_t)v;
    return 1;
}

static void print_value(f24_kind kind, uint32_t w)
{
    float f;
    switch (kind) {
    case F24_KIND_BOOL: printf("%u", (unsigned)w); return;
    case F24_KIND_I32: printf("%d", (int)(int32_t)w); return;
    case F24_KIND_F24: w = f24_to_f32(w); break;
    case F24_KIND_F32: break;
    }
    memcpy(&f, &w, sizeof f);
    printf("%.9g", (double)f);
}

int cmd_f24(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        printf("usage: saarcor f24 OP A [B]\n\n"
               "Evaluates one fp24 operation with the hardware reference and prints the result as hex\n"
               "and decimal. Operands: 0x... is a raw bit pattern, anything else a decimal number,\n"
               "rounded correctly to the operand's format.\n");
        list_ops(stdout);
        return SAARCOR_EXIT_OK;
    }
    f24_op op;
    if (argc < 2)
        return cli_usage_error("f24", "missing operation");
    if (!find_op("f24", argv[1], &op))
        return SAARCOR_EXIT_USAGE;
    const f24_op_info *info = &f24_ops[op];
    if (argc != 2 + info->arity)
        return cli_usage_error("f24", "'%s' takes %d operand(s)", info->name, info->arity);
    uint32_t a = 0, b = 0;
    if (!parse_operand(info->arg, argv[2], &a))
        return cli_usage_error("f24", "bad operand '%s'", argv[2]);
    if (info->arity == 2 && !parse_operand(info->arg, argv[3], &b))
        return cli_usage_error("f24", "bad operand '%s'", argv[3]);
    const uint32_t r = info->hw(a, b);
    printf("%s(", info->name);
    print_value(info->arg, a);
    if (info->arity == 2) {
        printf(", ");
        print_value(info->arg, b);
    }
    printf(") = ");
    print_value(info->result, r);
    printf("  [0x%0*X]\n", f24_kind_hex_digits(info->result), (unsigned)r);
    return SAARCOR_EXIT_OK;
}

/* ---- saarcor f24gen OP N ---------------------------------------------------------------- */

int cmd_f24gen(int argc, char **argv)
{
    static const struct option opts[] = {
        { "seed", required_argument, NULL, 's' }, { "no-edges", no_argument, NULL, 'E' },
        { "output", required_argument, NULL, 'o' }, { "help", no_argument, NULL, 'h' }, { 0, 0, 0, 0 }
    };
    uint64_t seed = 1, n = 0;
    int edges = 1;
    const char *path = NULL;
    int c;
    optind = 0;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "s:o:h", opts, NULL)) != -1) {
        switch (c) {
        case 's':
            if (!cli_parse_u64(optarg, 0, UINT64_MAX, &seed))
                return cli_usage_error("f24gen", "bad --seed '%s'", optarg);
            break;
        case 'E': edges = 0; break;
        case 'o': path = optarg; break;
        case 'h':
            printf("usage: saarcor f24gen OP N [--seed S] [--no-edges] [-o FILE]\n\n"
                   "Writes TestFloat-style test vectors, one per line in hex: 'a b result' (binary\n"
                   "operations) or 'a result' (unary). The edge set of OP comes first (unless\n"
                   "--no-edges), then N random vectors from the seed (default 1). Results are the\n"
                   "correctly rounded MPFR reference, independent of the implementation under test.\n"
                   "Format of this build: %s.\n", f24_format_name());
            list_ops(stdout);
            return SAARCOR_EXIT_OK;
        default: return cli_bad_option("f24gen", argc, argv);
        }
    }
    if (argc - optind != 2)
        return cli_usage_error("f24gen", "expected OP and N");
    f24_op op;
    if (!find_op("f24gen", argv[optind], &op))
        return SAARCOR_EXIT_USAGE;
    if (!cli_parse_u64(argv[optind + 1], 0, 1ull << 40, &n))
        return cli_usage_error("f24gen", "bad vector count '%s'", argv[optind + 1]);
    if (cli_parse_only)
        return SAARCOR_EXIT_OK;
    FILE *out = path ? fopen(path, "w") : stdout;
    if (!out) {
        cli_error("f24gen", "cannot write '%s'", path);
        return SAARCOR_EXIT_INPUT;
    }
    if (interrupt_catch() != 0)
        cli_error("f24gen", "cannot catch SIGINT/SIGTERM: Ctrl-C will not stop cleanly");
    f24_check_stop = interrupt_signal;
    f24_gen_vectors(out, op, n, seed, edges);
    if ((path ? fclose(out) : fflush(out)) != 0) {
        cli_error("f24gen", "write error on '%s'", path ? path : "stdout");
        return SAARCOR_EXIT_INPUT;
    }
    /* Ctrl-C: the vectors written so far are whole lines, kept */
    return interrupt_signal() ? interrupt_exit("f24gen", "the vectors written so far are kept") : SAARCOR_EXIT_OK;
}

/* ---- saarcor f24verify ------------------------------------------------------------------ */

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct {
    const char *kind; /* "random" or "exhaustive" */
    f24_op op;
    f24_check_stats st;
    double seconds;
} verify_row;

static void write_json(FILE *f, const verify_row *rows, int n, uint64_t n_random, uint64_t seed)
{
    fprintf(f, "{\n  \"format\": \"%s\", \"exp_bits\": %d, \"man_bits\": %d,\n"
               "  \"random_per_op\": %llu, \"seed\": %llu,\n  \"results\": [\n",
            f24_format_name(), F24_EXP_BITS, F24_MAN_BITS, (unsigned long long)n_random,
            (unsigned long long)seed);
    for (int i = 0; i < n; i++)
        fprintf(f, "    {\"op\": \"%s\", \"set\": \"%s\", \"vectors\": %llu, \"hw_mismatches\": %llu, "
                   "\"fast_mismatches\": %llu, \"seconds\": %.3f}%s\n",
                f24_ops[rows[i].op].name, rows[i].kind, (unsigned long long)rows[i].st.vectors,
                (unsigned long long)rows[i].st.hw_mismatches, (unsigned long long)rows[i].st.fast_mismatches,
                rows[i].seconds, i + 1 < n ? "," : "");
    fprintf(f, "  ]\n}\n");
}

int cmd_f24verify(int argc, char **argv)
{
    static const struct option opts[] = {
        { "count", required_argument, NULL, 'n' }, { "seed", required_argument, NULL, 's' },
        { "op", required_argument, NULL, 'p' }, { "exhaustive", no_argument, NULL, 'x' },
        { "json", required_argument, NULL, 'j' }, { "max-log", required_argument, NULL, 'm' },
        { "help", no_argument, NULL, 'h' }, { 0, 0, 0, 0 }
    };
    uint64_t n = 100000, seed = 1, max_log = 10;
    int only = -1, exhaustive = 0;
    const char *json = NULL;
    int c;
    optind = 0;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "n:s:p:xj:m:h", opts, NULL)) != -1) {
        switch (c) {
        case 'n':
            if (!cli_parse_u64(optarg, 0, 1ull << 40, &n))
                return cli_usage_error("f24verify", "bad --count '%s'", optarg);
            break;
        case 's':
            if (!cli_parse_u64(optarg, 0, UINT64_MAX, &seed))
                return cli_usage_error("f24verify", "bad --seed '%s'", optarg);
            break;
        case 'p':
            if ((only = f24_op_find(optarg)) < 0)
                return cli_usage_error("f24verify", "unknown operation '%s'", optarg);
            break;
        case 'x': exhaustive = 1; break;
        case 'j': json = optarg; break;
        case 'm':
            if (!cli_parse_u64(optarg, 0, 1000000, &max_log))
                return cli_usage_error("f24verify", "bad --max-log '%s'", optarg);
            break;
        case 'h':
            printf("usage: saarcor f24verify [-n N] [--seed S] [--op OP] [--exhaustive] [--json FILE]\n\n"
                   "Checks the integer hardware path and the fast path of every fp24 operation against\n"
                   "the correctly rounded MPFR reference: the edge set plus N random vectors per\n"
                   "operation (default 100000), and with --exhaustive every input of each unary\n"
                   "operation on fp24 values (formats of at most 24 bits). Mismatches are printed as\n"
                   "hex vectors (at most --max-log per operation, default 10). Exit 0 if everything\n"
                   "agrees, 1 otherwise. Format of this build: %s.\n", f24_format_name());
            return SAARCOR_EXIT_OK;
        default: return cli_bad_option("f24verify", argc, argv);
        }
    }
    if (optind != argc)
        return cli_usage_error("f24verify", "unexpected argument '%s'", argv[optind]);
    if (cli_parse_only)
        return SAARCOR_EXIT_OK;

    if (interrupt_catch() != 0)
        cli_error("f24verify", "cannot catch SIGINT/SIGTERM: Ctrl-C will not stop cleanly");
    f24_check_stop = interrupt_signal;
    verify_row rows[2 * F24_OP_COUNT];
    int nrows = 0;
    uint64_t bad = 0;
    printf("fp24 %s: %llu random vectors per operation after the edge set, seed %llu\n",
           f24_format_name(), (unsigned long long)n, (unsigned long long)seed);
    printf("%-10s %-10s %12s %12s %12s %9s\n", "op", "set", "vectors", "hw-mismatch", "fast-mismatch", "seconds");
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < F24_OP_COUNT; i++) {
            if (only >= 0 && i != only)
                continue;
            const f24_op op = (f24_op)i;
            if (pass == 1 && !(exhaustive && f24_ops[i].arity == 1 && f24_ops[i].arg == F24_KIND_F24 &&
                               F24_WIDTH <= 24))
                continue;
            verify_row *r = &rows[nrows++];
            r->kind = pass ? "exhaustive" : "random";
            r->op = op;
            const double t0 = now_seconds();
            r->st = pass ? f24_check_exhaustive(op, stdout, (int)max_log)
                         : f24_check_op(op, n, seed + (uint64_t)i, stdout, (int)max_log);
            r->seconds = now_seconds() - t0;
            if (interrupt_signal()) /* Ctrl-C: the operation in progress is not reported, nor --json */
                return interrupt_exit("f24verify", "the operations above were checked, --json not written");
            bad += r->st.hw_mismatches + r->st.fast_mismatches;
            printf("%-10s %-10s %12llu %12llu %12llu %9.2f\n", f24_ops[i].name, r->kind,
                   (unsigned long long)r->st.vectors, (unsigned long long)r->st.hw_mismatches,
                   (unsigned long long)r->st.fast_mismatches, r->seconds);
            fflush(stdout);
        }
    }
    if (json) {
        FILE *f = fopen(json, "w");
        if (!f) {
            cli_error("f24verify", "cannot write '%s'", json);
            return SAARCOR_EXIT_INPUT;
        }
        write_json(f, rows, nrows, n, seed);
        fclose(f);
    }
    printf("%s: %s\n", f24_format_name(), bad ? "MISMATCHES FOUND" : "all results agree with MPFR");
    return bad ? SAARCOR_EXIT_FAIL : SAARCOR_EXIT_OK;
}
