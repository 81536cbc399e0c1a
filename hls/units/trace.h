/*
 * Functional model of the ray tracing core for one packet of 4 rays (paper sections 2 and 3):
 * the traversal unit walks the top-level kd-tree, at a top-level leaf the list unit feeds the
 * instances to the transformation unit (world to object space), the traversal unit walks the
 * object's bottom-level tree, and at its leaves the list unit feeds (mailboxed) triangles to the
 * transformation unit (object to unit-triangle space) and the intersection unit. Closest hit.
 * Reads only the memory image, which mi_validate has checked. Integer-only fp24, bounded loops,
 * no recursion (the two tree levels have their own stacks).
 *
 * Traversal unit datapath (Table 2: 4 adders, 4 dividers, 13 comparators): per inner node and
 * ray, t_split = (split - O_axis) / D_axis; the near child is chosen by the sign bit of D_axis
 * and the child intervals are [tn, min(tf, t_split)] and [max(tn, t_split), tf]. Zero direction
 * components need no special case: +-Inf and NaN split distances, with signed zeros and
 * minimumNumber/maximumNumber (docs/fp24.md), send the ray only to the side it lies on (both
 * sides if it lies in the plane). Rays of a packet that disagree are followed with per-ray
 * masks; the packet descends into a child if any of its rays needs it.
 */
#ifndef SAARCOR_TRACE_H
#define SAARCOR_TRACE_H

#include <stdint.h>

#include "vec3.h"

#define TRACE_PACKET 4
#define TRACE_STACK 64     /* traversal states per packet and level (the prototype kept 64) */
#define TRACE_MAILBOX 8    /* entries of the per-ray mailbox of the list unit */
#define TRACE_NO_HIT 0xFFFFFFFFu

typedef struct {
    f24_vec3 o[TRACE_PACKET], d[TRACE_PACKET];
    f24_t tmin[TRACE_PACKET], tmax[TRACE_PACKET];
    uint32_t active; /* bit i: ray i is traced */
} ray_packet;

typedef struct {
    uint32_t instance; /* TRACE_NO_HIT for a miss */
    uint32_t triangle; /* index within the object's image triangles */
    f24_t t, u, v, cos_n;
} hit_record;

/* Memory words read, by data type (the prototype's per-type caches): kd nodes, leaf lists,
 * matrices (instance and triangle transformations, object descriptors) and shading data (camera,
 * lights, materials, shading records, texels; uncached). */
enum { MEM_NODES, MEM_LISTS, MEM_MATRICES, MEM_SHADING, MEM_KINDS };

typedef struct {
    uint64_t traversal_steps, leaves, list_entries, mailbox_skips, transformations, intersections;
    uint64_t words[MEM_KINDS];
} trace_counters;

void trace_packet(const uint32_t *mem, const ray_packet *rays, hit_record hits[TRACE_PACKET], trace_counters *c);

#endif
