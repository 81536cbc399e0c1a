#define _GNU_SOURCE
/*
 * saarcor: command-line front end of the simulator (subcommand dispatch, help, version).
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <errno.h>
#include <math.h>
#include <getopt.h>

#include "cli.h"

static const saarcor_cmd commands[] = {
    { "version", "print the version, the fp24 format and the arithmetic path", cmd_version },
    { "f24", "evaluate one fp24 operation: saarcor f24 OP A [B]", cmd_f24 },
    { "f24gen", "write TestFloat-style hex test vectors: saarcor f24gen OP N", cmd_f24gen },
    { "f24verify", "check the fp24 arithmetic against MPFR (edge, random, exhaustive)", cmd_f24verify },
    { "compare", "compare two images: PSNR, max error, differing pixels", cmd_compare },
    { "info", "scene statistics: objects, triangles, kd-trees, build times, memory image", cmd_info },
    { "profile", "scene profile: what the scene needs, what the device skips, hls/ configuration", cmd_profile },
    { "stress", "numerical stability stress suite of this number format (docs/stress.md)", cmd_stress },
    { "render", "render a scene through the hardware units (functional mode)", cmd_render },
    { "reference", "render a scene with the double-precision reference (own BVH, binary64)", cmd_reference },
    { "compare-hits", "per primary ray: the units' hits against the reference's", cmd_compare_hits },
    { "jobs", "run the shell commands of a file, across MPI ranks with --mpi (docs/mpi.md)", cmd_jobs },
    { "gen", "write a generated scene as glTF: saarcor gen NAME -o FILE (gen --list)", cmd_gen },
};
#define N_COMMANDS (sizeof commands / sizeof commands[0])

int cli_parse_only;

static void usage(FILE *out)
{
    fprintf(out, "usage: saarcor [--help] COMMAND [ARGS]\n\n"
                 "A ray tracing hardware design (SaarCOR-style pipeline) and its simulator.\n\n"
                 "commands:\n");
    for (size_t i = 0; i < N_COMMANDS; i++)
        fprintf(out, "  %-10s %s\n", commands[i].name, commands[i].summary);
    fprintf(out, "\n'saarcor COMMAND --help' describes one command. Exit codes: 0 ok, 1 check failed,\n"
                 "2 usage error, 3 input/output error, 4 internal error (docs/cli.md).\n");
}

void cli_error(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "saarcor %s: error: ", cmd);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

int cli_usage_error(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "saarcor %s: error: ", cmd);
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, " (see 'saarcor %s --help')\n", cmd);
    va_end(ap);
    return SAARCOR_EXIT_USAGE;
}

int cli_parse_double(const char *text, double *out)
{
    char *end = NULL;
    errno = 0;
    const double v = strtod(text, &end);
    if (end == text || *end != '\0' || errno == ERANGE || isnan(v))
        return 0;
    *out = v;
    return 1;
}

int cli_parse_u64(const char *text, uint64_t lo, uint64_t hi, uint64_t *out)
{
    char *end = NULL;
    errno = 0;
    if (text[0] == '-' || text[0] == '\0')
        return 0;
    unsigned long long v = strtoull(text, &end, 0);
    if (*end == 'e' || *end == 'E' || *end == '.') { /* 1e7, 2.5e6 */
        double d;
        if (!cli_parse_double(text, &d) || d != floor(d) || d < 0 || d > 1.8e19)
            return 0;
        v = (unsigned long long)d;
    } else if (end == text || *end != '\0' || errno == ERANGE) {
        return 0;
    }
    if (v < lo || v > hi)
        return 0;
    *out = v;
    return 1;
}

int cli_bad_option(const char *cmd, int argc, char **argv)
{
    const char *arg = optind > 0 && optind <= argc ? argv[optind - 1] : "";
    return cli_usage_error(cmd, "unknown option or missing value '%s'", arg);
}

int cli_wants_help(int argc, char **argv)
{
    for (int i = 1; i < argc && strcmp(argv[i], "--") != 0; i++)
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0)
            return 1;
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return SAARCOR_EXIT_USAGE;
    }
    if (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "help") == 0) {
        usage(stdout);
        return SAARCOR_EXIT_OK;
    }
    if (strcmp(argv[1], "--version") == 0)
        return cmd_version(1, argv + 1);
    for (size_t i = 0; i < N_COMMANDS; i++)
        if (strcmp(argv[1], commands[i].name) == 0)
            return commands[i].run(argc - 1, argv + 1);
    fprintf(stderr, "saarcor: error: unknown command '%s' (see 'saarcor --help')\n", argv[1]);
    return SAARCOR_EXIT_USAGE;
}
