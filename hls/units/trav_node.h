/*
 * Traversal unit, per-node decision for a packet of 4 rays (paper section 3; the datapath the
 * RTL module rtl/trav_node.sv builds). For each ray in the entry's mask: the split distance
 * t_split = (split - O_axis) / D_axis, its near side (left when D_axis has no sign bit, so -0
 * counts as negative), and the child intervals near = [tn, min(tf, t_split)] and
 * far = [max(tn, t_split), tf]; a child's mask bit is set when its interval is not empty
 * (tn <= tf). Rays outside the mask get empty intervals [0, 0] and no mask bit.
 * Datapath: 4 subtractors, 4 dividers (Table 2: 4 adders, 4 dividers), per ray a min, a max and
 * two interval comparators (16 comparisons; Table 2 counts 13). Latency 21 cycles
 * (rtl/trav_node.sv: subtractor 6 + divider 11 + min/max 2 + comparator 2), throughput one node
 * per cycle; docs/synth.md: 11455 LUTs at e7m16. Part of the traversal unit (trav_unit.h), used
 * by its stack family (trav_stack.c).
 */
#ifndef SAARCOR_TRAV_NODE_H
#define SAARCOR_TRAV_NODE_H

#include "trace.h"

/* l and r get the children's intervals and masks (node fields untouched); near_left bit i: ray
 * i's near child is the left one. The rays' origins o and directions d as the walk holds them
 * (trav_rays_of). */
void trav_node_split_held(const trav_entry *e, uint32_t axis, f24_t split, const trav_rays *rays, trav_entry *l,
                          trav_entry *r, uint32_t *near_left);

/* The rays by axis. */
void trav_rays_of(trav_rays *rays, const f24_vec3 o[], const f24_vec3 d[]);

/* trav_node_split_held of the rays o, d: the unit's interface for its HLS top and the benches. */
void trav_node_split(const trav_entry *e, uint32_t axis, f24_t split, const f24_vec3 o[], const f24_vec3 d[],
                     trav_entry *l, trav_entry *r, uint32_t *near_left);

#endif
