/*
 * saarcor render SCENE: rendering through the hardware units (hls/units). Functional mode
 * (render_region, in render_region.c): every 2x2 pixel block runs its ray tree to completion (the
 * steps of rgs_render_block, through pc_render_block, which also attributes the work to pixels
 * for --aov/--heatmap); host threads take block rows in a fixed interleaved order and write
 * disjoint pixels, so the image is bit-identical for any thread count. Cycle mode (--mode
 * cycle): the same unit steps timed by the DynRTC model of tb/cycle, with the paper-style report.
 * The device reads only the validated memory image.
 * Ctrl-C/SIGTERM (interrupt.h): the threads stop at the next block row (functional) or epoch
 * (cycle), the unfinished frame is dropped, the frames written so far stay (each file is written
 * under a temporary name and renamed when complete) and the exit code is 128 + the signal.
 */
#define _GNU_SOURCE
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "capture.h"
#include "cli.h"
#include "cycle_opts.h"
#include "cycle_trace.h"
#include "f24_fast.h"
#include "heatmap.h"
#include "img.h"
#include "interrupt.h"
#include "mpi_load.h"
#include "proc_mem.h"
#include "render.h"
#include "render_mpi.h"
#include "rgs.h"
#include "scene_opts.h"
#include "shading_model.h"
#include "trace.h"
#include "usage_plot.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int write_png(const char *path, const uint32_t *pixels, uint32_t w, uint32_t h)
{
    img_t img = { (int)w, (int)h, 3, malloc((size_t)w * h * 3 * sizeof(float)) };
    if (!img.pixels)
        return -1;
    for (size_t i = 0; i < (size_t)w * h; i++)
        for (int c = 0; c < 3; c++)
            img.pixels[3 * i + (size_t)c] = (float)(pixels[i] >> (16 - 8 * c) & 0xFF) / 255.0f;
    char err[256];
    const int rc = img_write(path, &img, err, sizeof err);
    if (rc != 0)
        cli_error("render", "%s", err);
    img_free(&img);
    return rc;
}

_Static_assert(RGS_MAX_DEPTH == SHADE_MAX_DEPTH, "the shading model and the RGS unit agree on the deepest level");

static int usage(void)
{
    printf("usage: saarcor render SCENE [-o out.png] [--mode functional|cycle|rtl] [--max-depth D] [--no-shadows]\n"
           "                      [--precision P] [--aov FILE.exr] [--heatmap FILE.png [--heatmap-of NAME]]\n"
           "                      [--frame N | --frames A:B] [--fps F]\n"
           "                      [--threads N] [--mpi [--mpi-tile N]]\n"
           "                      [--stats FILE] [--vcd FILE.vcd [--vcd-cycles A:B]] [--usage-plot FILE.svg]\n"
           "                      [cycle mode options] [scene options]\n\n"
           "Renders the scene through the hardware units: RGS, traversal, list, transformation and\n"
           "intersection units reading the memory image. Shading (docs/shading.md): Phong-like with\n"
           "interpolated normals, bilinear textures, the scene's lights with shadow rays (a default light\n"
           "if it has none), reflection and transmission/refraction rays weighted by the glTF material.\n"
           "The image is bit-identical for any --threads (host threads building the objects' trees and\n"
           "rendering; default: the number of cores) and in both modes.\n"
           "  --mode M           functional (default: each 2x2 block runs its ray tree to completion) or\n"
           "                     cycle (the same steps timed by the DynRTC model, docs/cycle-model.md:\n"
           "                     prints cycles, fps, unit usage, cache hit rates, bandwidth, stalls) or\n"
           "                     rtl (the Verilated DynRTP of rtl/dynrtp.sv, built by make rtl: tile\n"
           "                     controller, RGS, ray tracing core, caches and memory port in RTL;\n"
           "                     cycle mode's memory options; --stats \"cycle\": the RTL's cycles and\n"
           "                     operations per unit; --aov without the cost channels; TRAV_STACK only)\n"
           "  --max-depth D      levels of secondary rays, 0..%u (default %u; 0: primary rays only)\n"
           "  --no-shadows       lights are not occluded (no shadow rays)\n"
           "  --traversal A      the traversal unit's algorithm (docs/traversal.md): stack (default, the\n"
           "                     paper's 64-entry stack), short-stack (4 entries + push-down restarts),\n"
           "                     restart (kd-restart, no stack), push-down (no stack), ropes (kd-tree\n"
           "                     with ropes), grid (a uniform grid per object, 3D-DDA) or grid2 (grids\n"
           "                     at both levels: a two-level grid over the instances)\n"
           "  --precision P      number format of the units: fp24 (e7m16, default), fp32 (e8m23), or\n"
           "                     any built format eEmM (make widths); runs build/w/<format>/saarcor\n"
           "  --aov FILE.exr     per-pixel primary hits as float channels t, N.X N.Y N.Z (world geometric\n"
           "                     normal), node (glTF node of the instance), triangle (index in its glTF\n"
           "                     mesh, primitives in file order), u, v (barycentrics of A and B); misses:\n"
           "                     t = inf, -1 indices; and the cost of each pixel (its primary ray and all rays\n"
           "                     spawned from it; docs/cli.md): traversal_steps, list_entries, intersections,\n"
           "                     transformations (issue slots), cycles (cycle mode only); they sum to --stats\n"
           "  --heatmap FILE.png false-colour picture (viridis) of one cost channel with a scale bar below\n"
           "                     the image (width x height+%u)\n"
           "  --heatmap-of NAME  its channel: one of the cost channels above (default transformations,\n"
           "                     cycles in cycle mode)\n"
           "  --stats FILE       counters as JSON: rays by kind, traversal steps, leaves, list entries,\n"
           "                     mailbox skips, transformations, intersections, memory words read; in\n"
           "                     cycle mode also the timing (\"cycle\": cycles, fps, usage, caches, ...);\n"
           "                     host_rss_kb, host_peak_rss_kb: this program's memory after the frame;\n"
           "                     \"host\": upload_bytes, geometry_upload_bytes (of deforming objects),\n"
           "                     rebuilt_objects, seconds: what bringing the image to the frame cost the host\n"
           "  --vcd FILE.vcd     waveforms of the model (IEEE 1364 VCD, e.g. for GTKWave; cycle or rtl mode):\n"
           "                     per pipe and unit busy, issue, queue_depth, thread_id; per cache lookups,\n"
           "                     misses, fills; the memory port's outstanding transfers; threads in flight\n"
           "                     (rtl mode: these where the RTL has the same thing, and its own units;\n"
           "                     docs/cycle-model.md)\n"
           "  --vcd-cycles A:B   the cycles written: A up to but not including B (default 0:20000)\n"
           "  --usage-plot FILE.svg  cycle mode: each unit's utilisation per epoch as an SVG chart\n"
           "  --capture-unit-io DIR  record the transformation (also its wide mode), intersection,\n"
           "                     traversal-node, list-unit and rebase-unit transactions, the primary packets,\n"
           "                     every packet the core traces with its hits (and the memory images it read)\n"
           "                     (and in cycle mode the memory reads and the scheduler's issues) as hex vectors\n"
           "                     for the RTL co-simulation (DIR/xform.hex, isect.hex, trav.hex, list.hex,\n"
           "                     rgs.hex, rebase.hex, wide.hex, trav_unit.hex, trace.hex + image_N.bin,\n"
           "                     mem.hex, sched.hex; at most --capture-limit N per unit, default 100000),\n"
           "                     run by the capture build beside the program (capture/saarcor; make builds it)\n"
           "  --frame N          frame N of the animation at --fps (time N / fps), to -o\n"
           "  --frames A:B       frames A..B of the animation at --fps (default 30) to OUT_NNNN.png (and\n"
           "                     AOV/stats files numbered alike), rebuilding per frame only what changed\n"
           "  --mpi              under mpirun -np N (N >= 2): rank 0 hands out tiles of the frame (or whole\n"
           "                     frames with --frames) to ranks 1..N-1, each a board of --pipes pipes;\n"
           "                     the same files and bits as one process (docs/mpi.md)\n"
           "  --mpi-tile N       edge in pixels of the tiles handed out with --mpi (default 64)\n"
           "Ctrl-C (SIGINT) or SIGTERM stops at the next block row or cycle-model epoch: the frames done\n"
           "so far are kept (files appear only when complete), exit 130 (SIGINT) or 143 (SIGTERM).\n\n%s\n%s",
           RGS_MAX_DEPTH, SHADE_DEFAULT_DEPTH, HEATMAP_BAR, CYCLE_OPTIONS_HELP, SCENE_OPTIONS_HELP);
    return SAARCOR_EXIT_OK;
}


