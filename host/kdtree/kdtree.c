/*
 * SAH kd-tree builder (API and node layout: kdtree.h).
 *
 * Cost model (surface area heuristic). Splitting a node with box B at plane q costs
 *     C_t + C_i * (SA(L) / SA(B) * n_L + SA(R) / SA(B) * n_R),
 * times (1 - empty_bonus) if a side is empty; the split is made only if that is cheaper than the
 * leaf cost C_i * n. A node also becomes a leaf if n <= leaf_size or it is at max_depth (root:
 * depth 0; automatic: round(8 + 1.3 log2(count)), or 5 + log2(count) from shallow_from
 * primitives on, 6 + log2(count) if the tree is binned (auto_depth), at most 64). A box of zero
 * area (a segment) uses
 * length ratios instead, the limit of thin boxes. Every split lies strictly inside its node box,
 * except a split on a face of the box that separates the primitives lying flat in that face
 * (consider_face), so no input can loop: recursion ends at max_depth at the latest.
 *
 * Exact mode (bins == 0), after Wald & Havran, "On building fast kd-trees for ray tracing, and
 * on doing that in O(N log N)" (2006). Each primitive contributes per axis a start and an end
 * event at its bounds inside the node (from clip(), "perfect splits"), or one planar event if it
 * is flat on that axis. The three event lists are sorted once at the root (an O(N) radix sort on
 * an order-preserving integer key of the position). A node sweeps them for the cheapest plane;
 * primitives lying in a candidate plane are tried on both sides. Splitting keeps the events of
 * one-sided primitives (still sorted); primitives straddling the plane are clipped to the two
 * child boxes and only their new events are sorted and merged in.
 * Cost: O(N log N) for the sweeps/splits (O(n) per node, O(log N) levels), plus sorting the
 * straddlers' events per node (O(N log^2 N) in the worst case, in practice the straddlers are
 * few). Event counts are 32-bit: at most 2^31 primitives. The passes that classify the events,
 * list the straddlers, split the lists and merge (in sorts and into the children) choose without
 * branches on the data: event types and positions follow no pattern a branch predictor could use
 * (bunny.glb under callgrind: 34.5 -> 23.0 M mispredicted branches per build, 2.47 -> 2.68 G
 * instructions; same trees; about 5% less CPU time on bunny.glb and the gallery).
 *
 * Binned mode (bins > 0, the per-frame top level): candidates are the bins - 1 evenly spaced
 * planes per axis (with bin_size, the bottom level's, a node's own count: a bin per bin_size
 * primitives, KD_MIN_BINS to bins, node_bins). Every primitive is ranked against them exactly
 * (its bin, checked against the neighbouring planes), so the counts are exact at the candidate
 * planes: O(n + bins) per node, O(N log N) total. With a clip function, the primitives straddling
 * the chosen plane are clipped to the child boxes, as in exact mode. Small nodes (at most SMALL_NODE primitives, fewer
 * bounds than planes) use their primitives' own bounds as candidates, counted directly: exact
 * SAH, and cheaper there.
 *
 * Binned with exact subtrees (bins > 0, exact_max > 0, the bottom level): a node of at most
 * exact_max primitives turns its references into sorted events (their clipped bounds) and its
 * subtree is built in exact mode. The bins place the few planes near the root, where the nodes
 * are large and a plane's exact position matters little; the perfect splits and face cells near
 * the leaves, where most nodes and most of the SAH cost are. The sorted event lists are thus
 * only ever as long as exact_max primitives make them.
 *
 * Quantization: each candidate is snapped with params.quantize before it is evaluated, counts are
 * taken against the snapped plane, and candidates not strictly inside the node box after snapping
 * are skipped; primitives are then classified against the snapped plane, so the tree is exact
 * for the planes it stores. quantize should be monotone (any rounding is); exact mode skips a
 * snapped candidate that would move the sweep backwards.
 *
 * Threads: sources of at least PAR_MIN_COUNT primitives are built on params.threads threads (0: all
 * CPUs; at most PAR_MAX_THREADS), in every mode (exact mode also sorts the root's last axis beside
 * the other two): subtrees are built concurrently into separate arrays, which are
 * then merged in a fixed order into exactly the layout of the single-threaded build, so the tree
 * is the same bit for bit, whatever the thread timing. Such a build calls bounds, clip and
 * quantize from several threads at a time: they must be pure functions (thread-safe). If no
 * thread can be started, the calling thread builds alone. kd_build_many puts several trees' roots
 * into one such pool (build_pool): the threads take them in turn, and one that finds none left
 * takes subtrees of the trees still building; each tree is merged into its own layout, the same.
 *
 * Statistics are gathered while building; the SAH cost sums every subtree as its node's term plus
 * (left sum + right sum), so that subtrees built in different threads give the same bits as
 * kd_sah_cost, which sums the same way.
 */
#define _GNU_SOURCE /* clock_gettime, sched_getaffinity */
#include "kdtree.h"
#include "huge_pages.h"

#include <math.h>
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* Event types; the numeric order is the tie-break of events at the same position. */
enum { EV_END, EV_PLANAR, EV_START, EV_TYPES };
/* Where a primitive goes when its node is split. */
enum { SIDE_BOTH, SIDE_LEFT, SIDE_RIGHT };

typedef struct {
    double pos;
    uint32_t prim, type;
} event;

/* Binned mode: nodes of at most this many primitives, and fewer bounds than bin planes, are
 * split with exact SAH counted directly (O(n^2), cheaper than the bins there). */
enum { SMALL_NODE = 16 };

/* Parallel build (see offload): sources with fewer primitives are built single-threaded (thread
 * start-up costs ~20-50 us); only subtrees over at least PAR_GRAIN primitives are handed to
 * another thread; nodes over at least PAR_SPLIT_MIN primitives are counted and split by all
 * threads waiting for work, in PAR_PARTS parts; at most PAR_MAX_THREADS threads (the caller
 * included) and PAR_MAX_TASKS tasks per build. */
enum { PAR_MIN_COUNT = 512, PAR_GRAIN = 64, PAR_SPLIT_MIN = 2048, PAR_PARTS = 8 };
enum { PAR_MAX_THREADS = 8, PAR_MAX_TASKS = 4096 };
_Static_assert((int)PAR_SPLIT_MIN > (int)SMALL_NODE, "nodes split in parts are binned");

typedef struct {
    uint32_t id;
    aabb b; /* bounds of the part of the primitive inside the node */
} prim_ref;

/* The primitives of one node, in the representation of the build mode. */
typedef struct {
    uint32_t n;       /* primitives */
    event *ev[3];     /* exact mode: events per axis, sorted */
    uint32_t n_ev[3];
    size_t ev_bytes;  /* of the block at ev[0] (events_alloc) */
    prim_ref *ref;    /* binned mode */
} prim_set;

typedef struct {
    double cost;
    uint32_t axis;
    double pos;
    int planar_left; /* primitives lying in the plane go to the left child */
} split;

/* Node weights relative to the root: surface area, or length for a segment root, or 1 for a
 * point (or empty) root, which cannot be split anyway. */
typedef enum { MEASURE_AREA, MEASURE_LENGTH, MEASURE_UNIT } measure_kind;

static double half_area(const aabb *b)
{
    const double x = b->hi[0] - b->lo[0], y = b->hi[1] - b->lo[1], z = b->hi[2] - b->lo[2];
    return x * y + y * z + z * x;
}

static double length(const aabb *b) { return (b->hi[0] - b->lo[0]) + (b->hi[1] - b->lo[1]) + (b->hi[2] - b->lo[2]); }

static double measure(measure_kind m, const aabb *b)
{
    return m == MEASURE_AREA ? half_area(b) : m == MEASURE_LENGTH ? length(b) : 1.0;
}

/* The SAH sum of a subtree: C_t * weight of each inner node, C_i * count * weight of each leaf,
 * summed as own term + (left sum + right sum) at every node, so that subtrees built apart add up
 * to the same bits (tree_stats sums the same way). pending: a hole lies below, see pending_sum. */
typedef struct {
    double sum;
    int pending;
} subtree_sum;

/* A node's SAH sum (its term plus its children's sums) that waits for the sums of holes below. */
typedef struct {
    double own, sum[2]; /* sum[c]: of child c, unless pending[c] */
    uint8_t pending[2];
} pending_sum;

/* Parallel build: a subtree handed to another thread, and the place in the handing builder's
 * output where the single-threaded build would have put it (see layout()). */
typedef struct {
    uint32_t node;             /* the subtree's root in the handing builder's nodes */
    uint32_t task;             /* the task building it */
    uint32_t at_node, at_prim; /* n_nodes and n_prims of the handing builder when the subtree was due */
    uint32_t node_off, prim_off; /* layout(): output index - local index after this hole */
} hole;

typedef struct pool pool;

/* The nodes of one tree (all threads' builders), counted before they are allocated; used: the
 * build's own count, or params.shared_nodes (atomic builtins: the API type is plain). */
typedef struct {
    uint64_t *used;
    atomic_int exceeded;
} node_budget;

typedef struct {
    const kd_source *src;
    kd_params p;
    uint32_t max_depth;
    kd_node *nodes;
    uint32_t n_nodes, cap_nodes;
    uint32_t *prims;
    uint32_t n_prims, cap_prims;
    uint8_t *side;    /* exact mode: SIDE_* of each primitive of the node being split */
    event *scratch;   /* exact mode: the straddlers' events (clip_straddlers) */
    uint32_t cap_scratch;
    uint32_t *straddlers; /* exact mode: the straddlers of the node being split (classify lists them) */
    uint32_t cap_straddlers;
    event *kept;      /* exact mode: a node's freed event block, for the next lists that fit (set_keep) */
    size_t kept_bytes;
    double *cand;     /* binned mode: candidate planes of the three axes (planes_of) */
    uint32_t *counts; /* binned mode: 3 axes x count_stride counters */
    measure_kind kind;   /* of SAH weights: measure(kind, node box) / root_measure */
    double root_measure;
    kd_stats st;         /* of the nodes built here: counts, depth (sah_cost: see build_node) */
    pending_sum *pend;   /* parallel build: inner nodes with holes below (count - 1 indexes) */
    uint32_t n_pend, cap_pend;
    pool *pool;       /* parallel build (binned mode): where to hand subtrees; NULL: single-threaded */
    node_budget *budget; /* shared by the tree's builders */
    uint32_t tree;       /* parallel build: the tree of the pool's (kd_build_many) this builder's subtree is in */
    hole *holes;      /* subtrees handed away, in the order they were due */
    uint32_t n_holes, cap_holes, holes_owed; /* owed: handed away, not yet due (room reserved) */
} builder;

/* ---- boxes and cost ------------------------------------------------------------------------ */

/* min/max without fmin's NaN rules, which keep the compiler from inlining it (inputs are finite) */
static double dmin(double a, double b) { return a < b ? a : b; }
static double dmax(double a, double b) { return a > b ? a : b; }

static int box_intersect(const aabb *a, const aabb *b, aabb *out)
{
    for (int k = 0; k < 3; k++) {
        out->lo[k] = dmax(a->lo[k], b->lo[k]);
        out->hi[k] = dmin(a->hi[k], b->hi[k]);
        if (out->lo[k] > out->hi[k])
            return 0;
    }
    return 1;
}

static void box_union(aabb *a, const aabb *b)
{
    for (int k = 0; k < 3; k++) {
        a->lo[k] = dmin(a->lo[k], b->lo[k]);
        a->hi[k] = dmax(a->hi[k], b->hi[k]);
    }
}

static int strictly_inside(const aabb *box, uint32_t k, double q) { return q > box->lo[k] && q < box->hi[k]; }

/* SAH terms of the candidates on one axis of a node. The probabilities that a ray hitting the
 * box hits its parts below and above q are surface area ratios; a box without area (then only
 * the split axis has extent) uses length ratios. Either way p = (base + d * slope) * inv, d the
 * child's extent on the axis. */
typedef struct {
    uint32_t axis;
    double lo, hi, base, slope, inv;
    double ct, ci, empty; /* C_t, C_i, 1 - empty_bonus */
} axis_terms;

static axis_terms terms_of(const builder *b, const aabb *box, uint32_t k)
{
    const uint32_t u = (k + 1) % 3, v = (k + 2) % 3;
    const double eu = box->hi[u] - box->lo[u], ev = box->hi[v] - box->lo[v], d = box->hi[k] - box->lo[k];
    axis_terms t = { k, box->lo[k], box->hi[k], eu * ev, eu + ev, 0.0,
                     b->p.cost_traversal, b->p.cost_intersection, 1.0 - b->p.empty_bonus };
    const double half_area = t.base + d * t.slope;
    if (half_area > 0) {
        t.inv = 1.0 / half_area;
    } else {
        t.base = 0.0;
        t.slope = 1.0;
        t.inv = d > 0 ? 1.0 / d : 0.0; /* d == 0: no candidate lies strictly inside anyway */
    }
    return t;
}

static double split_cost(const axis_terms *t, double pl, double pr, uint32_t nl, uint32_t nr)
{
    const double c = t->ct + t->ci * (pl * nl + pr * nr);
    return nl == 0 || nr == 0 ? c * t->empty : c;
}

