/* The Embree harness of the benchmarks: see embree_scene.h. */
#define _GNU_SOURCE
#include "embree_scene.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "f24_fast.h"
#include "rgs.h"
#include "scenes.h"

#ifndef SAARCOR_SRC_DIR
#define SAARCOR_SRC_DIR "."
#endif

const char *const bench_scene_names[BENCH_SCENES] = { "cornell", "room", "plants", "terrain", "teapot.glb", "bunny.glb",
                                                      "CesiumMilkTruck.glb", "gallery_ccby_503k.glb" };

int bench_scene_load(const char *name, scene *s, char *err, size_t n)
{
    if (!strchr(name, '.')) {
        const scene_gen_params gp = { 1, 0 };
        return scene_generator_find(name)->build(s, &gp, err, n);
    }
    char path[512];
    snprintf(path, sizeof path, SAARCOR_SRC_DIR "/../shared/scenes/%s", name);
    return scene_load_gltf(path, s, err, n);
}

/* One RTCScene holding the mesh's triangles (uncommitted), or NULL for an empty mesh. */
RTCScene embree_mesh_scene(RTCDevice dev, const scene_mesh *m, enum RTCBuildQuality q)
{
    if (m->n_triangles == 0 || m->n_vertices == 0)
        return NULL;
    RTCScene sc = rtcNewScene(dev);
    rtcSetSceneFlags(sc, EMBREE_BENCH_FLAGS);
    rtcSetSceneBuildQuality(sc, q);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, q);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m->n_vertices);
    unsigned *ix = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m->n_triangles);
    if (v && ix) {
        memcpy(v, m->positions, 3 * sizeof(float) * m->n_vertices);
        memcpy(ix, m->indices, 3 * sizeof(unsigned) * m->n_triangles);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(sc, g);
    rtcReleaseGeometry(g);
    return sc;
}

/* Top-level scene with one instance per scene instance (uncommitted). */
RTCScene embree_top_scene(RTCDevice dev, const scene *s, RTCScene *meshes, enum RTCBuildQuality q)
{
    RTCScene top = rtcNewScene(dev);
    rtcSetSceneFlags(top, EMBREE_BENCH_FLAGS);
    rtcSetSceneBuildQuality(top, q);
    for (uint32_t i = 0; i < s->n_instances; i++) {
        const scene_instance *in = &s->instances[i];
        if (!meshes[in->mesh])
            continue;
        float xf[12];
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 4; c++)
                xf[4 * r + c] = (float)in->world.m[r][c];
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(g, meshes[in->mesh]);
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xf);
        rtcCommitGeometry(g);
        rtcAttachGeometry(top, g);
        rtcReleaseGeometry(g);
    }
    return top;
}

/* ---- the harness (embree_scene.h) ------------------------------------------------------------ */

void embree_bench_free(embree_bench *e)
{
    if (e->top)
        rtcReleaseScene(e->top);
    for (uint32_t i = 0; e->meshes && i < e->n_meshes; i++)
        if (e->meshes[i])
            rtcReleaseScene(e->meshes[i]);
    free(e->meshes);
    if (e->dev)
        rtcReleaseDevice(e->dev);
    memset(e, 0, sizeof *e);
}

int embree_bench_build(embree_bench *e, const scene *s, char *err, size_t n)
{
    memset(e, 0, sizeof *e);
    e->dev = rtcNewDevice(EMBREE_BENCH_DEVICE);
    e->meshes = calloc(s->n_meshes + 1, sizeof *e->meshes);
    if (!e->dev || !e->meshes) {
        snprintf(err, n, e->dev ? "out of memory" : "rtcNewDevice failed (error %d)", (int)rtcGetDeviceError(NULL));
        embree_bench_free(e);
        return -1;
    }
    e->n_meshes = s->n_meshes;
    for (uint32_t i = 0; i < s->n_meshes; i++)
        if ((e->meshes[i] = embree_mesh_scene(e->dev, &s->meshes[i], EMBREE_BENCH_QUALITY)))
            rtcCommitScene(e->meshes[i]);
    e->top = embree_top_scene(e->dev, s, e->meshes, EMBREE_BENCH_QUALITY);
    rtcCommitScene(e->top);
    const enum RTCError code = rtcGetDeviceError(e->dev);
    if (code != RTC_ERROR_NONE) {
        snprintf(err, n, "Embree build failed (error %d)", (int)code);
        embree_bench_free(e);
        return -1;
    }
    return 0;
}

