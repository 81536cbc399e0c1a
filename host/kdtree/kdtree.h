/*
 * SAH kd-tree builder (host). One builder serves both levels of the paper's two-level scheme:
 * the bottom level over the triangles of one object (built once: exact SAH over sorted event
 * lists, with perfect splits from triangle-box clipping throughout; optionally binned SAH near the
 * root, see kd_params.exact_max) and the top level over the world-space boxes of the object
 * instances (rebuilt every frame, binned SAH for speed).
 *
 * Primitives are abstract: the caller supplies their bounds and, for perfect splits, a clipping
 * function. Split planes can be snapped to the device's number format (quantize), and primitives
 * are classified against the snapped plane, so the tree stays exact after conversion to fp24.
 *
 * Node layout: nodes[0] is the root; an inner node's children are nodes[child] (below the split)
 * and nodes[child + 1] (above it), with child > the node's own index, so the tree has no cycles
 * and a validator can check that in one pass.
 */
#ifndef SAARCOR_KDTREE_H
#define SAARCOR_KDTREE_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct { double lo[3], hi[3]; } aabb;

/* Primitives for kd_build. Builds of at least 512 primitives (kdtree.c PAR_MIN_COUNT) call
 * bounds and clip from several threads at a time: they must be pure functions (thread-safe). */
typedef struct {
    uint32_t count;
    const void *user;
    /* Bounds of primitive i (finite; lo <= hi). */
    aabb (*bounds)(const void *user, uint32_t i);
    /* Bounds of the part of primitive i inside box; returns 0 if it does not overlap box.
     * NULL: the intersection of bounds(i) with box is used (exact for box primitives). */
    int (*clip)(const void *user, uint32_t i, const aabb *box, aabb *out);
    /* Optional (NULL: clip is called for each half): the parts of primitive i in the two halves of
     * box split at pos on axis, bit for bit what clip gives for each half, into out[0] (below)
     * and out[1] (above); returns bit c set if half c holds a part. Lets the source share the
     * work the halves have in common (kd_clip_triangle_split). */
    int (*clip_split)(const void *user, uint32_t i, const aabb *box, uint32_t axis, double pos, aabb out[2]);
} kd_source;

typedef struct {
    double cost_traversal;     /* C_t: cost of one traversal step, default 1.0 */
    double cost_intersection;  /* C_i: cost of one primitive test, default 1.5 */
    double empty_bonus;        /* a split with an empty side costs (1 - empty_bonus) x, default 0.2 */
    uint32_t max_depth;        /* 0: automatic, 8 + 1.3 log2(count) (pbrt's), at most 64; for at least
                                  shallow_from primitives 5 + log2(count), 6 + log2(count) if binned */
    uint32_t leaf_size;        /* never split a node with at most this many primitives, default 1 */
    uint32_t bins;             /* 0: exact SAH over all events; n > 0: binned SAH with n bins per axis
                                  (at most n: see bin_size) */
    /* Snaps a candidate split position to a representable device value (NULL: no snapping).
     * Must be a pure function: builds of at least 512 primitives use all cores and call it from
     * several threads (the tree is the same as a single-threaded build, bit for bit). */
    double (*quantize)(double split);
    int face_splits;           /* exact mode: flat cells for primitives lying in a face of their node
                                  (default 1); the restarting and rope walkers need 0 (docs/traversal.md) */
    uint32_t shallow_from;     /* see max_depth; 0 (default): never */
    uint32_t exact_max;        /* bins > 0: nodes of at most this many primitives are split as in exact
                                  mode (their subtrees get perfect splits and face cells); 0 (default):
                                  binned throughout */
    uint64_t max_nodes;        /* 0 (default): no limit; else kd_build stops with KD_TOO_MANY_NODES
                                  before the tree would grow past this many nodes (a hard limit is
                                  checked before the memory it bounds is allocated) */
    uint32_t threads;          /* threads of a build of at least 512 primitives: 0 (default):
                                  kd_thread_count(); at most 8 are used. The tree does not depend
                                  on it (callers building several trees at once pass 1) */
    uint64_t *shared_nodes;    /* NULL (default): max_nodes bounds this tree; else a counter (start
                                  it at 0) that the builds given it charge together, concurrently
                                  or not, so that max_nodes bounds the nodes of all of them */
    uint32_t bins_from;        /* bins > 0: only trees of at least this many primitives are binned, smaller
                                  ones are exact throughout; 0 (default): every tree */
    uint32_t bin_size;         /* bins > 0: a binned node of n primitives gets n / bin_size bins per axis,
                                  at least KD_MIN_BINS (or bins if fewer) and at most bins; 0 (default):
                                  bins for every node */
} kd_params;