/* A plane on a face of the node box that np of its n primitives lie in (walls, floors and table
 * tops at the edge of their node): the flat cell on the face takes those, the rest keeps the
 * whole box. Rays then meet the flat primitives only where they reach the face, instead of in
 * every leaf along the face; a strictly interior plane can never separate them. The flat side
 * has no volume, so it is never split again on this axis, and the other side holds fewer
 * primitives than the node (none if all lie in the face: an empty cell the rays skip): the
 * recursion still ends (at max_depth at the latest). */
static void consider_face(const axis_terms *t, double q, uint32_t np, uint32_t n, split *best)
{
    if (np == 0)
        return;
    const int at_lo = q == t->lo;
    const double flat = t->base * t->inv, whole = 1.0;
    const double c = split_cost(t, at_lo ? flat : whole, at_lo ? whole : flat, at_lo ? np : n - np, at_lo ? n - np : np);
    if (c < best->cost)
        *best = (split){ c, t->axis, q, at_lo };
}

/* Pairs of doubles (GCC and Clang vector extension, SSE2 on x86-64); a comparison gives -1 (true)
 * or 0 in each lane. */
typedef double v2d __attribute__((vector_size(16)));
typedef long long v2l __attribute__((vector_size(16)));

/* The costs of candidates a and b of consider_chunk (a == b: the last of an odd count) with the
 * primitives in the plane on the left, side by side: each lane the same binary64 operations in the
 * same order as split_cost (an empty side scales the cost by 1 - empty_bonus, a non-empty one by
 * 1, which is exact). */
static inline v2d pair_costs(const axis_terms *t, const double *q, const uint32_t *nl, const uint32_t *np,
                             const uint32_t *nr, uint32_t a, uint32_t b)
{
    const v2d x = { q[a], q[b] };
    const v2d l = { (double)(nl[a] + np[a]), (double)(nl[b] + np[b]) }, r = { (double)nr[a], (double)nr[b] };
    const v2d pl = (t->base + (x - t->lo) * t->slope) * t->inv;
    const v2d pr = (t->base + (t->hi - x) * t->slope) * t->inv;
    const v2l empty = (l == 0.0) | (r == 0.0);
    const v2d one = { 1.0, 1.0 }, scaled = { t->empty, t->empty };
    return (t->ct + t->ci * (pl * l + pr * r)) * (v2d)(((v2l)scaled & empty) | ((v2l)one & ~empty));
}

/* The candidates q[0..m) in order, m <= CHUNK, with nl primitives below, np in the plane and nr
 * above: the primitives in the plane go to the cheaper side; best keeps the cheapest candidate (the
 * first one on ties). The costs of all candidates first, two at a time and without branches, so
 * that they pipeline. */
enum { CHUNK = 32 };
static void consider_chunk(const axis_terms *t, const double *q, const uint32_t *nl, const uint32_t *np,
                           const uint32_t *nr, uint32_t m, split *best)
{
    double cost[CHUNK];
    for (uint32_t j = 0; j < m; j += 2) {
        const uint32_t b = j + 1 < m ? j + 1 : j;
        const v2d c = pair_costs(t, q, nl, np, nr, j, b);
        cost[j] = c[0];
        cost[b] = c[1];
    }
    for (uint32_t j = 0; j < m; j++) {
        double c = cost[j];
        int planar_left = 1;
        if (np[j]) { /* rare: primitives in the plane, try them on the right too */
            const double pl = (t->base + (q[j] - t->lo) * t->slope) * t->inv;
            const double pr = (t->base + (t->hi - q[j]) * t->slope) * t->inv;
            const double right = split_cost(t, pl, pr, nl[j], nr[j] + np[j]);
            planar_left = c <= right;
            c = planar_left ? c : right;
        }
        if (c < best->cost)
            *best = (split){ c, t->axis, q[j], planar_left };
    }
}

static double snap(const builder *b, double x) { return b->p.quantize ? b->p.quantize(x) : x; }

/* Side of a primitive whose part in the node spans [lo, hi] on the split axis. */
static int side_of(double lo, double hi, const split *sp)
{
    if (lo == sp->pos && hi == sp->pos)
        return sp->planar_left ? SIDE_LEFT : SIDE_RIGHT;
    if (hi <= sp->pos)
        return SIDE_LEFT;
    if (lo >= sp->pos)
        return SIDE_RIGHT;
    return SIDE_BOTH;
}

/* Bounds of the part of primitive id inside box; 0 if there is none. outer: bounds of the
 * primitive already known (NULL: ask the source), used when there is no clip function. The
 * result is clamped to box so that rounding in clip() cannot leave the node. */
static int part_in_box(const builder *b, uint32_t id, const aabb *outer, const aabb *box, aabb *out)
{
    aabb part;
    if (b->src->clip) {
        if (!b->src->clip(b->src->user, id, box, &part))
            return 0;
    } else {
        part = outer ? *outer : b->src->bounds(b->src->user, id);
    }
    return box_intersect(&part, box, out);
}

/* The parts of primitive id in the halves lb, rb of a node box (lb->hi[axis] == rb->lo[axis]), as
 * part_in_box gives them, into out[0..1]; returns bit c set if half c holds a part. One call of the
 * source's clip_split where it has one (the halves' common planes clipped once). */
static int parts_in_halves(const builder *b, uint32_t id, const aabb *outer, uint32_t axis, const aabb *lb,
                           const aabb *rb, aabb out[2])
{
    const aabb *const half[2] = { lb, rb };
    int mask = 0;
    if (b->src->clip_split) {
        aabb box = *lb, part[2];
        box.hi[axis] = rb->hi[axis];
        const int m = b->src->clip_split(b->src->user, id, &box, axis, lb->hi[axis], part);
        for (int c = 0; c < 2; c++)
            mask |= ((m >> c & 1) && box_intersect(&part[c], half[c], &out[c])) << c;
        return mask;
    }
    for (int c = 0; c < 2; c++)
        mask |= part_in_box(b, id, outer, half[c], &out[c]) << c;
    return mask;
}

/* ---- output arrays ------------------------------------------------------------------------- */

/* p with room for need elements of size bytes: p itself, or p reallocated to twice the need.
 * NULL if memory or the 32-bit index range runs out (p is then unchanged). */
static void *reserve(void *p, uint32_t *cap, uint64_t need, size_t size)
{
    if (need <= *cap)
        return p;
    if (need > UINT32_MAX)
        return NULL;
    const uint64_t c = need > UINT32_MAX / 2 ? UINT32_MAX : 2 * need;
    void *q = huge_pages_realloc(p, (size_t)c * size);
    if (q)
        *cap = (uint32_t)c;
    return q;
}

/* Counts k new nodes of the tree against p.max_nodes: 0, or -1 (and the budget marked
 * exceeded) if they would pass it. */
static int charge_nodes(builder *b, uint32_t k)
{
    if (b->p.max_nodes == 0 || __atomic_fetch_add(b->budget->used, k, __ATOMIC_RELAXED) + k <= b->p.max_nodes)
        return 0;
    atomic_store(&b->budget->exceeded, 1);
    return -1;
}

/* k nodes at the end of the builder's array: 0, or -1 (memory, or the node budget). A handed
 * subtree's root (charged: false) is the handing builder's node, already counted. */
static int add_nodes(builder *b, uint32_t k, int charged, uint32_t *first)
{
    if (charged && charge_nodes(b, k) != 0)
        return -1;
    kd_node *n = reserve(b->nodes, &b->cap_nodes, (uint64_t)b->n_nodes + k, sizeof *n);
    if (!n)
        return -1;
    b->nodes = n;
    *first = b->n_nodes;
    b->n_nodes += k;
    return 0;
}

/* The output arrays of a builder of n primitives, with room for about as many nodes and leaf
 * entries as its trees take (gallery_ccby_503k.glb: 2.6 nodes and 3.9 entries per triangle; at most
 * p.max_nodes nodes): grown by doubling from one node, each array had been copied into a new block
 * about 20 times, and the kernel zeroes a new block's pages at their first touch (2% of the
 * gallery's CPU samples). Room the tree does not use is never touched. Where that much address
 * space is refused, the arrays start small and grow as before. 0, or -1 (memory). */
static int output_alloc(builder *b, uint64_t n)
{
    const uint64_t nodes = b->p.max_nodes && b->p.max_nodes < 2 * n + 1 ? b->p.max_nodes : 2 * n + 1;
    b->nodes = reserve(NULL, &b->cap_nodes, nodes, sizeof *b->nodes); /* reserve: twice that */
    b->prims = reserve(NULL, &b->cap_prims, 3 * n + 1, sizeof *b->prims);
    if (!b->nodes)
        b->nodes = reserve(NULL, &b->cap_nodes, 1, sizeof *b->nodes);
    if (!b->prims)
        b->prims = reserve(NULL, &b->cap_prims, n + 1, sizeof *b->prims);
    return b->nodes && b->prims ? 0 : -1;
}

/* Writes leaf node `node` with a list of n entries at the end of prims; returns the list to fill. */
static uint32_t *new_leaf(builder *b, uint32_t node, uint32_t n)
{
    uint32_t *p = reserve(b->prims, &b->cap_prims, (uint64_t)b->n_prims + n, sizeof *p);
    if (!p)
        return NULL;
    b->prims = p;
    /* child (0 in a finished tree): how many holes came before the list, for copy_nodes() */
    b->nodes[node] = (kd_node){ KD_LEAF, b->n_holes, 0.0, b->n_prims, n };
    b->n_prims += n;
    return p + b->nodes[node].first;
}

/* ---- exact mode: event lists ---------------------------------------------------------------- */

/* a if take_a, else b, without a branch: which one follows no pattern (the merges), and at -O3
 * the compiler made the conditional expression a branch (bunny.glb under callgrind: 2.1 M more
 * mispredicted branches). A conditional move on x86-64; elsewhere the addresses masked. */
static inline event *pick(event *a, event *b, int take_a)
{
#if defined(__x86_64__) && defined(__GNUC__)
    __asm__("test %2, %2\n\tcmovne %1, %0" : "+r"(b) : "r"(a), "r"(take_a) : "cc");
    return b;
#else
    const uintptr_t mask = (uintptr_t)0 - (uintptr_t)(take_a != 0);
    return (event *)(((uintptr_t)a & mask) | ((uintptr_t)b & ~mask));
#endif
}

/* Events at the same position are ordered by type, then primitive: one 64-bit comparison. */
static uint64_t event_key(const event *e) { return (uint64_t)e->type << 32 | e->prim; }

static int event_less(const event *a, const event *b)
{
    return (a->pos < b->pos) | ((a->pos == b->pos) & (event_key(a) < event_key(b))); /* no branches */
}

/* Sorts e[0..n) by event_less: merge sort, insertion sort below 16 events; tmp has room for n / 2
 * events. (No two events are equal: a primitive has at most one event of each type per axis.) */
static void sort_events(event *e, uint32_t n, event *tmp)
{
    if (n <= 16) {
        for (uint32_t i = 1; i < n; i++) {
            const event x = e[i];
            uint32_t j = i;
            for (; j > 0 && event_less(&x, &e[j - 1]); j--)
                e[j] = e[j - 1];
            e[j] = x;
        }
        return;
    }
    const uint32_t h = n / 2;
    sort_events(e, h, tmp);
    sort_events(e + h, n - h, tmp);
    if (!event_less(&e[h], &e[h - 1]))
        return; /* already in order: common for the clipped parts of a few straddlers */
    memcpy(tmp, e, h * sizeof *e);
    uint32_t i = 0, j = h, o = 0; /* o < j: the merge never overtakes the right half it reads */
    while (i < h && j < n) { /* the first of the two selected without a branch */
        const int right = event_less(&e[j], &tmp[i]);
        e[o++] = *pick(&e[j], &tmp[i], right);
        j += (uint32_t)right;
        i += (uint32_t)!right;
    }
    memcpy(e + o, tmp + i, (h - i) * sizeof *e);
}

/* Room for per_axis events on each axis, in one block at ev[0], and one spare (no size is 0,
 * distribute() writes one entry past the events it keeps, and sweep_axis puts a sentinel there):
 * the block b keeps if it is large enough (b may be NULL), else a new one. */
static int events_alloc(builder *b, prim_set *s, size_t per_axis)
{
    s->ev_bytes = 3 * (per_axis + 1) * sizeof(event);
    if (b && b->kept && b->kept_bytes >= s->ev_bytes) {
        s->ev[0] = b->kept;
        s->ev_bytes = b->kept_bytes;
        b->kept = NULL;
    } else if (!(s->ev[0] = huge_pages_malloc(s->ev_bytes))) {
        return -1;
    }
    s->ev[1] = s->ev[0] + per_axis + 1;
    s->ev[2] = s->ev[1] + per_axis + 1;
    return 0;
}

/* Appends the events of a primitive whose part in the node has bounds `part`, to ev[0..2] at
 * n[0..2] (advanced). */
