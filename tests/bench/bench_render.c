/*
 * make bench-render: primary rays at 1024x768 traced through the hardware units in functional
 * mode (RGS + trace_packet, one thread, the simulator's speed, not the hardware's), against
 * Embree 3 tracing the same rays (rtcIntersect1, one thread, the same two-level instancing) as
 * the anchor; plus the full render with shading and shadow rays, and the agreement of the
 * primary hits (hit/miss, relative t difference) between the fp24 units and Embree's binary32.
 * Embree is built, fed and timed by the harness shared with bench-peers (embree_scene.h: build
 * quality medium, scene flags none, the RGS's rays decoded before timing); our side is timed by
 * the same bench_time. *units trace* includes the RGS's ray generation (the device generates its
 * rays; bench-peers reports trace_packet alone too); *units render* and *full* are render_region,
 * the render command's functional frame (bench_units.h).
 * Writes build/bench/render.md and render.json. The memory image is given 1 GB so every scene
 * fits (the 24 MB default is the prototype's; see saarcor info for the real sizes).
 */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_units.h"
#include "embree_scene.h"
#include "f24_fast.h"
#include "memimage.h"
#include "rgs.h"
#include "scenes.h"
#include "shading_model.h"
#include "trace.h"

enum { W = 1024, H = 768, N_RAYS = W * H };

typedef struct {
    char name[64];
    int ok;
    double ours_trace, ours_render, ours_full, embree_trace;
    double hit_agree, t_close;
    uint64_t tris;
} result;

typedef struct {
    const uint32_t *mem;
    float *t; /* per ray in 2x2 block order, as bench_primary_rays orders Embree's */
} rgs_trace_job;

/* Our primary rays: the RGS generates each block's packet, trace_packet traces it. */
static void rgs_trace_work(void *ctx, uint32_t part, uint32_t parts)
{
    const rgs_trace_job *j = ctx;
    trace_counters c;
    memset(&c, 0, sizeof c);
    uint32_t first, count;
    bench_split(N_RAYS / TRACE_PACKET, 1, part, parts, &first, &count);
    for (uint32_t b = first; b < first + count; b++) {
        ray_packet rp;
        hit_record h[TRACE_PACKET];
        rgs_primary(j->mem, 2 * (b % (W / 2)), 2 * (b / (W / 2)), &rp);
        trace_packet(j->mem, &rp, h, &c);
        for (uint32_t i = 0; i < TRACE_PACKET; i++)
            j->t[b * TRACE_PACKET + i] = h[i].instance == TRACE_NO_HIT ? INFINITY : (float)f24_fast_decode(h[i].t);
    }
}

/* Hit/miss agreement and the share of common hits within 1e-3 relative distance. */
static void agreement(const float *ours, const float *theirs, result *r)
{
    uint64_t agree = 0, both = 0, close = 0;
    for (uint32_t i = 0; i < N_RAYS; i++) {
        const int ohit = isfinite(ours[i]), ehit = isfinite(theirs[i]);
        agree += ohit == ehit;
        if (ohit && ehit) {
            both++;
            close += fabsf(ours[i] - theirs[i]) <= 1e-3f * theirs[i];
        }
    }
    r->hit_agree = (double)agree / N_RAYS;
    r->t_close = both ? (double)close / (double)both : 1.0;
}

/* Both sides on one built scene; 0, or -1 with err. */
static int measure(const scene *s, const uint32_t *mem, result *r, char *err, size_t n)
{
    embree_ray *rays = malloc(N_RAYS * sizeof *rays);
    float *ours = malloc(N_RAYS * sizeof *ours), *theirs = malloc(N_RAYS * sizeof *theirs);
    uint32_t *pixels = malloc(N_RAYS * sizeof *pixels);
    embree_bench e;
    int rc = -1;
    if (!rays || !ours || !theirs || !pixels)
        snprintf(err, n, "out of memory");
    else if (embree_bench_build(&e, s, err, n) == 0) {
        bench_primary_rays(mem, W, H, NULL, rays);
        rgs_trace_job tj = { mem, ours };
        r->ours_trace = bench_time(rgs_trace_work, &tj, 1);
        rgs_counters c;
        r->ours_render = units_frame_time(mem, &(rgs_config){ 0, 1, TRAV_STACK }, 1, pixels, &c);
        r->ours_full = units_frame_time(mem, &(rgs_config){ SHADE_DEFAULT_DEPTH, 1, TRAV_STACK }, 1, pixels, &c);
        r->embree_trace = embree_time(&e, rays, N_RAYS, 1, 1, theirs);
        agreement(ours, theirs, r);
        embree_bench_free(&e);
        rc = 0;
    }
    free(rays), free(ours), free(theirs), free(pixels);
    return rc;
}

