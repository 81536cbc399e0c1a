/*
 * Cursor walkers of the traversal unit (docs/traversal.md): instead of a stack of pending
 * subtrees, every ray of the packet keeps its own position and the packet does one node or
 * cell per step for the rays that share its first walking ray's position (coherent rays move
 * together; rays that part are served in turn, so no stack is needed at all).
 *
 *   ropes (Popov et al. 2007)   a kd-tree whose leaves carry their box and, per face, a rope to
 *                               the smallest node beyond it. A ray descends from its node to the
 *                               leaf holding its entry point (o + d tn on the split axis: 1 mul,
 *                               1 add, 1 compare), and from a leaf follows the rope of the face it
 *                               leaves by (3 subtractions, 3 divisions, 2 compares).
 *   grid  (Purcell et al. 2002) a uniform grid with 3D-DDA (Amanatides and Woo 1987): the start
 *                               cell from the entry point (3 mul, 6 add, 3 float-to-int), then per
 *                               cell the three far planes lo + (i + 1) size (recomputed from the
 *                               cell index, so no error accumulates along the ray: 3 int-to-float,
 *                               3 mul, 6 add, 3 div, 2 compares) and a step on the nearest one.
 *
 * Both hand the leaf's or cell's list to the list unit with the group's rays, exactly as the
 * stack walker does, and prune a ray when its closest hit lies before its next cell. Memory (all
 * checked by mi_validate): rope records of ROPE_WORDS before each leaf's list entries; a grid
 * header of GRID_WORDS words, cells of 2 words {first, count} into the grid's own lists.
 * Latency and throughput as the stack walker: one node or cell per step and packet.
 */
#ifndef SAARCOR_TRAV_CURSOR_H
#define SAARCOR_TRAV_CURSOR_H

#include "trace.h"

/* Accelerator bits of the image (header word 2, bits 16..; docs/memory-image.md). */
enum { ACCEL_ROPES = 1, ACCEL_GRID = 2, ACCEL_TOP_GRID = 4 };
#define ACCEL_SHIFT 16

/* Rope record: leaf box lo xyz, hi xyz (fp24), ropes -x +x -y +y -z +z (node or TRACE_NO_HIT). */
#define ROPE_WORDS 12
/* Grid header: lo xyz, cell size xyz, 1 / size xyz (fp24), cells per axis (3), cells, lists,
 * list length (read by the validator only). */
enum { G_LO = 0, G_SIZE = 3, G_INV = 6, G_N = 9, G_CELLS = 12, G_LISTS = 13, GRID_WORDS = 14 };
#define GRID_AXIS_BITS 10 /* cell index x | y << 10 | z << 20: at most 1023 cells per axis */
#define GRID_MAX_AXIS ((1u << GRID_AXIS_BITS) - 1u)

/* Starts the cursor walk of w (after walker_start set its rays and intervals): ropes at the
 * root; grid (header at word grid): reads the header and puts each ray into the cell of its
 * entry point. */
void cursor_start(trav_walker *w, const uint32_t *mem, uint32_t grid, const f24_vec3 o[], const f24_vec3 d[],
                  unit_op *op, trace_counters *c);

/* One node or cell for the rays at the first walking ray's position; returns 1 at a leaf or cell
 * with entries (w->leaf_*), !w->have_cur when every ray is done. */
int cursor_step(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[], const f24_t best_t[],
                uint32_t alive, unit_op *op, trace_counters *c);

#endif
