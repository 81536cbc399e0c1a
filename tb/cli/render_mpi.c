/* saarcor render --mpi: see render_mpi.h and docs/mpi.md. */
#define _GNU_SOURCE
#include "render_mpi.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"

/* What a worker sends before the pixels of an item. */
typedef struct {
    rgs_counters sum;
    cycle_stats cs;
    double secs;
    frame_host host;      /* frames: what bringing the image to the item's frame cost this board */
    uint64_t moved_bytes; /* frames: memory image bytes this board uploaded for the item (0: it held the frame) */
} item_head;

typedef struct {
    render_opts *ro;
    mi_builder *b;
    scene *s;
    const char *scene_name;
    uint32_t w, h, tiles_x, n_tiles;
    uint32_t *pixels;      /* the whole image: a worker's scratch, the controller's result */
    uint32_t current;      /* frames: the frame the memory image holds */
    frame_host host;       /* frames: what bringing the image to `current` cost */
    frame_result total;    /* one frame: the combined numbers */
    uint64_t *tile_cycles; /* one frame, cycle mode: cycles of each tile on its board */
    int rc;                /* the first failed frame's exit code (frames) */
    uint64_t moved_bytes;  /* frames: sum of the items' moved_bytes */
} mpi_render;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Renders region r of the memory image into m->pixels, from empty caches in cycle mode. */
static int render_part(mpi_render *m, const uint32_t r[4], item_head *hd)
{
    uint32_t n;
    const uint32_t *mem = mi_words(m->b, &n);
    const double t0 = now();
    int rc;
    if (m->ro->cycle) {
        cycle_flush(m->ro->sim); /* the item's cycles must not depend on what this board did before */
        rc = cycle_render_region(m->ro->sim, mem, &m->ro->cfg, r, m->pixels, NULL, &hd->sum, &hd->cs, NULL, NULL);
    } else {
        rc = render_region(mem, &m->ro->cfg, m->ro->threads, r, m->pixels, NULL, NULL, &hd->sum);
    }
    hd->secs = now() - t0;
    return rc;
}

static void tile_region(const mpi_render *m, uint32_t item, uint32_t r[4])
{
    const uint32_t t = m->ro->mpi_tile;
    r[0] = item % m->tiles_x * t;
    r[1] = item / m->tiles_x * t;
    r[2] = r[0] + t < m->w ? r[0] + t : m->w;
    r[3] = r[1] + t < m->h ? r[1] + t : m->h;
}

/* Copies the region's rows between the image and a packed buffer (to_image: unpack). */
static void copy_rows(mpi_render *m, const uint32_t r[4], uint32_t *packed, int to_image)
{
    const uint32_t rw = r[2] - r[0];
    for (uint32_t y = r[1]; y < r[3]; y++) {
        uint32_t *row = m->pixels + (size_t)y * m->w + r[0], *p = packed + (size_t)(y - r[1]) * rw;
        memcpy(to_image ? row : p, to_image ? p : row, rw * sizeof *row);
    }
}

static long tile_work(void *ctx, uint32_t item, void *result)
{
    mpi_render *m = ctx;
    uint32_t r[4];
    item_head hd = { .moved_bytes = 0 };
    tile_region(m, item, r);
    if (render_part(m, r, &hd) != 0) {
        cli_error("render", "--mpi: out of memory rendering tile %u", item);
        return -1;
    }
    memcpy(result, &hd, sizeof hd);
    copy_rows(m, r, (uint32_t *)((char *)result + sizeof hd), 0);
    return (long)(sizeof hd + (size_t)(r[2] - r[0]) * (r[3] - r[1]) * sizeof(uint32_t));
}

