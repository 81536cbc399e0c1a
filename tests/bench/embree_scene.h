/*
 * The Embree harness of the benchmarks: the anchor renderer's scene and how it is traced and
 * timed. bench_render.c and bench_peers.c both measure Embree only through embree_bench_build,
 * bench_primary_rays and embree_time, so "Embree rays/s" and "ours / Embree" mean the same in
 * both reports; bench_build.c uses the scene setup (embree_mesh_scene, embree_top_scene) with
 * its own build qualities and timing.
 *
 * Scene: the same two levels as our memory image: one RTCScene per mesh (one triangle geometry,
 * vertex and index buffers allocated by Embree), and a top scene with one instance geometry per
 * scene instance (its object-to-world matrix, RTC_FORMAT_FLOAT3X4_ROW_MAJOR).
 *
 * Build (embree_bench_build): build quality EMBREE_BENCH_QUALITY = RTC_BUILD_QUALITY_MEDIUM
 * (Embree's default, binned SAH) for every scene and geometry; scene flags EMBREE_BENCH_FLAGS =
 * RTC_SCENE_FLAG_NONE (no DYNAMIC, COMPACT, ROBUST or context filter: Embree's fastest
 * traversal for static scenes). HIGH (spatial splits, the analogue of our perfect splits)
 * traced teapot, bunny and room within 6% of MEDIUM at 512x384, so the choice does not move the
 * ratios. Device "threads=1": the build runs on the calling thread, so no TBB worker exists
 * while we time; device threads only change the build, which these benchmarks do not time
 * (make bench-build does), and tracing always runs on the calling host threads.
 *
 * Rays (bench_primary_rays): the RGS's fp24 primary rays (rgs_primary: 2x2 pixel blocks in row
 * order, 4 rays per block), decoded to binary32 once, before any timing. Ray generation is ours
 * (emulated fp24 on the transformation unit, 13-15 M rays/s here, about the cost of Embree's
 * whole trace), so it is never inside Embree's timed loop: timed there, it roughly halved
 * Embree's rays/s.
 * Each ray: tnear 0, tfar +inf, time 0, mask all ones.
 *
 * Tracing (embree_trace): width 1 is rtcIntersect1 per ray; width 4, 8, 16 is rtcIntersect4/8/16
 * on SOA packets of consecutive rays (one, two or four 2x2 blocks side by side). Timed per ray:
 * filling Embree's ray structure from the binary32 ray, the call, storing the hit distance. One
 * RTCIntersectContext (rtcInitIntersectContext: default flags, incoherent) per range of rays.
 *
 * Timing (bench_time): wall time (CLOCK_MONOTONIC) of the whole work split over 1 or 2 host
 * threads (part 0 on the calling thread), the median of up to BENCH_RUNS runs, with no new run
 * started once the runs took BENCH_BUDGET_S seconds: Embree's fast rows are medians of 5, our
 * slow rows of 1 or 2 runs (the mean of the two). Our side is timed by the same function.
 */
#ifndef SAARCOR_EMBREE_SCENE_H
#define SAARCOR_EMBREE_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include <embree3/rtcore.h>

#include "scene.h"
#include "trace.h"

#define EMBREE_BENCH_QUALITY RTC_BUILD_QUALITY_MEDIUM
#define EMBREE_BENCH_FLAGS RTC_SCENE_FLAG_NONE
#define EMBREE_BENCH_DEVICE "threads=1"
#define EMBREE_MAX_WIDTH 16
#define BENCH_MAX_THREADS 2
#define BENCH_RUNS 5
#define BENCH_BUDGET_S 1.0

/* The above in one line, for the reports. */
#define EMBREE_BENCH_SETUP                                                                                    \
    "Embree 3, two levels (a scene per mesh, an instance per scene instance), build quality medium, "        \
    "scene flags none, device threads=1; rays: the RGS's fp24 primary rays decoded to binary32 before "      \
    "timing; timed: filling the ray structures and the rtcIntersect calls; median of up to 5 runs"

/* One RTCScene holding the mesh's triangles (uncommitted), or NULL for an empty mesh. */
RTCScene embree_mesh_scene(RTCDevice dev, const scene_mesh *m, enum RTCBuildQuality q);

/* Top-level scene with one instance per scene instance (uncommitted). */
RTCScene embree_top_scene(RTCDevice dev, const scene *s, RTCScene *meshes, enum RTCBuildQuality q);

/* The scenes bench-render and bench-peers trace: the generated ones and the shared ones. */
#define BENCH_SCENES 8
extern const char *const bench_scene_names[BENCH_SCENES];

/* Loads a generator name (seed 1) or a file of ../shared/scenes/; 0, or -1 with err. */
int bench_scene_load(const char *name, scene *s, char *err, size_t n);

/* A primary ray in binary32, as Embree gets it. */
typedef struct {
    float o[3], d[3];
} embree_ray;

/* An evaluated scene built for tracing (see the header comment). */
typedef struct {
    RTCDevice dev;
    RTCScene top;     /* committed */
    RTCScene *meshes; /* per scene mesh, NULL for an empty one */
    uint32_t n_meshes;
} embree_bench;

/* Builds s; 0, or -1 with err (nothing to free then). */
int embree_bench_build(embree_bench *e, const scene *s, char *err, size_t n);
void embree_bench_free(embree_bench *e);

/* The RGS's primary rays of the image's camera (w, h even) in 2x2 block order: w * h rays;
 * packets (w * h / 4, may be NULL) gets them in fp24 as the units trace them. */
void bench_primary_rays(const uint32_t *mem, uint32_t w, uint32_t h, ray_packet *packets, embree_ray *rays);

/* Traces rays [first, first + count) at width 1, 4, 8 or 16 (count a multiple of it); t[i] is the
 * hit distance of ray i, INFINITY for a miss. */
void embree_trace(const embree_bench *e, const embree_ray *rays, uint32_t first, uint32_t count, int width, float *t);

/* The work of one timed run: part `part` of `parts` (one per host thread). */
typedef void (*bench_work)(void *ctx, uint32_t part, uint32_t parts);

/* [first, first + count) of part `part` of n items cut into `parts` runs of whole `align`s. */
void bench_split(uint32_t n, uint32_t align, uint32_t part, uint32_t parts, uint32_t *first, uint32_t *count);

/* Seconds of work on `threads` (1 .. BENCH_MAX_THREADS) host threads, median of the runs. */
double bench_time(bench_work work, void *ctx, uint32_t threads);

/* Seconds to trace rays [0, n) at width 1, 4, 8 or 16 on `threads` host threads (bench_time);
 * t as for embree_trace, of the last run. */
double embree_time(const embree_bench *e, const embree_ray *rays, uint32_t n, int width, uint32_t threads, float *t);

#endif
