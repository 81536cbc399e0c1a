/*
 * What `saarcor render` shares between its single-process path (cmd_render.c) and its MPI path
 * (render_mpi.c): the options, rendering a region of the image, and writing one frame's outputs.
 * Why: the distributed render must give the same bits and the same files as the single-process
 * one, so both call the same functions and only the work distribution differs.
 */
#ifndef SAARCOR_RENDER_H
#define SAARCOR_RENDER_H

#include <stdint.h>
#include <stdio.h>

#include "cycle_sim.h"
#include "memimage.h"
#include "pixel_cost.h"
#include "rgs.h"
#include "saarcor_mpi.h"
#include "scene.h"

typedef struct {
    const char *out, *stats, *aov;
    const char *heatmap; /* --heatmap FILE.png */
    int heatmap_of;      /* --heatmap-of: a PC_* channel; -1: transformations, cycles in cycle mode */
    uint32_t threads, first, last;
    int sequence, one_frame; /* --frames A:B, --frame N */
    double fps;
    rgs_config cfg;
    int cycle;       /* --mode cycle */
    int rtl;         /* --mode rtl (render_rtl.c) */
    cycle_config cc;
    cycle_sim *sim;  /* kept across the frames of a sequence (warm caches) */
    const char *capture; /* --capture-unit-io DIR */
    uint64_t capture_limit;
    const char *vcd, *usage_plot; /* --vcd FILE.vcd, --usage-plot FILE.svg (cycle mode) */
    uint64_t vcd_from, vcd_to;    /* --vcd-cycles A:B: cycles [A, B) */
    double build_secs; /* host time of the first frame's memory image (mi_build) */
    int mpi;           /* --mpi: distributed over MPI ranks (render_mpi.h) */
    uint32_t mpi_tile; /* --mpi-tile: edge in pixels of a work item of one frame */
} render_opts;

/* What the host did to bring the memory image to a frame: the paper's per-frame upload of the
 * changed objects and the top level. */
typedef struct {
    uint64_t upload_bytes;   /* memory image words rewritten for this frame, in bytes */
    uint64_t geometry_bytes; /* of which the geometry of deforming (morphed, skinned) objects and the object table */
    uint32_t rebuilt;        /* deforming objects whose bottom-level tree was rebuilt */
    double secs;             /* host time: scene_evaluate + mi_update (the first frame: mi_build) */
} frame_host;

/* --mode rtl: the counters of the RTL (rtl/dynrtp.sv): cycles of the frame, operations issued per
 * unit of trace_core, packets traced, reads per cache (the core's kd nodes, list entries and
 * descriptor words, the RGS's shading words), the memory port's transfers; the harness's
 * transactions checked per datapath unit against its C function (rtl/tb/tb_unit_check.h). */
enum { RTL_UNITS = 6, RTL_PORTS = 4, RTL_CHECKED = 16 };
extern const char *const rtl_unit_names[RTL_UNITS];
extern const char *const rtl_port_names[RTL_PORTS];
extern const char *const rtl_checked_names[RTL_CHECKED];
typedef struct {
    uint64_t cycles, packets, issues[RTL_UNITS], reads[RTL_PORTS], checked[RTL_CHECKED], mem_transfers, mem_bytes;
    uint32_t threads;
} rtl_stats;

/* One frame's numbers, however it was rendered. */
typedef struct {
    rgs_counters sum;
    cycle_stats cs;           /* cycle mode */
    rtl_stats rtl;            /* rtl mode */
    double secs;              /* wall time of the render */
    frame_host host;
    uint32_t boards;          /* MPI: worker ranks (each a board of --pipes pipes); 0: one process */
    uint32_t items;           /* MPI: work items of this frame (tiles, or 1 for a whole frame) */
    uint64_t image_bytes_per_board;    /* MPI, one frame in tiles: the memory image every board holds */
    uint64_t image_upload_bytes_total; /* ... uploaded to all boards: boards x image_bytes_per_board */
    const saarcor_mpi_report *mpi;
    const pixel_cost *costs;  /* per pixel, for --aov and --heatmap (NULL: not kept) */
} frame_result;

/* Functional mode (render_region.c): renders the pixels of region {x0, y0, x1, y1} (x0, y0 even;
 * clipped to the image) with `threads` host threads into the full-size pixels (and hits, costs,
 * may be NULL); sum = the counters of that work. 0, or -1 if out of memory. */
int render_region(const uint32_t *mem, const rgs_config *cfg, uint32_t threads, const uint32_t region[4],
                  uint32_t *pixels, hit_record *hits, pixel_cost *costs, rgs_counters *sum);

/* --mode rtl (render_rtl.c): the options the RTL model has and the model built (make rtl), else a
 * one-line error and its exit code; then the frame through the model: pixels, primary hits (may be
 * NULL), the RGS's counters and the RTL's. */
int render_rtl_check(const render_opts *ro);
int render_rtl(const uint32_t *mem, uint32_t n, const render_opts *ro, uint32_t w, uint32_t h, uint32_t *pixels,
               hit_record *hits, rgs_counters *sum, rtl_stats *st);
void rtl_report(FILE *f, const render_opts *ro, const rtl_stats *st);
void rtl_report_json(FILE *f, const render_opts *ro, const rtl_stats *st);

/* Writes the frame's image (and AOV, stats file) and prints its report lines; b and s are needed
 * for --aov only (may be NULL otherwise). A saarcor exit code. */
int render_frame_output(const render_opts *ro, const mi_builder *b, const scene *s, uint32_t frame,
                        const char *scene_name, uint32_t w, uint32_t h, const uint32_t *pixels, const hit_record *hits,
                        const frame_result *fr);

/* The frame_host of an image just built or updated in secs of host time. */
frame_host render_host(const mi_builder *b, double secs);

/* Brings scene and image to frame f (time f / fps) and says what that cost in *h.
 * 0, or -1 with err. */
int render_advance(scene *s, mi_builder *b, uint32_t f, double fps, frame_host *h, char *err, size_t errlen);

/* Validates the memory image; a saarcor exit code, with a one-line error. */
int render_validate(const mi_builder *b);

#endif
