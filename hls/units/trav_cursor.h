/*
 * Traversal unit, what the cursor walkers share (docs/traversal.md; the walkers: trav_ropes.c,
 * trav_grid.c behind trav_algo.h). Instead of a stack of pending subtrees, every ray of the
 * packet keeps its own position (w->at: a kd node or a grid cell, and w->cur.tn, the distance
 * where it enters it) and the packet does one node or cell per step for the rays that share its
 * first walking ray's position (coherent rays move together; rays that part are served in turn,
 * so no stack is needed at all).
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
 * Latency and throughput as the stack walker (trav_unit.h): one node or cell per step and packet.
 */
#ifndef SAARCOR_TRAV_CURSOR_H
#define SAARCOR_TRAV_CURSOR_H

#include "trace.h"

/* The ray's coordinate on axis k at distance t (1 mul, 1 add). */
f24_t cursor_point_on(f24_vec3 o, f24_vec3 d, f24_t t, uint32_t k);

/* The start of a cursor step: the rays done (alive) or whose closest hit lies before their
 * position leave the walk; returns the rays at the position of the packet's first walking ray
 * (its index in *lead), 0 if none is left. */
uint32_t cursor_group(trav_walker *w, const f24_t best_t[], uint32_t alive, int *lead);

/* Where a ray leaves a cell whose planes in the ray's direction are far[]: the distance and the
 * axis (3: it never leaves, a zero or NaN direction). */
uint32_t cursor_cell_exit(const f24_t far[3], f24_vec3 o, f24_vec3 d, f24_t *t);

/* Moves ray i on to its next position at distance t, or ends its walk (no next position, or its
 * interval ends there). */
void cursor_advance(trav_walker *w, int i, uint32_t next, int has_next, f24_t t);

/* The group's list (leaf or cell) for the list unit; returns 1 if it has entries. */
int cursor_list(trav_walker *w, uint32_t group, uint32_t first, uint32_t count, trace_counters *c);

#endif
