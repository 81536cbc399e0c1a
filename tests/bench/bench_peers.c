/*
 * make bench-peers (first part): the same primary rays (512x384, the RGS's fp24 rays) traced by
 * Embree 3 single rays (rtcIntersect1) and 4/8/16-wide packets (rtcIntersect4/8/16), on 1 and 2
 * host threads, and by our units in functional mode (trace_packet) on 1 and 2 host threads;
 * Embree's hit/miss is cross-checked against ours. Writes OUT/peers_rays.json (one object per
 * row) for tests/bench/bench_peers.py, which adds the cycle model and writes the table.
 * Packets are filled from 2x2 pixel blocks in row order (4: one block, 8: two, 16: four).
 */
#define _GNU_SOURCE
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "embree_scene.h"
#include "f24_fast.h"
#include "memimage.h"
#include "rgs.h"
#include "scenes.h"
#include "trace.h"

enum { W = 512, H = 384, N_RAYS = W * H, MAX_N = 16 };

typedef struct {
    float o[3], d[3];
} fray;

typedef struct {
    const fray *rays;
    const ray_packet *packets;
    RTCScene scene;
    const uint32_t *mem;
    uint32_t first, count; /* rays */
    int width;             /* 1, 4, 8, 16 for Embree; 0 for our units */
    uint8_t *hit;          /* per ray */
} job;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Embree's SOA packet layout (rtcore_ray.h): 12 ray fields of N words, then the hit's
 * Ng_x Ng_y Ng_z u v primID geomID instID, N words each. */
static float *ray_field(float *p, int n, int field, int i) { return &p[field * n + i]; }
static unsigned *hit_field(float *p, int n, int field, int i) { return (unsigned *)&p[(12 + field) * n + i]; }

static void embree_packet(const job *j, uint32_t first, int n)
{
    _Alignas(64) float buf[20 * MAX_N];
    _Alignas(64) int valid[MAX_N];
    for (int i = 0; i < n; i++) {
        const fray *r = &j->rays[first + (uint32_t)i];
        for (int k = 0; k < 3; k++) {
            *ray_field(buf, n, k, i) = r->o[k];
            *ray_field(buf, n, 4 + k, i) = r->d[k];
        }
        *ray_field(buf, n, 3, i) = 0;         /* tnear */
        *ray_field(buf, n, 7, i) = 0;         /* time */
        *ray_field(buf, n, 8, i) = INFINITY;  /* tfar */
        *(unsigned *)ray_field(buf, n, 9, i) = 0xFFFFFFFFu;
        *(unsigned *)ray_field(buf, n, 10, i) = 0;
        *(unsigned *)ray_field(buf, n, 11, i) = 0;
        *hit_field(buf, n, 6, i) = RTC_INVALID_GEOMETRY_ID;
        *hit_field(buf, n, 7, i) = RTC_INVALID_GEOMETRY_ID;
        valid[i] = -1;
    }
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    if (n == 4)
        rtcIntersect4(valid, j->scene, &ctx, (struct RTCRayHit4 *)buf);
    else if (n == 8)
        rtcIntersect8(valid, j->scene, &ctx, (struct RTCRayHit8 *)buf);
    else
        rtcIntersect16(valid, j->scene, &ctx, (struct RTCRayHit16 *)buf);
    for (int i = 0; i < n; i++)
        j->hit[first + (uint32_t)i] = *hit_field(buf, n, 6, i) != RTC_INVALID_GEOMETRY_ID;
}

