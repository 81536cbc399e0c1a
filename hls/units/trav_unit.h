/*
 * Traversal unit (paper section 3, Figure 2: paths b and f; Table 2 and section 4.3: 4 adders,
 * 4 dividers, 13 comparators for a packet of 4 rays).
 *
 * What it does, one operation per call for a packet of 4 rays with per-ray masks:
 *   scene clip    the rays against the scene bounds (the packet's start); rays that miss them
 *                 never enter traversal;
 *   object clip   the object-space rays against an object's bounds, after the transformation
 *                 unit mapped them (path d -> b), and the start of the object's tree;
 *   walk          one step of the level's walk: prune the rays whose closest hit lies before the
 *                 entry, read the node and split (trav_node.h: the per-node datapath) or report a
 *                 leaf (or grid cell) whose list goes to the list unit (list_unit.h). Closest hits
 *                 come back from the intersection unit (path f) through the packet's state.
 * The walk runs one of the traversal algorithms behind one interface (trav_algo.h,
 * docs/traversal.md): the paper's stack, the short stack, kd-restart and push-down
 * (trav_stack.c, trav_restart.c), ropes (trav_ropes.c), uniform grids (trav_grid.c), the cursor
 * walkers sharing trav_cursor.c. The algorithm is the one the trace flags ask for where the
 * memory image holds its structure (accelerator bits), else the stack.
 *
 * Latency 21 cycles (rtl/trav_node.sv: subtractor 6 + divider 11 + min/max 2 + comparator 2; the
 * cycle model's default, docs/cycle-model.md), throughput one operation (node, cell or clip) per
 * cycle and packet (1 issue slot). Operators: the node datapath 4 subtractors, 4 dividers, per ray
 * a min, a max and 2 interval comparators (docs/synth.md: trav_node, 11455 LUTs at e7m16); the
 * clips per ray 6 subtractors, 6 dividers, 3 min, 3 max and 1 comparator (slab test); the prune
 * 4 comparators. The cursor walkers add their own (trav_algo.h).
 * RTL: the per-node datapath rtl/trav_node.sv; the control of the stack algorithm (TRAV_STACK:
 * clips, start, walk with the per-thread stacks, overflow and restart) rtl/trav_unit.sv, a
 * pipeline around one trav_node taking one operation per cycle: latency 38 per walk step (its
 * node read queued), 146 per clip (its slab planes pass the trav_node in turn, so a clip takes 6
 * of its slots, where the figures above count one). The other algorithms have no RTL.
 */
#ifndef SAARCOR_TRAV_UNIT_H
#define SAARCOR_TRAV_UNIT_H

#include "trace.h"

/* Accelerator bits of the image (header word 2, bits 16..; docs/memory-image.md): which
 * structures besides the kd-trees it holds, and whether its kd-trees are compact (flat cells, no
 * stored empty leaves), which the restarting walkers cannot walk: they measure a ray's progress by
 * the cells it leaves. */
enum { ACCEL_ROPES = 1, ACCEL_GRID = 2, ACCEL_TOP_GRID = 4, ACCEL_COMPACT = 8 };
/* The traversal unit's issue slots of a clip (scene or object): its box's 6 slab planes pass
 * trav_node one a cycle (rtl/trav_unit.sv, trav_clip.sv); a kd-tree entry takes one slot. */
#define TRAV_CLIP_SLOTS 6u

#define ACCEL_SHIFT 16

/* Scene clip: each ray's [tmin, tmax] against the scene bounds (6 fp24 words) into [tn, tf];
 * returns the active rays whose interval is not empty. */
uint32_t trav_scene_clip(const uint32_t *bounds, const ray_packet *rays, f24_t tn[TRACE_PACKET], f24_t tf[TRACE_PACKET]);

/* Object clip: the rays in need, in object space (o, d), from tmin to their closest hit best_t,
 * against the object's bounds (6 fp24 words) into [tn, tf] (+Inf, 0 for the others); returns the
 * rays of need whose interval is not empty. */
uint32_t trav_object_clip(const uint32_t *bounds, const f24_vec3 o[], const f24_vec3 d[], const f24_t tmin[],
                          const f24_t best_t[], uint32_t need, f24_t tn[TRACE_PACKET], f24_t tf[TRACE_PACKET]);

/* Starts the walk of a level for the rays in mask with their intervals: the kd-tree at
 * nodes/lists, or the grid whose header is at grid (TRACE_NO_HIT: none), with algorithm asked
 * (TRAV_*) where the image's accelerator bits accel (ACCEL_*) hold its structure, else the stack
 * (also for a restarting walker on compact trees).
 * A grid start reads the grid's header (op). */
void trav_start(trav_walker *w, const uint32_t *mem, uint32_t asked, uint32_t accel, uint32_t nodes, uint32_t lists,
                uint32_t grid, uint32_t mask, const f24_t tn[], const f24_t tf[], const f24_vec3 o[], const f24_vec3 d[],
                unit_op *op, trace_counters *c);

/* One step of the walk (a traversal unit operation, described in op) with the rays that are
 * still traced (alive) and their closest hits so far; returns 1 at a leaf or cell with entries
 * (w->leaf_*: its list range and rays, for the list unit), !w->have_cur when the level is done. */
int trav_walk(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[], const f24_t best_t[],
              uint32_t alive, unit_op *op, trace_counters *c);

#endif