static int tile_take(void *ctx, uint32_t item, const void *result, size_t size, int rank)
{
    mpi_render *m = ctx;
    uint32_t r[4];
    item_head hd;
    tile_region(m, item, r);
    if (item >= m->n_tiles || size != sizeof hd + (size_t)(r[2] - r[0]) * (r[3] - r[1]) * sizeof(uint32_t)) {
        cli_error("render", "--mpi: rank %d sent %zu bytes for tile %u: not the size of that tile", rank, size, item);
        return -1;
    }
    memcpy(&hd, result, sizeof hd);
    copy_rows(m, r, (uint32_t *)((char *)result + sizeof hd), 1); /* (result is aligned: malloc + 4 + header) */
    rgs_counters_add(&m->total.sum, &hd.sum);
    cycle_stats_add(&m->total.cs, &hd.cs);
    m->tile_cycles[item] = hd.cs.cycles;
    return 0;
}

/* The frame's cycles on `boards` boards: tiles handed out in order, each to the board free first
 * in simulated time (lowest number on ties), as the controller would in hardware. */
static void schedule(mpi_render *m, uint32_t boards)
{
    uint64_t *free_at = calloc(boards, sizeof *free_at);
    if (!free_at)
        return;
    for (uint32_t i = 0; i < m->n_tiles; i++) {
        uint32_t best = 0;
        for (uint32_t k = 1; k < boards; k++)
            best = free_at[k] < free_at[best] ? k : best;
        free_at[best] += m->tile_cycles[i];
    }
    cycle_stats *cs = &m->total.cs;
    cs->pipe_cycles_min = UINT64_MAX;
    for (uint32_t k = 0; k < boards; k++) {
        cs->cycles = free_at[k] > cs->cycles ? free_at[k] : cs->cycles;
        cs->pipe_cycles_min = free_at[k] < cs->pipe_cycles_min ? free_at[k] : cs->pipe_cycles_min;
    }
    cs->pipe_cycles_max = cs->cycles;
    free(free_at);
}

/* Brings the memory image to frame f (every rank built frame ro->first). */
static int move_to(mpi_render *m, uint32_t f)
{
    char err[512];
    if (f == m->current)
        return 0;
    if (render_advance(m->s, m->b, f, m->ro->fps, &m->host, err, sizeof err) != 0) {
        cli_error("render", "frame %u: cannot update the memory image: %s", f, err);
        return -1;
    }
    m->current = f;
    return 0;
}

static long frame_work(void *ctx, uint32_t item, void *result)
{
    mpi_render *m = ctx;
    const uint32_t f = m->ro->first + item, all[4] = { 0, 0, m->w, m->h };
    item_head hd = { .moved_bytes = 0 };
    const int moved = f != m->current;
    if (move_to(m, f) != 0 || render_validate(m->b) != SAARCOR_EXIT_OK)
        return -1;
    hd.host = m->host;
    hd.moved_bytes = moved ? hd.host.upload_bytes : 0;
    if (render_part(m, all, &hd) != 0) {
        cli_error("render", "--mpi: out of memory rendering frame %u", f);
        return -1;
    }
    memcpy(result, &hd, sizeof hd);
    memcpy((char *)result + sizeof hd, m->pixels, (size_t)m->w * m->h * sizeof(uint32_t));
    return (long)(sizeof hd + (size_t)m->w * m->h * sizeof(uint32_t));
}

/* A whole frame: written as soon as it arrives, in whatever order frames finish. */
static int frame_take(void *ctx, uint32_t item, const void *result, size_t size, int rank)
{
    mpi_render *m = ctx;
    item_head hd;
    if (size != sizeof hd + (size_t)m->w * m->h * sizeof(uint32_t)) {
        cli_error("render", "--mpi: rank %d sent %zu bytes for frame %u: not the size of a frame", rank, size,
                  m->ro->first + item);
        return -1;
    }
    memcpy(&hd, result, sizeof hd);
    m->moved_bytes += hd.moved_bytes;
    memcpy(m->pixels, (const char *)result + sizeof hd, size - sizeof hd);
    const frame_result fr = { .sum = hd.sum, .cs = hd.cs, .secs = hd.secs, .host = hd.host, .boards = 1,
                              .items = 1 };
    const int rc = render_frame_output(m->ro, NULL, NULL, m->ro->first + item, m->scene_name, m->w, m->h, m->pixels,
                                       NULL, &fr);
    if (rc != SAARCOR_EXIT_OK && m->rc == SAARCOR_EXIT_OK)
        m->rc = rc;
    return 0;
}

