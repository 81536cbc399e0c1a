/*
 * The ray tracing core for one packet of 4 rays (paper sections 2 and 3, Figure 2): the traversal
 * unit walks the top-level kd-tree, at a top-level leaf the list unit feeds the instances to the
 * transformation unit (world to object space, path d), the traversal unit walks the object's
 * bottom-level tree (path b), and at its leaves the list unit feeds (mailboxed) triangles to the
 * transformation unit (object to unit-triangle space) and the intersection unit (path e), whose
 * results return to the traversal (path f). Closest hit. Reads only the memory image, which
 * mi_validate has checked. Integer-only fp24, bounded loops, no recursion (the two tree levels
 * have their own stacks).
 *
 * As a state machine: trace_state holds one packet's thread state (the prototype's per-thread
 * state: rays, stacks, mailboxes, closest hits), and trace_step performs exactly one operation of
 * one unit and describes it in a unit_op (which unit and kind of operation, how many issue slots,
 * which memory block it read). The functional mode (trace_packet) runs the steps back to back; the cycle model
 * (tb/cycle) times the same steps through pipelined units and caches, so both compute the same
 * bits by construction.
 *
 * Operations (one trace_step each):
 *   traversal unit    clip to the scene bounds (start), clip to an object's bounds (after its
 *                     transformation), or one kd-tree entry: prune rays whose closest hit lies
 *                     before it, read the node, split (4 rays in parallel) or report a leaf;
 *   list unit         one leaf-list entry: read it, check each ray's mailbox;
 *   transformation    an instance's world-to-object map or a triangle's transformation applied to
 *                     the rays that need it (2 steps per ray, n + 1 if all share their origin);
 *   intersection      the rays that need a triangle, one per issue slot.
 * The units' files: trav_unit.h (with its algorithms behind trav_algo.h and the per-node datapath
 * trav_node.h), list_unit.h, xform_unit.h, isect_unit.h; trace.c routes a packet between them.
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

#include "config.h"
#include "f24_held.h"
#include "vec3.h"

#define TRACE_PACKET 4
#if TRACE_PACKET != F24Q_LANES
#error "the units compute the rays of a packet as the lanes of f24q (hls/fp24/f24.h)"
#endif
#define TRACE_STACK 64     /* traversal states per packet and level (the prototype kept 64) */
#define TRACE_MAILBOX 8    /* entries of the per-ray mailbox of the list unit */
#define TRACE_NO_HIT 0xFFFFFFFFu
#define TRACE_STEP_LIMIT (1u << 26) /* bound of the operations of one packet (a valid image needs far fewer) */

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

/* The units of a DynRTP (paper Figure 2). */
enum { UNIT_RGS, UNIT_XFORM, UNIT_TRAV, UNIT_LIST, UNIT_ISECT, UNIT_KINDS };

/* What an operation does on its unit. A unit's operations of different kinds pass hardware
 * pipelines of different depths (the RTL's modules, named below), so the cycle model charges each
 * kind its own latency (docs/cycle-model.md); the kinds are grouped by unit, in the units' order
 * above but the RGS last (op_kind_unit). */
enum {
    OP_RAYGEN,   /* transformation unit: a packet's primary rays, T_init (rtl/rgs_raygen.sv) */
    OP_XFORM,    /* transformation unit: a triangle's directions (rtl/xform_unit.sv) */
    OP_INSTANCE, /* transformation unit: an instance's rays rebased, then in the wide mode (rebase_unit, xform_wide) */
    OP_SHADOW,   /* transformation unit: a light's shadow rays, T_shadow (the RTL forms them in rgs_light) */
    OP_CHILDREN, /* transformation unit: T_R steps of the child rays (the RTL forms them in rgs_spawn) */
    OP_TRAV,     /* traversal unit: the scene clip or a kd-tree entry (rtl/trav_unit.sv) */
    OP_OBJCLIP,  /* traversal unit: an object's clip, its tree's start (trace_thread: the object's record read,
                  * the mailboxes cleared, the relative distances, the clip, the start) */
    OP_LIST,     /* list unit: a leaf-list entry (rtl/list_unit.sv) */
    OP_LEAF,     /* list unit: the entry that opens a bottom-level leaf, its rays through the rebase unit */
    OP_ISECT,    /* intersection unit: a triangle's rays (rtl/isect_unit.sv) */
    OP_SURFACE,  /* RGS: the surfaces of a traced packet (rtl/rgs_surface.sv) */
    OP_LIGHT,    /* RGS: one light at the packet's surfaces, its shadow packet (rtl/rgs_light.sv) */
    OP_ACCUM,    /* RGS: the packet's colours accumulated, its child rays (rtl/rgs_accum.sv) */
    OP_KINDS
};

