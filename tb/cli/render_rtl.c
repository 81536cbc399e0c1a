/*
 * saarcor render --mode rtl: a frame through the Verilated DynRTP (rtl/dynrtp.sv, built by make rtl
 * as <build>/rtl/eEmM/tb_dynrtp, rtl/tb/tb_dynrtp.cpp). The memory image and the parameters go to
 * a temporary folder, the model renders the frame there (the RGS, the core, the caches and the
 * memory port in RTL, the memory with the cycle model's bandwidth and latency) and writes back the
 * pixels, the primary hits and its counters; the folder is removed afterwards.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"
#include "f24.h"
#include "render.h"

extern char **environ;

const char *const rtl_unit_names[RTL_UNITS] = { "trav", "list", "rebase", "wide", "isect", "add" };
const char *const rtl_port_names[RTL_PORTS] = { "nodes", "lists", "words", "shading" };
/* the units tb_dynrtp checks (its stats' checked_NAME) */
const char *const rtl_checked_names[RTL_CHECKED] = { "rebase",      "wide",        "isect",      "add",
                                                     "trav",        "list",        "raygen",     "light",
                                                     "colour",      "add_light",   "accum",      "surface",
                                                     "cache_nodes", "cache_lists", "cache_words", "cache_shading" };

/* The model for `threads` threads per pipe, beside this program (build/saarcor or
 * build/w/eEmM/saarcor): <build>/rtl/eEmM/b<threads>/tb_dynrtp, built with that many threads and
 * block controllers (make build/rtl/eEmM/b32/tb_dynrtp), where there is one, else
 * <build>/rtl/eEmM/tb_dynrtp (make rtl: 8 block controllers, the blocks in flight at most). */
static int model_path(char *path, size_t n, uint32_t threads)
{
    char self[1024];
    const ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len <= 0)
        return -1;
    self[len] = 0;
    *strrchr(self, '/') = 0;
    const char *dir = strrchr(self, '/');
    int e, m;
    char tail;
    const int in_w = dir && sscanf(dir + 1, "e%dm%d%c", &e, &m, &tail) == 2;
    char models[1100];
    snprintf(models, sizeof models, "%s%s/rtl/e%dm%d", self, in_w ? "/../.." : "", F24_EXP_BITS, F24_MAN_BITS);
    snprintf(path, n, "%s/b%u/tb_dynrtp", models, threads);
    if (access(path, X_OK) != 0)
        snprintf(path, n, "%s/tb_dynrtp", models);
    return 0;
}

int render_rtl_check(const render_opts *ro)
{
    cycle_config d;
    cycle_config_default(&d);
    if (ro->cfg.traversal != TRAV_STACK)
        return cli_usage_error("render", "--mode rtl: the RTL traversal unit has the stack algorithm only (--traversal stack)");
    if (ro->cc.pipes != 1)
        return cli_usage_error("render", "--mode rtl: the RTL is one DynRTP (--pipes 1)");
    if (memcmp(ro->cc.latency, d.latency, sizeof d.latency) != 0)
        return cli_usage_error("render", "--mode rtl: the units' latencies are the RTL's (no --unit-latency)");
    for (int k = 0; k < MEM_KINDS; k++)
        if (ro->cc.mem.cache[k].size_bytes != d.mem.cache[k].size_bytes ||
            ro->cc.mem.cache[k].line_bytes != d.mem.cache[k].line_bytes)
            return cli_usage_error("render", "--mode rtl: the RTL's caches are 4,2,6,4 KB with lines 8, 4, one triangle "
                                             "record and 16 (rtl/dynrtp.sv; no --cache-kb or --line-bytes)");
    if (ro->usage_plot || ro->heatmap || ro->capture || ro->mpi || ro->sequence)
        return cli_usage_error("render", "--mode rtl renders one frame without --usage-plot, --heatmap, "
                                         "--capture-unit-io, --mpi or --frames");
    char path[1200];
    if (model_path(path, sizeof path, ro->cc.threads_per_pipe) != 0 || access(path, X_OK) != 0) {
        if (F24_EXP_BITS == 7 && F24_MAN_BITS == 16) /* make rtl builds the default format's */
            cli_error("render", "--mode rtl: no RTL model at %s: run make rtl", path);
        else
            cli_error("render", "--mode rtl: no RTL model at %s: run make rtl build/rtl/e%dm%d/tb_dynrtp", path,
                      F24_EXP_BITS, F24_MAN_BITS);
        return SAARCOR_EXIT_USAGE;
    }
    return SAARCOR_EXIT_OK;
}

static int write_file(const char *path, const void *data, size_t bytes)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    const int ok = fwrite(data, 1, bytes, f) == bytes;
    return fclose(f) == 0 && ok ? 0 : -1;
}

static int read_file(const char *path, void *data, size_t bytes)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    const int ok = fread(data, 1, bytes, f) == bytes;
    fclose(f);
    return ok ? 0 : -1;
}

