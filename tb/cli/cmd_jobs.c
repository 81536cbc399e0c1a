/*
 * saarcor jobs [--mpi] FILE: runs the independent shell commands of FILE (one a line; blank lines
 * and lines starting with # are skipped) and reports which failed. Without --mpi one after the
 * other in this process; with --mpi (under mpirun) rank 0 hands the lines out dynamically to the
 * other ranks through libsaarcor_mpi.so, the distributor of render --mpi. Why: the precision
 * sweep and the stress suite are many independent runs (tests/bench/bench_precision.py and
 * bench_stress.py --mpi N write their runs to such a file). Every rank reads FILE itself (a
 * shared file system on a cluster); only line numbers and exit statuses cross the network.
 */
#define _GNU_SOURCE
#include <getopt.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>

#include "cli.h"
#include "interrupt.h"
#include "mpi_load.h"

typedef struct {
    char **cmd; /* the job lines */
    uint32_t n, failed, done;
    int stop_sig; /* a job died of SIGINT/SIGTERM (Ctrl-C reaches the job, not us: system() ignores it) */
} job_list;

static int read_jobs(const char *path, job_list *j)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return cli_error("jobs", "cannot read '%s'", path), -1;
    char *line = NULL;
    size_t cap = 0;
    ssize_t len;
    while ((len = getline(&line, &cap, f)) >= 0) {
        while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r'))
            line[--len] = 0;
        const char *p = line + strspn(line, " \t");
        if (!*p || *p == '#')
            continue;
        char **grown = realloc(j->cmd, (j->n + 1) * sizeof *grown);
        if (!grown || !(grown[j->n] = strdup(p))) {
            free(grown ? grown : j->cmd);
            j->cmd = NULL;
            j->n = 0;
            break;
        }
        j->cmd = grown;
        j->n++;
    }
    free(line);
    fclose(f);
    return j->cmd || !j->n ? 0 : (cli_error("jobs", "out of memory reading '%s'", path), -1);
}

/* Runs job `item` with /bin/sh; its result is the exit status (128 + signal if killed). */
static long job_work(void *ctx, uint32_t item, void *result)
{
    const job_list *j = ctx;
    fflush(NULL);
    const int st = system(j->cmd[item]);
    const int32_t code = st == -1 ? 127 : WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    memcpy(result, &code, sizeof code);
    return sizeof code;
}

static int job_take(void *ctx, uint32_t item, const void *result, size_t size, int rank)
{
    job_list *j = ctx;
    int32_t code;
    if (item >= j->n || size != sizeof code) {
        cli_error("jobs", "rank %d sent %zu bytes for job %u: not an exit status", rank, size, item);
        return -1;
    }
    memcpy(&code, result, sizeof code);
    j->done++;
    j->failed += code != 0;
    if (code == 128 + SIGINT || code == 128 + SIGTERM) {
        j->stop_sig = code - 128; /* the interrupt line says it */
        return 0;
    }
    if (code != 0) {
        fprintf(stderr, "saarcor jobs: job %u failed with exit status %d (rank %d): %s\n", item + 1, code, rank,
                j->cmd[item]);
    }
    return 0;
}

static int usage(void)
{
    printf("usage: saarcor jobs [--mpi] FILE\n\n"
           "Runs the shell commands of FILE, one a line (blank lines and # comments skipped), and\n"
           "exits 1 if any of them failed. Without --mpi one after the other; with --mpi, under\n"
           "mpirun -np N (N >= 2), rank 0 hands the lines out to ranks 1..N-1 as they become free\n"
           "(docs/mpi.md). Every rank reads FILE; job output goes to the rank's stdout/stderr.\n");
    return SAARCOR_EXIT_OK;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int cmd_jobs(int argc, char **argv)
{
    static const struct option opts[] = { { "mpi", no_argument, NULL, 'M' }, { "help", no_argument, NULL, 'h' }, { 0, 0, 0, 0 } };
    int c, mpi = 0;
    optind = 0;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "+h", opts, NULL)) != -1) {
        if (c == 'M')
            mpi = 1;
        else if (c == 'h')
            return usage();
        else
            return cli_bad_option("jobs", argc, argv);
    }
    if (argc - optind != 1)
        return cli_usage_error("jobs", "expected one FILE of commands");
    if (cli_parse_only) /* the command line fuzzer: never run the commands of a file */
        return SAARCOR_EXIT_OK;
    saarcor_mpi_run_fn run = mpi ? mpi_load("jobs") : NULL;
    if (mpi && !run)
        return SAARCOR_EXIT_INTERNAL;
    job_list j = { NULL, 0, 0, 0, 0 };
    if (read_jobs(argv[optind], &j) != 0)
        return SAARCOR_EXIT_INPUT;
    const saarcor_mpi_work w = { j.n, sizeof(int32_t), &j, job_work, job_take };
    saarcor_mpi_report rep = { .rank = 0, .ranks = 1 };
    char err[512], result[sizeof(int32_t)];
    int rc = SAARCOR_EXIT_OK;
    const double t0 = now();
    if (run && run(SAARCOR_MPI_ABI, &w, &rep, err, sizeof err) != 0)
        rc = (cli_error("jobs", "--mpi: %s", err), SAARCOR_EXIT_USAGE);
    if (!run && interrupt_catch() != 0)
        cli_error("jobs", "cannot catch SIGINT/SIGTERM: Ctrl-C will not stop cleanly");
    for (uint32_t i = 0; !run && i < j.n && !j.stop_sig && !interrupt_signal(); i++)
        job_take(&j, i, result, (size_t)job_work(&j, i, result), 0);
    const int sig = run ? 0 : interrupt_signal() ? interrupt_signal() : j.stop_sig;
    if (sig) { /* no more jobs after Ctrl-C */
        fprintf(stderr, "saarcor jobs: interrupted by %s: %u of %u jobs run\n", interrupt_name(sig), j.done, j.n);
        rc = 128 + sig;
    } else if (rc == SAARCOR_EXIT_OK && rep.rank == 0) {
        printf("jobs: %u run, %u failed, %d worker%s, %.3f s\n", j.n, j.failed, run ? rep.ranks - 1 : 1,
               run && rep.ranks == 2 ? "" : run ? "s" : "", now() - t0);
        rc = j.failed ? SAARCOR_EXIT_FAIL : SAARCOR_EXIT_OK;
    }
    for (uint32_t i = 0; i < j.n; i++)
        free(j.cmd[i]);
    free(j.cmd);
    return rc;
}
