/*
 * The functional frame of `saarcor render` (render.h): host threads take the region's block rows
 * one at a time, the next free one as they finish one (so that a thread the machine runs slower
 * takes fewer rows instead of holding up the frame), each 2x2 block runs its whole ray tree
 * (pc_render_block) and writes its own pixels, and the counters are integer sums, so the image
 * and the counters are bit-identical for any thread count and any order. In a file of its
 * own so that make bench-peers times exactly this path beside Embree (tests/bench/bench_peers.c)
 * without linking the command line.
 */
#define _GNU_SOURCE
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "interrupt.h"
#include "render.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct {
    const uint32_t *mem;
    const rgs_config *cfg;
    uint32_t x0, y0, x1, y1, stride; /* the region rendered (even x0, y0), the image's width */
    uint32_t thread, threads;
    uint32_t *pixels;
    rgs_counters counters;  /* this thread's, written when it is done */
    atomic_uint *next_row;  /* the next block row to take (0: the region's first) */
    atomic_uint *rows_done; /* block rows finished by all threads, for the progress line */
    hit_record *hits;       /* per pixel primary hit, for --aov (NULL: not kept) */
    pixel_cost *costs;      /* per pixel cost, for --aov and --heatmap (NULL: not kept) */
} render_job;

/* Progress on stderr (thread 0, a terminal, at most every half second). */
static void progress(const render_job *j, double *last)
{
    const double t = now();
    if (j->thread != 0 || !isatty(2) || t - *last < 0.5)
        return;
    *last = t;
    const unsigned rows = (j->y1 - j->y0 + 1) / 2;
    fprintf(stderr, "\rrender: %3u%%", 100u * atomic_load(j->rows_done) / (rows ? rows : 1));
}

static void *render_rows(void *arg)
{
    render_job *j = arg;
    double last = now();
    /* counted on this thread's stack: the jobs' counters share cache lines with each other's */
    rgs_counters counters = { { 0 }, { 0 }, 0 };
    for (;;) {
        const uint32_t y = j->y0 + 2 * atomic_fetch_add(j->next_row, 1u);
        if (y >= j->y1 || interrupt_signal())
            break;
        for (uint32_t x = j->x0; x < j->x1; x += 2) {
            hit_record h[TRACE_PACKET];
            uint32_t rgb[TRACE_PACKET];
            pixel_cost cost[TRACE_PACKET];
            pc_render_block(j->mem, j->cfg, x, y, rgb, h, &counters, j->costs ? cost : NULL);
            if (j->costs)
                pc_store_block(j->costs, cost, x, y, j->stride, j->y1);
            for (int i = 0; i < TRACE_PACKET; i++) {
                const uint32_t px = x + (uint32_t)(i & 1), py = y + (uint32_t)(i >> 1);
                if (px >= j->x1 || py >= j->y1)
                    continue;
                j->pixels[(size_t)py * j->stride + px] = rgb[i];
                if (j->hits)
                    j->hits[(size_t)py * j->stride + px] = h[i];
            }
        }
        atomic_fetch_add(j->rows_done, 1u);
        progress(j, &last);
    }
    j->counters = counters;
    if (j->thread == 0 && isatty(2))
        fprintf(stderr, "\r%*s\r", 14, ""); /* clear the progress line */
    return NULL;
}

int render_region(const uint32_t *mem, const rgs_config *cfg, uint32_t threads, const uint32_t region[4],
                  uint32_t *pixels, hit_record *hits, pixel_cost *costs, rgs_counters *sum)
{
    uint32_t w, h;
    rgs_image_size(mem, &w, &h);
    const uint32_t x1 = region[2] < w ? region[2] : w, y1 = region[3] < h ? region[3] : h;
    atomic_uint next_row = 0, rows_done = 0;
    render_job *jobs = calloc(threads, sizeof *jobs);
    pthread_t *tid = calloc(threads, sizeof *tid);
    if (!jobs || !tid) {
        free(jobs);
        free(tid);
        return -1;
    }
    for (uint32_t t = 0; t < threads; t++) {
        jobs[t] = (render_job){ mem, cfg, region[0], region[1], x1, y1, w, t, threads, pixels, { { 0 }, { 0 }, 0 }, &next_row, &rows_done, hits, costs };
        if (t > 0 && pthread_create(&tid[t], NULL, render_rows, &jobs[t]) != 0)
            jobs[t].threads = 0; /* could not start: the others take its rows */
    }
    render_rows(&jobs[0]);
    memset(sum, 0, sizeof *sum);
    for (uint32_t t = 0; t < threads; t++) {
        if (t > 0 && jobs[t].threads)
            pthread_join(tid[t], NULL);
        rgs_counters_add(sum, &jobs[t].counters);
    }
    free(jobs);
    free(tid);
    return atomic_load(&rows_done) < (y1 - region[1] + 1) / 2 ? 1 : 0; /* rows left out: stopped by a signal */
}
