/*
 * Options and report of `saarcor render --mode cycle` (tb/cycle): the model's parameters on the
 * command line, the paper-style table (Tables 3 and 4: fps, unit usage, cache hit rates,
 * external bandwidth) on stdout, and the same figures as JSON for --stats.
 */
#ifndef SAARCOR_CYCLE_OPTS_H
#define SAARCOR_CYCLE_OPTS_H

#include <getopt.h>
#include <stdio.h>

#include "cycle_sim.h"

enum { CYCLE_OPT_BASE = 2000 }; /* above SCENE_OPT_BASE + its options */

#define CYCLE_LONG_OPTIONS                                                                                          \
    { "pipes", required_argument, NULL, CYCLE_OPT_BASE + 0 },                                                     \
        { "threads-per-pipe", required_argument, NULL, CYCLE_OPT_BASE + 1 },                                      \
        { "clock-mhz", required_argument, NULL, CYCLE_OPT_BASE + 2 },                                             \
        { "cache-kb", required_argument, NULL, CYCLE_OPT_BASE + 3 },                                              \
        { "line-bytes", required_argument, NULL, CYCLE_OPT_BASE + 4 },                                            \
        { "mem-latency", required_argument, NULL, CYCLE_OPT_BASE + 5 },                                           \
        { "mem-mbps", required_argument, NULL, CYCLE_OPT_BASE + 6 },                                              \
        { "unit-latency", required_argument, NULL, CYCLE_OPT_BASE + 7 },                                          \
        { "tile", required_argument, NULL, CYCLE_OPT_BASE + 8 }

extern const char CYCLE_OPTIONS_HELP[];

/* Parses option c (>= CYCLE_OPT_BASE) into cfg: 1 if it was one, 0 if not, -1 on a bad value
 * (the error is printed). */
int cycle_opts_parse(cycle_config *cfg, const char *cmd, int c, const char *arg);

/* The paper-style report of one frame. */
void cycle_report(FILE *f, const cycle_config *cfg, const cycle_stats *st, uint64_t rays);

/* The same as a JSON object (no trailing newline). */
void cycle_report_json(FILE *f, const cycle_config *cfg, const cycle_stats *st, uint64_t rays);

#endif
