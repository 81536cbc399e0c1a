/*
 * Cycle-level model of the SaarCOR DynRTC (paper sections 3 and 4): several dynamic ray tracing
 * pipelines (DynRTPs), each with T threads (2x2 pixel blocks, a packet of 4 rays in flight each),
 * five pipelined units (RGS, transformation, traversal, list, intersection) fed from input
 * queues, and a memory interface with per-type caches (mem_iface.h). A ray generation
 * controller hands out screen tiles to the pipes.
 *
 * The work is the hardware's own: every thread runs the same step functions as the functional
 * mode (rgs_step -> trace_step, hls/units), one unit operation at a time, so image and work
 * counters are bit-identical to the functional mode for any T and P. This model adds only time:
 *   - a thread whose operation is decided reads its memory blocks through the caches; a miss
 *     parks only that thread until its data arrives, then it joins the unit's queue;
 *   - a unit issues the operation of the first ready thread at or after its round-robin pointer
 *     (the RTL scheduler's policy, rtl/thread_sched.sv) when its issue slots are free; the
 *     operation occupies `slots` issue cycles (transformation steps, rays intersected, rays
 *     shaded) and its result leaves the pipeline `latency` cycles after its last slot, when the
 *     thread decides its next operation (the routing of paths a..g);
 *   - the traversal unit, as rtl/trav_unit.sv, takes one operation per issue cycle into its
 *     queue; its datapath (trav_node) takes the queue's operations in issue order, a clip for its
 *     `slots` (the slab planes), a kd-tree entry for one, each once it got there (trav_front
 *     cycles after its issue, + node_read for a node's words); the result leaves the rest of its
 *     latency after its last slot. An object clip joins the ready set objclip_front cycles after
 *     it is decided (its thread's own steps before it raises the clip).
 * Two-phase clock (as in Utah's simtrax): per cycle, every unit decides from the current state
 * whom it issues, then all changes commit in a fixed order (issues, then the threads whose
 * results arrive, in thread order), so nothing depends on the order units are stepped. Cycles in
 * which nothing can happen are skipped. Pipes are independent between controller epochs and run
 * on host threads in parallel; the controller refills each pipe's tile queue at epoch boundaries
 * in pipe order, so the result is deterministic for any host thread count.
 */
#ifndef SAARCOR_CYCLE_SIM_H
#define SAARCOR_CYCLE_SIM_H

#include <stdint.h>

#include "mem_iface.h"
#include "pixel_cost.h"
#include "rgs.h"

typedef struct {
    uint32_t pipes, threads_per_pipe; /* P DynRTPs, T threads each */
    uint32_t latency[OP_KINDS];       /* pipeline latency of each kind of operation (trace.h), cycles */
    uint32_t surface_hit;             /* a surface operation's cycles per hit after the first (rgs_surface's front
                                       * reads its hits one after another: docs/cycle-model.md) */
    uint32_t surface_miss;            /* a surface operation's cycles after its last slot when no ray hit (its
                                       * misses pass rgs_surface in a cycle each, nothing is read) */
    uint32_t shade_hit;               /* cycles from a word's request to its answer on a shading cache hit (the
                                       * first word of a light record rgs_ctrl reads) */
    uint32_t trav_front;              /* cycles from a traversal operation's issue to its first trav_node slot when
                                       * nothing is ahead of it (rtl/trav_unit.sv; part of its kind's latency) */
    uint32_t node_read;               /* ... more for a kd-tree entry that reads its node (trav_unit's N stage waits
                                       * for the node's words) */
    uint32_t objclip_front;           /* cycles from an object clip's decision to its joining the traversal unit's
                                       * ready set (trace_thread's steps before it raises the clip: the records, the
                                       * mailboxes' clear, the relative distances; part of its latency) */
    uint32_t tile;                    /* tile edge in pixels (even) handed out by the controller */
    uint32_t epoch;                   /* cycles between controller refills */
    uint32_t host_threads;            /* simulator threads (no effect on any result) */
    uint32_t reverse_order;           /* step units and threads in reverse (for the order test) */
    mem_config mem;
} cycle_config;

/* The defaults of docs/cycle-model.md (the prototype's caches, 1 GB/s at 90 MHz). */
void cycle_config_default(cycle_config *c);

/* The shading cache lines an operation's reads take on the RGS's line port (rtl/dynrtp.sv): a read
 * of n words from word address a, ceil((a mod L + n) / L) lines of the shading cache's L words. */
uint64_t cycle_shading_lines(const cycle_config *cfg, const unit_op *op);