/* out.png -> out_0007.png for frame sequences. */
static void frame_path(const render_opts *ro, uint32_t frame, char *buf, size_t n)
{
    if (!ro->sequence) {
        snprintf(buf, n, "%s", ro->out);
        return;
    }
    const char *dot = strrchr(ro->out, '.');
    const int stem = dot ? (int)(dot - ro->out) : (int)strlen(ro->out);
    snprintf(buf, n, "%.*s_%04u%s", stem, ro->out, frame, dot ? dot : ".png");
}

static const char *const ray_kind_names[RAY_KINDS] = { "primary", "shadow", "reflection", "transmission" };

static uint64_t words_total(const trace_counters *t)
{
    return t->words[MEM_NODES] + t->words[MEM_LISTS] + t->words[MEM_MATRICES] + t->words[MEM_SHADING];
}

static uint64_t all_rays(const rgs_counters *c)
{
    uint64_t n = 0;
    for (int k = 0; k < RAY_KINDS; k++)
        n += c->rays[k];
    return n;
}

/* Counters of one frame as JSON: rays by kind, work of the units, memory words read. */
static int write_stats(const char *path, const render_opts *ro, const cycle_config *cc, uint32_t frame,
                       const frame_result *fr)
{
    const double secs = fr->secs;
    const rgs_counters *c = &fr->sum;
    char tmp[1100]; /* complete files only: written under path.tmp, renamed when closed */
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f)
        return -1;
    const trace_counters *t = &c->trace;
    fprintf(f, "{\"mode\": \"%s\", \"frame\": %u, \"seconds\": %.6f, \"max_depth\": %u, \"shadows\": %s, \"rays\": %llu, \"rays_by_kind\": {",
            ro->cycle ? "cycle" : ro->rtl ? "rtl" : "functional", frame, secs, ro->cfg.max_depth, ro->cfg.shadows ? "true" : "false", (unsigned long long)all_rays(c));
    for (int k = 0; k < RAY_KINDS; k++)
        fprintf(f, "%s\"%s\": %llu", k ? ", " : "", ray_kind_names[k], (unsigned long long)c->rays[k]);
    fprintf(f, "}, \"traversal_steps\": %llu, \"leaves\": %llu, \"list_entries\": %llu, \"mailbox_skips\": %llu, "
               "\"transformations\": %llu, \"intersections\": %llu, \"words_read\": %llu, \"words_by_type\": {\"kd_nodes\": %llu, "
               "\"lists\": %llu, \"matrices\": %llu, \"shading\": %llu}, \"dropped_packets\": %llu",
            (unsigned long long)t->traversal_steps, (unsigned long long)t->leaves, (unsigned long long)t->list_entries,
            (unsigned long long)t->mailbox_skips, (unsigned long long)t->transformations,
            (unsigned long long)t->intersections, (unsigned long long)words_total(t),
            (unsigned long long)t->words[MEM_NODES], (unsigned long long)t->words[MEM_LISTS],
            (unsigned long long)t->words[MEM_MATRICES], (unsigned long long)t->words[MEM_SHADING],
            (unsigned long long)c->dropped);
    proc_mem pm;
    proc_mem_read(&pm); /* after the frame: what a long run must keep constant */
    fprintf(f, ", \"host_rss_kb\": %ld, \"host_peak_rss_kb\": %ld", pm.rss_kb, pm.peak_rss_kb);
    /* one object: its time varies from run to run, and with --mpi --frames its bytes with what a
     * board held before, so comparisons of the device's counters leave it out whole */
    fprintf(f, ", \"host\": {\"upload_bytes\": %llu, \"geometry_upload_bytes\": %llu, \"rebuilt_objects\": %u, "
               "\"seconds\": %.6f}", (unsigned long long)fr->host.upload_bytes, (unsigned long long)fr->host.geometry_bytes,
            fr->host.rebuilt, fr->host.secs);
    if (ro->cycle) {
        fprintf(f, ", \"cycle\": ");
        cycle_report_json(f, cc, &fr->cs, all_rays(c));
    }
    if (ro->rtl) { /* the RTL's counters: cycles and the issues per unit of trace_core */
        fprintf(f, ", \"cycle\": ");
        rtl_report_json(f, ro, &fr->rtl);
    }
    if (fr->mpi)
        fprintf(f, ", \"mpi\": {\"ranks\": %d, \"boards\": %u, \"items\": %u, \"bytes_to_workers\": %llu, "
                   "\"bytes_from_workers\": %llu, \"messages\": %llu, \"wall_seconds\": %.6f, \"work_seconds\": %.6f, "
                   "\"comm_seconds\": %.6f, \"comm_seconds_max\": %.6f, \"image_bytes_per_board\": %llu, "
                   "\"image_upload_bytes_total\": %llu}",
                fr->mpi->ranks, fr->boards, fr->items, (unsigned long long)fr->mpi->bytes_to_workers,
                (unsigned long long)fr->mpi->bytes_from_workers, (unsigned long long)fr->mpi->messages,
                fr->mpi->wall_seconds, fr->mpi->work_seconds, fr->mpi->comm_seconds, fr->mpi->comm_seconds_max,
                (unsigned long long)fr->image_bytes_per_board, (unsigned long long)fr->image_upload_bytes_total);
    fprintf(f, "}\n");
    if (fclose(f) != 0 || rename(tmp, path) != 0) {
        remove(tmp);
        return -1;
    }
    return 0;
}