/* key = prefix + names[k]: the counter goes to out[k] */
static void read_named(const char *key, const char *prefix, const char *const names[], int n, uint64_t out[],
                       unsigned long long v)
{
    const size_t len = strlen(prefix);
    if (strncmp(key, prefix, len) != 0)
        return;
    for (int k = 0; k < n; k++)
        if (!strcmp(key + len, names[k]))
            out[k] = v;
}

/* The model's key-value counters into sum and st. */
static int read_stats(const char *path, rgs_counters *sum, rtl_stats *st)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    char key[64];
    unsigned long long v;
    static const char *const trace_keys[10] = { "traversal_steps", "leaves", "list_entries", "mailbox_skips",
                                                "transformations", "intersections", "words_nodes", "words_lists",
                                                "words_matrices", "words_shading" };
    uint64_t *tw = &sum->trace.traversal_steps;
    memset(sum, 0, sizeof *sum);
    memset(st, 0, sizeof *st);
    while (fscanf(f, "%63s %llu", key, &v) == 2) {
        int k;
        if (!strcmp(key, "cycles")) st->cycles = v;
        else if (!strcmp(key, "packets")) st->packets = v;
        else if (!strcmp(key, "threads")) st->threads = (uint32_t)v;
        else if (!strcmp(key, "mem_transfers")) st->mem_transfers = v;
        else if (!strcmp(key, "mem_bytes")) st->mem_bytes = v;
        else if (!strcmp(key, "dropped")) sum->dropped = v;
        else if (sscanf(key, "rays_%d", &k) == 1 && k >= 0 && k < RAY_KINDS) sum->rays[k] = v;
        read_named(key, "issues_", rtl_unit_names, RTL_UNITS, st->issues, v);
        read_named(key, "reads_", rtl_port_names, RTL_PORTS, st->reads, v);
        read_named(key, "checked_", rtl_checked_names, RTL_CHECKED, st->checked, v);
        read_named(key, "", trace_keys, 10, tw, v);
    }
    fclose(f);
    return st->cycles ? 0 : -1;
}

/* The model's output (its first line, or the first MISMATCH) as the error. */
static void report_failure(const char *log, int status)
{
    char line[512] = "", first[512] = "";
    FILE *f = fopen(log, "r");
    while (f && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        if (!first[0] || (!strncmp(line, "MISMATCH", 8) && strncmp(first, "MISMATCH", 8)))
            snprintf(first, sizeof first, "%s", line);
    }
    if (f)
        fclose(f);
    cli_error("render", "--mode rtl: the RTL model failed (exit %d): %s", status, first);
}