static void print_sequence_mpi(const saarcor_mpi_report *rep, uint32_t frames, uint64_t image, uint64_t image_total)
{
    printf("mpi: %d ranks (%d worker boards), %u frames, %.1f KB to workers, %.1f KB from workers, %llu messages; "
           "memory image %.1f KB per board, %.1f KB uploaded to the boards (with the per-frame changes); "
           "wall %.3f s, worker time working %.3f s, communicating %.3f s (max %.3f s on one worker)\n",
           rep->ranks, rep->ranks - 1, frames, (double)rep->bytes_to_workers / 1024.0,
           (double)rep->bytes_from_workers / 1024.0, (unsigned long long)rep->messages, (double)image / 1024.0,
           (double)image_total / 1024.0, rep->wall_seconds, rep->work_seconds, rep->comm_seconds,
           rep->comm_seconds_max);
}

int render_mpi(render_opts *ro, saarcor_mpi_run_fn run, mi_builder *b, scene *s, const char *scene_name)
{
    uint32_t n;
    mpi_render m = { .ro = ro, .b = b, .s = s, .scene_name = scene_name, .current = ro->first,
                      .host = render_host(b, ro->build_secs) };
    rgs_image_size(mi_words(b, &n), &m.w, &m.h);
    if (render_validate(b) != SAARCOR_EXIT_OK)
        return SAARCOR_EXIT_INTERNAL;
    m.tiles_x = (m.w + ro->mpi_tile - 1) / ro->mpi_tile;
    m.n_tiles = m.tiles_x * ((m.h + ro->mpi_tile - 1) / ro->mpi_tile);
    const size_t tile_bytes = (size_t)ro->mpi_tile * ro->mpi_tile * sizeof(uint32_t);
    const saarcor_mpi_work w = ro->sequence
        ? (saarcor_mpi_work){ ro->last - ro->first + 1, sizeof(item_head) + (size_t)m.w * m.h * sizeof(uint32_t), &m,
                              frame_work, frame_take }
        : (saarcor_mpi_work){ m.n_tiles, sizeof(item_head) + tile_bytes, &m, tile_work, tile_take };
    m.pixels = calloc((size_t)m.w * m.h, sizeof *m.pixels);
    m.tile_cycles = calloc(m.n_tiles, sizeof *m.tile_cycles);
    if (!m.pixels || !m.tile_cycles) {
        free(m.pixels);
        free(m.tile_cycles);
        cli_error("render", "out of memory");
        return SAARCOR_EXIT_INTERNAL;
    }
    saarcor_mpi_report rep;
    char err[512];
    int rc = SAARCOR_EXIT_OK;
    if (run(SAARCOR_MPI_ABI, &w, &rep, err, sizeof err) != 0) {
        cli_error("render", "--mpi: %s", err);
        rc = SAARCOR_EXIT_USAGE;
    } else if (rep.rank == 0 && ro->sequence) {
        /* every board is loaded with the image of the first frame, then uploads each of its
         * frames' changes (rank 0 never moves its image: its stats are the first frame's build) */
        const uint64_t image = mi_get_stats(b)->frame_upload_bytes, boards = (uint64_t)rep.ranks - 1;
        print_sequence_mpi(&rep, w.n_items, image, boards * image + m.moved_bytes);
        rc = m.rc;
    } else if (rep.rank == 0) {
        schedule(&m, (uint32_t)rep.ranks - 1);
        m.total.secs = rep.wall_seconds;
        m.total.host = render_host(b, ro->build_secs);
        m.total.boards = (uint32_t)rep.ranks - 1;
        m.total.image_bytes_per_board = m.total.host.upload_bytes; /* every board holds the whole image */
        m.total.image_upload_bytes_total = m.total.host.upload_bytes * m.total.boards;
        m.total.items = m.n_tiles;
        m.total.mpi = &rep;
        rc = render_frame_output(ro, b, s, ro->first, scene_name, m.w, m.h, m.pixels, NULL, &m.total);
    }
    free(m.pixels);
    free(m.tile_cycles);
    return rc;
}