static void bench_one(const char *name, result *r)
{
    snprintf(r->name, sizeof r->name, "%s", name);
    scene s;
    char err[512] = "cannot evaluate the scene";
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
    if (b) {
        uint32_t nw;
        for (uint32_t i = 0; i < s.n_instances; i++)
            r->tris += s.meshes[s.instances[i].mesh].n_triangles;
        r->ok = measure(&s, mi_words(b, &nw), r, err, sizeof err) == 0;
    }
    if (r->ok)
        fprintf(stderr, " done\n");
    else
        fprintf(stderr, " failed (%s)\n", err);
    mi_free(b);
    scene_free(&s);
}

static void write_md(FILE *md, const result *r, int n)
{
    fprintf(md, "# Primary rays at %dx%d: the units (functional simulation) and Embree\n\n"
                "One thread each, the same RGS primary rays. *units trace*: RGS ray generation + trace_packet (fp24, "
                "functional model of the traversal, list, transformation and intersection units); *units render*: "
                "the render command's functional frame (render_region) with shading and shadow rays; *full*: plus "
                "reflection and transmission rays to depth 3 (docs/shading.md); *Embree*: rtcIntersect1 on the "
                "same rays (" EMBREE_BENCH_SETUP "; docs/architecture.md). *hit agreement*: share of pixels where "
                "both hit or both miss; *t within 1e-3*: share of common hits whose distances agree to 1e-3 "
                "relative. Every time is the median of up to 5 runs (fewer when the runs took 1 s) on a noisy "
                "machine.\n\n"
                "| scene | instanced tris | units trace s | units render s | full s | Embree s | Embree M rays/s | "
                "units / Embree | hit agreement | t within 1e-3 |\n"
                "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n", W, H);
    for (int i = 0; i < n; i++)
        if (r[i].ok)
            fprintf(md, "| %s | %llu | %.2f | %.2f | %.2f | %.3f | %.2f | %.0fx | %.4f%% | %.4f%% |\n", r[i].name,
                    (unsigned long long)r[i].tris, r[i].ours_trace, r[i].ours_render, r[i].ours_full,
                    r[i].embree_trace, N_RAYS / r[i].embree_trace / 1e6, r[i].ours_trace / r[i].embree_trace,
                    100 * r[i].hit_agree, 100 * r[i].t_close);
}

static void write_json(FILE *js, const result *r, int n)
{
    fprintf(js, "{\"width\": %d, \"height\": %d, \"embree_setup\": \"%s\", \"scenes\": [\n", W, H, EMBREE_BENCH_SETUP);
    const char *sep = "";
    for (int i = 0; i < n; i++) {
        if (!r[i].ok)
            continue;
        fprintf(js, "%s  {\"scene\": \"%s\", \"instanced_triangles\": %llu, \"units_trace_s\": %.4f, "
                    "\"units_render_s\": %.4f, \"units_full_s\": %.4f, \"embree_s\": %.4f, "
                    "\"embree_rays_per_second\": %.1f, \"hit_agreement\": %.6f, \"t_close\": %.6f}",
                sep, r[i].name, (unsigned long long)r[i].tris, r[i].ours_trace, r[i].ours_render, r[i].ours_full,
                r[i].embree_trace, N_RAYS / r[i].embree_trace, r[i].hit_agree, r[i].t_close);
        sep = ",\n";
    }
    fprintf(js, "\n]}\n");
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
    write_md(md, r, N);
    write_json(js, r, N);
    return fclose(md) != 0 || fclose(js) != 0 ? 3 : 0;
}