static double f24d(uint32_t w) { return (double)f24_fast_decode(w); }

/* Per-pixel primary-hit data as named float channels: t, world geometric normal (unit, in the
 * triangle's A B C orientation), glTF node of the instance, triangle index within its glTF mesh
 * (primitives concatenated in file order), barycentrics u (of A) and v (of B). Misses: t = +inf,
 * node = triangle = -1. Then the per-pixel costs (pixel_cost.h) under their names, cycles only in
 * cycle mode: multiples of 1/12, exact in float up to 2^24 / 12. */
static int write_aov(const char *path, const mi_builder *b, const scene *s, const hit_record *hits,
                     const pixel_cost *costs, int cycle, uint32_t w, uint32_t h)
{
    enum { HITS = 8 };
    const char *names[HITS + PC_KINDS] = { "t", "N.X", "N.Y", "N.Z", "node", "triangle", "u", "v" };
    const int ncost = !costs ? 0 : cycle ? PC_KINDS : PC_CYCLES, nch = HITS + ncost; /* rtl mode: no costs */
    for (int k = 0; k < ncost; k++)
        names[HITS + k] = pc_names[k];
    uint32_t n;
    const uint32_t *mem = mi_words(b, &n);
    img_t img = { (int)w, (int)h, nch, calloc((size_t)w * h * (size_t)nch, sizeof(float)) };
    if (!img.pixels)
        return -1;
    for (size_t p = 0; p < (size_t)w * h; p++) {
        float *o = &img.pixels[(size_t)nch * p];
        const hit_record *hr = &hits[p];
        for (int k = 0; k < ncost; k++)
            o[HITS + k] = (float)((double)costs[p].v[k] / PC_UNIT);
        if (hr->instance == TRACE_NO_HIT) {
            o[0] = INFINITY;
            o[4] = o[5] = -1.0f;
            continue;
        }
        const uint32_t ia = mem[MI_H_REGION_TABLE + 2 * MI_R_INSTANCES] + MI_INSTANCE_WORDS * hr->instance;
        const uint32_t object = mem[ia + 12];
        const uint32_t *od = mem + mem[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS] + MI_OBJECT_WORDS * object;
        const uint32_t tri = od[MI_O_TRIANGLES] + MI_TRIANGLE_WORDS * hr->triangle;
        double nw[3] = { 0, 0, 0 }, len = 0;
        for (int j = 0; j < 3; j++) { /* n_world = (world-to-object)^T n_object, n_object = row 2 of T */
            for (int i = 0; i < 3; i++)
                nw[j] += f24d(mem[ia + 4 * i + j]) * f24d(f24_record_get(mem, tri, 8 + (uint32_t)i));
            len += nw[j] * nw[j];
        }
        len = len > 0 ? sqrt(len) : 1;
        uint32_t si, mt;
        mi_hit_source(b, hr->instance, hr->triangle, &si, &mt);
        o[0] = (float)f24d(hr->t);
        for (int k = 0; k < 3; k++)
            o[1 + k] = (float)(nw[k] / len);
        o[4] = si < s->n_instances ? (float)s->instances[si].node : -1.0f;
        o[5] = (float)(int64_t)mt;
        o[6] = (float)f24d(hr->u);
        o[7] = (float)f24d(hr->v);
    }
    char err[256];
    const int rc = img_write_channels(path, &img, names, err, sizeof err);
    if (rc != 0)
        cli_error("render", "%s", err);
    img_free(&img);
    return rc;
}