static void put_events(event *const ev[3], uint32_t n[3], uint32_t id, const aabb *part)
{
    for (int a = 0; a < 3; a++) {
        event *e = ev[a] + n[a];
        if (part->lo[a] == part->hi[a]) {
            e[0] = (event){ part->lo[a], id, EV_PLANAR };
            n[a] += 1;
        } else {
            e[0] = (event){ part->lo[a], id, EV_START };
            e[1] = (event){ part->hi[a], id, EV_END };
            n[a] += 2;
        }
    }
}

/* The sweep's two counts in one word: an event adds to the high half if its primitive starts (or
 * lies) there, to the low half if it ends (or lies) there. Neither half passes 2^31 (primitives). */
static const uint64_t sweep_count[EV_TYPES] = { [EV_END] = 1, [EV_PLANAR] = 1ull << 32 | 1, [EV_START] = 1ull << 32 };

/* Candidates of sweep_axis waiting for consider_chunk. */
typedef struct {
    double q[CHUNK];
    uint32_t nl[CHUNK], np[CHUNK], nr[CHUNK], m;
} chunk;

static void chunk_flush(const axis_terms *t, chunk *c, split *best)
{
    consider_chunk(t, c->q, c->nl, c->np, c->nr, c->m, best);
    c->m = 0;
}

/* Sweeps the events of axis k; candidates are the snapped event positions, and the counts at a
 * candidate q come from a second pointer that has passed every event below q. The candidates are
 * costed in chunks in their order (consider_chunk), a face candidate after the chunk before it, so
 * that best is the first cheapest one, as if each were considered on its own. */
static void sweep_axis(const builder *b, const prim_set *s, const aabb *box, uint32_t k, split *best)
{
    event *const ev = s->ev[k];
    const uint32_t m = s->n_ev[k], n = s->n;
    ev[m].pos = INFINITY; /* in the spare entry (events_alloc): the second pointer stops there, not past m */
    const axis_terms t = terms_of(b, box, k);
    const double lo = box->lo[k], hi = box->hi[k]; /* in locals: quantize could change *box, for all the compiler knows */
    const int faces = b->p.face_splits && hi > lo;
    uint64_t below = 0; /* sweep_count of the events below the candidate */
    uint32_t j = 0;
    double last = -INFINITY, prev = NAN; /* no position equals NAN */
    chunk c;
    c.m = 0;
    for (uint32_t i = 0; i < m; i++) {
        const double x = ev[i].pos;
        if (x == prev)
            continue;
        prev = x;
        const double q = snap(b, x);
        const int inside = q > lo && q < hi, face = !inside && faces && (q == lo || q == hi);
        if (!(q > last) || !(inside || face))
            continue;
        last = q;
        while (ev[j].pos < q) /* q is finite */
            below += sweep_count[ev[j++].type];
        uint64_t at = 0;
        uint32_t planar = 0;
        for (; ev[j].pos == q; j++) {
            at += sweep_count[ev[j].type];
            planar += ev[j].type == EV_PLANAR;
        }
        const uint32_t nl = (uint32_t)(below >> 32), nr = n - (uint32_t)below - (uint32_t)at;
        below += at;
        if (face) {
            chunk_flush(&t, &c, best);
            consider_face(&t, q, planar, n, best);
            continue;
        }
        c.q[c.m] = q;
        c.nl[c.m] = nl;
        c.np[c.m] = planar;
        c.nr[c.m] = nr;
        if (++c.m == CHUNK)
            chunk_flush(&t, &c, best);
    }
    chunk_flush(&t, &c, best);
}

/* Primitives of a node by where they go. */
typedef struct {
    uint32_t left, right, both;
} side_counts;

/* Sets b->side for the primitives of s from their events on the split axis (a primitive's start
 * comes before its end): a start at or above the plane means right only, an end at or below it
 * left only, the rest straddles; a planar event goes by side_of. Lists the straddlers, in the
 * order of their end events, in straddlers (room for s->n + 1). Without branches on the events'
 * types and positions, which follow no pattern. */
static side_counts classify(builder *b, const prim_set *s, const split *sp, uint32_t *straddlers)
{
    const event *ev = s->ev[sp->axis];
    const uint32_t m = s->n_ev[sp->axis];
    const double q = sp->pos;
    const uint8_t in_plane = sp->planar_left ? SIDE_LEFT : SIDE_RIGHT;
    uint32_t left = 0, right = 0, both = 0;
    for (uint32_t i = 0; i < m; i++) {
        const double x = ev[i].pos;
        const uint32_t t = ev[i].type;
        const uint32_t prim = ev[i].prim;
        uint8_t *side = &b->side[prim];
        const uint8_t planar = x == q ? in_plane : x < q ? SIDE_LEFT : SIDE_RIGHT;
        const uint8_t start = x >= q ? SIDE_RIGHT : SIDE_BOTH;
        const uint8_t end = x <= q ? SIDE_LEFT : *side; /* above: as its start said */
        const uint8_t by_type[EV_TYPES] = { [EV_END] = end, [EV_PLANAR] = planar, [EV_START] = start };
        const uint8_t v = by_type[t];
        *side = v;
        left += (t != EV_START) & (v == SIDE_LEFT); /* counted at the end (or planar) event */
        right += (t != EV_END) & (v == SIDE_RIGHT); /* at the start (or planar) event */
        straddlers[both] = prim;                     /* listed at the end event, where the side is final */
        both += (t == EV_END) & (v == SIDE_BOTH);
    }
    return (side_counts){ left, right, both };
}

/* Where the straddlers' events for child c on axis a go in b->scratch (nb straddlers). */
static event *clipped_events(const builder *b, uint32_t nb, int c, int a)
{
    return b->scratch + (3 * (size_t)c + (size_t)a) * 2 * nb;
}

/* The events of the nb straddlers list[0..nb)' parts in the child boxes cb[0..1], sorted, at
 * clipped_events(b, nb, c, a), k[c][a] of them; kept[c]: straddlers with a part in child c. The
 * straddlers' order does not matter: no two of their events are equal in the sort's order. */
static int clip_straddlers(builder *b, const uint32_t *list, const split *sp, const aabb *const cb[2], uint32_t nb,
                           uint32_t k[2][3], uint32_t kept[2])
{
    /* 2 nb events per child and axis, and nb to sort with */
    event *scratch = reserve(b->scratch, &b->cap_scratch, 13 * (uint64_t)nb + 1, sizeof *scratch);
    if (!scratch)
        return -1;
    b->scratch = scratch;
    event *ev[2][3];
    for (int c = 0; c < 2; c++)
        for (int a = 0; a < 3; a++)
            ev[c][a] = clipped_events(b, nb, c, a);
    for (uint32_t i = 0; i < nb; i++) {
        aabb part[2];
        const int in = parts_in_halves(b, list[i], NULL, sp->axis, cb[0], cb[1], part);
        for (int c = 0; c < 2; c++)
            if (in >> c & 1) {
                put_events(ev[c], k[c], list[i], &part[c]);
                kept[c]++;
            }
    }
    if (nb > 1) /* one straddler's events are in order: a start below its end, or one planar event */
        for (int c = 0; c < 2; c++)
            for (int a = 0; a < 3; a++)
                sort_events(ev[c][a], k[c][a], scratch + 12 * (size_t)nb);
    return 0;
}

/* The events of one axis for both children: the one-sided events of ev[0..n) in their order, each
 * child's merged with its sorted straddler events add[c][0..k[c]), into out[c] (m[c] events; one
 * spare entry). First every event is written to the child it belongs to (after room for the
 * straddlers' events; a straddler's to the left child's next entry, which the next event there
 * overwrites), then the merge runs in place (its write index never passes its read index); both
 * without branches on the data. */
static void distribute(const builder *b, const event *ev, uint32_t n, event *const add[2], const uint32_t k[2],
                       event *const out[2], uint32_t m[2])
{
    uint32_t o[2] = { k[0], k[1] };
    for (uint32_t i = 0; i < n; i++) {
        const int side = b->side[ev[i].prim];
        *pick(out[1] + o[1], out[0] + o[0], side == SIDE_RIGHT) = ev[i]; /* one store */
        o[0] += side == SIDE_LEFT;
        o[1] += side == SIDE_RIGHT;
    }
    for (int c = 0; c < 2; c++) {
        event *const e = out[c];
        event *const a = add[c];
        uint32_t i = k[c], j = 0, w = 0; /* w = (i - k) + j < i while j < k */
        while (j < k[c] && i < o[c]) {
            const int first = event_less(&a[j], &e[i]);
            e[w++] = *pick(&a[j], &e[i], first);
            j += (uint32_t)first;
            i += (uint32_t)!first;
        }
        memcpy(e + w, a + j, (k[c] - j) * sizeof *e); /* j == k: the rest is in place already */
        m[c] = o[c];
    }
}

static int split_events(builder *b, const prim_set *s, const split *sp, const aabb *lb, const aabb *rb,
                        prim_set *l, prim_set *r)
{
    uint32_t *list = reserve(b->straddlers, &b->cap_straddlers, (uint64_t)s->n + 1, sizeof *list);
    if (!list)
        return -1;
    b->straddlers = list;
    const side_counts n = classify(b, s, sp, list);
    const aabb *const cb[2] = { lb, rb };
    uint32_t k[2][3] = { { 0, 0, 0 }, { 0, 0, 0 } }, kept[2] = { 0, 0 };
    if (clip_straddlers(b, list, sp, cb, n.both, k, kept))
        return -1;
    prim_set *const child[2] = { l, r };
    const uint32_t one_sided[2] = { n.left, n.right };
    for (int c = 0; c < 2; c++) {
        uint32_t most = 0; /* straddler events on any axis */
        for (int a = 0; a < 3; a++)
            most = k[c][a] > most ? k[c][a] : most;
        if (events_alloc(b, child[c], 2 * (size_t)one_sided[c] + most))
            return -1;
        child[c]->n = one_sided[c] + kept[c];
    }
    for (int a = 0; a < 3; a++) {
        event *const add[2] = { clipped_events(b, n.both, 0, a), clipped_events(b, n.both, 1, a) };
        event *const out[2] = { l->ev[a], r->ev[a] };
        const uint32_t ka[2] = { k[0][a], k[1][a] };
        uint32_t m[2];
        distribute(b, s->ev[a], s->n_ev[a], add, ka, out, m);
        l->n_ev[a] = m[0];
        r->n_ev[a] = m[1];
    }
    return 0;
}

/* Order-preserving integer key of an event position: key(x) < key(y) iff x < y, for finite x, y;
 * -0 and +0, equal positions, get the same key. */
static uint64_t pos_key(double x)
{
    x += 0.0; /* -0 + +0 = +0 */
    uint64_t k;
    memcpy(&k, &x, sizeof k);
    return k ^ ((uint64_t)((int64_t)k >> 63) | 1ull << 63); /* negative: all bits flipped; else the sign bit set */
}

/* Sorts e[0..n) by position, stably: LSD radix sort over pos_key, a byte a pass, skipping the
 * bytes all keys share; tmp has room for n events. O(n), without the comparisons' mispredicted
 * branches: the root's lists are the longest of the build. */
static void radix_sort_events(event *e, uint32_t n, event *tmp)
{
    if (n == 0)
        return;
    uint32_t hist[8][256];
    memset(hist, 0, sizeof hist);
    for (uint32_t i = 0; i < n; i++) {
        const uint64_t k = pos_key(e[i].pos);
        for (int d = 0; d < 8; d++)
            hist[d][k >> 8 * d & 255]++;
    }
    event *src = e, *dst = tmp;
    const uint64_t k0 = pos_key(e[0].pos);
    for (int d = 0; d < 8; d++) {
        uint32_t *h = hist[d];
        if (h[k0 >> 8 * d & 255] == n)
            continue; /* every key has this byte */
        for (uint32_t v = 0, sum = 0; v < 256; v++) { /* counts to first indexes */
            const uint32_t c = h[v];
            h[v] = sum;
            sum += c;
        }
        for (uint32_t i = 0; i < n; i++)
            dst[h[pos_key(src[i].pos) >> 8 * d & 255]++] = src[i];
        event *const t = src;
        src = dst;
        dst = t;
    }
    if (src != e)
        memcpy(e, src, n * sizeof *e);
}

/* The root's events of axis a from the primitives' bounds bx[0..n), written by type, then
 * primitive, and sorted stably by position: event_less order. tmp: room for 2 n events. */
static void root_axis(const aabb *bx, uint32_t n, int a, prim_set *s, event *tmp)
{
    event *e = s->ev[a];
    uint32_t m = 0;
    for (uint32_t type = EV_END; type < EV_TYPES; type++)
        for (uint32_t i = 0; i < n; i++) {
            const int flat = bx[i].lo[a] == bx[i].hi[a];
            if (flat ? type == EV_PLANAR : type != EV_PLANAR)
                e[m++] = (event){ type == EV_END ? bx[i].hi[a] : bx[i].lo[a], i, type };
        }
    s->n_ev[a] = m;
    radix_sort_events(e, m, tmp);
}

typedef struct {
    const aabb *bx;
    uint32_t n;
    prim_set *s;
    event *tmp;
} root_axis_job;