static inline uint32_t op_kind_unit(uint32_t kind)
{
    return kind >= OP_SURFACE ? UNIT_RGS
         : kind >= OP_ISECT   ? UNIT_ISECT
         : kind >= OP_LIST    ? UNIT_LIST
         : kind >= OP_TRAV    ? UNIT_TRAV
                              : UNIT_XFORM;
}

/* One operation of one unit: its kind, the memory blocks it reads before it issues (word address
 * and count by data type) and the issue slots it occupies. The core's operations read at most 2
 * blocks; the RGS's surface operation up to 15 per ray (rgs.c surface_at: instance, object,
 * shading record, geometric normal, material, and per texture sampled, base colour and
 * emissive, its entry and 4 texels). */
#define UNIT_OP_READS (15 * TRACE_PACKET)
typedef struct {
    uint32_t kind, slots, n_reads; /* its unit: op_kind_unit(kind) */
    uint32_t hits;                 /* a surface operation's rays with a hit: the RGS reads and shades those, a miss
                                    * passes rgs_surface in a cycle (rtl/rgs_surface.sv) */
    struct { uint32_t kind, addr, words; } read[UNIT_OP_READS];
} unit_op;

/* A kd-tree entry of the walk: a node, its rays, and each ray's interval [tn, tf] in it, held as
 * the traversal unit's packet values (f24h, hls/fp24/f24_held.h: fp24 words in the hardware). */
typedef struct {
    uint32_t node, mask;
    f24h tn, tf;
} trav_entry;

/* dst = src field by field: the walk copies the children trav_node_split_held has just written,
 * and a copy of the whole struct would read them in chunks that straddle its separate field
 * stores (on the host, a stalled store-to-load forward each: 5% of a render's time). */
static inline void trav_entry_copy(trav_entry *dst, const trav_entry *src)
{
    dst->node = src->node;
    dst->mask = src->mask;
    f24h_copy(&dst->tn, &src->tn);
    f24h_copy(&dst->tf, &src->tf);
}

/* Traversal algorithms of the traversal unit (docs/traversal.md; make bench-peers compares them):
 * the paper's stack of TRACE_STACK entries; a short stack of TRACE_SHORT_STACK entries that drops
 * its oldest entry when full and restarts when it runs dry after a drop, with push-down (Horn
 * et al. 2007); kd-restart without a stack (Foley and Sugerman 2005); push-down without a stack.
 * A restart walks down again from the root (or the push-down node) with each ray's interval
 * starting where its last leaf ended, excluding cells that end there. The cursor walkers
 * (trav_algo.h, trav_cursor.h) keep a position per ray instead: kd-trees with ropes (Popov et al. 2007); a
 * uniform grid per object with 3D-DDA (Purcell et al. 2002) under the top-level kd-tree; grids at
 * both levels (a two-level grid over the instances, Adinetz and Berezin). A level whose structure
 * the image does not hold (docs/memory-image.md, accelerator bits) is walked with the stack. */
enum { TRAV_STACK, TRAV_SHORT_STACK, TRAV_RESTART, TRAV_PUSH_DOWN, TRAV_ROPES, TRAV_GRID, TRAV_GRID2, TRAV_KINDS };
#define TRACE_SHORT_STACK 4

/* The rays of a packet by axis (lane i: ray i), as the traversal unit holds them for a walk. */
typedef struct {
    f24h o[3], d[3];
} trav_rays;