void bench_primary_rays(const uint32_t *mem, uint32_t w, uint32_t h, ray_packet *packets, embree_ray *rays)
{
    uint32_t n = 0;
    for (uint32_t y = 0; y < h; y += 2)
        for (uint32_t x = 0; x < w; x += 2, n += TRACE_PACKET) {
            ray_packet rp;
            rgs_primary(mem, x, y, &rp);
            for (uint32_t i = 0; i < TRACE_PACKET; i++)
                for (int k = 0; k < 3; k++) {
                    rays[n + i].o[k] = (float)f24_fast_decode((&rp.o[i].x)[k]);
                    rays[n + i].d[k] = (float)f24_fast_decode((&rp.d[i].x)[k]);
                }
            if (packets)
                packets[n / TRACE_PACKET] = rp;
        }
}

static void trace_single(RTCScene top, struct RTCIntersectContext *ctx, const embree_ray *r, float *t)
{
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = r->o[0], rh.ray.org_y = r->o[1], rh.ray.org_z = r->o[2];
    rh.ray.dir_x = r->d[0], rh.ray.dir_y = r->d[1], rh.ray.dir_z = r->d[2];
    rh.ray.tfar = INFINITY;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(top, ctx, &rh);
    *t = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh.ray.tfar : INFINITY;
}

/* Embree's SOA packet layout (rtcore_ray.h): 12 ray fields of n words (org xyz, tnear, dir xyz,
 * time, tfar, mask, id, flags), then the hit's Ng xyz, u, v, primID, geomID, instID. */
enum { RAY_TNEAR = 3, RAY_TIME = 7, RAY_TFAR = 8, RAY_MASK = 9, RAY_ID = 10, RAY_FLAGS = 11, HIT_GEOM = 12 + 6,
       HIT_INST = 12 + 7, SOA_FIELDS = 20 };

static float *soa(float *p, int n, int field, int i) { return &p[field * n + i]; }
static unsigned *soa_u(float *p, int n, int field, int i) { return (unsigned *)soa(p, n, field, i); }

static void trace_packet_n(RTCScene top, struct RTCIntersectContext *ctx, const embree_ray *r, int n, float *t)
{
    /* every lane active; Embree wants the mask aligned to the packet's size */
    static _Alignas(64) const int valid[EMBREE_MAX_WIDTH] = { -1, -1, -1, -1, -1, -1, -1, -1,
                                                              -1, -1, -1, -1, -1, -1, -1, -1 };
    _Alignas(64) float buf[SOA_FIELDS * EMBREE_MAX_WIDTH];
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) {
            *soa(buf, n, k, i) = r[i].o[k];
            *soa(buf, n, 4 + k, i) = r[i].d[k];
        }
        *soa(buf, n, RAY_TNEAR, i) = 0;
        *soa(buf, n, RAY_TIME, i) = 0;
        *soa(buf, n, RAY_TFAR, i) = INFINITY;
        *soa_u(buf, n, RAY_MASK, i) = 0xFFFFFFFFu;
        *soa_u(buf, n, RAY_ID, i) = 0;
        *soa_u(buf, n, RAY_FLAGS, i) = 0;
        *soa_u(buf, n, HIT_GEOM, i) = *soa_u(buf, n, HIT_INST, i) = RTC_INVALID_GEOMETRY_ID;
    }
    if (n == 4)
        rtcIntersect4(valid, top, ctx, (struct RTCRayHit4 *)buf);
    else if (n == 8)
        rtcIntersect8(valid, top, ctx, (struct RTCRayHit8 *)buf);
    else
        rtcIntersect16(valid, top, ctx, (struct RTCRayHit16 *)buf);
    for (int i = 0; i < n; i++)
        t[i] = *soa_u(buf, n, HIT_GEOM, i) != RTC_INVALID_GEOMETRY_ID ? *soa(buf, n, RAY_TFAR, i) : INFINITY;
}