static void *root_last_axis(void *arg)
{
    const root_axis_job *j = arg;
    root_axis(j->bx, j->n, 2, j->s, j->tmp);
    return NULL;
}

/* Root set: bounds of every primitive (no clipping needed: they lie in the root box) and the
 * events of the three axes. With threads > 1 the last axis is sorted on a thread of its own (the
 * axes are independent; the root's lists are the build's longest and run before any other work
 * can), with its own scratch list. */
static int root_events(const builder *b, prim_set *s, aabb *root, uint32_t threads)
{
    const uint32_t n = b->src->count;
    const size_t scratch = 2 * (size_t)n + 1, lists = threads > 1 ? 2 : 1;
    aabb *bx = huge_pages_malloc(((size_t)n + 1) * sizeof *bx);
    event *tmp = huge_pages_malloc(lists * scratch * sizeof *tmp);
    if (!bx || !tmp || events_alloc(NULL, s, 2 * (size_t)n)) {
        free(bx);
        free(tmp);
        return -1;
    }
    for (uint32_t i = 0; i < n; i++) {
        bx[i] = b->src->bounds(b->src->user, i);
        box_union(root, &bx[i]);
    }
    root_axis_job last = { bx, n, s, tmp + (lists - 1) * scratch };
    pthread_t tid;
    const int beside = lists > 1 && pthread_create(&tid, NULL, root_last_axis, &last) == 0;
    for (int a = 0; a < 2; a++)
        root_axis(bx, n, a, s, tmp);
    if (beside)
        pthread_join(tid, NULL);
    else
        root_last_axis(&last);
    s->n = n;
    free(bx);
    free(tmp);
    return 0;
}

/* Leaf list in the order of the events on axis 0 (one start or planar event per primitive). */
static int leaf_from_events(builder *b, uint32_t node, const prim_set *s)
{
    uint32_t *out = new_leaf(b, node, s->n);
    if (!out)
        return -1;
    for (uint32_t i = 0; i < s->n_ev[0]; i++)
        if (s->ev[0][i].type != EV_END)
            *out++ = s->ev[0][i].prim;
    return 0;
}

/* ---- binned mode ---------------------------------------------------------------------------- */

/* Snapped boundaries of `bins` bins of axis k strictly inside box, sorted and distinct, into
 * c[0..m) (m <= bins - 1), returns m; c[-1] and c[m] get the sentinels -inf and +inf, which every
 * position is above and below (rank_of). */
static uint32_t bin_planes(const builder *b, const aabb *box, uint32_t k, uint32_t bins, double *c)
{
    const double w = (box->hi[k] - box->lo[k]) / bins;
    uint32_t m = 0;
    int sorted = 1; /* c[0..m) sorted and distinct so far */
    c[-1] = -INFINITY;
    for (uint32_t j = 1; j < bins; j++) {
        const double q = snap(b, box->lo[k] + j * w);
        const double last = (c + m)[-1]; /* -inf while m = 0 */
        if (!strictly_inside(box, k, q) || q == last)
            continue;
        if (q > last) { /* the rule when quantize is monotone */
            c[m++] = q;
            continue;
        }
        sorted = 0;
        uint32_t i = m++; /* insertion sort */
        for (; i > 0 && c[i - 1] > q; i--)
            c[i] = c[i - 1];
        c[i] = q;
    }
    uint32_t u = m;
    if (!sorted) /* a planes lying out of order may repeat an earlier one */
        for (uint32_t i = u = 0; i < m; i++)
            if (u == 0 || c[i] != c[u - 1])
                c[u++] = c[i];
    c[u] = INFINITY;
    return u;
}

/* Number of planes c[0..m) below x (c < x), or at most x if inclusive. */
static inline int below(double c, double x, int inclusive) { return inclusive ? c <= x : c < x; }