/* Progress of the cycle mode on stderr (a terminal, at most every half second); called between
 * epochs, so it is also where a signal stops the cycle model. */
static int cycle_progress(uint64_t done, uint64_t all, void *arg)
{
    static double last;
    (void)arg;
    if (interrupt_signal())
        return 1;
    const double t = now();
    if (t - last < 0.5 || !isatty(2))
        return 0;
    last = t;
    fprintf(stderr, "\rrender: %3u%%", (unsigned)(100 * done / (all ? all : 1)));
    return 0;
}

int render_validate(const mi_builder *b)
{
    char err[512];
    uint32_t n;
    const uint32_t *mem = mi_words(b, &n);
    if (mi_validate(mem, n, err, sizeof err) != 0) {
        cli_error("render", "%s", err);
        return SAARCOR_EXIT_INTERNAL;
    }
    return SAARCOR_EXIT_OK;
}

/* The MPI line of the report: how the frame was distributed and what it cost to move. */
static void print_mpi(const frame_result *fr)
{
    const saarcor_mpi_report *m = fr->mpi;
    printf("mpi: %d ranks (%u worker boards), %u item%s, %.1f KB to workers, %.1f KB from workers, %llu messages; "
           "memory image %.1f KB per board, %.1f KB uploaded to the boards; "
           "wall %.3f s, worker time working %.3f s, communicating %.3f s (max %.3f s on one worker)\n",
           m->ranks, fr->boards, fr->items, fr->items == 1 ? "" : "s", (double)m->bytes_to_workers / 1024.0,
           (double)m->bytes_from_workers / 1024.0, (unsigned long long)m->messages,
           (double)fr->image_bytes_per_board / 1024.0, (double)fr->image_upload_bytes_total / 1024.0, m->wall_seconds,
           m->work_seconds, m->comm_seconds, m->comm_seconds_max);
}

/* The frame's --heatmap file (numbered like -o in a sequence). */
static int write_heatmap(const render_opts *ro, uint32_t frame, uint32_t w, uint32_t h, const pixel_cost *costs)
{
    char path[1024], err[512];
    render_opts hm = *ro;
    hm.out = ro->heatmap;
    frame_path(&hm, frame, path, sizeof path);
    const int kind = ro->heatmap_of >= 0 ? ro->heatmap_of : ro->cycle ? PC_CYCLES : PC_TRANSFORMATIONS;
    const int rc = heatmap_write(path, costs, w, h, kind, err, sizeof err);
    if (rc != 0)
        cli_error("render", "%s", err);
    return rc;
}

int render_frame_output(const render_opts *ro, const mi_builder *b, const scene *s, uint32_t frame,
                        const char *scene_name, uint32_t w, uint32_t h, const uint32_t *pixels, const hit_record *hits,
                        const frame_result *fr)
{
    char path[1024];
    frame_path(ro, frame, path, sizeof path);
    int wrc = write_png(path, pixels, w, h);
    if (wrc == 0 && ro->aov) {
        char aov_path[1024];
        render_opts aov = *ro;
        aov.out = ro->aov;
        frame_path(&aov, frame, aov_path, sizeof aov_path);
        wrc = write_aov(aov_path, b, s, hits, fr->costs, ro->cycle, w, h);
    }
    if (wrc == 0 && ro->heatmap)
        wrc = write_heatmap(ro, frame, w, h, fr->costs);
    if (wrc != 0)
        return SAARCOR_EXIT_INPUT;
    const rgs_counters *sum = &fr->sum;
    const uint64_t rays = all_rays(sum), primary = sum->rays[RAY_PRIMARY] ? sum->rays[RAY_PRIMARY] : 1;
    const trace_counters *t = &sum->trace;
    printf("rendered %s: %ux%u, %llu rays (%llu primary, %llu shadow, %llu reflection, %llu transmission) in %.3f s "
           "(%u threads), host %.2f ms, rebuilt %u (geometry %.1f KB), upload %.1f KB -> %s\n", scene_name, w, h,
           (unsigned long long)rays, (unsigned long long)sum->rays[RAY_PRIMARY],
           (unsigned long long)sum->rays[RAY_SHADOW], (unsigned long long)sum->rays[RAY_REFLECTION],
           (unsigned long long)sum->rays[RAY_TRANSMISSION], fr->secs, ro->threads, 1e3 * fr->host.secs, fr->host.rebuilt,
           (double)fr->host.geometry_bytes / 1024.0, (double)fr->host.upload_bytes / 1024.0, path);
    printf("per primary ray (secondary rays included): %.2f traversal steps, %.2f leaves, %.2f list entries, "
           "%.2f mailbox skips, %.2f intersections, %.1f words read\n", (double)t->traversal_steps / primary,
           (double)t->leaves / primary, (double)t->list_entries / primary, (double)t->mailbox_skips / primary,
           (double)t->intersections / primary, (double)words_total(t) / primary);
    cycle_config cc = ro->cc; /* a frame split over boards is reported as all their pipes on one chip */
    if (fr->boards && !ro->sequence)
        cc.pipes *= fr->boards;
    if (ro->cycle)
        cycle_report(stdout, &cc, &fr->cs, rays);
    if (ro->rtl)
        rtl_report(stdout, ro, &fr->rtl);
    if (fr->mpi)
        print_mpi(fr);
    fflush(stdout);
    char stats_path[1024];
    if (ro->stats) {
        render_opts st = *ro;
        st.out = ro->stats;
        frame_path(&st, frame, stats_path, sizeof stats_path);
    }
    if (ro->stats && write_stats(stats_path, ro, &cc, frame, fr) != 0) {
        cli_error("render", "cannot write '%s'", stats_path);
        return SAARCOR_EXIT_INPUT;
    }
    return SAARCOR_EXIT_OK;
}