void embree_trace(const embree_bench *e, const embree_ray *rays, uint32_t first, uint32_t count, int width, float *t)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (uint32_t i = first; i < first + count; i += (uint32_t)width)
        if (width == 1)
            trace_single(e->top, &ctx, &rays[i], &t[i]);
        else
            trace_packet_n(e->top, &ctx, &rays[i], width, &t[i]);
}

/* ---- timing ---------------------------------------------------------------------------------- */

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void bench_split(uint32_t n, uint32_t align, uint32_t part, uint32_t parts, uint32_t *first, uint32_t *count)
{
    const uint64_t units = n / align;
    const uint32_t begin = (uint32_t)(units * part / parts) * align;
    const uint32_t end = part + 1 == parts ? n : (uint32_t)(units * (part + 1) / parts) * align;
    *first = begin;
    *count = end - begin;
}

typedef struct {
    bench_work work;
    void *ctx;
    uint32_t part, parts;
} bench_part;

static void *run_part(void *arg)
{
    const bench_part *p = arg;
    p->work(p->ctx, p->part, p->parts);
    return NULL;
}

/* One run: parts 1.. on new threads, part 0 here (as render_region does). */
static double time_once(bench_work work, void *ctx, uint32_t threads)
{
    pthread_t tid[BENCH_MAX_THREADS];
    bench_part p[BENCH_MAX_THREADS];
    int started[BENCH_MAX_THREADS] = { 0 };
    const double t0 = now();
    for (uint32_t k = 0; k < threads; k++) {
        p[k] = (bench_part){ work, ctx, k, threads };
        if (k > 0)
            started[k] = pthread_create(&tid[k], NULL, run_part, &p[k]) == 0;
    }
    run_part(&p[0]);
    for (uint32_t k = 1; k < threads; k++)
        if (started[k])
            pthread_join(tid[k], NULL);
        else
            run_part(&p[k]); /* no thread: done here, the time shows it */
    return now() - t0;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_time(bench_work work, void *ctx, uint32_t threads)
{
    double runs[BENCH_RUNS], total = 0;
    int n = 0;
    if (threads < 1)
        threads = 1;
    if (threads > BENCH_MAX_THREADS)
        threads = BENCH_MAX_THREADS;
    while (n < BENCH_RUNS && (n == 0 || total < BENCH_BUDGET_S)) {
        runs[n] = time_once(work, ctx, threads);
        total += runs[n++];
    }
    qsort(runs, (size_t)n, sizeof runs[0], cmp_double);
    return n % 2 ? runs[n / 2] : 0.5 * (runs[n / 2 - 1] + runs[n / 2]);
}

typedef struct {
    const embree_bench *e;
    const embree_ray *rays;
    uint32_t n;
    int width;
    float *t;
} embree_job;

static void embree_work(void *ctx, uint32_t part, uint32_t parts)
{
    const embree_job *j = ctx;
    uint32_t first, count;
    bench_split(j->n, EMBREE_MAX_WIDTH, part, parts, &first, &count);
    embree_trace(j->e, j->rays, first, count, j->width, j->t);
}

double embree_time(const embree_bench *e, const embree_ray *rays, uint32_t n, int width, uint32_t threads, float *t)
{
    embree_job j = { e, rays, n, width, t };
    return bench_time(embree_work, &j, threads);
}
