/*
 * The saarcor command-line program: subcommands, shared option helpers and exit codes.
 * Exit codes are stable and documented in docs/cli.md.
 */
#ifndef SAARCOR_CLI_H
#define SAARCOR_CLI_H

#include <stdint.h>

enum {
    SAARCOR_EXIT_OK = 0,       /* success; a check or threshold passed */
    SAARCOR_EXIT_FAIL = 1,     /* a check failed or a threshold was not met */
    SAARCOR_EXIT_USAGE = 2,    /* bad command line */
    SAARCOR_EXIT_INPUT = 3,    /* unreadable or invalid input, or an output that cannot be written */
    SAARCOR_EXIT_INTERNAL = 4, /* out of memory or another internal error */
    SAARCOR_EXIT_LIMIT = 5,    /* a hard limit was exceeded (docs/limits.md; --limit NAME=N raises it) */
};

typedef struct {
    const char *name;
    const char *summary;
    int (*run)(int argc, char **argv); /* argv[0] is the subcommand name */
} saarcor_cmd;

int cmd_version(int argc, char **argv);
int cmd_f24(int argc, char **argv);
int cmd_f24gen(int argc, char **argv);
int cmd_f24verify(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_info(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_gen(int argc, char **argv);
int cmd_reference(int argc, char **argv);
int cmd_compare_hits(int argc, char **argv);
int cmd_profile(int argc, char **argv);
int cmd_stress(int argc, char **argv);
int cmd_jobs(int argc, char **argv);

/* Set only by the command-line fuzzer (tests/fuzz/fuzz_cli.c): every command returns right after
 * parsing and checking its arguments, before it reads or writes a file or runs anything long. */
extern int cli_parse_only;

/* Prints "saarcor CMD: error: ..." on one line to stderr and returns SAARCOR_EXIT_USAGE. */
int cli_usage_error(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Prints "saarcor CMD: error: ..." on one line to stderr (no return code implied). */
void cli_error(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Strict number parsing: the whole text must be a number in [lo, hi]; 0 on failure.
 * cli_parse_u64 accepts 1e7-style integers for vector counts. */
int cli_parse_u64(const char *text, uint64_t lo, uint64_t hi, uint64_t *out);
int cli_parse_double(const char *text, double *out);

/* Message for getopt's '?' (unknown option or missing argument); returns SAARCOR_EXIT_USAGE.
 * Subcommands set opterr = 0 so that this is the only line printed. */
int cli_bad_option(const char *cmd, int argc, char **argv);

/* True if argv has -h or --help before any "--". */
int cli_wants_help(int argc, char **argv);

#endif