/* The frame's recorder for --vcd and --usage-plot (numbered like -o in a sequence), NULL if
 * neither is asked for or it could not be made (*rc says which). */
static cycle_trace *waveform_begin(const render_opts *ro, uint32_t frame, int *rc)
{
    char path[1024], err[512];
    render_opts v = *ro;
    *rc = SAARCOR_EXIT_OK;
    if (!ro->cycle || (!ro->vcd && !ro->usage_plot))
        return NULL;
    v.out = ro->vcd;
    if (ro->vcd)
        frame_path(&v, frame, path, sizeof path);
    cycle_trace *tr = cycle_trace_open(ro->vcd ? path : NULL, ro->vcd_from, ro->vcd_to, &ro->cc, err, sizeof err);
    if (!tr) {
        cli_error("render", "%s", err);
        *rc = SAARCOR_EXIT_INPUT;
    }
    return tr;
}

/* Writes the frame's --usage-plot and completes its --vcd file. */
static int waveform_end(const render_opts *ro, cycle_trace *tr, uint32_t frame, uint64_t cycles)
{
    char path[1024], err[512];
    render_opts v = *ro;
    int bad = 0;
    v.out = ro->usage_plot;
    if (ro->usage_plot) {
        frame_path(&v, frame, path, sizeof path);
        if ((bad = usage_plot_write(path, tr, &ro->cc, cycles, err, sizeof err) != 0))
            cli_error("render", "%s", err);
    }
    if (cycle_trace_close(tr, cycles, err, sizeof err) != 0 && !bad) {
        cli_error("render", "%s", err);
        bad = 1;
    }
    return bad ? SAARCOR_EXIT_INPUT : SAARCOR_EXIT_OK;
}

frame_host render_host(const mi_builder *b, double secs)
{
    const mi_stats *st = mi_get_stats(b);
    return (frame_host){ st->frame_upload_bytes, st->frame_geometry_bytes, st->rebuilt_objects, secs };
}

int render_advance(scene *s, mi_builder *b, uint32_t f, double fps, frame_host *h, char *err, size_t errlen)
{
    const double t0 = now();
    if (scene_evaluate(s, f / fps, 1) != 0) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    if (mi_update(b, s, err, errlen) != 0)
        return -1;
    *h = render_host(b, now() - t0);
    return 0;
}

/* Renders one frame of the current image (host: what bringing it to this frame cost) and writes it. */
static int render_frame(const mi_builder *b, const scene *s, const render_opts *ro, uint32_t frame,
                        const char *scene_name, frame_host host)
{
    uint32_t n, w, h;
    const uint32_t *mem = mi_words(b, &n);
    if (render_validate(b) != SAARCOR_EXIT_OK)
        return SAARCOR_EXIT_INTERNAL;
    rgs_image_size(mem, &w, &h);
    int trc;
    cycle_trace *tr = waveform_begin(ro, frame, &trc);
    if (trc != SAARCOR_EXIT_OK)
        return trc;
    uint32_t *pixels = calloc((size_t)w * h, sizeof *pixels);
    hit_record *hits = ro->aov ? calloc((size_t)w * h, sizeof *hits) : NULL;
    const int want_costs = (ro->aov || ro->heatmap) && !ro->rtl; /* the RTL attributes no work to pixels */
    pixel_cost *costs = want_costs ? calloc((size_t)w * h, sizeof *costs) : NULL;
    frame_result fr = { .host = host, .costs = costs };
    static const uint32_t all[4] = { 0, 0, UINT32_MAX, UINT32_MAX };
    const double t0 = now();
    if (ro->sim) {
        cycle_set_costs(ro->sim, costs);
        cycle_set_trace(ro->sim, tr);
    }
    const int no_memory = !pixels || (ro->aov && !hits) || (want_costs && !costs);
    /* rtl mode: the model's exit code (its one-line error printed), else 0 */
    const int rtl_rc = ro->rtl && !no_memory ? render_rtl(mem, n, ro, w, h, pixels, hits, &fr.sum, &fr.rtl) : 0;
    const int failed = no_memory ? -1
                       : ro->cycle ? cycle_render(ro->sim, mem, &ro->cfg, pixels, hits, &fr.sum, &fr.cs, cycle_progress, NULL)
                       : ro->rtl   ? 0
                                   : render_region(mem, &ro->cfg, ro->threads, all, pixels, hits, costs, &fr.sum);
    if (ro->sim)
        cycle_set_trace(ro->sim, NULL); /* tr is closed below */
    if (isatty(2) && ro->cycle)
        fprintf(stderr, "\r%*s\r", 14, "");
    fr.secs = now() - t0;
    int rc = rtl_rc ? rtl_rc
           : failed > 0 ? 128 + interrupt_signal() /* stopped by a signal: this frame is not written */
           : failed ? (cli_error("render", "out of memory"), SAARCOR_EXIT_INTERNAL)
                    : render_frame_output(ro, b, s, frame, scene_name, w, h, pixels, hits, &fr);
    if (tr && rc == SAARCOR_EXIT_OK)
        rc = waveform_end(ro, tr, frame, fr.cs.cycles);
    else
        cycle_trace_abort(tr);
    free(pixels);
    free(hits);
    free(costs);
    return rc;
}