static void embree_single(const job *j, uint32_t i)
{
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    const fray *r = &j->rays[i];
    rh.ray.org_x = r->o[0], rh.ray.org_y = r->o[1], rh.ray.org_z = r->o[2];
    rh.ray.dir_x = r->d[0], rh.ray.dir_y = r->d[1], rh.ray.dir_z = r->d[2];
    rh.ray.tfar = INFINITY;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rtcIntersect1(j->scene, &ctx, &rh);
    j->hit[i] = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

static void *run_job(void *arg)
{
    const job *j = arg;
    trace_counters c;
    memset(&c, 0, sizeof c);
    for (uint32_t i = j->first; i < j->first + j->count;) {
        if (j->width == 0) {
            hit_record h[TRACE_PACKET];
            trace_packet(j->mem, &j->packets[i / TRACE_PACKET], h, &c);
            for (int k = 0; k < TRACE_PACKET; k++)
                j->hit[i + (uint32_t)k] = h[k].instance != TRACE_NO_HIT;
            i += TRACE_PACKET;
        } else if (j->width == 1) {
            embree_single(j, i++);
        } else {
            embree_packet(j, i, j->width);
            i += (uint32_t)j->width;
        }
    }
    return NULL;
}

/* Runs the work split over `threads` host threads; returns seconds. */
static double timed(job base, int threads)
{
    pthread_t t[2];
    job j[2];
    const uint32_t half = (N_RAYS / 2 / MAX_N) * MAX_N;
    const double t0 = now();
    for (int k = 0; k < threads; k++) {
        j[k] = base;
        j[k].first = threads == 1 ? 0 : k == 0 ? 0 : half;
        j[k].count = threads == 1 ? N_RAYS : k == 0 ? half : N_RAYS - half;
        pthread_create(&t[k], NULL, run_job, &j[k]);
    }
    for (int k = 0; k < threads; k++)
        pthread_join(t[k], NULL);
    return now() - t0;
}

static void bench_scene(const char *name, FILE *json, int *first_row)
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
    fray *rays = malloc(N_RAYS * sizeof *rays);
    ray_packet *packets = malloc(N_RAYS / TRACE_PACKET * sizeof *packets);
    uint8_t *ours = malloc(N_RAYS), *theirs = malloc(N_RAYS);
    if (!b || !rays || !packets || !ours || !theirs) {
        fprintf(stderr, "bench-peers: %s: skipped (%s)\n", name, b ? "out of memory" : err);
        goto done;
    }
    uint32_t nw, n = 0;
    const uint32_t *mem = mi_words(b, &nw);
    for (uint32_t y = 0; y < H; y += 2)
        for (uint32_t x = 0; x < W; x += 2, n += TRACE_PACKET) {
            rgs_primary(mem, x, y, &packets[n / TRACE_PACKET]);
            for (int i = 0; i < TRACE_PACKET; i++)
                for (int k = 0; k < 3; k++) {
                    rays[n + (uint32_t)i].o[k] = (float)f24_fast_decode((&packets[n / TRACE_PACKET].o[i].x)[k]);
                    rays[n + (uint32_t)i].d[k] = (float)f24_fast_decode((&packets[n / TRACE_PACKET].d[i].x)[k]);
                }
        }
    RTCDevice dev = rtcNewDevice("threads=2");
    RTCScene *meshes = calloc(s.n_meshes + 1, sizeof *meshes);
    for (uint32_t i = 0; i < s.n_meshes; i++)
        if ((meshes[i] = embree_mesh_scene(dev, &s.meshes[i], RTC_BUILD_QUALITY_MEDIUM)))
            rtcCommitScene(meshes[i]);
    RTCScene top = embree_top_scene(dev, &s, meshes, RTC_BUILD_QUALITY_MEDIUM);
    rtcCommitScene(top);
    const job base = { rays, packets, top, mem, 0, N_RAYS, 0, ours };
    static const int widths[] = { 0, 1, 4, 8, 16 };
    for (int threads = 1; threads <= 2; threads++)
        for (size_t w = 0; w < sizeof widths / sizeof widths[0]; w++) {
            job j = base;
            j.width = widths[w];
            j.hit = widths[w] ? theirs : ours;
            const double sec = timed(j, threads);
            uint64_t agree = 0;
            for (uint32_t i = 0; i < N_RAYS && widths[w]; i++)
                agree += ours[i] == theirs[i];
            char what[64], agreement[32] = "null";
            snprintf(what, sizeof what, widths[w] == 0 ? "units functional (trace_packet)" : widths[w] == 1 ? "Embree rtcIntersect1" : "Embree rtcIntersect%d", widths[w]);
            if (widths[w])
                snprintf(agreement, sizeof agreement, "%.6f", (double)agree / N_RAYS);
            fprintf(json, "%s  {\"scene\": \"%s\", \"tracer\": \"%s\", \"threads\": %d, \"rays\": %d, \"seconds\": %.6f, "
                          "\"rays_per_second\": %.1f, \"hit_agreement_with_units\": %s}",
                    *first_row ? "" : ",\n", name, what, threads, N_RAYS, sec, N_RAYS / sec, agreement);
            *first_row = 0;
        }
    rtcReleaseScene(top);
    for (uint32_t i = 0; i < s.n_meshes; i++)
        if (meshes[i])
            rtcReleaseScene(meshes[i]);
    free(meshes);
    rtcReleaseDevice(dev);
    fprintf(stderr, "bench-peers: %s done\n", name);
done:
    free(rays), free(packets), free(ours), free(theirs);
    if (b)
        mi_free(b);
    scene_free(&s);
}

int main(int argc, char **argv)
{
    const char *out = argc > 2 && !strcmp(argv[1], "--out") ? argv[2] : "build/bench";
    char path[512];
    snprintf(path, sizeof path, "%s/peers_rays.json", out);
    FILE *json = fopen(path, "w");
    if (!json) {
        fprintf(stderr, "bench-peers: cannot write %s\n", path);
        return 3;
    }
    int first = 1;
    fprintf(json, "[\n");
    for (size_t i = 0; i < BENCH_SCENES; i++)
        bench_scene(bench_scene_names[i], json, &first);
    fprintf(json, "\n]\n");
    return fclose(json) != 0 ? 3 : 0;
}