/* The fewest bins per axis a binned node gets with kd_params.bin_size (as many as Embree's binned
 * BVH builder uses for every node). */
#define KD_MIN_BINS 32u

typedef struct {
    uint32_t axis;   /* 0, 1, 2: inner node split axis; KD_LEAF: leaf */
    uint32_t child;  /* inner: index of the left child, the right child is child + 1 */
    double split;    /* inner: split plane position on axis */
    uint32_t first;  /* leaf: first entry in kd_tree.prims */
    uint32_t count;  /* leaf: number of entries */
} kd_node;

#define KD_LEAF 3u

typedef struct {
    uint32_t n_leaves, n_empty_leaves, depth;
    uint64_t references;       /* sum of leaf counts (primitives are referenced by every leaf they overlap) */
    uint32_t max_leaf_count;
    double sah_cost;           /* C_t * sum_inner SA/SA_root + C_i * sum_leaf count * SA/SA_root */
    double build_seconds;
} kd_stats;

typedef struct {
    kd_node *nodes;
    uint32_t n_nodes;
    uint32_t *prims;           /* leaf lists, concatenated */
    uint32_t n_prims;
    aabb bounds;               /* union of all primitive bounds */
    kd_stats stats;
} kd_tree;

void kd_params_default(kd_params *p);

/* The deepest tree kd_build makes for count primitives with p: p->max_depth, or the automatic
 * depth (the kd-depth limit is checked against it before building, tb/cli/cli_limits.h). */
uint32_t kd_depth_bound(const kd_params *p, uint32_t count);

/* Threads kd_build uses for a large source unless kd_params.threads says: the CPUs the calling
 * thread may run on, at most 8 (the host's other parallel stages use the same budget). */
uint32_t kd_thread_count(void);

#define KD_TOO_MANY_NODES (-2)

/* Builds a tree; 0 on success, -1 if memory ran out, KD_TOO_MANY_NODES if it would pass
 * p->max_nodes (out is then empty). count may be 0. */
int kd_build(const kd_source *src, const kd_params *p, kd_tree *out);

/* Builds the trees out[0..n) of src[i] with p[i] (p[i].threads is not used) together, on
 * `threads` threads (0: kd_thread_count(), at most 8), so that a thread that has finished one
 * tree helps with the subtrees of the others instead of waiting for the last one. Each tree is
 * bit for bit the one kd_build makes; rc[i] is what kd_build would return for it (a tree that
 * fails leaves the others unharmed); stats.build_seconds is the time of the whole call. Returns
 * 0, or -1 if memory ran out before any tree was started (the rc[] are then not set). */
int kd_build_many(const kd_source *src, const kd_params *p, uint32_t n, uint32_t threads, kd_tree *out, int *rc);

void kd_free(kd_tree *t);

/* Clips triangle (a, b, c) to box (Sutherland-Hodgman against the six planes) and returns the
 * bounds of the clipped polygon; 0 if nothing is left. For kd_source.clip of triangle meshes. */
int kd_clip_triangle(const double a[3], const double b[3], const double c[3], const aabb *box, aabb *out);

/* kd_clip_triangle to the halves of box below and above pos on axis, out[0] and out[1], the same
 * bits; returns bit c set if half c holds a part. The planes before the split axis's (the clipping
 * order is x, y, z) are clipped once for both. For kd_source.clip_split. */
int kd_clip_triangle_split(const double a[3], const double b[3], const double c[3], const aabb *box, uint32_t axis,
                           double pos, aabb out[2]);

/* Ropes (Popov et al. 2007): per leaf its box and, per face -x +x -y +y -z +z, the smallest
 * node beyond that face covering all of it, or KD_NO_ROPE on the root box's boundary. */
#define KD_NO_ROPE 0xFFFFFFFFu
typedef struct {
    aabb box;
    uint32_t rope[6];
} kd_rope;

/* Fills out[n] for every leaf n of t (out has t->n_nodes entries; inner nodes' are untouched),
 * with root as the root node's box. */
void kd_ropes(const kd_tree *t, const aabb *root, kd_rope *out);

/* SAH cost of any tree under p (used to compare against baselines in tests). */
double kd_sah_cost(const kd_tree *t, const kd_params *p);

#ifdef __cplusplus
}
#endif

#endif