/* The one line of a stopped render: the signal and the frames that are on disk. */
static void report_interrupt(const render_opts *ro, uint32_t written)
{
    char first[1024], last[1024] = "";
    frame_path(ro, ro->first, first, sizeof first);
    if (written > 0)
        frame_path(ro, ro->first + written - 1, last, sizeof last);
    fprintf(stderr, "saarcor render: interrupted by %s: %u frame%s written%s%s%s%s%s\n",
            interrupt_name(interrupt_signal()), written, written == 1 ? "" : "s", written ? " (" : "",
            written ? first : "", written > 1 ? " .. " : "", written > 1 ? last : "", written ? ")" : "");
}

static int parse_frames(const char *arg, render_opts *ro)
{
    uint64_t a, b;
    char first[32];
    const char *colon = strchr(arg, ':');
    if (!colon || colon - arg >= (long)sizeof first)
        return 0;
    snprintf(first, sizeof first, "%.*s", (int)(colon - arg), arg);
    if (!cli_parse_u64(first, 0, 1000000, &a) || !cli_parse_u64(colon + 1, 0, 1000000, &b) || b < a)
        return 0;
    ro->first = (uint32_t)a;
    ro->last = (uint32_t)b;
    ro->sequence = 1;
    return 1;
}

/* --vcd-cycles A:B -> the window [A, B); 0 if malformed or empty. */
static int parse_window(const char *arg, uint64_t *from, uint64_t *to)
{
    char first[32];
    const char *colon = strchr(arg, ':');
    if (!colon || colon - arg >= (long)sizeof first)
        return 0;
    snprintf(first, sizeof first, "%.*s", (int)(colon - arg), arg);
    return cli_parse_u64(first, 0, UINT64_MAX / 4, from) && cli_parse_u64(colon + 1, 1, UINT64_MAX / 4, to) && *from < *to;
}

/* --precision: fp24, fp32 or eEmM -> exponent and fraction bits; 0 if malformed. */
static int parse_precision(const char *arg, int *e, int *m)
{
    char tail;
    if (strcmp(arg, "fp24") == 0)
        *e = 7, *m = 16;
    else if (strcmp(arg, "fp32") == 0)
        *e = 8, *m = 23;
    else if (sscanf(arg, "e%dm%d%c", e, m, &tail) != 2)
        return 0;
    return *e >= 3 && *e <= 8 && *m >= 2 && *m <= 23;
}

/* The units are compiled for one number format per program (build/w/eEmM/saarcor): a render
 * in another format runs that program with the same arguments. Returns only on error. */
/* The folder of this program, or of the program whose capture build this is (build/capture/saarcor
 * and build/w/eEmM/capture/saarcor stand for build/saarcor and build/w/eEmM/saarcor); 0, or -1. */
static int program_dir(char *dir, size_t len)
{
    const ssize_t n = readlink("/proc/self/exe", dir, len - 1);
    if (n <= 0)
        return -1;
    dir[n] = 0;
    *strrchr(dir, '/') = 0;
    const char *last = strrchr(dir, '/');
    if (last && strcmp(last, "/" CAPTURE_DIR) == 0)
        *strrchr(dir, '/') = 0;
    return 0;
}

/* render --precision eEmM: the same command line run by the program of that format. */
static int run_format(int e, int m, char **argv)
{
    char self[1024], path[1200];
    if (program_dir(self, sizeof self) != 0)
        return cli_error("render", "cannot locate this program to find the e%dm%d build", e, m), SAARCOR_EXIT_INTERNAL;
    const char *dir = strrchr(self, '/'); /* build/ or build/w/eEmM/ */
    int fe, fm;
    char tail;
    if (dir && sscanf(dir + 1, "e%dm%d%c", &fe, &fm, &tail) == 2)
        snprintf(path, sizeof path, "%s/../e%dm%d/saarcor", self, e, m);
    else
        snprintf(path, sizeof path, "%s/w/e%dm%d/saarcor", self, e, m);
    execv(path, argv);
    cli_error("render", "--precision e%dm%d: no program for that format at %s (build it with make widths)", e, m, path);
    return SAARCOR_EXIT_USAGE;
}

/* render --capture-unit-io in a program without the capture: the same command line run by the
 * capture build beside it (CAPTURE_DIR/saarcor), which records as if it had been called. */
static int run_capture(char **argv)
{
    char self[1024], path[1200];
    if (program_dir(self, sizeof self) != 0)
        return cli_error("render", "cannot locate this program to find its capture build"), SAARCOR_EXIT_INTERNAL;
    snprintf(path, sizeof path, "%s/" CAPTURE_DIR "/saarcor", self);
    execv(path, argv);
    cli_error("render", "--capture-unit-io needs the capture build %s (make builds it beside each program)", path);
    return SAARCOR_EXIT_USAGE;
}

