/*
 * make bench-peers (first part): the same primary rays (512x384, the RGS's fp24 rays) traced by
 * Embree 3 single rays (rtcIntersect1) and 4/8/16-wide packets (rtcIntersect4/8/16), on 1 and 2
 * host threads, and by our units in functional mode, in the same run:
 *   trace only:   trace_packet over the same rays, generated before timing (1 and 2 threads);
 *   with shading: the render command's functional frame (render_region: the RGS's ray
 *                 generation, trace and shading; max depth 0, no shadows; 1 thread), i.e.
 *                 `saarcor render SCENE --width 512 --height 384 --max-depth 0 --no-shadows
 *                 --threads 1` without loading, building and writing the image.
 * Embree is built, fed and timed by the harness shared with bench-render (embree_scene.h), our
 * side by the same bench_time (bench_units.h). Embree's hit/miss is cross-checked against
 * trace_packet's. Writes OUT/peers_rays.json (one object per row) for
 * tests/bench/bench_peers.py, which adds the cycle model and writes the table.
 */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_units.h"
#include "embree_scene.h"
#include "memimage.h"
#include "rgs.h"
#include "scenes.h"
#include "trace.h"

enum { W = 512, H = 384, N_RAYS = W * H };

#define WORK_TRACE "trace only"
#define WORK_SHADING "with shading"

typedef struct {
    FILE *json;
    const char *sep; /* before the next row */
    const char *scene;
} report;

/* One row of peers_rays.json; agreement < 0: none (our own rows). */
static void row(report *rp, const char *tracer, const char *work, int threads, uint64_t rays, double sec,
                double agreement)
{
    char ag[32] = "null";
    if (agreement >= 0)
        snprintf(ag, sizeof ag, "%.6f", agreement);
    fprintf(rp->json, "%s  {\"scene\": \"%s\", \"tracer\": \"%s\", \"work\": \"%s\", \"threads\": %d, \"rays\": %llu, "
                      "\"seconds\": %.6f, \"rays_per_second\": %.1f, \"hit_agreement_with_units\": %s",
            rp->sep, rp->scene, tracer, work, threads, (unsigned long long)rays, sec, (double)rays / sec, ag);
    if (strncmp(tracer, "Embree", 6) == 0)
        fprintf(rp->json, ", \"embree_setup\": \"%s\"", EMBREE_BENCH_SETUP);
    fprintf(rp->json, "}");
    rp->sep = ",\n";
}

static double hit_agreement(const float *ours, const float *theirs)
{
    uint64_t agree = 0;
    for (uint32_t i = 0; i < N_RAYS; i++)
        agree += isfinite(ours[i]) == isfinite(theirs[i]);
    return (double)agree / N_RAYS;
}

/* Our functional frame with shading, as the render command times it (1 host thread). */
static void frame_row(report *rp, const uint32_t *mem, uint32_t *pixels)
{
    const rgs_config cfg = { 0, 0, TRAV_STACK }; /* --max-depth 0 --no-shadows, the default traversal */
    rgs_counters c;
    const double sec = units_frame_time(mem, &cfg, 1, pixels, &c);
    uint64_t rays = 0;
    for (int k = 0; k < RAY_KINDS; k++)
        rays += c.rays[k];
    row(rp, "units functional (RGS frame: ray generation + trace + shading)", WORK_SHADING, 1, rays, sec, -1);
}

/* Every tracer on the scene's rays, 1 then 2 host threads. */
static void rows_of_scene(report *rp, const embree_bench *e, const uint32_t *mem, const ray_packet *packets,
                          const embree_ray *rays, float *ours, float *theirs, uint32_t *pixels)
{
    static const int widths[] = { 1, 4, 8, 16 };
    for (uint32_t threads = 1; threads <= 2; threads++) {
        double sec = units_trace_time(mem, packets, N_RAYS / TRACE_PACKET, threads, ours);
        row(rp, "units functional (trace_packet)", WORK_TRACE, (int)threads, N_RAYS, sec, -1);
        if (threads == 1)
            frame_row(rp, mem, pixels);
        for (size_t w = 0; w < sizeof widths / sizeof widths[0]; w++) {
            char what[64];
            snprintf(what, sizeof what, "Embree rtcIntersect%d", widths[w]);
            sec = embree_time(e, rays, N_RAYS, widths[w], threads, theirs);
            row(rp, what, WORK_TRACE, (int)threads, N_RAYS, sec, hit_agreement(ours, theirs));
        }
    }
}

static void bench_scene(const char *name, report *rp)
{
    scene s;
    char err[512] = "cannot evaluate the scene";
    if (bench_scene_load(name, &s, err, sizeof err) != 0 || scene_evaluate(&s, 0, 0) != 0) {
        fprintf(stderr, "bench-peers: %s: skipped (%s)\n", name, err);
        return;
    }
    mi_params p;
    mi_params_default(&p);
    p.memory_bytes = 1u << 30;
    p.width = W;
    p.height = H;
    mi_builder *b = mi_build(&s, &p, err, sizeof err);
    embree_ray *rays = malloc(N_RAYS * sizeof *rays);
    ray_packet *packets = malloc(N_RAYS / TRACE_PACKET * sizeof *packets);
    float *ours = malloc(N_RAYS * sizeof *ours), *theirs = malloc(N_RAYS * sizeof *theirs);
    uint32_t *pixels = malloc(N_RAYS * sizeof *pixels);
    embree_bench e;
    if (!b || !rays || !packets || !ours || !theirs || !pixels)
        fprintf(stderr, "bench-peers: %s: skipped (%s)\n", name, b ? "out of memory" : err);
    else if (embree_bench_build(&e, &s, err, sizeof err) != 0)
        fprintf(stderr, "bench-peers: %s: skipped (%s)\n", name, err);
    else {
        uint32_t nw;
        const uint32_t *mem = mi_words(b, &nw);
        bench_primary_rays(mem, W, H, packets, rays);
        rp->scene = name;
        rows_of_scene(rp, &e, mem, packets, rays, ours, theirs, pixels);
        embree_bench_free(&e);
        fprintf(stderr, "bench-peers: %s done\n", name);
    }
    free(rays), free(packets), free(ours), free(theirs), free(pixels);
    if (b)
        mi_free(b);
    scene_free(&s);
}

int main(int argc, char **argv)
{
    const char *out = argc > 2 && !strcmp(argv[1], "--out") ? argv[2] : "build/bench";
    char path[512];
    snprintf(path, sizeof path, "%s/peers_rays.json", out);
    report rp = { fopen(path, "w"), "", NULL };
    if (!rp.json) {
        fprintf(stderr, "bench-peers: cannot write %s\n", path);
        return 3;
    }
    fprintf(rp.json, "[\n");
    for (size_t i = 0; i < BENCH_SCENES; i++)
        bench_scene(bench_scene_names[i], &rp);
    fprintf(rp.json, "\n]\n");
    return fclose(rp.json) != 0 ? 3 : 0;
}
