/* Our side of the benchmarks' timing: see bench_units.h. */
#include "bench_units.h"

#include <math.h>
#include <string.h>

#include "embree_scene.h"
#include "f24_fast.h"
#include "render.h"

typedef struct {
    const uint32_t *mem;
    const ray_packet *packets;
    uint32_t n_packets;
    float *t;
} trace_job;

static void trace_work(void *ctx, uint32_t part, uint32_t parts)
{
    const trace_job *j = ctx;
    trace_counters c;
    memset(&c, 0, sizeof c);
    uint32_t first, count;
    bench_split(j->n_packets, 1, part, parts, &first, &count);
    for (uint32_t p = first; p < first + count; p++) {
        hit_record h[TRACE_PACKET];
        trace_packet(j->mem, &j->packets[p], h, &c);
        for (uint32_t i = 0; i < TRACE_PACKET; i++)
            j->t[p * TRACE_PACKET + i] = h[i].instance == TRACE_NO_HIT ? INFINITY : (float)f24_fast_decode(h[i].t);
    }
}

double units_trace_time(const uint32_t *mem, const ray_packet *packets, uint32_t n_packets, uint32_t threads, float *t)
{
    trace_job j = { .mem = mem, .packets = packets, .n_packets = n_packets, .t = t };
    return bench_time(trace_work, &j, threads);
}

typedef struct {
    const uint32_t *mem;
    const rgs_config *cfg;
    uint32_t *pixels;
    rgs_counters sum[BENCH_MAX_THREADS];
} frame_job;

/* Part k of n renders its share of the block rows with one render_region thread; one part is
 * the whole image, as the render command asks for it. */
static void frame_work(void *ctx, uint32_t part, uint32_t parts)
{
    frame_job *j = ctx;
    uint32_t w, h, first, count;
    rgs_image_size(j->mem, &w, &h);
    bench_split((h + 1) / 2, 1, part, parts, &first, &count);
    const uint32_t region[4] = { 0, 2 * first, UINT32_MAX, parts == 1 ? UINT32_MAX : 2 * (first + count) };
    render_region(j->mem, j->cfg, 1, region, j->pixels, NULL, NULL, &j->sum[part]);
}

double units_frame_time(const uint32_t *mem, const rgs_config *cfg, uint32_t threads, uint32_t *pixels,
                        rgs_counters *sum)
{
    frame_job j = { .mem = mem, .cfg = cfg, .pixels = pixels };
    const double sec = bench_time(frame_work, &j, threads);
    memset(sum, 0, sizeof *sum);
    for (uint32_t k = 0; k < threads && k < BENCH_MAX_THREADS; k++)
        rgs_counters_add(sum, &j.sum[k]);
    return sec;
}
