/*
 * make bench-build: how fast the host builds the scene (bottom-level kd-trees, top-level kd-tree,
 * memory image) and how large the result is, with Embree 3's BVH build as the anchor.
 *
 * 1. Every scene (the shared glTF scenes in ../shared/scenes and the scene generators) is loaded
 *    or generated, evaluated at t = 0 and built with mi_build and the default mi_params. Reported:
 *    unique and instanced triangles, objects, instances, dropped degenerate triangles, the
 *    bottom-level time (triangle transformations + kd-trees: mi_stats.bottom_build_seconds +
 *    transform_seconds), the top-level time, kd nodes / leaves / leaf references per unique
 *    triangle, geometry bytes per unique triangle (STATIC_GEOMETRY + DYNAMIC_GEOMETRY words x 4),
 *    the image size and the SAH cost of the bottom-level trees (mi_stats.bottom_sah per triangle:
 *    each tree's cost under the builder's own cost model, weighted by its triangles), beside the
 *    same figure and the time for the exact sweep throughout (render --kd-bins 0, the default before
 *    the large meshes were binned). A scene
 *    that does not fit the default 24 MB image is built with 1 GB.
 * 2. The same scene in Embree, two-level like ours: one RTCScene per mesh, one instance geometry
 *    per scene instance (its object-to-world matrix) in a top-level scene, at build quality
 *    MEDIUM (Embree's default, binned SAH) and HIGH (spatial splits, the analogue of our perfect
 *    splits). Timed: the sum of the per-mesh rtcCommitScene calls and the top-level commit;
 *    memory: bytes the device allocated during those commits (memory monitor callback), and
 *    separately its vertex/index buffers. Both sides get the same CPUs: every measurement runs in
 *    a forked child bound to 1 CPU, and again to all CPUs this process may use (our builder uses
 *    the CPUs it may run on; Embree gets a threads=N device for N CPUs; a fresh child per device,
 *    as TBB's global thread limit would otherwise leak between devices). Every time is the median
 *    of 3 runs (1 run when a run takes longer than SLOW_SECONDS; the "runs" column says which).
 * 3. Top-level rebuilds: kd_build in binned mode (mi_params_default's top parameters) over the
 *    world boxes of the plants scene's instances and over 10,000 random boxes, median of 21
 *    rebuilds; and a full mi_update per frame (scene_evaluate at successive times, 30 frames per
 *    second) with the bytes each frame uploads, for the animated scene, BoxAnimated.glb,
 *    CesiumMilkTruck.glb, the skinned Fox.glb (all its animations at once: the last, "Run", wins;
 *    the skin is applied in scene_evaluate, its object rebuilt in mi_update) and the (static)
 *    plants scene; the host time per frame is the median of scene_evaluate + mi_update.
 *
 * 4. Loading and building the 500k-triangle scene as `saarcor info` does (load, evaluate, then
 *    mi_build with the default 24 MB, again with 1 GB when it does not fit): the wall time of
 *    the command (with --saarcor PROGRAM; process start-up included), and in this process the
 *    load and the build separately; all CPUs, median of 3.
 *
 * Output: --out DIR writes DIR/build.md and DIR/build.json (with the load average at the start
 * and the end of the run); progress goes to stderr.
 * --scenes DIR overrides the glTF folder (default: ../shared/scenes next to the source tree).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <sched.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <embree3/rtcore.h>

#include "embree_scene.h"

#include "kdtree.h"
#include "memimage.h"
#include "scene.h"
#include "scenes.h"
#include "shade_rec.h"

#ifndef SAARCOR_SRC_DIR
#define SAARCOR_SRC_DIR "."
#endif

enum { REPS = 3, TOP_REPS = 21, RANDOM_BOXES = 10000, FRAMES = 30 };
#define SLOW_SECONDS 12.0          /* a run longer than this is not repeated */
#define BIG_MEMORY (1ull << 30)    /* for scenes that do not fit the default image */
#define FPS 30.0

static const char *const gltf_files[] = {
    "Box.glb", "CesiumMilkTruck.glb", "teapot.glb", "primitives.glb", "subpass_scene_opaque.glb",
    "bunny.glb", "bunny_instanced16.glb", "gallery_ccby_503k.glb",
};
static const char *const generator_names[] = { "cornell", "room", "plants", "terrain", "animated" };
/* per-frame updates: generator or glTF file */
static const char *const frame_scenes[] = { "animated", "BoxAnimated.glb", "CesiumMilkTruck.glb", "Fox.glb",
                                            "plants" };
/* section 4: the 500k-triangle scene (issue 19: loaded and built in at most 1.5 s) */
static const char *const load_scene_name = "gallery_ccby_503k.glb";
#define LOAD_TARGET_SECONDS 1.5

/* CPU budgets of sections 1 and 2: one CPU, and every CPU this process may use (cpus_all) */
enum { CPU_ONE, CPU_ALL, CPU_CONFIGS };
static int cpus_all = 1;
static int cpus_of(int config) { return config == CPU_ONE ? 1 : cpus_all; }

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

/* ---- helpers ------------------------------------------------------------------------------ */

static int line_open; /* a progress line on stderr waits for its "done" */

__attribute__((format(printf, 1, 2))) static void progress(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    line_open = fmt[strlen(fmt) - 1] != '\n';
}

__attribute__((format(printf, 1, 2), noreturn)) static void fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs(line_open ? "\nbench-build: error: " : "bench-build: error: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    exit(1);
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Median of n values (sorts v). */
static double median(double *v, int n)
{
    if (n <= 0)
        return 0;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Whether to run again after `done` runs, the first of which took first_seconds. */
static int run_again(int done, double first_seconds)
{
    return done < REPS && !(done >= 1 && first_seconds > SLOW_SECONDS);
}

static int is_gltf(const char *name) { return strchr(name, '.') != NULL; }

/* Loads a glTF file from dir or runs a generator (seed 1, default size), then evaluates at t = 0. */
static int load_scene(const char *dir, const char *name, scene *s, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    if (is_gltf(name)) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, name);
        if (scene_load_gltf(path, s, err, errlen) != 0)
            return -1;
    } else {
        const scene_generator *g = scene_generator_find(name);
        const scene_gen_params gp = { 1, 0 };
        if (!g) {
            snprintf(err, errlen, "no scene generator called '%s'", name);
            return -1;
        }
        if (g->build(s, &gp, err, errlen) != 0) {
            scene_free(s);
            return -1;
        }
    }
    if (scene_evaluate(s, 0.0, 1) != 0) {
        snprintf(err, errlen, "%s: out of memory in scene_evaluate", name);
        scene_free(s);
        return -1;
    }
    return 0;
}

