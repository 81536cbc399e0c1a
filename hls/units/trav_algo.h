/*
 * The traversal algorithms of the traversal unit behind one interface (docs/traversal.md): the
 * unit (trav_unit.c) sets up the walker (trav_walker: rays, intervals, stack capacity, restart
 * state) for every algorithm, calls the algorithm's start to place the rays in its structure,
 * and then one step per traversal unit operation (after op_set). A step returns 1 at a leaf or
 * cell with entries (w->leaf_first, leaf_count, leaf_mask, k = 0) and clears w->have_cur when
 * the level is done. The same kd-trees, list, transformation and intersection units serve all.
 *
 *   stack family   trav_stack.c: the walker with a stack of w->cap entries; the paper's stack
 *                  (64), the short stack (4, Horn et al. 2007), kd-restart (0, Foley and
 *                  Sugerman 2005) and push-down (0, Horn et al. 2007). What a dropped entry
 *                  costs, the restart, is trav_restart.c. No start of its own.
 *   ropes          trav_ropes.c (Popov et al. 2007), a cursor walker (trav_cursor.h).
 *   grid           trav_grid.c: a uniform grid with 3D-DDA (Purcell et al. 2002), per object
 *                  or also over the instances (two-level grid), a cursor walker.
 *
 * Cost per step as the stack walker: one node or cell per operation and packet, the latency of
 * the traversal unit (trav_unit.h). Extra operators per ray: ropes 1 mul, 1 add, 1 compare per
 * inner node, 3 sub, 3 div, 2 compares per leaf; grid 3 mul, 6 add, 3 float-to-int at the start,
 * 3 int-to-float, 3 mul, 6 add, 3 div, 2 compares per cell (details in trav_cursor.h).
 */
#ifndef SAARCOR_TRAV_ALGO_H
#define SAARCOR_TRAV_ALGO_H

#include "trace.h"

/* kd node word 0 (docs/memory-image.md): count << 2 | 3 for a leaf, or child << 4 | empty << 2 |
 * axis for an inner node (empty bits 1, 2: the side below / above the split is an empty leaf
 * that is not stored; only in compact trees, never with ropes). */
#define TRAV_NODE_LEAF 3u
#define TRAV_NODE_CHILD_SHIFT 4

/* ---- stack family (TRAV_STACK, TRAV_SHORT_STACK, TRAV_RESTART, TRAV_PUSH_DOWN): trav_stack.c */

/* One kd-tree entry: prune the rays whose closest hit lies before it, then read the node and
 * split (the rays held in w->rays since the start), or report a leaf; then the next entry from
 * the stack, or the restart after a drop. */
int trav_stack_step(trav_walker *w, const uint32_t *mem, const f24_t best_t[], uint32_t alive, unit_op *op,
                    trace_counters *c);

/* The restart (trav_restart.c) for the stack walkers that drop entries (w->cap < TRACE_STACK). */

/* The rays of e whose cell ends where the ray's last leaf ended (w->t_exit: visited already). */
uint32_t trav_restart_done(const trav_walker *w, const trav_entry *e);

/* After a restart, the rays of a child cell that ends where the ray's last leaf ended leave its
 * mask (before any restart, at every inner node, nothing to compare: inline). */
static inline void trav_restart_drop_done(const trav_walker *w, trav_entry *e)
{
    if (w->pass)
        e->mask &= ~trav_restart_done(w, e);
}

/* At a leaf (entry e): extends each ray's covered segment (w->t_exit) if the leaf continues it. */
void trav_restart_leaf(trav_walker *w, const trav_entry *e);

/* The stack ran dry after dropping entries: walk down again from the restart point. */
void trav_restart(trav_walker *w, const f24_t best_t[]);

/* ---- ropes (TRAV_ROPES): trav_ropes.c ----------------------------------------------------- */

/* Every ray at the root. */
void trav_ropes_start(trav_walker *w);

int trav_ropes_step(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[], const f24_t best_t[],
                    uint32_t alive, unit_op *op, trace_counters *c);

/* ---- grid (TRAV_GRID): trav_grid.c ---------------------------------------------------------- */

/* Reads the grid header at word grid and puts each ray into the cell of its entry point. */
void trav_grid_start(trav_walker *w, const uint32_t *mem, uint32_t grid, const f24_vec3 o[], const f24_vec3 d[],
                     unit_op *op, trace_counters *c);

int trav_grid_step(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[], const f24_t best_t[],
                   uint32_t alive, unit_op *op, trace_counters *c);

#endif