typedef struct {
    uint32_t nodes, lists; /* word addresses of the tree */
    trav_rays rays;        /* the walk's rays, from its start (the stack family's splits read them) */
    trav_entry stack[TRACE_STACK];
    uint32_t sp;
    trav_entry cur;
    uint32_t have_cur;
    uint32_t leaf_first, leaf_count, leaf_mask, k; /* the current leaf: list range, its rays, next entry */
    f24_t leaf_tn[TRACE_PACKET];               /* where each ray of the current leaf enters it */
    /* restart state (TRAV_SHORT_STACK, _RESTART, _PUSH_DOWN) */
    uint32_t algo, cap, lost, pass, push_down; /* cap: stack entries; lost: an entry was dropped */
    trav_entry root;                           /* where a restart begins: root or push-down node */
    f24_t t_exit[TRACE_PACKET];                /* where each ray's last leaf ended */
    /* cursor walkers (TRAV_ROPES, TRAV_GRID): each ray's node or cell (x | y << 10 | z << 20) */
    uint32_t at[TRACE_PACKET];
    uint32_t stalls[TRACE_PACKET]; /* ropes: leaves left in a row without moving on along the ray */
    f24_t grid_lo[3], grid_size[3], grid_inv[3]; /* grid: origin, cell size and its inverse */
    uint32_t grid_n[3];                          /* grid: cells per axis */
} trav_walker;

typedef struct {
    uint32_t key[TRACE_MAILBOX];
    uint32_t next;
} trace_mailbox;

/* The scene profile's skip bits (memory image, camera word 3; docs/memory-image.md): what the host
 * proved this scene does not need, so that the device skips it with the same image. 0 is the
 * general pipeline. */
enum {
    PROFILE_SINGLE_OBJECT = 1, /* one instance, alone in a one-leaf top-level tree: rays go
                                  straight to its transformation (no top-level traversal, no list) */
    PROFILE_ANY_HIT = 2,       /* shadow rays stop at their first occluder */
    PROFILE_NO_SECONDARY = 4,  /* no material reflects or transmits: no child rays to generate */
    PROFILE_LIVE_CHILDREN = 8, /* T_R steps only for surfaces that spawn a child ray */
    PROFILE_IDENTITY = 16,     /* with SINGLE_OBJECT: its transformation is the identity, skipped */
    PROFILE_ALL = 31
};

/* How a packet is traced: the closest hit, or any hit (a ray is done at its first hit, and the
 * packet drops it); TRACE_SKIP_TOP and TRACE_IDENTITY as PROFILE_SINGLE_OBJECT and _IDENTITY. */
enum { TRACE_SKIP_TOP = 1, TRACE_ANY_HIT = 2, TRACE_IDENTITY = 4 };
#define TRACE_TRAV_SHIFT 4 /* flags bits 4..6: the traversal algorithm (TRAV_*) */
#define TRACE_TRAV_MASK 7u

typedef struct {
    ray_packet rays;
    hit_record hits[TRACE_PACKET];
    uint32_t flags, alive; /* TRACE_* bits; rays still being traced */
    f24_t best_t[TRACE_PACKET];
    uint32_t phase, level;             /* next operation; tree level 0 (top) or 1 (bottom) */
    trav_walker walk[2];
    trace_mailbox box[2][TRACE_PACKET]; /* instances per ray; triangles per ray and instance visit */
    uint32_t inst, obj, tris, tri, need; /* current instance, its object, triangle, rays needing it */
    /* the rays in the current object's space: origins moved to t0 along the ray when it entered the
     * instance, in double words (high words in o, what the traversal walks with), distances at this
     * level from there (best_rel, tmin_rel: best_t and tmin less t0) */
    f24_vec3 o[TRACE_PACKET], d[TRACE_PACKET];
    f24_vec3 o_lo[TRACE_PACKET], d_lo[TRACE_PACKET];
    f24_t t0[TRACE_PACKET], best_rel[TRACE_PACKET], tmin_rel[TRACE_PACKET];
    f24_vec3x2 p[TRACE_PACKET];        /* origins rebased to the current leaf (rebase_unit.h) */
    f24_t te[TRACE_PACKET];            /* the distance they were moved by */
    f24_triangle tx;                   /* the current triangle's record */
} trace_state;

/* The profile word of the memory image. */
uint32_t trace_profile(const uint32_t *mem);

/* The TRACE_* flags for a packet under the profile (shadow: a shadow packet, which needs any hit). */
uint32_t trace_flags_of(uint32_t profile, int shadow);

/* Starts tracing a packet with TRACE_* flags (no unit operation yet). */
void trace_begin(const ray_packet *rays, uint32_t flags, trace_state *s);

/* Performs the next operation and describes it in op; returns 0 (and performs nothing) when the
 * packet is done: the closest hits are in s->hits. */
int trace_step(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c);


/* Functional mode: the whole packet, closest hits (skipping the top level if the profile says so). */
void trace_packet(const uint32_t *mem, const ray_packet *rays, hit_record hits[TRACE_PACKET], trace_counters *c);

#endif
