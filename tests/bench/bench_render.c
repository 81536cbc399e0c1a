/*
 * make bench-render: primary rays at 1024x768 traced through the hardware units in functional
 * mode (RGS + trace_packet, one thread, the simulator's speed, not the hardware's), against
 * Embree 3 tracing the same rays (rtcIntersect1, one thread, the same two-level instancing) as
 * the anchor; plus the full render with shading and shadow rays, and the agreement of the
 * primary hits (hit/miss, relative t difference) between the fp24 units and Embree's binary32.
 * Writes build/bench/render.md and render.json. The memory image is given 1 GB so every scene
 * fits (the 24 MB default is the prototype's; see saarcor info for the real sizes).
 */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "embree_scene.h"
#include "f24_fast.h"
#include "memimage.h"
#include "rgs.h"
#include "scenes.h"
#include "shading_model.h"
#include "trace.h"

enum { W = 1024, H = 768 };

typedef struct {
    char name[64];
    int ok;
    double ours_trace, ours_render, ours_full, embree_trace;
    double hit_agree, t_close;
    uint64_t tris;
} result;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Our primary rays, one thread: t per pixel (INFINITY for a miss) and the trace time. */
static double trace_ours(const uint32_t *mem, float *t_out)
{
    trace_counters c;
    memset(&c, 0, sizeof c);
    const double t0 = now();
    for (uint32_t y = 0; y < H; y += 2)
        for (uint32_t x = 0; x < W; x += 2) {
            ray_packet rp;
            hit_record h[TRACE_PACKET];
            rgs_primary(mem, x, y, &rp);
            trace_packet(mem, &rp, h, &c);
            for (int i = 0; i < TRACE_PACKET; i++)
                t_out[(y + (uint32_t)(i >> 1)) * W + x + (uint32_t)(i & 1)] =
                    h[i].instance == TRACE_NO_HIT ? INFINITY : (float)f24_fast_decode(h[i].t);
        }
    return now() - t0;
}

/* The whole frame through the units with the given ray depth (0: primary rays and shadows). */
static double render_ours(const uint32_t *mem, uint32_t max_depth)
{
    rgs_counters c;
    memset(&c, 0, sizeof c);
    const rgs_config cfg = { max_depth, 1, TRAV_STACK };
    uint32_t sink = 0;
    const double t0 = now();
    for (uint32_t y = 0; y < H; y += 2)
        for (uint32_t x = 0; x < W; x += 2) {
            uint32_t rgb[TRACE_PACKET];
            rgs_render_block(mem, &cfg, x, y, rgb, NULL, &c);
            sink ^= rgb[0];
        }
    return now() - t0 + 0.0 * sink;
}

/* Embree on the same (fp24) rays; fills result agreement figures. */
static int trace_embree(const scene *s, const uint32_t *mem, const float *ours, result *r)
{
    RTCDevice dev = rtcNewDevice("threads=1");
    if (!dev)
        return -1;
    RTCScene *meshes = calloc(s->n_meshes + 1, sizeof *meshes);
    for (uint32_t i = 0; i < s->n_meshes; i++) {
        meshes[i] = embree_mesh_scene(dev, &s->meshes[i], RTC_BUILD_QUALITY_MEDIUM);
        if (meshes[i])
            rtcCommitScene(meshes[i]);
    }
    RTCScene top = embree_top_scene(dev, s, meshes, RTC_BUILD_QUALITY_MEDIUM);
    rtcCommitScene(top);
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    uint64_t agree = 0, both = 0, close = 0;
    const double t0 = now();
    for (uint32_t y = 0; y < H; y += 2)
        for (uint32_t x = 0; x < W; x += 2) {
            ray_packet rp;
            rgs_primary(mem, x, y, &rp);
            for (int i = 0; i < TRACE_PACKET; i++) {
                struct RTCRayHit rh;
                memset(&rh, 0, sizeof rh);
                rh.ray.org_x = (float)f24_fast_decode(rp.o[i].x);
                rh.ray.org_y = (float)f24_fast_decode(rp.o[i].y);
                rh.ray.org_z = (float)f24_fast_decode(rp.o[i].z);
                rh.ray.dir_x = (float)f24_fast_decode(rp.d[i].x);
                rh.ray.dir_y = (float)f24_fast_decode(rp.d[i].y);
                rh.ray.dir_z = (float)f24_fast_decode(rp.d[i].z);
                rh.ray.tfar = INFINITY;
                rh.ray.mask = 0xFFFFFFFFu;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(top, &ctx, &rh);
                const float ot = ours[(y + (uint32_t)(i >> 1)) * W + x + (uint32_t)(i & 1)];
                const int ehit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID, ohit = isfinite(ot);
                agree += ehit == ohit;
                if (ehit && ohit) {
                    both++;
                    close += fabsf(ot - rh.ray.tfar) <= 1e-3f * rh.ray.tfar;
                }
            }
        }
    r->embree_trace = now() - t0;
    r->hit_agree = (double)agree / ((double)W * H);
    r->t_close = both ? (double)close / (double)both : 1.0;
    rtcReleaseScene(top);
    for (uint32_t i = 0; i < s->n_meshes; i++)
        if (meshes[i])
            rtcReleaseScene(meshes[i]);
    free(meshes);
    rtcReleaseDevice(dev);
    return 0;
}

