/*
 * libFuzzer target: the command-line parser (tb/cli: main.c's dispatch, each command's options,
 * scene_opts.c, cycle_opts.c). The input is split at newlines and NUL bytes into at most 24
 * arguments after "saarcor"; tb/cli/main.c is compiled with main renamed to saarcor_main, and
 * cli_parse_only makes every command return right after parsing and checking its arguments.
 * Seeds: tests/fuzz/cli_seeds.txt (one command line per entry, written by tests/fuzz/corpus.sh).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

int saarcor_main(int argc, char **argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

enum { MAX_ARGS = 24 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1), *argv[MAX_ARGS + 2] = { "saarcor" };
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = 0;
    int argc = 1;
    for (size_t i = 0, start = 0; i <= size && argc <= MAX_ARGS; i++)
        if (i == size || text[i] == '\n' || text[i] == 0) {
            text[i] = 0;
            argv[argc++] = text + start;
            start = i + 1;
        }
    argv[argc] = NULL;
    cli_parse_only = 1;
    saarcor_main(argc, argv);
    fflush(stdout);
    free(text);
    return 0;
}