/* The same by binary search. */
static uint32_t rank_search(const double *c, uint32_t m, double x, int inclusive)
{
    uint32_t lo = 0, hi = m;
    while (lo < hi) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (below(c[mid], x, inclusive))
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* The same, trying first the bin of x, floor(f) (f >= 0: parts lie in the node box; at most m,
 * given as fm = m too), which is the answer unless snapping moved planes; c has bin_planes'
 * sentinels at c[-1] and c[m]. */
static inline uint32_t rank_of(const double *c, uint32_t m, double fm, double x, int inclusive, double f)
{
    const uint32_t g = (uint32_t)dmin(f, fm); /* f NaN (an axis without extent): m */
    if (below((c + g)[-1], x, inclusive) && !below(c[g], x, inclusive))
        return g;
    return rank_search(c, m, x, inclusive);
}

/* Bins per axis of a binned node of n primitives: n / bin_size, at least KD_MIN_BINS and at most
 * bins (all bins if bin_size is 0). Few bins are enough where few primitives are: a node's cost is
 * dominated by its bins' planes (snapped, counted and costed on three axes) unless it has many
 * more primitives than planes, while the nodes near the root, where a plane's position weighs
 * most, get the most bins (docs/memory-image.md: 16 primitives a bin, 32 to 256 bins). */
static uint32_t node_bins(const kd_params *p, uint32_t n)
{
    const uint32_t least = p->bins < KD_MIN_BINS ? p->bins : KD_MIN_BINS;
    const uint32_t want = p->bin_size ? n / p->bin_size : p->bins;
    return want < least ? least : want > p->bins ? p->bins : want;
}

/* The bin planes of a binned node: axis k's at c[k][0..m[k]) with bin_planes' sentinels. */
typedef struct {
    double *c[3];
    uint32_t m[3];
} plane_set;

/* Counters per axis: starts, ends and planar primitives at up to bins - 1 planes (count_planes). */
static size_t count_stride(const builder *b) { return 3 * ((size_t)b->p.bins + 1); }

/* plane_set of a node (box, n primitives) in cand, which has room for 3 (bins + 1) values. */
static plane_set planes_of(const builder *b, const aabb *box, uint32_t n, double *cand)
{
    plane_set ps;
    const uint32_t bins = node_bins(&b->p, n);
    for (uint32_t k = 0; k < 3; k++) {
        ps.c[k] = cand + k * ((size_t)b->p.bins + 1) + 1;
        ps.m[k] = bin_planes(b, box, k, bins, ps.c[k]);
    }
    return ps;
}

/* Exact counts at the planes ps of the three axes, of primitives [from, to) of s, added to the
 * counters at ns + k stride for axis k: starts at ns, ends at ne = ns + m + 1, planar at ne + m + 1
 * (m = ps.m[k]). A primitive with rank s = #(planes <= lo) is left of planes s, s+1, ...; with
 * e = #(planes < hi) it is right of planes 0..e-1; a flat primitive lying in plane s-1 is in
 * neither and counted as planar there. All axes in one pass over the references: a large node's
 * list is read once, not three times. */
static void count_planes(const prim_set *s, uint32_t from, uint32_t to, const aabb *box, const plane_set *ps,
                         uint32_t *counts, size_t stride)
{
    double scale[3], fm[3]; /* planes per unit length; planes */
    for (uint32_t k = 0; k < 3; k++) {
        scale[k] = (ps->m[k] + 1) / (box->hi[k] - box->lo[k]);
        fm[k] = ps->m[k];
    }
    for (uint32_t i = from; i < to; i++)
        for (uint32_t k = 0; k < 3; k++) {
            const double *c = ps->c[k];
            const uint32_t m = ps->m[k];
            uint32_t *ns = counts + k * stride, *ne = ns + m + 1, *np = ne + m + 1;
            const double lo = s->ref[i].b.lo[k], hi = s->ref[i].b.hi[k];
            const uint32_t rs = rank_of(c, m, fm[k], lo, 1, (lo - box->lo[k]) * scale[k]);
            ns[rs]++;
            ne[rank_of(c, m, fm[k], hi, 0, (hi - box->lo[k]) * scale[k])]++;
            if (lo == hi && (c + rs)[-1] == lo) /* (never the sentinel -inf: rs > 0) */
                np[rs - 1]++;
        }
}

/* The candidates c[0..m) of axis k with the counts of count_planes over all of s. */
static void eval_planes(const builder *b, const prim_set *s, const aabb *box, uint32_t k, const double *c, uint32_t m,
                        const uint32_t *ns, split *best)
{
    const uint32_t *ne = ns + m + 1, *np = ne + m + 1;
    const axis_terms t = terms_of(b, box, k);
    uint32_t nl[CHUNK], nr[CHUNK], below = 0, ended = 0;
    for (uint32_t j0 = 0; j0 < m; j0 += CHUNK) {
        const uint32_t n = m - j0 < CHUNK ? m - j0 : CHUNK;
        for (uint32_t j = 0; j < n; j++) {
            below += ns[j0 + j];
            ended += ne[j0 + j];
            nl[j] = below;
            nr[j] = s->n - ended;
        }
        consider_chunk(&t, c + j0, nl, np + j0, nr, n, best);
    }
}

/* The bin planes of all three axes, counted exactly (in one pass) and tried axis by axis. */
static void binned_split(const builder *b, const prim_set *s, const aabb *box, split *best)
{
    const plane_set ps = planes_of(b, box, s->n, b->cand);
    const size_t stride = count_stride(b);
    for (uint32_t k = 0; k < 3; k++)
        memset(b->counts + k * stride, 0, 3 * ((size_t)ps.m[k] + 1) * sizeof *b->counts);
    count_planes(s, 0, s->n, box, &ps, b->counts, stride);
    for (uint32_t k = 0; k < 3; k++)
        if (ps.m[k] > 0)
            eval_planes(b, s, box, k, ps.c[k], ps.m[k], b->counts + k * stride, best);
}

/* Small nodes (SMALL_NODE): exact SAH over the snapped bounds of their primitives, counted two
 * primitives at a time. */
static void small_axis(const builder *b, const prim_set *s, const aabb *box, uint32_t k, split *best)
{
    const axis_terms t = terms_of(b, box, k);
    /* the bounds on axis k in pairs, padded with an entry on no side of any plane */
    v2d lo[SMALL_NODE / 2], hi[SMALL_NODE / 2];
    const uint32_t nv = (s->n + 1) / 2;
    for (uint32_t i = 0; i < 2 * nv; i++) {
        lo[i / 2][i % 2] = i < s->n ? s->ref[i].b.lo[k] : INFINITY;
        hi[i / 2][i % 2] = i < s->n ? s->ref[i].b.hi[k] : -INFINITY;
    }
    double q[2 * SMALL_NODE];
    uint32_t nl[2 * SMALL_NODE], np[2 * SMALL_NODE], nr[2 * SMALL_NODE], m = 0;
    for (uint32_t j = 0; j < 2 * s->n; j++) {
        q[m] = snap(b, j % 2 ? s->ref[j / 2].b.hi[k] : s->ref[j / 2].b.lo[k]);
        if (!strictly_inside(box, k, q[m]))
            continue;
        const v2d qv = { q[m], q[m] };
        v2l l = { 0, 0 }, r = l, side = l;
        for (uint32_t i = 0; i < nv; i++) {
            const v2l left = lo[i] < qv, right = hi[i] > qv;
            l -= left;
            r -= right;
            side -= left | right;
        }
        nl[m] = (uint32_t)(l[0] + l[1]);
        np[m] = s->n - (uint32_t)(side[0] + side[1]); /* the others lie in the plane: lo >= q >= hi */
        nr[m++] = (uint32_t)(r[0] + r[1]);
    }
    consider_chunk(&t, q, nl, np, nr, m, best);
}

/* Appends primitive pr (side: SIDE_*) to the children l, r it goes to; a straddler clipped to
 * their boxes lb, rb. */
static void keep_sides(const builder *b, prim_set *l, prim_set *r, const prim_ref *pr, int side, uint32_t axis,
                       const aabb *lb, const aabb *rb)
{
    if (side != SIDE_BOTH) {
        prim_set *c = side == SIDE_LEFT ? l : r;
        c->ref[c->n++] = *pr;
        return;
    }
    aabb part[2];
    const int in = parts_in_halves(b, pr->id, &pr->b, axis, lb, rb, part);
    if (in & 1)
        l->ref[l->n++] = (prim_ref){ pr->id, part[0] };
    if (in & 2)
        r->ref[r->n++] = (prim_ref){ pr->id, part[1] };
}

static int split_refs_parallel(const builder *b, const prim_set *s, const split *sp, const aabb *lb, const aabb *rb,
                               prim_set *l, prim_set *r);

static int split_refs(const builder *b, const prim_set *s, const split *sp, const aabb *lb, const aabb *rb,
                      prim_set *l, prim_set *r)
{
    if (b->pool && s->n >= PAR_SPLIT_MIN)
        return split_refs_parallel(b, s, sp, lb, rb, l, r);
    size_t nl = 0, nr = 0;
    for (uint32_t i = 0; i < s->n; i++) {
        const int side = side_of(s->ref[i].b.lo[sp->axis], s->ref[i].b.hi[sp->axis], sp);
        nl += side != SIDE_RIGHT;
        nr += side != SIDE_LEFT;
    }
    l->ref = huge_pages_malloc((nl + 1) * sizeof *l->ref);
    r->ref = huge_pages_malloc((nr + 1) * sizeof *r->ref);
    if (!l->ref || !r->ref)
        return -1;
    for (uint32_t i = 0; i < s->n; i++) {
        const prim_ref *pr = &s->ref[i];
        keep_sides(b, l, r, pr, side_of(pr->b.lo[sp->axis], pr->b.hi[sp->axis], sp), sp->axis, lb, rb);
    }
    return 0;
}

static int root_refs(const builder *b, prim_set *s, aabb *root)
{
    if (!(s->ref = huge_pages_malloc(((size_t)b->src->count + 1) * sizeof *s->ref)))
        return -1;
    for (uint32_t i = 0; i < b->src->count; i++) {
        s->ref[i] = (prim_ref){ i, b->src->bounds(b->src->user, i) };
        box_union(root, &s->ref[i].b);
    }
    s->n = b->src->count;
    return 0;
}

static int leaf_from_refs(builder *b, uint32_t node, const prim_set *s)
{
    uint32_t *out = new_leaf(b, node, s->n);
    if (!out)
        return -1;
    for (uint32_t i = 0; i < s->n; i++)
        out[i] = s->ref[i].id;
    return 0;
}

/* ---- recursion ------------------------------------------------------------------------------ */

static void set_free(prim_set *s)
{
    free(s->ev[0]); /* the block of all three axes (events_alloc) */
    free(s->ref);
    memset(s, 0, sizeof *s);
}

/* Blocks of events up to this size are kept for reuse: the exact subtrees' many small nodes
 * otherwise cost a malloc and a free each (larger blocks are few, and huge-page blocks). */
enum { KEEP_MAX_BYTES = 1 << 20 };

/* set_free, but s's event block kept in b for the next events_alloc if it is small and larger than
 * the one b keeps (which is then freed). */
static void set_keep(builder *b, prim_set *s)
{
    if (s->ev[0] && s->ev_bytes <= KEEP_MAX_BYTES && (!b->kept || b->kept_bytes < s->ev_bytes)) {
        free(b->kept);
        b->kept = s->ev[0];
        b->kept_bytes = s->ev_bytes;
        s->ev[0] = NULL;
    }
    set_free(s);
}

static int binned(const builder *b) { return b->p.bins > 0; }

/* Whether the builder may meet nodes in exact mode's representation (events). */
static int sweeps(const builder *b) { return b->p.bins == 0 || b->p.exact_max > 0; }

/* Whether s holds binned mode's representation (primitive references) rather than events. */
static int has_refs(const prim_set *s) { return s->ref != NULL; }

/* Turns the references of s into exact mode's sorted events (binned mode, at most exact_max
 * primitives: the subtree from here on is built as in exact mode). */
static int refs_to_events(builder *b, prim_set *s)
{
    prim_set e = { .n = s->n };
    event *tmp = reserve(b->scratch, &b->cap_scratch, (uint64_t)s->n + 1, sizeof *tmp); /* half of 2n */
    if (!tmp)
        return -1;
    b->scratch = tmp;
    if (events_alloc(b, &e, 2 * (size_t)s->n))
        return -1;
    for (uint32_t i = 0; i < s->n; i++)
        put_events(e.ev, e.n_ev, s->ref[i].id, &s->ref[i].b);
    for (int a = 0; a < 3; a++)
        sort_events(e.ev[a], e.n_ev[a], tmp);
    set_free(s);
    *s = e;
    return 0;
}

static int find_split_parallel(const builder *b, const prim_set *s, const aabb *box, split *best);

static void find_split(const builder *b, const prim_set *s, const aabb *box, split *best)
{
    /* large binned nodes (never small ones) in parts on several threads, unless memory ran out */
    if (b->pool && has_refs(s) && s->n >= PAR_SPLIT_MIN && find_split_parallel(b, s, box, best) == 0)
        return;
    if (has_refs(s) && !(s->n <= SMALL_NODE && 2 * s->n < node_bins(&b->p, s->n) - 1)) {
        binned_split(b, s, box, best);
        return;
    }
    for (uint32_t k = 0; k < 3; k++) {
        if (!has_refs(s))
            sweep_axis(b, s, box, k, best);
        else
            small_axis(b, s, box, k, best);
    }
}

/* ---- parallel build: handing subtrees to other threads --------------------------------------- *
 *
 * The source's functions and quantize are pure (kdtree.h), so subtrees can be built
 * concurrently. Every thread of a pool runs tasks: a task builds one subtree into its own builder
 * (nodes, leaf lists; scratch while it runs). A builder splitting a node while a
 * thread of the pool waits for work hands the larger child (at least PAR_GRAIN primitives) to a
 * new task and leaves a hole there. Afterwards layout() and copy_nodes() merge the outputs of all
 * tasks into the layout of the single-threaded build, so the tree does not depend on the number
 * of threads or their timing: it is bit-identical to the single-threaded one. Large nodes (the
 * root) of binned mode are counted and split by several threads in parts (pool_for), again with
 * the same result. */

/* Node marking a hole while a builder runs; child is the task. */
#define KD_HOLE 4u

typedef struct {
    builder b;  /* output: the subtree at b.nodes[0] */
    aabb box;
    prim_set s; /* freed by the build */
    uint32_t depth;
    subtree_sum sum; /* of the subtree */
    int started;     /* 0: a tree's root whose primitive set start() has yet to make (kd_build_many) */
    uint32_t out_root, out_first, out_first_prim; /* layout(): where nodes 0, 1 and prims[0] go */
} task;

typedef void (*for_fn)(void *ctx, uint32_t i);

struct pool {
    pthread_mutex_t mu;
    pthread_cond_t cv;   /* any change: a task or loop item to run, one finished, shutdown */
    atomic_uint changes; /* counts the changes, for waiting threads that spin before they sleep */
    task **tasks;        /* [0, n_trees): the trees' roots; [next, n_tasks): waiting to run */
    uint32_t n_tasks, next, max_tasks;
    uint32_t unfinished; /* tasks not yet finished: when 0, the build is over */
    uint32_t idle;       /* threads waiting for work */
    uint8_t *failed;     /* per tree: a task of it failed, its remaining tasks only free their input */
    int shutdown;        /* the threads other than the caller return */
    /* one parallel loop at a time (pool_for): items [for_next, for_n) wait, for_left unfinished */
    for_fn fn;
    void *ctx;
    uint32_t for_next, for_n, for_left;
    int for_busy;
};

/* A change of the pool's state (made with pl->mu locked): wakes the waiting threads. */
static void notify(pool *pl)
{
    atomic_fetch_add_explicit(&pl->changes, 1, memory_order_release);
    pthread_cond_broadcast(&pl->cv);
}

static double now(void);

/* Waits for a change (called and returns with pl->mu locked; the caller checks what changed).
 * Waking a sleeping thread takes ~20 us, more than handing it most pieces of work would gain,
 * so it watches for a change for up to SPIN_SECONDS first. */
#define SPIN_SECONDS 100e-6
static void wait_change(pool *pl)
{
    const unsigned seen = atomic_load_explicit(&pl->changes, memory_order_relaxed);
    pthread_mutex_unlock(&pl->mu);
    const double t0 = now();
    int changed = 0;
    for (unsigned i = 1; !changed; i++) {
        changed = atomic_load_explicit(&pl->changes, memory_order_acquire) != seen;
        if (i % 64 == 0 && now() - t0 > SPIN_SECONDS)
            break;
    }
    pthread_mutex_lock(&pl->mu);
    if (!changed && atomic_load_explicit(&pl->changes, memory_order_relaxed) == seen)
        pthread_cond_wait(&pl->cv, &pl->mu);
}

/* Runs the next loop item; called and returns with pl->mu locked. */
static void run_item(pool *pl)
{
    const uint32_t i = pl->for_next++;
    const for_fn fn = pl->fn;
    void *ctx = pl->ctx;
    pthread_mutex_unlock(&pl->mu);
    fn(ctx, i);
    pthread_mutex_lock(&pl->mu);
    if (--pl->for_left == 0)
        notify(pl);
}

/* fn(ctx, i) for i in [0, n), on this thread and those of the pool that wait for work or become
 * free meanwhile; while another loop runs, on this thread alone. */
static void pool_for(pool *pl, uint32_t n, for_fn fn, void *ctx)
{
    pthread_mutex_lock(&pl->mu);
    if (pl->for_busy || n < 2) {
        pthread_mutex_unlock(&pl->mu);
        for (uint32_t i = 0; i < n; i++)
            fn(ctx, i);
        return;
    }
    pl->for_busy = 1;
    pl->fn = fn;
    pl->ctx = ctx;
    pl->for_next = 0;
    pl->for_n = pl->for_left = n;
    notify(pl);
    while (pl->for_next < pl->for_n)
        run_item(pl);
    while (pl->for_left > 0)
        wait_change(pl);
    pl->for_busy = 0;
    pl->for_n = pl->for_next = 0;
    pthread_mutex_unlock(&pl->mu);
}

/* Binned SAH of a large node, counted in parts by the waiting threads: the same counts, the same
 * candidates in the same order as binned_split(), so the same split. */
typedef struct {
    const prim_set *s;
    const aabb *box;
    plane_set ps;
    size_t stride;    /* counters per axis (count_stride) */
    uint32_t *counts; /* PAR_PARTS x 3 axes x stride */
} count_job;

static void count_part(void *arg, uint32_t i)
{
    const count_job *j = arg;
    const uint64_t n = j->s->n;
    count_planes(j->s, (uint32_t)(n * i / PAR_PARTS), (uint32_t)(n * (i + 1) / PAR_PARTS), j->box, &j->ps,
                 j->counts + 3 * (size_t)i * j->stride, j->stride);
}

static int find_split_parallel(const builder *b, const prim_set *s, const aabb *box, split *best)
{
    count_job j = { s, box, { { NULL, NULL, NULL }, { 0, 0, 0 } }, count_stride(b), NULL };
    j.counts = calloc(PAR_PARTS * 3 * j.stride, sizeof *j.counts);
    if (!j.counts)
        return -1;
    j.ps = planes_of(b, box, s->n, b->cand);
    pool_for(b->pool, PAR_PARTS, count_part, &j);
    for (uint32_t k = 0; k < 3; k++) {
        if (j.ps.m[k] == 0)
            continue;
        uint32_t *sum = j.counts + k * j.stride;
        for (uint32_t i = 1; i < PAR_PARTS; i++)
            for (size_t c = 0; c < 3 * ((size_t)j.ps.m[k] + 1); c++)
                sum[c] += j.counts[(3 * (size_t)i + k) * j.stride + c];
        eval_planes(b, s, box, k, j.ps.c[k], j.ps.m[k], sum, best);
    }
    free(j.counts);
    return 0;
}

/* split_refs() of a large node in parts by the waiting threads: each part counts its primitives
 * on each side, then copies them to its range of the children's lists, which are then closed up
 * (a clipped part may come out empty): the same lists in the same order. */
typedef struct {
    const builder *b;
    const prim_set *s;
    const split *sp;
    const aabb *lb, *rb;
    prim_set *l, *r;
    uint32_t nl[PAR_PARTS], nr[PAR_PARTS];     /* per part: entries for the children, then kept */
    uint32_t offl[PAR_PARTS], offr[PAR_PARTS]; /* where the part's entries start */
} split_job;

static void side_part(void *arg, uint32_t i)
{
    split_job *j = arg;
    const uint64_t n = j->s->n;
    uint32_t nl = 0, nr = 0;
    for (uint32_t e = (uint32_t)(n * i / PAR_PARTS); e < (uint32_t)(n * (i + 1) / PAR_PARTS); e++) {
        const int side = side_of(j->s->ref[e].b.lo[j->sp->axis], j->s->ref[e].b.hi[j->sp->axis], j->sp);
        nl += side != SIDE_RIGHT;
        nr += side != SIDE_LEFT;
    }
    j->nl[i] = nl;
    j->nr[i] = nr;
}

static void copy_part(void *arg, uint32_t i)
{
    split_job *j = arg;
    const uint64_t n = j->s->n;
    prim_set l = { .ref = j->l->ref + j->offl[i] }, r = { .ref = j->r->ref + j->offr[i] };
    for (uint32_t e = (uint32_t)(n * i / PAR_PARTS); e < (uint32_t)(n * (i + 1) / PAR_PARTS); e++) {
        const prim_ref *pr = &j->s->ref[e];
        keep_sides(j->b, &l, &r, pr, side_of(pr->b.lo[j->sp->axis], pr->b.hi[j->sp->axis], j->sp), j->sp->axis, j->lb,
                   j->rb);
    }
    j->nl[i] = l.n;
    j->nr[i] = r.n;
}

/* Moves the parts of c (at off[i], n[i] entries each) together. */
static void close_up(prim_set *c, const uint32_t *off, const uint32_t *n)
{
    c->n = 0;
    for (uint32_t i = 0; i < PAR_PARTS; i++) {
        if (off[i] != c->n && n[i] > 0)
            memmove(c->ref + c->n, c->ref + off[i], n[i] * sizeof *c->ref);
        c->n += n[i];
    }
}

static int split_refs_parallel(const builder *b, const prim_set *s, const split *sp, const aabb *lb, const aabb *rb,
                               prim_set *l, prim_set *r)
{
    split_job j = { .b = b, .s = s, .sp = sp, .lb = lb, .rb = rb, .l = l, .r = r };
    pool_for(b->pool, PAR_PARTS, side_part, &j);
    size_t nl = 0, nr = 0;
    for (uint32_t i = 0; i < PAR_PARTS; i++) {
        j.offl[i] = (uint32_t)nl;
        j.offr[i] = (uint32_t)nr;
        nl += j.nl[i];
        nr += j.nr[i];
    }
    l->ref = huge_pages_malloc((nl + 1) * sizeof *l->ref);
    r->ref = huge_pages_malloc((nr + 1) * sizeof *r->ref);
    if (!l->ref || !r->ref)
        return -1;
    pool_for(b->pool, PAR_PARTS, copy_part, &j);
    close_up(l, j.offl, j.nl);
    close_up(r, j.offr, j.nr);
    return 0;
}

/* Hands primitives s of a child (box, depth) to a new task if a thread is waiting for work; s is
 * then the task's. Returns the task, or UINT32_MAX if the caller builds the child itself. */
static uint32_t offload(builder *b, const aabb *box, prim_set *s, uint32_t depth)
{
    pool *pl = b->pool;
    pthread_mutex_lock(&pl->mu);
    const int wanted = pl->idle > pl->n_tasks - pl->next && pl->n_tasks < pl->max_tasks && !pl->failed[b->tree];
    pthread_mutex_unlock(&pl->mu);
    if (!wanted)
        return UINT32_MAX;
    hole *h = reserve(b->holes, &b->cap_holes, (uint64_t)b->n_holes + b->holes_owed + 1, sizeof *h);
    if (!h)
        return UINT32_MAX;
    b->holes = h;
    task *t = calloc(1, sizeof *t);
    if (t) {
        t->b = (builder){ .src = b->src, .p = b->p, .max_depth = b->max_depth, .kind = b->kind,
                          .root_measure = b->root_measure, .pool = pl, .budget = b->budget, .tree = b->tree };
        uint32_t root;
        if (output_alloc(&t->b, s->n) != 0 || add_nodes(&t->b, 1, 0, &root) != 0) {
            free(t->b.prims);
            free(t->b.nodes);
            free(t);
            t = NULL;
        }
    }
    if (!t)
        return UINT32_MAX;
    t->box = *box;
    t->s = *s;
    t->depth = depth;
    t->started = 1;
    memset(s, 0, sizeof *s);
    pthread_mutex_lock(&pl->mu);
    const uint32_t id = pl->n_tasks++;
    pl->tasks[id] = t;
    pl->unfinished++;
    notify(pl);
    pthread_mutex_unlock(&pl->mu);
    b->holes_owed++;
    return id;
}

/* The subtree at node, handed to task, is due now: where the single-threaded build would start it. */
static void add_hole(builder *b, uint32_t node, uint32_t task_id)
{
    b->nodes[node] = (kd_node){ KD_HOLE, task_id, 0.0, 0, 0 };
    b->holes[b->n_holes++] = (hole){ node, task_id, b->n_nodes, b->n_prims, 0, 0 };
    b->holes_owed--;
}

static int build_node(builder *b, uint32_t node, const aabb *box, prim_set *s, uint32_t depth, subtree_sum *sum);

/* Builds children child and child + 1 (boxes lb, rb, primitives l, r), one of them perhaps in
 * another thread. */
static int build_children(builder *b, uint32_t child, const aabb *lb, const aabb *rb, prim_set *l, prim_set *r,
                          uint32_t depth, subtree_sum sum[2])
{
    if (b->pool) {
        const int right = r->n > l->n;
        if ((right ? r : l)->n >= PAR_GRAIN) {
            const uint32_t t = offload(b, right ? rb : lb, right ? r : l, depth);
            sum[right] = (subtree_sum){ 0.0, 1 };
            if (t != UINT32_MAX && !right) {
                add_hole(b, child, t);
                return build_node(b, child + 1, rb, r, depth, &sum[1]);
            }
            if (t != UINT32_MAX) {
                if (build_node(b, child, lb, l, depth, &sum[0]) != 0)
                    return -1;
                add_hole(b, child + 1, t);
                return 0;
            }
        }
    }
    if (build_node(b, child, lb, l, depth, &sum[0]) != 0) {
        set_free(r);
        return -1;
    }
    return build_node(b, child + 1, rb, r, depth, &sum[1]);
}

/* Builds node `node` (already allocated) over s, which it frees; adds its subtree to b->st and
 * returns its SAH sum in *sum. */
static int build_node(builder *b, uint32_t node, const aabb *box, prim_set *s, uint32_t depth, subtree_sum *sum)
{
    const double weight = measure(b->kind, box) / b->root_measure;
    split best = { INFINITY, 0, 0.0, 0 };
    if (depth > b->st.depth)
        b->st.depth = depth;
    const int try_split = s->n > b->p.leaf_size && depth < b->max_depth;
    if (try_split && has_refs(s) && s->n <= b->p.exact_max && refs_to_events(b, s) != 0) {
        set_free(s);
        return -1;
    }
    if (try_split)
        find_split(b, s, box, &best);
    if (!(best.cost < b->p.cost_intersection * s->n)) {
        const uint32_t n = s->n;
        b->st.n_leaves++;
        b->st.n_empty_leaves += n == 0;
        b->st.references += n;
        if (n > b->st.max_leaf_count)
            b->st.max_leaf_count = n;
        *sum = (subtree_sum){ b->p.cost_intersection * n * weight, 0 };
        const int rc = has_refs(s) ? leaf_from_refs(b, node, s) : leaf_from_events(b, node, s);
        set_keep(b, s);
        return rc;
    }
    aabb lb = *box, rb = *box;
    lb.hi[best.axis] = rb.lo[best.axis] = best.pos;
    prim_set l = { 0 }, r = { 0 };
    uint32_t child = 0;
    int rc = has_refs(s) ? split_refs(b, s, &best, &lb, &rb, &l, &r) : split_events(b, s, &best, &lb, &rb, &l, &r);
    set_keep(b, s); /* before recursing: the parent's lists are the largest */
    if (rc == 0)
        rc = add_nodes(b, 2, 1, &child);
    if (rc != 0) {
        set_free(&l);
        set_free(&r);
        return -1;
    }
    b->nodes[node] = (kd_node){ best.axis, child, best.pos, 0, 0 };
    subtree_sum cs[2];
    if (build_children(b, child, &lb, &rb, &l, &r, depth + 1, cs) != 0)
        return -1;
    const double own = b->p.cost_traversal * weight;
    if (!cs[0].pending && !cs[1].pending) {
        *sum = (subtree_sum){ own + (cs[0].sum + cs[1].sum), 0 };
        return 0;
    }
    pending_sum *ps = reserve(b->pend, &b->cap_pend, (uint64_t)b->n_pend + 1, sizeof *ps);
    if (!ps)
        return -1;
    b->pend = ps;
    ps[b->n_pend++] = (pending_sum){ own, { cs[0].sum, cs[1].sum }, { (uint8_t)cs[0].pending, (uint8_t)cs[1].pending } };
    b->nodes[node].count = b->n_pend; /* until copy_nodes() */
    *sum = (subtree_sum){ 0.0, 1 };
    return 0;
}

/* ---- parallel build: threads and merging --------------------------------------------------- */

/* The scratch arrays of the modes b may meet: bin planes and counters, each primitive's side and
 * the straddlers' events (these grow on demand). 0, or -1 if memory ran out. */
static int scratch_alloc(builder *b)
{
    if (binned(b)) {
        b->cand = malloc(3 * ((size_t)b->p.bins + 1) * sizeof *b->cand);
        b->counts = malloc(3 * count_stride(b) * sizeof *b->counts);
        if (!b->cand || !b->counts)
            return -1;
    }
    if (sweeps(b) && !(b->side = malloc((size_t)b->src->count + 1)))
        return -1;
    return 0;
}

static void scratch_free(builder *b)
{
    free(b->cand);
    free(b->counts);
    free(b->side);
    free(b->scratch);
    free(b->straddlers);
    free(b->kept);
    b->cand = NULL;
    b->counts = NULL;
    b->side = NULL;
    b->scratch = NULL;
    b->cap_scratch = 0;
    b->straddlers = NULL;
    b->cap_straddlers = 0;
    b->kept = NULL;
}

static void task_free(task *t)
{
    set_free(&t->s);
    free(t->b.nodes);
    free(t->b.prims);
    scratch_free(&t->b);
    free(t->b.holes);
    free(t->b.pend);
    memset(&t->b, 0, sizeof t->b);
}

static int start(builder *b, prim_set *s, aabb *root, uint32_t threads);
static measure_kind measure_of(const aabb *root);

/* Builds the subtree of task t, with scratch only while it runs (one set per thread, not per
 * task); a tree's root not yet started first gets its primitive set, on this thread. */
static int task_run(task *t)
{
    if (!t->started) {
        if (start(&t->b, &t->s, &t->box, 1) != 0)
            return -1;
        t->b.kind = measure_of(&t->box);
        t->b.root_measure = measure(t->b.kind, &t->box);
    } else if (scratch_alloc(&t->b) != 0) {
        return -1;
    }
    return build_node(&t->b, 0, &t->box, &t->s, t->depth, &t->sum);
}

/* Runs loop items and tasks: the caller until every task has finished, the other threads until
 * shutdown. */
static void work(pool *pl, int caller)
{
    pthread_mutex_lock(&pl->mu);
    for (;;) {
        if (pl->for_next < pl->for_n) {
            run_item(pl);
            continue;
        }
        if (pl->next < pl->n_tasks) {
            task *t = pl->tasks[pl->next++];
            const int skip = pl->failed[t->b.tree];
            pthread_mutex_unlock(&pl->mu);
            const int rc = skip ? -1 : task_run(t);
            set_free(&t->s);
            scratch_free(&t->b);
            pthread_mutex_lock(&pl->mu);
            pl->failed[t->b.tree] |= rc != 0;
            if (--pl->unfinished == 0)
                notify(pl);
            continue;
        }
        if (caller ? pl->unfinished == 0 : pl->shutdown)
            break;
        pl->idle++;
        wait_change(pl);
        pl->idle--;
    }
    pthread_mutex_unlock(&pl->mu);
}

static void *worker(void *arg)
{
    work(arg, 0);
    return NULL;
}

/* Output index of local node i >= 1 of b, given the offsets of the holes before holes[n_holes]
 * (the last hole due at or before i decides; local 1 goes to first). */
static uint32_t map_node(const builder *b, uint32_t n_holes, uint32_t first, uint32_t i)
{
    uint32_t h = 0; /* holes[0..n_holes) are sorted by at_node and few: a count without branches */
    for (uint32_t k = 0; k < n_holes; k++)
        h += b->holes[k].at_node <= i;
    return i + (h == 0 ? first - 1 : b->holes[h - 1].node_off);
}

/* Places the subtree of task id in the output, in the order of the single-threaded build: its
 * root at node `root`, its other nodes and its leaf entries from *n_nodes and *n_prims on (which
 * it advances), with the subtree of each hole inserted where it was due. Sets the offsets that
 * copy_nodes() and copy_prims() use. */
static void layout(pool *pl, uint32_t id, uint32_t root, uint32_t *n_nodes, uint32_t *n_prims)
{
    task *t = pl->tasks[id];
    builder *b = &t->b;
    t->out_root = root;
    t->out_first = *n_nodes;
    t->out_first_prim = *n_prims;
    uint32_t at_node = 1, at_prim = 0; /* local entries up to here are placed */
    for (uint32_t h = 0; h < b->n_holes; h++) {
        hole *ho = &b->holes[h];
        *n_nodes += ho->at_node - at_node;
        *n_prims += ho->at_prim - at_prim;
        layout(pl, ho->task, map_node(b, h, t->out_first, ho->node), n_nodes, n_prims);
        ho->node_off = *n_nodes - ho->at_node; /* unsigned: modulo 2^32, exact in the end */
        ho->prim_off = *n_prims - ho->at_prim;
        at_node = ho->at_node;
        at_prim = ho->at_prim;
    }
    *n_nodes += b->n_nodes - at_node;
    *n_prims += b->n_prims - at_prim;
}

/* Copies nodes [lo, hi) of task t to out, with their final child and first indices. From the
 * last one down: no node goes below its own index in its tree's layout (holes only insert), so a
 * tree's root task can be copied onto its own array (merge_trees). */
static void copy_nodes(const task *t, uint32_t lo, uint32_t hi, kd_node *out)
{
    const builder *b = &t->b;
    const uint32_t first = t->out_first, first_prim = t->out_first_prim;
    uint32_t h = b->n_holes; /* holes[0..h): the holes due at or before node i */
    for (uint32_t i = hi; i-- > lo;) {
        while (h > 0 && b->holes[h - 1].at_node > i)
            h--;
        kd_node n = b->nodes[i];
        if (n.axis == KD_HOLE)
            continue; /* written by its task */
        /* without branches on the kind of node, which is unpredictable */
        const int leaf = n.axis == KD_LEAF;
        const uint32_t holes_before = leaf ? n.child : 0;
        const uint32_t prim_off = holes_before ? b->holes[holes_before - 1].prim_off : first_prim;
        const uint32_t child = map_node(b, b->n_holes, first, n.child);
        n.first = leaf ? n.first + prim_off : 0;
        n.count = leaf ? n.count : 0; /* inner: pending_sum index */
        n.child = leaf ? 0 : child;
        out[i == 0 ? t->out_root : i + (h == 0 ? first - 1 : b->holes[h - 1].node_off)] = n;
    }
}

/* Copies leaf entries [lo, hi) of task t to out, the segments between the holes from the last one
 * down (as copy_nodes: out may be the root task's own array). */
static void copy_prims(const task *t, uint32_t lo, uint32_t hi, uint32_t *out)
{
    const builder *b = &t->b;
    for (uint32_t h = b->n_holes + 1; h-- > 0;) {
        const uint32_t start = h == 0 ? 0 : b->holes[h - 1].at_prim;
        const uint32_t end = h < b->n_holes ? b->holes[h].at_prim : b->n_prims;
        const uint32_t off = h == 0 ? t->out_first_prim : b->holes[h - 1].prim_off;
        const uint32_t from = start > lo ? start : lo, to = end < hi ? end : hi;
        if (to > from)
            memmove(out + from + off, b->prims + from, (size_t)(to - from) * sizeof *out);
    }
}

/* Copying in parallel: the trees' root tasks onto their own arrays, one item each (in place, from
 * the end); then the other tasks, item i part i % COPY_PARTS of task n_trees + i / COPY_PARTS. */
enum { COPY_PARTS = 4 };

typedef struct {
    pool *pl;
    kd_tree *out;     /* per tree (nodes NULL: the tree failed, nothing to copy) */
    uint32_t n_trees; /* copy_item: the first task it copies */
} copy_ctx;

static void copy_root(void *arg, uint32_t i)
{
    const copy_ctx *c = arg;
    const task *t = c->pl->tasks[i];
    if (c->out[i].nodes) {
        copy_nodes(t, 0, t->b.n_nodes, c->out[i].nodes);
        copy_prims(t, 0, t->b.n_prims, c->out[i].prims);
    }
}

static void copy_item(void *arg, uint32_t i)
{
    const copy_ctx *c = arg;
    const task *t = c->pl->tasks[c->n_trees + i / COPY_PARTS];
    const kd_tree *out = &c->out[t->b.tree];
    if (!out->nodes)
        return;
    const uint64_t part = i % COPY_PARTS, n = t->b.n_nodes, np = t->b.n_prims;
    copy_nodes(t, (uint32_t)(n * part / COPY_PARTS), (uint32_t)(n * (part + 1) / COPY_PARTS), out->nodes);
    copy_prims(t, (uint32_t)(np * part / COPY_PARTS), (uint32_t)(np * (part + 1) / COPY_PARTS), out->prims);
}

/* SAH sum of the subtree at node (box) of task id: the sums left pending by holes, finished. */
static double resolve(const pool *pl, uint32_t id, uint32_t node, const aabb *box)
{
    const task *t = pl->tasks[id];
    if (node == 0 && !t->sum.pending)
        return t->sum.sum;
    const kd_node *n = &t->b.nodes[node];
    if (n->axis == KD_HOLE)
        return resolve(pl, n->child, 0, box);
    const pending_sum *ps = &t->b.pend[n->count - 1];
    aabb cb[2] = { *box, *box };
    cb[0].hi[n->axis] = cb[1].lo[n->axis] = n->split;
    double sum[2];
    for (int c = 0; c < 2; c++)
        sum[c] = ps->pending[c] ? resolve(pl, id, n->child + (uint32_t)c, &cb[c]) : ps->sum[c];
    return ps->own + (sum[0] + sum[1]);
}

static void stats_add(kd_stats *a, const kd_stats *b)
{
    a->n_leaves += b->n_leaves;
    a->n_empty_leaves += b->n_empty_leaves;
    a->references += b->references;
    if (b->depth > a->depth)
        a->depth = b->depth;
    if (b->max_leaf_count > a->max_leaf_count)
        a->max_leaf_count = b->max_leaf_count;
}

uint32_t kd_thread_count(void)
{
    cpu_set_t set;
    long n = 0;
    if (sched_getaffinity(0, sizeof set, &set) == 0)
        n = CPU_COUNT(&set);
    if (n <= 0)
        n = sysconf(_SC_NPROCESSORS_ONLN);
    return n <= 1 ? 1u : n >= PAR_MAX_THREADS ? (uint32_t)PAR_MAX_THREADS : (uint32_t)n;
}

/* Merges the outputs of the tasks of a finished pool into each tree's layout, in roots[i].b
 * (nodes, prims, their counts and statistics; the tasks' outputs freed), with sah[i] its SAH
 * sum; rc[i]: 0, or -1 if the tree failed (its output is then empty). The layout is made in the
 * root task's arrays, which mostly have room for it already (output_alloc), the other tasks'
 * subtrees copied into the gaps it leaves: the gallery's merged copies had been 40 MB of fresh
 * pages, which the kernel zeroes at the first touch (2.8% of its CPU samples). */
static void merge_trees(pool *pl, task *roots, uint32_t n, int *rc, double *sah)
{
    kd_tree *out = calloc(n, sizeof *out);
    uint64_t *count = calloc(2 * (size_t)n, sizeof *count); /* per tree: nodes, leaf entries */
    for (uint32_t i = 0; i < n && count; i++)
        count[2 * i] = 1;
    for (uint32_t j = 0; j < pl->n_tasks && count; j++) {
        const builder *b = &pl->tasks[j]->b;
        count[2 * b->tree] += b->n_nodes - 1u;
        count[2 * b->tree + 1] += b->n_prims;
        if (j >= n)
            stats_add(&roots[b->tree].b.st, &b->st);
    }
    for (uint32_t i = 0; i < n; i++) {
        builder *b = &roots[i].b;
        rc[i] = pl->failed[i] || !out || !count ? -1 : 0;
        if (rc[i] == 0 && count[2 * i] <= UINT32_MAX && count[2 * i + 1] < UINT32_MAX) {
            kd_node *nodes = reserve(b->nodes, &b->cap_nodes, count[2 * i], sizeof *nodes);
            b->nodes = nodes ? nodes : b->nodes;
            uint32_t *prims = reserve(b->prims, &b->cap_prims, count[2 * i + 1] + 1, sizeof *prims);
            b->prims = prims ? prims : b->prims;
            out[i].nodes = nodes && prims ? nodes : NULL;
            out[i].prims = nodes && prims ? prims : NULL;
        }
        if (rc[i] == 0 && out[i].nodes) {
            out[i].n_nodes = 1;
            layout(pl, i, 0, &out[i].n_nodes, &out[i].n_prims);
            sah[i] = resolve(pl, i, 0, &roots[i].box); /* before the copies: it reads the tasks' nodes */
        } else {
            sah[i] = 0.0;
            rc[i] = -1;
            if (out)
                out[i] = (kd_tree){ 0 };
        }
    }
    if (out) {
        copy_ctx c = { pl, out, n };
        pool_for(pl, n, copy_root, &c);
        pool_for(pl, (pl->n_tasks - n) * COPY_PARTS, copy_item, &c);
    }
    for (uint32_t j = n; j < pl->n_tasks; j++) {
        task_free(pl->tasks[j]);
        free(pl->tasks[j]);
    }
    for (uint32_t i = 0; i < n; i++) {
        builder *b = &roots[i].b;
        if (rc[i] != 0) {
            free(b->nodes);
            free(b->prims);
            b->nodes = NULL;
            b->prims = NULL;
            b->cap_nodes = b->cap_prims = 0;
        }
        free(b->holes);
        free(b->pend);
        b->holes = NULL;
        b->pend = NULL;
        b->n_holes = b->n_pend = 0;
        b->n_nodes = rc[i] == 0 ? out[i].n_nodes : 0;
        b->n_prims = rc[i] == 0 ? out[i].n_prims : 0;
    }
    free(out);
    free(count);
}

/* Builds the trees of the tasks roots[0..n) (started, or not: task_run) with one pool of threads
 * (the caller being one of them), so that a thread done with one tree helps with the others'
 * subtrees; each tree comes out as the single-threaded build_node(b, 0, box, s, 0, ...) makes it,
 * in roots[i].b (merge_trees), and the primitive sets are freed. rc[i]: 0, or -1 (no memory,
 * or the node budget: see the builder's budget). A thread that cannot be started is done without;
 * with none, the caller builds the trees alone. */
static void build_pool(task *roots, uint32_t n, uint32_t threads, int *rc, double *sah)
{
    pool pl = { .n_tasks = n, .unfinished = n, .max_tasks = n + PAR_MAX_TASKS };
    atomic_init(&pl.changes, 0);
    pl.tasks = malloc(pl.max_tasks * sizeof *pl.tasks);
    pl.failed = calloc(n, 1);
    int ok = pl.tasks && pl.failed;
    if (ok && pthread_mutex_init(&pl.mu, NULL) != 0)
        ok = 0;
    if (ok && pthread_cond_init(&pl.cv, NULL) != 0) {
        pthread_mutex_destroy(&pl.mu);
        ok = 0;
    }
    if (!ok) { /* single-threaded after all */
        free(pl.tasks);
        free(pl.failed);
        for (uint32_t i = 0; i < n; i++) {
            roots[i].b.pool = NULL;
            rc[i] = task_run(&roots[i]);
            set_free(&roots[i].s);
            scratch_free(&roots[i].b);
            sah[i] = roots[i].sum.sum;
        }
        return;
    }
    for (uint32_t i = 0; i < n; i++) {
        pl.tasks[i] = &roots[i];
        roots[i].b.pool = &pl;
        roots[i].b.tree = i;
    }
    pthread_t tid[PAR_MAX_THREADS];
    uint32_t started = 0;
    for (uint32_t i = 1; i < threads; i++)
        if (pthread_create(&tid[started], NULL, worker, &pl) == 0)
            started++;
    work(&pl, 1);
    merge_trees(&pl, roots, n, rc, sah);

    pthread_mutex_lock(&pl.mu);
    pl.shutdown = 1;
    notify(&pl);
    pthread_mutex_unlock(&pl.mu);
    for (uint32_t i = 0; i < started; i++)
        pthread_join(tid[i], NULL);
    pthread_cond_destroy(&pl.cv);
    pthread_mutex_destroy(&pl.mu);
    free(pl.tasks);
    free(pl.failed);
    for (uint32_t i = 0; i < n; i++)
        roots[i].b.pool = NULL;
}

/* ---- statistics ----------------------------------------------------------------------------- */

typedef struct {
    const kd_tree *t;
    const kd_params *p;
    measure_kind kind;
    double root_measure;
    kd_stats st;
} walker;

/* Adds the subtree at node (box, depth) to w->st; returns its SAH sum, added up like build_node. */
static double walk(walker *w, uint32_t node, const aabb *box, uint32_t depth)
{
    const kd_node *n = &w->t->nodes[node];
    const double weight = measure(w->kind, box) / w->root_measure;
    if (depth > w->st.depth)
        w->st.depth = depth;
    if (n->axis == KD_LEAF) {
        w->st.n_leaves++;
        w->st.n_empty_leaves += n->count == 0;
        w->st.references += n->count;
        if (n->count > w->st.max_leaf_count)
            w->st.max_leaf_count = n->count;
        return w->p->cost_intersection * n->count * weight;
    }
    const double own = w->p->cost_traversal * weight;
    aabb lb = *box, rb = *box;
    lb.hi[n->axis] = rb.lo[n->axis] = n->split;
    const double left = walk(w, n->child, &lb, depth + 1);
    return own + (left + walk(w, n->child + 1, &rb, depth + 1));
}

static measure_kind measure_of(const aabb *root)
{
    return half_area(root) > 0 ? MEASURE_AREA : length(root) > 0 ? MEASURE_LENGTH : MEASURE_UNIT;
}

static kd_stats tree_stats(const kd_tree *t, const kd_params *p)
{
    walker w = { t, p, measure_of(&t->bounds), 1.0, { 0 } };
    w.root_measure = measure(w.kind, &t->bounds);
    if (t->n_nodes > 0)
        w.st.sah_cost = walk(&w, 0, &t->bounds, 0);
    return w.st;
}

/* ---- API ------------------------------------------------------------------------------------ */

void kd_params_default(kd_params *p)
{
    memset(p, 0, sizeof *p);
    p->cost_traversal = 1.0;
    p->cost_intersection = 1.5;
    p->empty_bonus = 0.2;
    p->leaf_size = 1;
    p->face_splits = 1;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Whether a tree of count primitives is built binned (kd_params.bins, bins_from). */
static int binned_tree(const kd_params *p, uint32_t count) { return p->bins > 0 && count >= p->bins_from; }

/* A shallow tree built binned gets one level more than an exact one: the binned planes cut less
 * tightly per level, and at 5 + log2(count) its leaves hold more triangles than the exact tree's
 * (bunny.glb 6.1 against 4.8 per non-empty leaf, 4.6 against 3.7 intersections per ray); one
 * level deeper it has fewer nodes than the exact tree and costs fewer cycles per ray
 * (docs/memory-image.md). */
static uint32_t auto_depth(const kd_params *p, uint32_t count)
{
    const int shallow = p->shallow_from && count >= p->shallow_from;
    const double base = binned_tree(p, count) ? 6.0 : 5.0;
    const double d = count > 1 ? (shallow ? base + log2((double)count) : 8.0 + 1.3 * log2((double)count)) : 8.0;
    return d >= 64.0 ? 64u : (uint32_t)lround(d);
}

uint32_t kd_depth_bound(const kd_params *p, uint32_t count) { return p->max_depth ? p->max_depth : auto_depth(p, count); }

/* p without the spare capacity of doubling; a failed shrink keeps p as it is. */
static void *shrink(void *p, size_t bytes)
{
    void *q = realloc(p, bytes);
    return q ? q : p;
}

/* Scratch arrays and the root primitive set. */
static int start(builder *b, prim_set *s, aabb *root, uint32_t threads)
{
    const aabb empty = { { INFINITY, INFINITY, INFINITY }, { -INFINITY, -INFINITY, -INFINITY } };
    *root = empty;
    if (!binned(b) && b->src->count > UINT32_MAX / 2)
        return -1; /* 2 events per primitive and axis must fit in 32 bits */
    if (scratch_alloc(b) || (binned(b) ? root_refs(b, s, root) : root_events(b, s, root, threads)))
        return -1;
    if (b->src->count == 0)
        *root = (aabb){ { 0, 0, 0 }, { 0, 0, 0 } }; /* no primitives: a point at the origin */
    uint32_t first;
    return output_alloc(b, b->src->count) == 0 ? add_nodes(b, 1, 1, &first) : -1;
}

/* A tree's builder before start(), with the parameters as the build uses them. */
static builder tree_builder(const kd_source *src, const kd_params *p, node_budget *budget)
{
    builder b = { .src = src, .p = *p, .budget = budget };
    b.p.bins = binned_tree(p, src->count) ? p->bins : 0;
    b.max_depth = kd_depth_bound(p, src->count);
    return b;
}

/* Threads of a build of count primitives: the asked ones (0: kd_thread_count()), at most
 * PAR_MAX_THREADS, and 1 for a small one. */
static uint32_t build_threads(uint32_t asked, uint64_t count)
{
    asked = asked ? asked : kd_thread_count();
    return count < PAR_MIN_COUNT ? 1 : asked < PAR_MAX_THREADS ? asked : PAR_MAX_THREADS;
}

/* The tree of root (the build's rc, sah its SAH sum) into out, the builder's scratch freed: 0,
 * -1 (memory) or KD_TOO_MANY_NODES. */
static int tree_finish(task *root, int rc, double sah, double t0, kd_tree *out)
{
    builder *b = &root->b;
    set_free(&root->s);
    scratch_free(b);
    if (rc != 0) {
        free(b->nodes);
        free(b->prims);
        return atomic_load(&b->budget->exceeded) ? KD_TOO_MANY_NODES : -1;
    }
    *out = (kd_tree){ shrink(b->nodes, b->n_nodes * sizeof *b->nodes), b->n_nodes,
                      shrink(b->prims, ((size_t)b->n_prims + 1) * sizeof *b->prims), b->n_prims, root->box, { 0 } };
    out->stats = b->st;
    out->stats.sah_cost = sah;
    out->stats.build_seconds = now() - t0;
    return 0;
}

int kd_build(const kd_source *src, const kd_params *p, kd_tree *out)
{
    const double t0 = now();
    memset(out, 0, sizeof *out);
    uint64_t own_nodes = 0;
    node_budget budget = { p->shared_nodes ? p->shared_nodes : &own_nodes, 0 };
    const uint32_t threads = build_threads(p->threads, src->count);
    task root = { .b = tree_builder(src, p, &budget), .started = 1 };
    int rc = start(&root.b, &root.s, &root.box, threads);
    root.b.kind = measure_of(&root.box);
    root.b.root_measure = measure(root.b.kind, &root.box);
    subtree_sum sum = { 0.0, 0 };
    if (rc == 0 && threads > 1) {
        scratch_free(&root.b); /* the pool's thread that runs the root allocates its own */
        build_pool(&root, 1, threads, &rc, &sum.sum); /* frees s */
    } else if (rc == 0) {
        rc = build_node(&root.b, 0, &root.box, &root.s, 0, &sum); /* frees s */
    }
    return tree_finish(&root, rc, sum.sum, t0, out);
}

int kd_build_many(const kd_source *src, const kd_params *p, uint32_t n, uint32_t threads, kd_tree *out, int *rc)
{
    if (n == 1) { /* kd_build starts the root on this thread with the others' help (root_events) */
        kd_params q = p[0];
        q.threads = threads;
        rc[0] = kd_build(&src[0], &q, &out[0]);
        return 0;
    }
    const double t0 = now();
    task *roots = calloc((size_t)n + 1, sizeof *roots);
    node_budget *budget = calloc((size_t)n + 1, sizeof *budget);
    uint64_t *own_nodes = calloc((size_t)n + 1, sizeof *own_nodes), count = 0;
    double *sah = calloc((size_t)n + 1, sizeof *sah);
    if (!roots || !budget || !own_nodes || !sah) {
        free(roots);
        free(budget);
        free(own_nodes);
        free(sah);
        return -1;
    }
    for (uint32_t i = 0; i < n; i++) {
        memset(&out[i], 0, sizeof out[i]);
        budget[i].used = p[i].shared_nodes ? p[i].shared_nodes : &own_nodes[i];
        atomic_init(&budget[i].exceeded, 0);
        roots[i].b = tree_builder(&src[i], &p[i], &budget[i]); /* not started: task_run starts it */
        count += src[i].count;
    }
    threads = build_threads(threads, count);
    if (threads > 1) {
        build_pool(roots, n, threads, rc, sah);
    } else {
        for (uint32_t i = 0; i < n; i++) {
            rc[i] = task_run(&roots[i]);
            sah[i] = roots[i].sum.sum;
        }
    }
    for (uint32_t i = 0; i < n; i++)
        rc[i] = tree_finish(&roots[i], rc[i], sah[i], t0, &out[i]);
    free(roots);
    free(budget);
    free(own_nodes);
    free(sah);
    return 0;
}

void kd_free(kd_tree *t)
{
    free(t->nodes);
    free(t->prims);
    memset(t, 0, sizeof *t);
}

double kd_sah_cost(const kd_tree *t, const kd_params *p) { return tree_stats(t, p).sah_cost; }

/* ---- triangle clipping ---------------------------------------------------------------------- */

/* A convex polygon gains at most one vertex per plane (3 + 6); rounding can make the clipped
 * polygon very slightly non-convex, so there is room to spare and a bound check on top. */
enum { CLIP_MAX = 16 };

typedef struct {
    double v[CLIP_MAX][3];
    int n;
} polygon;

static inline void poly_add(polygon *p, const double v[3])
{
    if (p->n == CLIP_MAX)
        return;
    double *w = p->v[p->n++];
    w[0] = v[0];
    w[1] = v[1];
    w[2] = v[2];
}

/* Point where segment in-out crosses x[axis] = d, computed from the inside end so that an edge
 * shared by two triangles gives the same point both ways; kept within the segment's bounds. */
static inline __attribute__((always_inline)) void crossing(const double in[3], const double out[3], int axis, double d, double p[3])
{
    const double t = (d - in[axis]) / (out[axis] - in[axis]);
    for (int k = 0; k < 3; k++) {
        const double x = in[k] + t * (out[k] - in[k]);
        p[k] = dmin(dmax(x, dmin(in[k], out[k])), dmax(in[k], out[k]));
    }
    p[axis] = d;
}

static inline int kept_side(double x, double d, int keep_above) { return keep_above ? x >= d : x <= d; }

/* Keeps the part of src with x[axis] >= d (keep_above) or <= d; points on the plane are kept.
 * Returns 0 without touching dst if every vertex is on the kept side already (most planes of a
 * node box): the polygon stays src. */
static inline __attribute__((always_inline)) int clip_plane(const polygon *src, int axis, double d, int keep_above, polygon *dst)
{
    int in[CLIP_MAX], all = 1;
    for (int i = 0; i < src->n; i++) {
        in[i] = kept_side(src->v[i][axis], d, keep_above);
        all &= in[i];
    }
    if (all)
        return 0;
    dst->n = 0;
    for (int i = 0; i < src->n; i++) {
        const int j = i + 1 < src->n ? i + 1 : 0;
        const double *a = src->v[i], *c = src->v[j];
        if (in[i])
            poly_add(dst, a);
        /* a crossing only between strict sides: a vertex on the plane is the crossing itself */
        if (in[i] != in[j] && a[axis] != d && c[axis] != d) {
            double p[3];
            crossing(in[i] ? a : c, in[i] ? c : a, axis, d, p);
            poly_add(dst, p);
        }
    }
    return 1;
}

/* Clips p[*cur] by the planes [from, to) of box, in the fixed order (the result's rounding depends
 * on it) plane 2a: x_a >= lo, plane 2a + 1: x_a <= hi, a = x, y, z; 0 if nothing is left. Each
 * plane's clip_plane has constant axis and side, so that the compiler specializes it. outer: the
 * bounds of the triangle, which hold every polygon clipped from it (crossings lie within their
 * edge): a plane they lie inside keeps every vertex, as clip_plane would find vertex by vertex. */
#define CLIP_PLANE(plane, axis, above, d)                                                                              \
    do {                                                                                                               \
        if (from <= (plane) && (plane) < to && !((above) ? outer->lo[axis] >= (d) : outer->hi[axis] <= (d)) &&        \
            clip_plane(&p[*cur], axis, d, above, &p[1 - *cur])) {                                                      \
            *cur = 1 - *cur;                                                                                           \
            if (p[*cur].n == 0)                                                                                        \
                return 0;                                                                                              \
        }                                                                                                              \
    } while (0)

static inline __attribute__((always_inline)) int clip_planes(polygon p[2], int *cur, const aabb *outer, const aabb *box,
                                                             int from, int to)
{
    CLIP_PLANE(0, 0, 1, box->lo[0]);
    CLIP_PLANE(1, 0, 0, box->hi[0]);
    CLIP_PLANE(2, 1, 1, box->lo[1]);
    CLIP_PLANE(3, 1, 0, box->hi[1]);
    CLIP_PLANE(4, 2, 1, box->lo[2]);
    CLIP_PLANE(5, 2, 0, box->hi[2]);
    return 1;
}

/* Bounds of polygon p: minima and maxima in vertex order from infinity, so that of equal values
 * (-0 and +0) the same one wins as when they were kept per added vertex. After clipping: exact
 * inside tests, crossings on their plane and within their edge, so the polygon lies in the box. */
static aabb poly_bounds(const polygon *p)
{
    aabb r = { { INFINITY, INFINITY, INFINITY }, { -INFINITY, -INFINITY, -INFINITY } };
    for (int i = 0; i < p->n; i++)
        for (int k = 0; k < 3; k++) {
            r.lo[k] = dmin(r.lo[k], p->v[i][k]);
            r.hi[k] = dmax(r.hi[k], p->v[i][k]);
        }
    return r;
}

static void poly_triangle(polygon *p, const double a[3], const double b[3], const double c[3])
{
    p->n = 0;
    poly_add(p, a);
    poly_add(p, b);
    poly_add(p, c);
}

int kd_clip_triangle(const double a[3], const double b[3], const double c[3], const aabb *box, aabb *out)
{
    polygon p[2];
    int cur = 0;
    poly_triangle(&p[0], a, b, c);
    const aabb outer = poly_bounds(&p[0]);
    if (!clip_planes(p, &cur, &outer, box, 0, 6))
        return 0;
    *out = poly_bounds(&p[cur]);
    return 1;
}

int kd_clip_triangle_split(const double a[3], const double b[3], const double c[3], const aabb *box, uint32_t axis,
                           double pos, aabb out[2])
{
    polygon p[2], q[2];
    int cur = 0;
    poly_triangle(&p[0], a, b, c);
    const aabb outer = poly_bounds(&p[0]);
    const int first = 2 * (int)axis; /* the first plane where the halves differ */
    if (!clip_planes(p, &cur, &outer, box, 0, first))
        return 0;
    q[0].n = p[cur].n; /* the upper half's copy: the lower half's clipping overwrites p */
    memcpy(q[0].v, p[cur].v, (size_t)p[cur].n * sizeof q[0].v[0]);
    aabb half[2] = { *box, *box };
    half[0].hi[axis] = half[1].lo[axis] = pos;
    int mask = 0, qcur = 0;
    if (clip_planes(p, &cur, &outer, &half[0], first, 6)) {
        out[0] = poly_bounds(&p[cur]);
        mask |= 1;
    }
    if (clip_planes(q, &qcur, &outer, &half[1], first, 6)) {
        out[1] = poly_bounds(&q[qcur]);
        mask |= 2;
    }
    return mask;
}