/* Where a thread's time went, in thread-cycles. */
enum { ST_UNIT_QUEUE, ST_UNIT_BUSY, ST_MEMORY, ST_NO_WORK, ST_KINDS };

typedef struct {
    uint64_t cycles;                          /* of the frame: the last pipe's last result */
    uint64_t pipe_cycles_max, pipe_cycles_min;
    uint64_t busy[UNIT_KINDS];                /* issue slots used, over all pipes */
    uint64_t ops[UNIT_KINDS];                 /* operations issued */
    uint64_t thread_cycles[ST_KINDS];         /* over all threads of all pipes */
    uint64_t wait_unit[UNIT_KINDS];           /* thread-cycles queued at each unit */
    uint64_t wait_mem[MEM_KINDS];             /* thread-cycles waiting for memory, by data type */
    uint64_t shade_port_wait;                 /* cycles RGS operations waited for the shading line port */
    uint64_t blocks, tiles;
    mem_stats mem;                            /* summed over pipes */
} cycle_stats;

typedef struct cycle_sim cycle_sim;
typedef struct cycle_trace cycle_trace; /* cycle_trace.h */

/* NULL if out of memory. */
cycle_sim *cycle_create(const cycle_config *cfg);
void cycle_free(cycle_sim *s);

/* Per-pixel costs of the following renders (pixel_cost.h; width x height of the camera block,
 * pixels outside the region rendered untouched), NULL (the default): not kept. */
void cycle_set_costs(cycle_sim *s, pixel_cost *costs);

/* Records the following render's signals into tr (cycle_trace.h; made for this config), NULL: none. */
void cycle_set_trace(cycle_sim *s, cycle_trace *tr);

/* The scheduler's events of the following renders, for the RTL co-simulation of the thread
 * scheduler (rtl/thread_sched.sv; tb/cli/capture.c writes them to DIR/sched.hex): SCHED_FRAME
 * when pipe `pipe` starts a frame (thread = its thread count), SCHED_READY when a thread joins
 * unit u's ready set, with the issue slots of its operation (`cycle`: the first cycle the unit can
 * issue it), SCHED_ISSUE when unit u issues it. Called from the pipe's host thread. NULL: none. */
enum { SCHED_FRAME, SCHED_READY, SCHED_ISSUE };
typedef void (*cycle_sched_probe)(void *arg, uint32_t pipe, int what, uint64_t cycle, uint32_t unit, uint32_t thread,
                                  uint32_t slots);
void cycle_set_sched_probe(cycle_sim *s, cycle_sched_probe probe, void *arg);

/* Empties the caches: the memory image changed. */
void cycle_flush(cycle_sim *s);

/* progress(done blocks, all blocks) is called by the controller between epochs (may be NULL);
 * a non-zero return stops the frame there (Ctrl-C: the caller's threads must not run on). */
typedef int (*cycle_progress_fn)(uint64_t done, uint64_t all, void *arg);

/* Renders one frame of the memory image: pixels (0xRRGGBB, width x height of the camera block),
 * primary hits per pixel (may be NULL), the work counters (summed) and the timing. The caches
 * keep their contents from the previous frame unless cycle_flush was called. 0, -1 if out
 * of memory, 1 if progress asked to stop (pixels, counters and stats incomplete). */
int cycle_render(cycle_sim *s, const uint32_t *mem, const rgs_config *rcfg, uint32_t *pixels, hit_record *hits,
                 rgs_counters *counters, cycle_stats *stats, cycle_progress_fn progress, void *arg);

/* The same for the pixels of region {x0, y0, x1, y1} only (clipped to the image; the controller
 * numbers tiles within it, tiles of the whole image if the region starts at a multiple of the
 * tile edge). The work of each 2x2 block is the same as in cycle_render, so its pixels are too. */
int cycle_render_region(cycle_sim *s, const uint32_t *mem, const rgs_config *rcfg, const uint32_t region[4],
                        uint32_t *pixels, hit_record *hits, rgs_counters *counters, cycle_stats *stats,
                        cycle_progress_fn progress, void *arg);

/* sum += s for everything but the frame's cycles (busy, operations, thread time, memory, blocks) */
void cycle_stats_add(cycle_stats *sum, const cycle_stats *s);

/* sum += c */
void rgs_counters_add(rgs_counters *sum, const rgs_counters *c);

extern const char *const unit_names[UNIT_KINDS];
extern const char *const op_kind_names[OP_KINDS]; /* the keys of --unit-latency and --stats */
extern const char *const mem_kind_names[MEM_KINDS];

#endif