int render_rtl(const uint32_t *mem, uint32_t n, const render_opts *ro, uint32_t w, uint32_t h, uint32_t *pixels,
               hit_record *hits, rgs_counters *sum, rtl_stats *st)
{
    char dir[] = "/tmp/saarcor-rtl-XXXXXX", path[1200], model[1200], log[1200];
    if (!mkdtemp(dir) || model_path(model, sizeof model, ro->cc.threads_per_pipe) != 0) {
        cli_error("render", "--mode rtl: cannot make a temporary folder: %s", strerror(errno));
        return SAARCOR_EXIT_INTERNAL;
    }
    int rc = SAARCOR_EXIT_INTERNAL;
    uint32_t *hw = malloc((size_t)w * h * 6 * sizeof *hw);
    snprintf(path, sizeof path, "%s/image.bin", dir);
    FILE *pf = NULL;
    if (!hw || write_file(path, mem, (size_t)n * sizeof *mem) != 0)
        goto out;
    snprintf(path, sizeof path, "%s/params", dir);
    if (!(pf = fopen(path, "w")))
        goto out;
    fprintf(pf, "tile %u\nthreads %u\nmax_depth %u\nshadows %u\ntraversal %u\nmem_latency %u\nmem_mbps %.17g\n"
                "clock_mhz %.17g\nvcd_from %llu\nvcd_to %llu\n", ro->cc.tile, ro->cc.threads_per_pipe, ro->cfg.max_depth,
            ro->cfg.shadows, ro->cfg.traversal, ro->cc.mem.latency, ro->cc.mem.mbps, ro->cc.mem.clock_mhz,
            (unsigned long long)ro->vcd_from, (unsigned long long)ro->vcd_to);
    if (fclose(pf) != 0)
        goto out;
    snprintf(log, sizeof log, "%s/log", dir);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    char *const args[] = { model, dir, (char *)ro->vcd, NULL }; /* --vcd: the model writes it (NULL: none) */
    pid_t pid;
    int status = -1;
    const int spawned = posix_spawn(&pid, model, &fa, NULL, args, environ) == 0;
    posix_spawn_file_actions_destroy(&fa);
    if (!spawned || waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        report_failure(log, WIFEXITED(status) ? WEXITSTATUS(status) : -1);
        rc = !WIFEXITED(status)            ? SAARCOR_EXIT_FAIL
           : WEXITSTATUS(status) == 2      ? SAARCOR_EXIT_USAGE
           : WEXITSTATUS(status) == 3      ? SAARCOR_EXIT_INPUT /* --vcd cannot be written */
                                           : SAARCOR_EXIT_FAIL;
        goto out;
    }
    snprintf(path, sizeof path, "%s/pixels.bin", dir);
    if (read_file(path, pixels, (size_t)w * h * sizeof *pixels) != 0)
        goto out;
    snprintf(path, sizeof path, "%s/hits.bin", dir);
    if (read_file(path, hw, (size_t)w * h * 6 * sizeof *hw) != 0)
        goto out;
    if (hits)
        for (size_t p = 0; p < (size_t)w * h; p++)
            hits[p] = (hit_record){ hw[6 * p], hw[6 * p + 1], hw[6 * p + 2], hw[6 * p + 3], hw[6 * p + 4], hw[6 * p + 5] };
    snprintf(path, sizeof path, "%s/stats", dir);
    if (read_stats(path, sum, st) != 0)
        goto out;
    if (st->threads < ro->cc.threads_per_pipe) /* not what --mode cycle with the same options times */
        fprintf(stderr, "saarcor render: warning: --mode rtl: %u of the %u threads per pipe in flight, the model's "
                        "block controllers (make build/rtl/e%dm%d/b%u/tb_dynrtp builds one with %u)\n",
                st->threads, ro->cc.threads_per_pipe, F24_EXP_BITS, F24_MAN_BITS, ro->cc.threads_per_pipe,
                ro->cc.threads_per_pipe);
    rc = SAARCOR_EXIT_OK;
out:
    if (rc == SAARCOR_EXIT_INTERNAL)
        cli_error("render", "--mode rtl: cannot exchange the frame with the RTL model in %s", dir);
    free(hw);
    static const char *const files[] = { "image.bin", "params", "log", "pixels.bin", "hits.bin", "stats" };
    for (size_t k = 0; k < sizeof files / sizeof *files; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[k]);
        unlink(path);
    }
    rmdir(dir);
    return rc;
}

void rtl_report(FILE *f, const render_opts *ro, const rtl_stats *st)
{
    fprintf(f, "rtl: %llu cycles (%.1f fps at %.0f MHz), %u threads, %llu packets, %llu memory transfers (%llu bytes); "
               "unit usage:", (unsigned long long)st->cycles, ro->cc.mem.clock_mhz * 1e6 / (double)st->cycles,
            ro->cc.mem.clock_mhz, st->threads, (unsigned long long)st->packets, (unsigned long long)st->mem_transfers,
            (unsigned long long)st->mem_bytes);
    for (int k = 0; k < RTL_UNITS; k++)
        fprintf(f, " %s %.1f%%", rtl_unit_names[k], 100.0 * (double)st->issues[k] / (double)st->cycles);
    fprintf(f, "; reads per cycle:");
    for (int k = 0; k < RTL_PORTS; k++)
        fprintf(f, " %s %.3f", rtl_port_names[k], (double)st->reads[k] / (double)st->cycles);
    fprintf(f, "\n");
}

/* a JSON object's members "names[k]": values[k] */
static void json_counts(FILE *f, const char *const names[], const uint64_t values[], int n)
{
    for (int k = 0; k < n; k++)
        fprintf(f, "%s\"%s\": %llu", k ? ", " : "", names[k], (unsigned long long)values[k]);
}

void rtl_report_json(FILE *f, const render_opts *ro, const rtl_stats *st)
{
    fprintf(f, "{\"cycles\": %llu, \"fps\": %.6f, \"threads\": %u, \"packets\": %llu, \"mem_transfers\": %llu, "
               "\"mem_bytes\": %llu, \"issues\": {", (unsigned long long)st->cycles,
            ro->cc.mem.clock_mhz * 1e6 / (double)st->cycles, st->threads, (unsigned long long)st->packets,
            (unsigned long long)st->mem_transfers, (unsigned long long)st->mem_bytes);
    json_counts(f, rtl_unit_names, st->issues, RTL_UNITS);
    fprintf(f, "}, \"reads\": {");
    json_counts(f, rtl_port_names, st->reads, RTL_PORTS);
    fprintf(f, "}, \"usage\": {");
    for (int k = 0; k < RTL_UNITS; k++)
        fprintf(f, "%s\"%s\": %.6f", k ? ", " : "", rtl_unit_names[k], (double)st->issues[k] / (double)st->cycles);
    fprintf(f, "}, \"checked_units\": {");
    json_counts(f, rtl_checked_names, st->checked, RTL_CHECKED);
    fprintf(f, "}}");
}