static void bench_one(const char *name, result *r)
{
    snprintf(r->name, sizeof r->name, "%s", name);
    scene s;
    char err[512];
    fprintf(stderr, "bench-render: %s ...", name);
    if (bench_scene_load(name, &s, err, sizeof err) != 0 || scene_evaluate(&s, 0, 0) != 0) {
        fprintf(stderr, " skipped (%s)\n", err);
        return;
    }
    mi_params p;
    mi_params_default(&p);
    p.width = W;
    p.height = H;
    p.memory_bytes = 1ull << 30;
    mi_builder *b = mi_build(&s, &p, err, sizeof err);
    float *t = malloc((size_t)W * H * sizeof *t);
    if (b && t) {
        uint32_t n;
        const uint32_t *mem = mi_words(b, &n);
        for (uint32_t i = 0; i < s.n_instances; i++)
            r->tris += s.meshes[s.instances[i].mesh].n_triangles;
        r->ours_trace = trace_ours(mem, t);
        r->ours_render = render_ours(mem, 0);
        r->ours_full = render_ours(mem, SHADE_DEFAULT_DEPTH);
        r->ok = trace_embree(&s, mem, t, r) == 0;
    }
    fprintf(stderr, " %s\n", r->ok ? "done" : "failed");
    free(t);
    mi_free(b);
    scene_free(&s);
}

int main(int argc, char **argv)
{
    const char *out = argc > 2 && !strcmp(argv[1], "--out") ? argv[2] : "build/bench";
    enum { N = BENCH_SCENES };
    result r[N];
    memset(r, 0, sizeof r);
    for (int i = 0; i < N; i++)
        bench_one(bench_scene_names[i], &r[i]);
    char path[512];
    snprintf(path, sizeof path, "%s/render.md", out);
    FILE *md = fopen(path, "w");
    snprintf(path, sizeof path, "%s/render.json", out);
    FILE *js = fopen(path, "w");
    if (!md || !js) {
        fprintf(stderr, "bench_render: error: cannot write to %s\n", out);
        return 3;
    }
    fprintf(md, "# Primary rays at %dx%d: the units (functional simulation) and Embree\n\n"
                "One thread each. *units trace*: RGS primary rays + trace_packet (fp24, functional model of the "
                "traversal, list, transformation and intersection units); *units render*: plus shading with shadow "
                "rays; *full*: plus reflection and transmission rays to depth 3 (docs/shading.md); *Embree*: rtcIntersect1 on the same rays (binary32, two-level instancing, build quality "
                "medium). *hit agreement*: share of pixels where both hit or both miss; *t within 1e-3*: share of "
                "common hits whose distances agree to 1e-3 relative. Single runs on a noisy machine.\n\n"
                "| scene | instanced tris | units trace s | units render s | full s | Embree s | units / Embree | hit agreement | t within 1e-3 |\n"
                "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n", W, H);
    fprintf(js, "{\"width\": %d, \"height\": %d, \"scenes\": [\n", W, H);
    int first = 1;
    for (int i = 0; i < N; i++) {
        if (!r[i].ok)
            continue;
        fprintf(md, "| %s | %llu | %.2f | %.2f | %.2f | %.3f | %.0fx | %.4f%% | %.4f%% |\n", r[i].name,
                (unsigned long long)r[i].tris, r[i].ours_trace, r[i].ours_render, r[i].ours_full, r[i].embree_trace, r[i].ours_trace / r[i].embree_trace,
                100 * r[i].hit_agree, 100 * r[i].t_close);
        fprintf(js, "%s  {\"scene\": \"%s\", \"instanced_triangles\": %llu, \"units_trace_s\": %.4f, \"units_render_s\": %.4f, "
                    "\"units_full_s\": %.4f, \"embree_s\": %.4f, \"hit_agreement\": %.6f, \"t_close\": %.6f}", first ? "" : ",\n", r[i].name,
                (unsigned long long)r[i].tris, r[i].ours_trace, r[i].ours_render, r[i].ours_full, r[i].embree_trace, r[i].hit_agree,
                r[i].t_close);
        first = 0;
    }
    fprintf(js, "\n]}\n");
    fclose(md);
    fclose(js);
    return 0;
}
