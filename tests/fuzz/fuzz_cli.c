/*
 * libFuzzer target: the command line (tb/cli: main.c's dispatch, each command's options, scene
 * and cycle options) and what the commands then do. The input is split at newlines and NUL bytes
 * into at most 24 arguments after "saarcor"; tb/cli/main.c is compiled with main renamed to
 * saarcor_main. Seeds: tests/fuzz/cli_seeds.txt (one command line per entry, corpus.sh).
 *
 * The commands run for real, on tiny inputs, so that option combinations are exercised and not
 * only parsed: each input runs in a fresh private directory holding a 1-triangle scene t.gltf and
 * two 8x8 images t.png, u.png, and gets trailing options that win over its own (getopt takes the
 * last): an 8x8 image, at most one frame and 100 triangles for the scene commands, 16 rays per
 * stress case, 64 vectors per f24verify operation, detail 1 for gen. A watchdog stops a command
 * that runs longer than TIME_BOUND_MS as Ctrl-C would (interrupt.h; every long loop polls it).
 * Only parsed (cli_parse_only), never run: paths with '/' (files outside the directory), jobs
 * (runs shell commands), f24gen (unbounded output), --precision (execs another program) and
 * --mpi (loads MPI).
 */
#define _GNU_SOURCE
#include <ftw.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "img.h"
#include "interrupt.h"

int saarcor_main(int argc, char **argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

enum { MAX_ARGS = 24, MAX_FORCED = 10, TIME_BOUND_MS = 1000 };

/* One triangle (0,0,0) (1,0,0) (0,1,0), the default view and light. */
static const char tri_gltf[] =
    "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],"
    "\"max\":[1,1,0]}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"buffers\":[{\"byteLength\":36,"
    "\"uri\":\"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}]}";

static char root[64];    /* private directory; each input runs in root/run */
static char home[4096];  /* the fuzzer's working directory (its corpus and artifact paths) */
static atomic_llong started_ms; /* when the running input began, 0: none */

static long long now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* Stops an input that runs too long, as SIGTERM would (the commands poll interrupt_signal). */
static void *watchdog(void *arg)
{
    (void)arg;
    for (;;) {
        const long long t0 = atomic_load(&started_ms);
        if (t0 && now_ms() - t0 > TIME_BOUND_MS)
            interrupt_set(SIGTERM);
        usleep(20000);
    }
    return NULL;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static void remove_root(void) { nftw(root, remove_entry, 16, FTW_DEPTH | FTW_PHYS); }

static int write_png(const char *path, float level)
{
    float px[8 * 8 * 3];
    for (int i = 0; i < 8 * 8 * 3; i++)
        px[i] = level * (float)(i % 7) / 6.0f;
    img_t img = { 8, 8, 3, px };
    char err[256];
    return img_write(path, &img, err, sizeof err);
}

/* A fresh root/run with the fixtures, as the working directory. */
static int fresh_run_dir(void)
{
    char run[80];
    snprintf(run, sizeof run, "%s/run", root);
    nftw(run, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
    if (mkdir(run, 0700) != 0 || chdir(run) != 0)
        return -1;
    FILE *f = fopen("t.gltf", "w");
    if (!f || fputs(tri_gltf, f) < 0 || fclose(f) != 0)
        return -1;
    return write_png("t.png", 1.0f) | write_png("u.png", 0.5f);
}

/* True if arg is an abbreviation getopt_long would accept for --name (at least "--" + 2). */
static int abbreviates(const char *arg, const char *name)
{
    const size_t n = strcspn(arg, "=");
    return n >= 4 && n <= strlen(name) && strncmp(arg, name, n) == 0;
}

/* Whether the command line may run for real (see the top of the file). */
static int may_run(int argc, char **argv)
{
    static const char *const run[] = { "version", "f24", "compare", "gen", "info", "render", "reference",
                                       "compare-hits", "profile", "stress", "f24verify" };
    int ok = 0;
    for (size_t i = 0; argc > 1 && i < sizeof run / sizeof run[0]; i++)
        ok |= strcmp(argv[1], run[i]) == 0;
    for (int i = 1; ok && i < argc; i++)
        ok = !strchr(argv[i], '/') && !abbreviates(argv[i], "--precision") && !abbreviates(argv[i], "--mpi");
    return ok;
}

/* The trailing options of command cmd that keep its input tiny; returns their number. */
static int forced_options(const char *cmd, char **out)
{
    static char *scene[] = { "--width", "8", "--height", "8", "--limit", "frames=1", "--limit", "triangles=100" };
    static char *stress[] = { "--rays", "16" }, *verify[] = { "-n", "64" }, *gen[] = { "--detail", "1" };
    char **list = NULL;
    int n = 0;
    if (!strcmp(cmd, "info") || !strcmp(cmd, "render") || !strcmp(cmd, "reference") || !strcmp(cmd, "compare-hits") ||
        !strcmp(cmd, "profile"))
        list = scene, n = 8;
    else if (!strcmp(cmd, "stress"))
        list = stress, n = 2;
    else if (!strcmp(cmd, "f24verify"))
        list = verify, n = 2;
    else if (!strcmp(cmd, "gen"))
        list = gen, n = 2;
    for (int i = 0; i < n; i++)
        out[i] = list[i];
    return n;
}

static void run_for_real(int argc, char **argv)
{
    static pthread_t dog;
    if (!root[0]) {
        snprintf(root, sizeof root, "/tmp/saarcor-fuzz-cli-XXXXXX");
        if (!getcwd(home, sizeof home) || !mkdtemp(root) || pthread_create(&dog, NULL, watchdog, NULL) != 0)
            abort(); /* the harness cannot work: not a finding */
        atexit(remove_root);
    }
    if (fresh_run_dir() != 0)
        abort();
    argc += forced_options(argv[1], argv + argc);
    argv[argc] = NULL;
    interrupt_set(0);
    cli_parse_only = 0;
    atomic_store(&started_ms, now_ms());
    saarcor_main(argc, argv);
    atomic_store(&started_ms, 0);
    if (chdir(home) != 0)
        abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1), *argv[MAX_ARGS + MAX_FORCED + 2] = { "saarcor" };
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
    if (may_run(argc, argv)) {
        run_for_real(argc, argv);
    } else {
        cli_parse_only = 1;
        saarcor_main(argc, argv);
    }
    fflush(stdout);
    free(text);
    return 0;
}