int cmd_render(int argc, char **argv)
{
    static const struct option opts[] = {
        SCENE_LONG_OPTIONS, { "output", required_argument, NULL, 'o' }, { "threads", required_argument, NULL, 't' },
        { "stats", required_argument, NULL, 's' }, { "frames", required_argument, NULL, 'F' },
        { "fps", required_argument, NULL, 'r' }, { "frame", required_argument, NULL, 'f' }, { "aov", required_argument, NULL, 'a' },
        { "heatmap", required_argument, NULL, 'H' }, { "heatmap-of", required_argument, NULL, 'O' },
        { "max-depth", required_argument, NULL, 'd' }, { "no-shadows", no_argument, NULL, 'S' },
        { "traversal", required_argument, NULL, 'T' }, { "precision", required_argument, NULL, 'p' }, { "mode", required_argument, NULL, 'm' },
        { "capture-unit-io", required_argument, NULL, 'C' }, { "capture-limit", required_argument, NULL, 'L' },
        { "mpi", no_argument, NULL, 'M' }, { "mpi-tile", required_argument, NULL, 'X' },
        { "vcd", required_argument, NULL, 'V' }, { "vcd-cycles", required_argument, NULL, 'W' },
        { "usage-plot", required_argument, NULL, 'U' }, CYCLE_LONG_OPTIONS, { "help", no_argument, NULL, 'h' }, { 0, 0, 0, 0 }
    };
    scene_opts o;
    const long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    render_opts ro = { .out = "render.png", .heatmap_of = -1, .threads = ncpu > 0 && ncpu < 256 ? (uint32_t)ncpu : 1,
                       .fps = 30.0, .cfg = { SHADE_DEFAULT_DEPTH, 1, TRAV_STACK }, .capture_limit = 100000, .mpi_tile = 64,
                       .vcd_to = 20000 };
    int c, prec_e = F24_EXP_BITS, prec_m = F24_MAN_BITS;
    scene_opts_default(&o);
    cycle_config_default(&ro.cc);
    optind = 0;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "o:h", opts, NULL)) != -1) {
        uint64_t v;
        const int r = c >= CYCLE_OPT_BASE ? cycle_opts_parse(&ro.cc, "render", c, optarg)
                      : c >= SCENE_OPT_BASE ? scene_opts_parse(&o, "render", c, optarg) : 0;
        if (r < 0)
            return SAARCOR_EXIT_USAGE;
        if (r > 0)
            continue;
        switch (c) {
        case 'o': ro.out = optarg; break;
        case 't':
            if (!cli_parse_u64(optarg, 1, 256, &v))
                return cli_usage_error("render", "bad --threads '%s'", optarg);
            ro.threads = (uint32_t)v;
            break;
        case 's': ro.stats = optarg; break;
        case 'a': ro.aov = optarg; break;
        case 'H': ro.heatmap = optarg; break;
        case 'O':
            if ((ro.heatmap_of = heatmap_channel(optarg)) < 0)
                return cli_usage_error("render", "bad --heatmap-of '%s' (traversal_steps, list_entries, intersections, "
                                       "transformations or cycles)", optarg);
            break;
        case 'F':
            if (!parse_frames(optarg, &ro))
                return cli_usage_error("render", "bad --frames '%s' (expected A:B with A <= B)", optarg);
            break;
        case 'f':
            if (!cli_parse_u64(optarg, 0, 1000000, &v))
                return cli_usage_error("render", "bad --frame '%s' (0..1000000)", optarg);
            ro.first = ro.last = (uint32_t)v;
            ro.one_frame = 1;
            break;
        case 'r':
            if (!cli_parse_double(optarg, &ro.fps) || ro.fps <= 0 || ro.fps > 1e4)
                return cli_usage_error("render", "bad --fps '%s'", optarg);
            break;
        case 'd':
            if (!cli_parse_u64(optarg, 0, 1000000, &v)) /* limit ray-depth: after the options */
                return cli_usage_error("render", "bad --max-depth '%s'", optarg);
            ro.cfg.max_depth = (uint32_t)v;
            break;
        case 'S': ro.cfg.shadows = 0; break;
        case 'T': {
            const int k = scene_opts_traversal(&o, "render", optarg);
            if (k < 0)
                return SAARCOR_EXIT_USAGE;
            ro.cfg.traversal = (uint32_t)k;
            break;
        }
        case 'C': ro.capture = optarg; break;
        case 'V': ro.vcd = optarg; break;
        case 'U': ro.usage_plot = optarg; break;
        case 'W':
            if (!parse_window(optarg, &ro.vcd_from, &ro.vcd_to))
                return cli_usage_error("render", "bad --vcd-cycles '%s' (expected A:B with A < B, cycles A up to B)",
                                       optarg);
            break;
        case 'M': ro.mpi = 1; break;
        case 'X':
            if (!cli_parse_u64(optarg, 2, 4096, &v) || v % 2)
                return cli_usage_error("render", "bad --mpi-tile '%s' (even, 2..4096)", optarg);
            ro.mpi_tile = (uint32_t)v;
            break;
        case 'L':
            if (!cli_parse_u64(optarg, 1, 100000000, &v))
                return cli_usage_error("render", "bad --capture-limit '%s' (1..1e8)", optarg);
            ro.capture_limit = v;
            break;
        case 'm':
            if (strcmp(optarg, "functional") != 0 && strcmp(optarg, "cycle") != 0 && strcmp(optarg, "rtl") != 0)
                return cli_usage_error("render", "bad --mode '%s' (functional, cycle or rtl)", optarg);
            ro.cycle = strcmp(optarg, "cycle") == 0;
            ro.rtl = strcmp(optarg, "rtl") == 0;
            break;
        case 'p':
            if (strcmp(optarg, "fp64") == 0)
                return cli_usage_error("render", "--precision fp64 is not available: the units' formats are at most "
                                                 "32 bits wide (fp32 = e8m23)");
            if (!parse_precision(optarg, &prec_e, &prec_m))
                return cli_usage_error("render", "bad --precision '%s' (fp24, fp32 or eEmM with E 3..8, M 2..23)", optarg);
            break;
        case 'h': return usage();
        default: return cli_bad_option("render", argc, argv);
        }
    }
    if (argc - optind != 1)
        return cli_usage_error("render", "expected one SCENE");
    if (ro.heatmap_of == PC_CYCLES && !ro.cycle)
        return cli_usage_error("render", "--heatmap-of cycles needs --mode cycle");
    if (ro.vcd && !ro.cycle && !ro.rtl)
        return cli_usage_error("render", "--vcd needs --mode cycle or rtl");
    if (ro.usage_plot && !ro.cycle)
        return cli_usage_error("render", "--usage-plot needs --mode cycle");
    if (ro.heatmap_of >= 0 && !ro.heatmap)
        return cli_usage_error("render", "--heatmap-of needs --heatmap FILE.png");
    int rc = limit_check(&o.lim, "render", LIMIT_RAY_DEPTH, ro.cfg.max_depth, "--max-depth");
    if (rc == SAARCOR_EXIT_OK)
        rc = limit_check(&o.lim, "render", LIMIT_FRAMES, ro.last - ro.first + 1ull, "the frame count of --frames");
    if (rc != SAARCOR_EXIT_OK)
        return rc;
    if (cli_parse_only)
        return SAARCOR_EXIT_OK;
    if (prec_e != F24_EXP_BITS || prec_m != F24_MAN_BITS)
        return run_format(prec_e, prec_m, argv - 1);
    if (ro.capture && !capture_start)
        return run_capture(argv - 1);
    o.scene = argv[optind];
    if (ro.rtl && (rc = render_rtl_check(&ro)) != SAARCOR_EXIT_OK)
        return rc;
    if (ro.sequence && ro.one_frame)
        return cli_usage_error("render", "--frame and --frames exclude each other");
    /* from here on a signal stops at the next safe point (a long scene load is not one: the
     * render stops at its first block row) */
    if (interrupt_catch() != 0)
        cli_error("render", "cannot catch SIGINT/SIGTERM: Ctrl-C will not stop cleanly");
    if (ro.mpi && (ro.aov || ro.heatmap || ro.capture || ro.vcd || ro.usage_plot))
        return cli_usage_error("render", "--mpi does not write --aov, --heatmap, --capture-unit-io, --vcd or --usage-plot "
                                         "(render those in one process)");
    if (ro.mpi && ro.cycle && ro.mpi_tile % ro.cc.tile)
        return cli_usage_error("render", "--mpi-tile %u must be a multiple of the cycle model's --tile %u", ro.mpi_tile,
                               ro.cc.tile);
    saarcor_mpi_run_fn mpi_run = ro.mpi ? mpi_load("render") : NULL;
    if (ro.mpi && !mpi_run)
        return SAARCOR_EXIT_INTERNAL;
    char err[600];
    /* before the render, not after it */
    if (img_ready_for(ro.out, 3, 0, err, sizeof err) != 0 || img_ready_for(ro.heatmap, 3, 0, err, sizeof err) != 0 ||
        img_ready_for(ro.aov, 0, 1, err, sizeof err) != 0) {
        cli_error("render", "%s", err);
        return SAARCOR_EXIT_INTERNAL;
    }
    if (ro.sequence || ro.one_frame)
        o.time = ro.first / ro.fps;
    scene s;
    rc = scene_opts_load(&o, "render", &s);
    if (rc != SAARCOR_EXIT_OK)
        return rc;
    const double build_t0 = now();
    o.mi.bottom.threads = ro.threads; /* the objects' trees too (the image does not depend on it) */
    mi_builder *b = scene_opts_build(&o, "render", &s, NULL, &rc);
    ro.build_secs = now() - build_t0;
    if (!b) {
        scene_free(&s);
        return rc;
    }
    scene_opts_warn_dropped(&o, "render", &s);
    ro.cc.host_threads = ro.threads;
    if (ro.capture && capture_start(ro.capture, ro.capture_limit, err, sizeof err) != 0) {
        cli_error("render", "--capture-unit-io: %s", err);
        mi_free(b);
        scene_free(&s);
        return SAARCOR_EXIT_INPUT;
    }
    if (ro.cycle && !(ro.sim = cycle_create(&ro.cc))) {
        cli_error("render", "out of memory for the cycle model");
        mi_free(b);
        scene_free(&s);
        return SAARCOR_EXIT_INTERNAL;
    }
    if (ro.sim && ro.capture)
        cycle_set_sched_probe(ro.sim, capture_sched_probe, NULL);
    rc = mpi_run ? render_mpi(&ro, mpi_run, b, &s, o.scene)
                 : render_frame(b, &s, &ro, ro.first, o.scene, render_host(b, ro.build_secs));
    uint32_t written = rc == SAARCOR_EXIT_OK;
    for (uint32_t f = ro.first + 1; !mpi_run && rc == SAARCOR_EXIT_OK && f <= ro.last; f++) {
        if (interrupt_signal()) { /* between frames: the safest point of all */
            rc = 128 + interrupt_signal();
            break;
        }
        frame_host host;
        if (render_advance(&s, b, f, ro.fps, &host, err, sizeof err) != 0) {
            cli_error("render", "frame %u: %s", f, err);
            rc = SAARCOR_EXIT_INTERNAL;
            break;
        }
        if (ro.sim)
            cycle_flush(ro.sim); /* the image changed */
        rc = render_frame(b, &s, &ro, f, o.scene, host);
        written += rc == SAARCOR_EXIT_OK;
    }
    if (rc > 128 && !mpi_run)
        report_interrupt(&ro, written);
    cycle_free(ro.sim);
    if (ro.capture) {
        uint64_t n[CAPTURE_UNITS];
        capture_counts(n);
        if (capture_stop() != 0 && rc == SAARCOR_EXIT_OK) {
            cli_error("render", "--capture-unit-io: writing the vectors in '%s' failed", ro.capture);
            rc = SAARCOR_EXIT_INPUT;
        } else {
            printf("captured unit transactions in %s:", ro.capture);
            for (int u = 0; u < CAPTURE_UNITS; u++)
                printf("%s %s %llu", u ? "," : "", capture_unit_names[u], (unsigned long long)n[u]);
            printf("\n");
        }
    }
    mi_free(b);
    scene_free(&s);
    return rc;
}