static uint64_t unique_triangles(const scene *s)
{
    uint64_t n = 0;
    for (uint32_t i = 0; i < s->n_meshes; i++)
        n += s->meshes[i].n_triangles;
    return n;
}

static uint64_t instanced_triangles(const scene *s)
{
    uint64_t n = 0;
    for (uint32_t i = 0; i < s->n_instances; i++)
        n += s->meshes[s->instances[i].mesh].n_triangles;
    return n;
}

static int read_all(int fd, void *buf, size_t n)
{
    char *p = buf;
    while (n > 0) {
        const ssize_t k = read(fd, p, n);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1;
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

static void write_all(int fd, const void *buf, size_t n)
{
    const char *p = buf;
    while (n > 0) {
        const ssize_t k = write(fd, p, n);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return;
        p += k;
        n -= (size_t)k;
    }
}

/* Binds this process to the first `cpus` of the CPUs it may use. */
static void bind_cpus(int cpus)
{
    cpu_set_t all, use;
    if (sched_getaffinity(0, sizeof all, &all) != 0)
        return;
    CPU_ZERO(&use);
    for (int c = 0, n = 0; c < CPU_SETSIZE && n < cpus; c++)
        if (CPU_ISSET(c, &all)) {
            CPU_SET(c, &use);
            n++;
        }
    sched_setaffinity(0, sizeof use, &use);
}

/* Runs fn(ctx, result) in a forked child bound to `cpus` CPUs and copies its result (size bytes,
 * zeroed before) back. The child has the parent's data (the loaded scene) but its own threads:
 * our builder's pool sizes itself to the CPUs it may use, and each Embree device starts in a
 * fresh TBB state. */
static int run_child(int cpus, void (*fn)(const void *ctx, void *result), const void *ctx, void *result, size_t size,
                     char *err, size_t errlen)
{
    int fd[2];
    memset(result, 0, size);
    if (pipe(fd) != 0) {
        snprintf(err, errlen, "pipe: %s", strerror(errno));
        return -1;
    }
    fflush(NULL);
    const pid_t pid = fork();
    if (pid < 0) {
        snprintf(err, errlen, "fork: %s", strerror(errno));
        close(fd[0]);
        close(fd[1]);
        return -1;
    }
    if (pid == 0) {
        close(fd[0]);
        bind_cpus(cpus);
        fn(ctx, result);
        write_all(fd[1], result, size);
        close(fd[1]);
        _exit(0);
    }
    close(fd[1]);
    const int got = read_all(fd[0], result, size);
    close(fd[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    if (got != 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        snprintf(err, errlen, "the child process failed (status 0x%x)", (unsigned)status);
        return -1;
    }
    return 0;
}

/* ---- our builder -------------------------------------------------------------------------- */

typedef struct {
    int ok, runs, big_memory;
    char err[512];
    uint64_t unique_tris, instanced_tris;
    uint32_t objects, instances, degenerate, bottom_depth, top_nodes;
    double bottom_ms, top_ms;   /* medians */
    double nodes_per_tri, leaves_per_tri, refs_per_tri;
    double geom_bytes_per_tri, geom_noshade_bytes_per_tri, image_mb;
    double sah;                 /* bottom level: SAH cost per tree, weighted by triangles */
} ours_result;

/* mi_build with p (NULL: the default parameters), or with BIG_MEMORY if the scene does not fit
 * (*big is set then; a caller that already knows passes *big = 1 to skip the failing attempt). */
static mi_builder *build_image(const scene *s, const mi_params *params, int *big, char *err, size_t errlen)
{
    mi_params p;
    mi_params_default(&p);
    if (params)
        p = *params;
    if (*big)
        p.memory_bytes = BIG_MEMORY;
    mi_builder *b = mi_build(s, &p, err, errlen);
    if (!b && !*big && strstr(err, "does not fit")) {
        p.memory_bytes = BIG_MEMORY;
        *big = 1;
        b = mi_build(s, &p, err, errlen);
    }
    return b;
}

static void ours_describe(const scene *s, const mi_builder *b, ours_result *r)
{
    const mi_stats *st = mi_get_stats(b);
    uint32_t n_words;
    const uint32_t *w = mi_words(b, &n_words);
    const double tris = st->triangles ? (double)st->triangles : 1.0;
    const double geom_bytes = 4.0 * ((double)st->region_words[MI_R_STATIC_GEOMETRY] +
                                     (double)st->region_words[MI_R_DYNAMIC_GEOMETRY]);
    double shading_bytes = 0; /* the objects' shading records (their stride depends on the object) */
    for (uint32_t o = 0; o < w[MI_H_OBJECTS]; o++) {
        const uint32_t *d = w + w[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS] + MI_OBJECT_WORDS * o;
        shading_bytes += 4.0 * shade_rec_words(d[MI_O_FLAGS]) * d[MI_O_N_TRIANGLES];
    }
    r->unique_tris = unique_triangles(s);
    r->instanced_tris = instanced_triangles(s);
    r->objects = st->objects;
    r->instances = st->instances;
    r->degenerate = st->degenerate_triangles;
    r->bottom_depth = st->bottom_depth;
    r->top_nodes = st->top_nodes;
    r->nodes_per_tri = st->bottom_nodes / tris;
    r->leaves_per_tri = st->bottom_leaves / tris;
    r->refs_per_tri = (double)st->bottom_references / tris;
    r->geom_bytes_per_tri = geom_bytes / tris;
    r->geom_noshade_bytes_per_tri = (geom_bytes - shading_bytes) / tris;
    r->image_mb = 4.0 * n_words / (1024.0 * 1024.0);
    r->sah = st->triangles ? st->bottom_sah / st->triangles : 0;
}

static int validate_image(const mi_builder *b, char *err, size_t errlen)
{
    uint32_t n_words;
    const uint32_t *w = mi_words(b, &n_words);
    char why[400];
    if (mi_validate(w, n_words, why, sizeof why) == 0)
        return 0;
    snprintf(err, errlen, "the image is invalid: %s", why);
    return -1;
}

/* Section 1 in a child process (run_child): r->ok, or r->err says why not. */
static void bench_ours(const void *ctx, void *result)
{
    const scene *s = ctx;
    ours_result *r = result;
    double bottom[REPS], top[REPS], first = 0;
    while (run_again(r->runs, first)) {
        mi_builder *b = build_image(s, NULL, &r->big_memory, r->err, sizeof r->err);
        if (!b)
            return;
        if (r->runs == 0 && validate_image(b, r->err, sizeof r->err) != 0) {
            mi_free(b);
            return;
        }
        const mi_stats *st = mi_get_stats(b);
        bottom[r->runs] = 1e3 * (st->bottom_build_seconds + st->transform_seconds);
        top[r->runs] = 1e3 * st->top_build_seconds;
        if (r->runs == 0)
            first = 1e-3 * (bottom[0] + top[0]);
        ours_describe(s, b, r);
        mi_free(b);
        r->runs++;
    }
    r->bottom_ms = median(bottom, r->runs);
    r->top_ms = median(top, r->runs);
    r->ok = 1;
}

/* The alternative for the SAH column: every bottom-level tree built with the exact sweep
 * (render --kd-bins 0); *ms: the time of that build's trees (one run, all CPUs). */
static double exact_sah(const scene *s, double *ms)
{
    char err[512];
    mi_params p;
    mi_params_default(&p);
    p.bottom.bins = 0;
    int big = 0;
    mi_builder *b = build_image(s, &p, &big, err, sizeof err);
    if (!b)
        fail("exact trees: %s", err);
    const mi_stats *st = mi_get_stats(b);
    const double sah = st->triangles ? st->bottom_sah / st->triangles : 0;
    *ms = 1e3 * (st->bottom_build_seconds + st->transform_seconds);
    mi_free(b);
    return sah;
}

/* ---- Embree ------------------------------------------------------------------------------- */

typedef struct {
    int ok, runs;
    char err[200];
    double bottom_ms, top_ms;         /* medians */
    int64_t bvh_bytes, buffer_bytes;  /* first run */
} embree_result;

typedef struct {
    double bottom_s, top_s;
    int64_t bvh_bytes, buffer_bytes;
} embree_run;

static int64_t embree_allocated; /* net bytes allocated by the device (child process only) */
static char embree_error[200];

static bool embree_monitor(void *user, ssize_t bytes, bool post)
{
    (void)user;
    (void)post;
    embree_allocated += bytes;
    return true;
}

static void embree_on_error(void *user, enum RTCError code, const char *str)
{
    (void)user;
    if (!embree_error[0])
        snprintf(embree_error, sizeof embree_error, "Embree error %d: %s", (int)code, str ? str : "?");
}

/* Builds the two-level structure once; 0 or -1 (embree_error says why). */
static int embree_build_once(RTCDevice dev, const scene *s, enum RTCBuildQuality q, embree_run *run)
{
    RTCScene *meshes = calloc((size_t)s->n_meshes + 1, sizeof *meshes);
    if (!meshes) {
        snprintf(embree_error, sizeof embree_error, "out of memory");
        return -1;
    }
    const int64_t before = embree_allocated;
    for (uint32_t i = 0; i < s->n_meshes; i++)
        meshes[i] = embree_mesh_scene(dev, &s->meshes[i], q);
    RTCScene top = embree_top_scene(dev, s, meshes, q);
    const int64_t buffers = embree_allocated;
    run->bottom_s = 0;
    for (uint32_t i = 0; i < s->n_meshes; i++) {
        if (!meshes[i])
            continue;
        const double t0 = now();
        rtcCommitScene(meshes[i]);
        run->bottom_s += now() - t0;
    }
    const double t0 = now();
    rtcCommitScene(top);
    run->top_s = now() - t0;
    run->buffer_bytes = buffers - before;
    run->bvh_bytes = embree_allocated - buffers;
    rtcReleaseScene(top);
    for (uint32_t i = 0; i < s->n_meshes; i++)
        if (meshes[i])
            rtcReleaseScene(meshes[i]);
    free(meshes);
    return embree_error[0] ? -1 : 0;
}

typedef struct {
    const scene *s;
    enum RTCBuildQuality quality;
    int threads;
} embree_job;

/* Section 2 in a child process (run_child): r->ok, or r->err says why not. */
static void embree_measure(const void *ctx, void *result)
{
    const embree_job *j = ctx;
    const scene *s = j->s;
    const enum RTCBuildQuality q = j->quality;
    embree_result *r = result;
    char config[32];
    snprintf(config, sizeof config, "threads=%d", j->threads);
    RTCDevice dev = rtcNewDevice(config);
    if (!dev) {
        snprintf(r->err, sizeof r->err, "rtcNewDevice failed (error %d)", (int)rtcGetDeviceError(NULL));
        return;
    }
    rtcSetDeviceErrorFunction(dev, embree_on_error, NULL);
    rtcSetDeviceMemoryMonitorFunction(dev, embree_monitor, NULL);
    double bottom[REPS], top[REPS], first = 0;
    while (run_again(r->runs, first)) {
        embree_run run;
        const double t0 = now();
        if (embree_build_once(dev, s, q, &run) != 0)
            break;
        if (r->runs == 0) {
            first = now() - t0;
            r->bvh_bytes = run.bvh_bytes;
            r->buffer_bytes = run.buffer_bytes;
        }
        bottom[r->runs] = 1e3 * run.bottom_s;
        top[r->runs] = 1e3 * run.top_s;
        r->runs++;
    }
    rtcReleaseDevice(dev);
    if (embree_error[0]) {
        snprintf(r->err, sizeof r->err, "%s", embree_error);
        return;
    }
    r->bottom_ms = median(bottom, r->runs);
    r->top_ms = median(top, r->runs);
    r->ok = 1;
}

/* ---- section 1 + 2: one scene ------------------------------------------------------------- */

enum { EMB_MEDIUM, EMB_HIGH, EMB_COUNT };
static const enum RTCBuildQuality emb_quality[EMB_COUNT] = { RTC_BUILD_QUALITY_MEDIUM, RTC_BUILD_QUALITY_HIGH };
static const char *const emb_names[EMB_COUNT] = { "medium", "high" };

typedef struct {
    char name[64];
    ours_result ours[CPU_CONFIGS];
    embree_result emb[CPU_CONFIGS][EMB_COUNT];
    double exact_sah, exact_ms; /* the exact sweep throughout (exact_sah()) */
} scene_result;

/* Our build and Embree's on c CPUs. */
static void bench_config(const char *name, const scene *s, int c, scene_result *r)
{
    char err[512];
    if (run_child(cpus_of(c), bench_ours, s, &r->ours[c], sizeof r->ours[c], err, sizeof err) != 0)
        fail("%s: %s", name, err);
    if (!r->ours[c].ok)
        fail("%s: mi_build: %s", name, r->ours[c].err);
    progress(" %d CPU: ours %.1f ms", cpus_of(c), r->ours[c].bottom_ms + r->ours[c].top_ms);
    for (int q = 0; q < EMB_COUNT; q++) {
        const embree_job job = { s, emb_quality[q], cpus_of(c) };
        embree_result *e = &r->emb[c][q];
        if (run_child(cpus_of(c), embree_measure, &job, e, sizeof *e, err, sizeof err) != 0)
            fail("%s: Embree: %s", name, err);
        if (!e->ok)
            fail("%s: Embree: %s", name, e->err);
        progress(", Embree %s %.1f ms", emb_names[q], e->bottom_ms + e->top_ms);
    }
}

static void bench_scene(const char *dir, const char *name, scene_result *r)
{
    char err[512];
    scene s;
    memset(r, 0, sizeof *r);
    snprintf(r->name, sizeof r->name, "%s", name);
    if (load_scene(dir, name, &s, err, sizeof err) != 0)
        fail("%s: %s", name, err);
    progress("bench-build: %s ...", name);
    for (int c = 0; c < CPU_CONFIGS; c++)
        bench_config(name, &s, c, r);
    r->exact_sah = exact_sah(&s, &r->exact_ms);
    progress(", exact %.1f ms done\n", r->exact_ms);
    scene_free(&s);
}

/* ---- section 3: top-level rebuilds -------------------------------------------------------- */

typedef struct {
    const char *name;
    uint32_t boxes, nodes, depth;
    double median_ms, min_ms, refs_per_box;
} top_result;

static aabb box_bounds(const void *user, uint32_t i) { return ((const aabb *)user)[i]; }

static void bench_top(const char *name, const aabb *boxes, uint32_t n, top_result *r)
{
    mi_params mp;
    mi_params_default(&mp);
    const kd_source src = { n, boxes, box_bounds, NULL, NULL };
    double t[TOP_REPS];
    memset(r, 0, sizeof *r);
    r->name = name;
    r->boxes = n;
    for (int i = 0; i < TOP_REPS; i++) {
        kd_tree tree;
        const double t0 = now();
        if (kd_build(&src, &mp.top, &tree) != 0)
            fail("top level over %s: out of memory", name);
        t[i] = 1e3 * (now() - t0);
        r->nodes = tree.n_nodes;
        r->depth = tree.stats.depth;
        r->refs_per_box = n ? (double)tree.stats.references / n : 0;
        kd_free(&tree);
    }
    r->median_ms = median(t, TOP_REPS); /* sorts t */
    r->min_ms = t[0];
    progress("bench-build: top level over %s (%u boxes) %.3f ms done\n", name, n, r->median_ms);
}

/* Bounds of the referenced vertices of a mesh (empty mesh: a zero box). */
static aabb mesh_bounds(const scene_mesh *m)
{
    aabb b = { { 0, 0, 0 }, { 0, 0, 0 } };
    for (uint32_t i = 0; i < 3 * m->n_triangles; i++) {
        const float *p = &m->positions[3 * (size_t)m->indices[i]];
        for (int k = 0; k < 3; k++) {
            b.lo[k] = i ? fmin(b.lo[k], p[k]) : p[k];
            b.hi[k] = i ? fmax(b.hi[k], p[k]) : p[k];
        }
    }
    return b;
}

/* World boxes of the scene's instances (the 8 transformed corners of the object box). */
static aabb *instance_boxes(const scene *s)
{
    aabb *mb = malloc(((size_t)s->n_meshes + 1) * sizeof *mb), *out = malloc(((size_t)s->n_instances + 1) * sizeof *out);
    if (!mb || !out)
        fail("out of memory");
    for (uint32_t i = 0; i < s->n_meshes; i++)
        mb[i] = mesh_bounds(&s->meshes[i]);
    for (uint32_t i = 0; i < s->n_instances; i++) {
        const aabb *ob = &mb[s->instances[i].mesh];
        for (int c = 0; c < 8; c++) {
            const double p[3] = { c & 1 ? ob->hi[0] : ob->lo[0], c & 2 ? ob->hi[1] : ob->lo[1], c & 4 ? ob->hi[2] : ob->lo[2] };
            double q[3];
            affine_apply_point(&s->instances[i].world, p, q);
            for (int k = 0; k < 3; k++) {
                out[i].lo[k] = c ? fmin(out[i].lo[k], q[k]) : q[k];
                out[i].hi[k] = c ? fmax(out[i].hi[k], q[k]) : q[k];
            }
        }
    }
    free(mb);
    return out;
}

/* n boxes with centres uniform in a 1000 x 100 x 1000 field and log-uniform sizes 0.5 .. 20. */
static aabb *random_boxes(uint32_t n)
{
    aabb *out = malloc((size_t)n * sizeof *out);
    if (!out)
        fail("out of memory");
    uint64_t x = 0x9E3779B97F4A7C15ull;
    const double field[3] = { 1000, 100, 1000 };
    for (uint32_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            double u[2];
            for (int j = 0; j < 2; j++) {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                u[j] = (double)(x >> 11) / 9007199254740992.0;
            }
            const double c = field[k] * u[0], h = 0.25 * exp(log(40.0) * u[1]);
            out[i].lo[k] = c - h;
            out[i].hi[k] = c + h;
        }
    return out;
}

/* ---- section 3: per-frame updates --------------------------------------------------------- */

typedef struct {
    char name[64];
    int big_memory;
    uint32_t instances, rebuilt;
    double eval_ms, update_ms, top_ms, host_ms; /* medians over the frames (host: evaluate + update) */
    double upload_median, upload_max, upload_first;
} frame_result;

static void bench_frames(const char *dir, const char *name, frame_result *r)
{
    char err[512];
    scene s;
    double ev[FRAMES], up[FRAMES], top[FRAMES], bytes[FRAMES], host[FRAMES];
    memset(r, 0, sizeof *r);
    snprintf(r->name, sizeof r->name, "%s", name);
    if (load_scene(dir, name, &s, err, sizeof err) != 0)
        fail("%s: %s", name, err);
    progress("bench-build: frames of %s ...", name);
    mi_builder *b = build_image(&s, NULL, &r->big_memory, err, sizeof err);
    if (!b)
        fail("%s: mi_build: %s", name, err);
    r->upload_first = (double)mi_get_stats(b)->frame_upload_bytes;
    for (int f = 0; f < FRAMES; f++) {
        const double t0 = now();
        if (scene_evaluate(&s, (f + 1) / FPS, 1) != 0)
            fail("%s: out of memory in scene_evaluate", name);
        const double t1 = now();
        if (mi_update(b, &s, err, sizeof err) != 0)
            fail("%s: mi_update: %s", name, err);
        const mi_stats *st = mi_get_stats(b);
        ev[f] = 1e3 * (t1 - t0);
        up[f] = 1e3 * (now() - t1);
        host[f] = ev[f] + up[f];
        top[f] = 1e3 * st->top_build_seconds;
        bytes[f] = (double)st->frame_upload_bytes;
        r->upload_max = fmax(r->upload_max, bytes[f]);
        r->rebuilt += st->rebuilt_objects;
        r->instances = st->instances;
    }
    r->eval_ms = median(ev, FRAMES);
    r->update_ms = median(up, FRAMES);
    r->top_ms = median(top, FRAMES);
    r->host_ms = median(host, FRAMES);
    r->upload_median = median(bytes, FRAMES);
    mi_free(b);
    scene_free(&s);
    progress(" %.3f ms/frame done\n", r->update_ms);
}

/* ---- section 4: loading and building the 500k-triangle scene ------------------------------ */

typedef struct {
    int runs, have_command;
    char command[4200];
    uint64_t triangles;
    double command_s;             /* wall time of the command (median) */
    double load_s, build_s, trees_s; /* in this process (medians): load + evaluate, mi_build, its trees */
} load_result;

/* Wall time of running argv with its output discarded; fails the bench if it does not exit 0. */
static double run_command(char *const argv[])
{
    fflush(NULL);
    const double t0 = now();
    const pid_t pid = fork();
    if (pid < 0)
        fail("fork: %s", strerror(errno));
    if (pid == 0) {
        if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr))
            _exit(127);
        execv(argv[0], argv);
        _exit(127);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    const double t = now() - t0;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        fail("%s %s %s: exit status 0x%x", argv[0], argv[1], argv[2], (unsigned)status);
    return t;
}

/* The load and build of `saarcor info` in this process, once: load_s, build_s, trees_s, and the
 * scene's triangles into r. */
static void load_and_build_once(const char *dir, load_result *r, double *load_s, double *build_s, double *trees_s)
{
    char err[512];
    scene s;
    const double t0 = now();
    if (load_scene(dir, load_scene_name, &s, err, sizeof err) != 0)
        fail("%s: %s", load_scene_name, err);
    const double t1 = now();
    int big = 0; /* as scene_opts_build: the default device memory first, then a larger one */
    mi_builder *b = build_image(&s, NULL, &big, err, sizeof err);
    if (!b)
        fail("%s: mi_build: %s", load_scene_name, err);
    *load_s = t1 - t0;
    *build_s = now() - t1;
    const mi_stats *st = mi_get_stats(b);
    *trees_s = st->transform_seconds + st->bottom_build_seconds + st->top_build_seconds;
    r->triangles = unique_triangles(&s);
    mi_free(b);
    scene_free(&s);
}

static void bench_load(const char *dir, const char *saarcor, load_result *r)
{
    double cmd[REPS], load[REPS], build[REPS], trees[REPS];
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, load_scene_name);
    char *argv[] = { (char *)saarcor, "info", path, NULL };
    memset(r, 0, sizeof *r);
    r->have_command = saarcor != NULL;
    const size_t src = strlen(SAARCOR_SRC_DIR "/"); /* make runs the command from the source tree */
    const char *shown = strncmp(path, SAARCOR_SRC_DIR "/", src) == 0 ? path + src : path;
    snprintf(r->command, sizeof r->command, "%s info %s", saarcor ? saarcor : "saarcor", shown);
    progress("bench-build: loading and building %s ...", load_scene_name);
    for (; r->runs < REPS; r->runs++) {
        cmd[r->runs] = r->have_command ? run_command(argv) : 0;
        load_and_build_once(dir, r, &load[r->runs], &build[r->runs], &trees[r->runs]);
    }
    r->command_s = median(cmd, REPS);
    r->load_s = median(load, REPS);
    r->build_s = median(build, REPS);
    r->trees_s = median(trees, REPS);
    progress(" %.2f s done\n", r->have_command ? r->command_s : r->load_s + r->build_s);
}

/* ---- report ------------------------------------------------------------------------------- */

typedef struct {
    scene_result *scenes;
    int n_scenes;
    top_result top[2];
    int n_top;
    frame_result *frames;
    int n_frames;
    load_result load;
    int have_gltf;
    const char *gltf_dir;
    double load_avg[2]; /* 1-minute load average at the start and the end of the run (-1: unknown) */
} report;

static double per_tri(int64_t bytes, uint64_t tris) { return tris ? (double)bytes / (double)tris : 0; }

static void md_scenes(FILE *f, const report *rp)
{
    fprintf(f, "## Our build (mi_build, default parameters, %d CPUs)\n\n"
               "| scene | unique tris | instanced tris | objects | instances | degenerate | bottom ms | top ms | "
               "nodes/tri | leaves/tri | refs/tri | geometry B/tri | excl. shading B/tri | image MB | SAH | "
               "exact SAH | SAH change | exact bottom ms | runs |\n|---|---:|---:|---:|---:|---:|---:|---:|"
               "---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n", cpus_all);
    for (int i = 0; i < rp->n_scenes; i++) {
        const scene_result *r = &rp->scenes[i];
        const ours_result *o = &r->ours[CPU_ALL];
        const double change = r->exact_sah > 0 ? 100 * (o->sah / r->exact_sah - 1) : 0;
        fprintf(f, "| %s | %llu | %llu | %u | %u | %u | %.2f | %.3f | %.2f | %.2f | %.2f | %.1f | %.1f | %.2f%s | "
                   "%.3f | %.3f | %+.2f%% | %.2f | %d |\n",
                r->name, (unsigned long long)o->unique_tris, (unsigned long long)o->instanced_tris,
                o->objects, o->instances, o->degenerate, o->bottom_ms, o->top_ms, o->nodes_per_tri, o->leaves_per_tri,
                o->refs_per_tri, o->geom_bytes_per_tri, o->geom_noshade_bytes_per_tri, o->image_mb,
                o->big_memory ? " (1 GB)" : "", o->sah, r->exact_sah, change, r->exact_ms, o->runs);
    }
}

static void md_embree(FILE *f, const report *rp)
{
    fprintf(f, "\n## Against Embree 3 (same CPUs for both; medium = binned SAH, high = spatial splits)\n\n"
               "| scene | CPUs | bottom ms: ours | Embree medium | Embree high | ours / medium | top ms: ours | "
               "Embree medium | Embree high | B/tri: ours geometry | ours excl. shading | Embree BVH medium | "
               "Embree BVH high | Embree buffers | runs ours/med/high |\n"
               "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (int i = 0; i < rp->n_scenes; i++)
        for (int c = 0; c < CPU_CONFIGS; c++) {
            const scene_result *r = &rp->scenes[i];
            const ours_result *o = &r->ours[c];
            const embree_result *m = &r->emb[c][EMB_MEDIUM], *h = &r->emb[c][EMB_HIGH];
            const uint64_t t = o->unique_tris;
            fprintf(f, "| %s | %d | %.2f | %.2f | %.2f | %.1f | %.3f | %.3f | %.3f | %.1f | %.1f | %.1f | %.1f | "
                       "%.1f | %d/%d/%d |\n", r->name, cpus_of(c), o->bottom_ms, m->bottom_ms, h->bottom_ms,
                    m->bottom_ms > 0 ? o->bottom_ms / m->bottom_ms : 0, o->top_ms, m->top_ms, h->top_ms,
                    o->geom_bytes_per_tri, o->geom_noshade_bytes_per_tri, per_tri(m->bvh_bytes, t),
                    per_tri(h->bvh_bytes, t), per_tri(m->buffer_bytes, t), o->runs, m->runs, h->runs);
        }
}

static void md_top(FILE *f, const report *rp)
{
    fprintf(f, "\n## Top-level rebuild (kd_build, binned SAH, %d rebuilds)\n\n"
               "| boxes from | boxes | median ms | min ms | nodes | depth | refs/box |\n"
               "|---|---:|---:|---:|---:|---:|---:|\n", TOP_REPS);
    for (int i = 0; i < rp->n_top; i++) {
        const top_result *t = &rp->top[i];
        fprintf(f, "| %s | %u | %.3f | %.3f | %u | %u | %.2f |\n", t->name, t->boxes, t->median_ms, t->min_ms, t->nodes,
                t->depth, t->refs_per_box);
    }
}

static void md_frames(FILE *f, const report *rp)
{
    fprintf(f, "\n## Per-frame update (scene_evaluate + mi_update, %d frames at %.0f fps, medians)\n\n"
               "| scene | instances | scene_evaluate ms | mi_update ms | of which top level ms | host ms/frame | "
               "upload KB/frame | max KB/frame | first image KB | objects rebuilt |\n"
               "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n", FRAMES, FPS);
    for (int i = 0; i < rp->n_frames; i++) {
        const frame_result *r = &rp->frames[i];
        fprintf(f, "| %s | %u | %.3f | %.3f | %.3f | %.3f | %.1f | %.1f | %.1f%s | %u |\n", r->name, r->instances,
                r->eval_ms, r->update_ms, r->top_ms, r->host_ms, r->upload_median / 1024, r->upload_max / 1024, r->upload_first / 1024,
                r->big_memory ? " (1 GB)" : "", r->rebuilt);
    }
}

static void md_load(FILE *f, const report *rp)
{
    const load_result *l = &rp->load;
    fprintf(f, "\n## Loading and building a 500k-triangle scene (target: at most %.1f s)\n\n"
               "| scene | triangles | command | command wall s | in process: load s | mi_build s | of which trees s | "
               "runs |\n|---|---:|---|---:|---:|---:|---:|---:|\n", LOAD_TARGET_SECONDS);
    fprintf(f, "| %s | %llu | `%s` | ", load_scene_name, (unsigned long long)l->triangles, l->command);
    if (l->have_command)
        fprintf(f, "%.3f", l->command_s);
    else
        fprintf(f, "(no --saarcor)");
    fprintf(f, " | %.3f | %.3f | %.3f | %d |\n", l->load_s, l->build_s, l->trees_s, l->runs);
}

static void write_markdown(const char *path, const report *rp)
{
    FILE *f = fopen(path, "w");
    if (!f)
        fail("cannot write %s: %s", path, strerror(errno));
    fprintf(f, "# Scene build benchmark\n\n"
               "Each scene is loaded (glTF) or generated (seed 1, default size), evaluated at t = 0 and built into the "
               "device memory image by `mi_build` with the default parameters (SAH kd-trees with perfect splits per "
               "object, binned above 48 triangles in meshes of 32768 or more, "
               "binned top level over the instances, fp24-snapped planes); a scene that does not fit the "
               "24 MB image is built with 1 GB and marked. *Bottom* = triangle transformations + bottom-level trees, "
               "*top* = top-level tree (mi_stats). *SAH* is the bottom-level trees' SAH cost under the builder's own "
               "cost model (kd_stats.sah_cost, relative to each root box), averaged over the objects weighted by their "
               "triangles; *exact* is the same build with `--kd-bins 0` (the exact sweep throughout, where the default "
               "bins the nodes over 48 triangles of meshes from 32768 triangles on; one run on all CPUs): its SAH, the "
               "default trees' SAH change against it and its bottom time. Per-triangle figures divide by the unique "
               "triangles (before "
               "dropping degenerate ones); *geometry B/tri* is the STATIC+DYNAMIC_GEOMETRY regions (nodes, lists, "
               "12-word triangle transformations, 16-word shading records), *excl. shading* leaves out the shading "
               "records. The anchor is Embree 3 building the same two levels (one scene per mesh, one instance per "
               "scene instance): *bottom* = sum of the per-mesh `rtcCommitScene`, *top* = the instance scene's commit, "
               "*BVH B/tri* = bytes the device allocated during the commits (memory monitor), *buffers* = its "
               "vertex/index buffers. Both sides get the same CPUs: each measurement runs in a forked child process "
               "bound to 1 CPU, and again to all %d (our builders use the CPUs they may run on; Embree gets a "
               "`threads=N` device for N CPUs); *ours / medium* divides the bottom times. The table of our build shows "
               "the run on all CPUs. Times are medians of %d runs (1 run where a run took more than %.0f s; see "
               "*runs*); "
               "the machine is noisy. Top-level rebuilds are medians of %d `kd_build` calls; per-frame updates are "
               "medians over %d frames. The last table times `saarcor info` on the 500k-triangle scene as a command "
               "(process start-up included) and, in this process, its load (glTF + evaluation) and its `mi_build` "
               "(default device memory first, then a larger one, as `info` does).\n\n",
            cpus_all, REPS, SLOW_SECONDS, TOP_REPS, FRAMES);
    fprintf(f, "Load average (1 minute) at the start and the end of the run: %.2f and %.2f on %d CPUs (a "
               "load above the CPU count means other work shared the CPUs and stretched both sides' times).\n\n",
            rp->load_avg[0], rp->load_avg[1], cpus_all);
    if (!rp->have_gltf)
        fprintf(f, "The glTF scenes were skipped: %s not found.\n\n", rp->gltf_dir);
    md_scenes(f, rp);
    md_embree(f, rp);
    md_top(f, rp);
    md_frames(f, rp);
    if (rp->have_gltf)
        md_load(f, rp);
    if (fclose(f) != 0)
        fail("cannot write %s", path);
}

/* One CPU configuration of a scene: {"cpus": N, "ours": {...}, "embree": {...}}. */
static void json_config(FILE *f, const scene_result *r, int c)
{
    const ours_result *o = &r->ours[c];
    fprintf(f, "{\"cpus\": %d, \"ours\": {\"runs\": %d, \"memory_1gb\": %s, \"bottom_ms\": %.4f, \"top_ms\": %.4f, "
               "\"nodes_per_tri\": %.4f, \"leaves_per_tri\": %.4f, \"refs_per_tri\": %.4f, \"bottom_depth\": %u, "
               "\"top_nodes\": %u, \"geometry_bytes_per_tri\": %.2f, \"geometry_bytes_per_tri_excl_shading\": %.2f, "
               "\"image_mb\": %.3f, \"bottom_sah\": %.6f},\n       \"embree\": {", cpus_of(c), o->runs,
            o->big_memory ? "true" : "false", o->bottom_ms, o->top_ms, o->nodes_per_tri, o->leaves_per_tri,
            o->refs_per_tri, o->bottom_depth, o->top_nodes, o->geom_bytes_per_tri, o->geom_noshade_bytes_per_tri,
            o->image_mb, o->sah);
    for (int q = 0; q < EMB_COUNT; q++) {
        const embree_result *e = &r->emb[c][q];
        fprintf(f, "%s\"%s\": {\"runs\": %d, \"bottom_ms\": %.4f, \"top_ms\": %.4f, \"bvh_bytes\": %lld, "
                   "\"buffer_bytes\": %lld}", q ? ", " : "", emb_names[q], e->runs, e->bottom_ms, e->top_ms,
                (long long)e->bvh_bytes, (long long)e->buffer_bytes);
    }
    fprintf(f, "}}");
}

static void json_scene(FILE *f, const scene_result *r, int last)
{
    const ours_result *o = &r->ours[CPU_ALL];
    fprintf(f, "    {\"name\": \"%s\", \"unique_triangles\": %llu, \"instanced_triangles\": %llu, \"objects\": %u, "
               "\"instances\": %u, \"degenerate_triangles\": %u,\n", r->name, (unsigned long long)o->unique_tris,
            (unsigned long long)o->instanced_tris, o->objects, o->instances, o->degenerate);
    fprintf(f, "     \"exact\": {\"bottom_sah\": %.6f, \"bottom_ms\": %.4f},\n     \"configs\": [",
            r->exact_sah, r->exact_ms);
    for (int c = 0; c < CPU_CONFIGS; c++) {
        fprintf(f, c ? ",\n      " : "");
        json_config(f, r, c);
    }
    fprintf(f, "]}%s\n", last ? "" : ",");
}

static void write_json(const char *path, const report *rp)
{
    FILE *f = fopen(path, "w");
    if (!f)
        fail("cannot write %s: %s", path, strerror(errno));
    fprintf(f, "{\n  \"cpus\": [%d, %d], \"runs\": %d, \"slow_seconds\": %.1f, \"gltf_scenes\": %s, "
               "\"load_average\": [%.2f, %.2f],\n  \"scenes\": [\n", cpus_of(CPU_ONE), cpus_of(CPU_ALL), REPS,
            SLOW_SECONDS, rp->have_gltf ? "true" : "false", rp->load_avg[0], rp->load_avg[1]);
    for (int i = 0; i < rp->n_scenes; i++)
        json_scene(f, &rp->scenes[i], i + 1 == rp->n_scenes);
    fprintf(f, "  ],\n  \"top_level\": [\n");
    for (int i = 0; i < rp->n_top; i++) {
        const top_result *t = &rp->top[i];
        fprintf(f, "    {\"boxes_from\": \"%s\", \"boxes\": %u, \"rebuilds\": %d, \"median_ms\": %.4f, \"min_ms\": %.4f, "
                   "\"nodes\": %u, \"depth\": %u, \"refs_per_box\": %.4f}%s\n", t->name, t->boxes, TOP_REPS, t->median_ms,
                t->min_ms, t->nodes, t->depth, t->refs_per_box, i + 1 == rp->n_top ? "" : ",");
    }
    fprintf(f, "  ],\n  \"frames\": [\n");
    for (int i = 0; i < rp->n_frames; i++) {
        const frame_result *r = &rp->frames[i];
        fprintf(f, "    {\"name\": \"%s\", \"frames\": %d, \"instances\": %u, \"evaluate_ms\": %.4f, \"update_ms\": %.4f, "
                   "\"top_ms\": %.4f, \"host_ms\": %.4f, \"upload_bytes_median\": %.0f, \"upload_bytes_max\": %.0f, "
                   "\"first_image_bytes\": %.0f, \"memory_1gb\": %s, \"objects_rebuilt\": %u}%s\n", r->name, FRAMES,
                r->instances, r->eval_ms, r->update_ms, r->top_ms, r->host_ms, r->upload_median, r->upload_max, r->upload_first,
                r->big_memory ? "true" : "false", r->rebuilt, i + 1 == rp->n_frames ? "" : ",");
    }
    const load_result *l = &rp->load;
    char command_s[32] = "null";
    if (l->have_command)
        snprintf(command_s, sizeof command_s, "%.4f", l->command_s);
    fprintf(f, "  ]");
    if (rp->have_gltf)
        fprintf(f, ",\n  \"load\": {\"scene\": \"%s\", \"triangles\": %llu, \"command\": \"%s\", \"command_s\": %s, "
                   "\"load_s\": %.4f, \"build_s\": %.4f, \"trees_s\": %.4f, \"runs\": %d, \"target_s\": %.1f}",
                load_scene_name, (unsigned long long)l->triangles, l->command, command_s, l->load_s, l->build_s,
                l->trees_s, l->runs, LOAD_TARGET_SECONDS);
    fprintf(f, "\n}\n");
    if (fclose(f) != 0)
        fail("cannot write %s", path);
}

/* ---- main --------------------------------------------------------------------------------- */

static void usage(void)
{
    fprintf(stderr, "usage: bench_build --out DIR [--scenes GLTF_DIR] [--saarcor PROGRAM]\n");
    exit(2);
}

/* Section 3a/3b: the plants scene's instance boxes and random boxes. */
static int bench_top_levels(const char *dir, top_result *top)
{
    char err[512];
    scene s;
    if (load_scene(dir, "plants", &s, err, sizeof err) != 0)
        fail("plants: %s", err);
    aabb *boxes = instance_boxes(&s);
    bench_top("plants instances", boxes, s.n_instances, &top[0]);
    free(boxes);
    scene_free(&s);
    boxes = random_boxes(RANDOM_BOXES);
    bench_top("random boxes", boxes, RANDOM_BOXES, &top[1]);
    free(boxes);
    return 2;
}

/* The 1-minute load average (-1 if unknown): other work on the machine stretches every time here,
 * ours and Embree's alike, so the report states it. */
static double load_average(void)
{
    double l;
    return getloadavg(&l, 1) == 1 ? l : -1.0;
}

int main(int argc, char **argv)
{
    const char *out = NULL, *dir = SAARCOR_SRC_DIR "/../shared/scenes", *saarcor = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else if (!strcmp(argv[i], "--saarcor") && i + 1 < argc)
            saarcor = argv[++i];
        else if (!strcmp(argv[i], "--scenes") && i + 1 < argc)
            dir = argv[++i];
        else
            usage();
    }
    if (!out)
        usage();
    mkdir(out, 0777);
    cpu_set_t cpus;
    if (sched_getaffinity(0, sizeof cpus, &cpus) == 0 && CPU_COUNT(&cpus) > 0)
        cpus_all = CPU_COUNT(&cpus);

    struct stat st;
    report rp = { 0 };
    rp.gltf_dir = dir;
    rp.have_gltf = stat(dir, &st) == 0 && S_ISDIR(st.st_mode);
    if (!rp.have_gltf)
        fprintf(stderr, "bench-build: %s not found, skipping the glTF scenes\n", dir);
    rp.scenes = calloc(COUNT(gltf_files) + COUNT(generator_names), sizeof *rp.scenes);
    rp.frames = calloc(COUNT(frame_scenes), sizeof *rp.frames);
    if (!rp.scenes || !rp.frames)
        fail("out of memory");

    const double t0 = now();
    rp.load_avg[0] = load_average();
    for (size_t i = 0; rp.have_gltf && i < COUNT(gltf_files); i++)
        bench_scene(dir, gltf_files[i], &rp.scenes[rp.n_scenes++]);
    for (size_t i = 0; i < COUNT(generator_names); i++)
        bench_scene(dir, generator_names[i], &rp.scenes[rp.n_scenes++]);
    rp.n_top = bench_top_levels(dir, rp.top);
    for (size_t i = 0; i < COUNT(frame_scenes); i++)
        if (rp.have_gltf || !is_gltf(frame_scenes[i]))
            bench_frames(dir, frame_scenes[i], &rp.frames[rp.n_frames++]);
    if (rp.have_gltf)
        bench_load(dir, saarcor, &rp.load);
    rp.load_avg[1] = load_average();

    char path[4096];
    snprintf(path, sizeof path, "%s/build.md", out);
    write_markdown(path, &rp);
    snprintf(path, sizeof path, "%s/build.json", out);
    write_json(path, &rp);
    fprintf(stderr, "bench-build: wrote %s/build.md and build.json in %.0f s\n", out, now() - t0);
    free(rp.scenes);
    free(rp.frames);
    return 0;
}
