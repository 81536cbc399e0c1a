/*
 * SAH kd-tree builder (API and node layout: kdtree.h).
 *
 * Cost model (surface area heuristic). Splitting a node with box B at plane q costs
 *     C_t + C_i * (SA(L) / SA(B) * n_L + SA(R) / SA(B) * n_R),
 * times (1 - empty_bonus) if a side is empty; the split is made only if that is cheaper than the
 * leaf cost C_i * n. A node also becomes a leaf if n <= leaf_size or it is at max_depth (root:
 * depth 0; automatic: round(8 + 1.3 log2(count)), at most 64). A box of zero area (a segment) uses
 * length ratios instead, the limit of thin boxes. Every split lies strictly inside its node box,
 * so no input can loop: recursion ends at max_depth at the latest.
 *
 * Exact mode (bins == 0), after Wald & Havran, "On building fast kd-trees for ray tracing, and
 * on doing that in O(N log N)" (2006). Each primitive contributes per axis a start and an end
 * event at its bounds inside the node (from clip(), "perfect splits"), or one planar event if it
 * is flat on that axis. The three event lists are sorted once at the root. A node sweeps them for
 * the cheapest plane; primitives lying in a candidate plane are tried on both sides. Splitting
 * keeps the events of one-sided primitives (still sorted); primitives straddling the plane are
 * clipped to the two child boxes and only their new events are sorted and merged in.
 * Cost: O(N log N) for the root sort and the sweeps/splits (O(n) per node, O(log N) levels),
 * plus sorting the straddlers' events per node (O(N log^2 N) in the worst case, in practice the
 * straddlers are few). Event counts are 32-bit: at most 2^31 primitives.
 *
 * Binned mode (bins > 0, the per-frame top level): candidates are the bins - 1 evenly spaced
 * planes per axis. Every primitive is ranked against them exactly (its bin, checked against the
 * neighbouring planes), so the counts are exact at the candidate planes: O(n + bins) per node,
 * O(N log N) total. Small nodes (at most SMALL_NODE primitives, fewer bounds than planes) use
 * their primitives' own bounds as candidates, counted directly: exact SAH, and cheaper there.
 *
 * Quantization: each candidate is snapped with params.quantize before it is evaluated, counts are
 * taken against the snapped plane, and candidates not strictly inside the node box after snapping
 * are skipped; primitives are then classified against the snapped plane, so the tree is exact
 * for the planes it stores. quantize should be monotone (any rounding is); exact mode skips a
 * snapped candidate that would move the sweep backwards.
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "kdtree.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

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

typedef struct {
    uint32_t id;
    aabb b; /* bounds of the part of the primitive inside the node */
} prim_ref;

/* The primitives of one node, in the representation of the build mode. */
typedef struct {
    uint32_t n;       /* primitives */
    event *ev[3];     /* exact mode: events per axis, sorted */
    uint32_t n_ev[3];
    prim_ref *ref;    /* binned mode */
} prim_set;

typedef struct {
    double cost;
    uint32_t axis;
    double pos;
    int planar_left; /* primitives lying in the plane go to the left child */
} split;

typedef struct {
    const kd_source *src;
    kd_params p;
    uint32_t max_depth;
    kd_node *nodes;
    uint32_t n_nodes, cap_nodes;
    uint32_t *prims;
    uint32_t n_prims, cap_prims;
    uint8_t *side;    /* exact mode: SIDE_* of each primitive of the node being split */
    double *cand;     /* binned mode: candidate planes of one axis */
    uint32_t *counts; /* binned mode: 3 x (bins + 1) counters */
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

/* Candidate q with nl primitives below, np in the plane and nr above: the primitives in the plane
 * go to the cheaper side; best keeps the cheapest candidate (the first one on ties). */
static void consider(const axis_terms *t, double q, uint32_t nl, uint32_t np, uint32_t nr, split *best)
{
    const double pl = (t->base + (q - t->lo) * t->slope) * t->inv;
    const double pr = (t->base + (t->hi - q) * t->slope) * t->inv;
    const double left = split_cost(t, pl, pr, nl + np, nr);
    const double right = np ? split_cost(t, pl, pr, nl, nr + np) : INFINITY;
    const double c = left <= right ? left : right;
    if (c < best->cost)
        *best = (split){ c, t->axis, q, left <= right };
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
    void *q = realloc(p, (size_t)c * size);
    if (q)
        *cap = (uint32_t)c;
    return q;
}

static int add_nodes(builder *b, uint32_t k, uint32_t *first)
{
    kd_node *n = reserve(b->nodes, &b->cap_nodes, (uint64_t)b->n_nodes + k, sizeof *n);
    if (!n)
        return -1;
    b->nodes = n;
    *first = b->n_nodes;
    b->n_nodes += k;
    return 0;
}

/* Writes leaf node `node` with a list of n entries at the end of prims; returns the list to fill. */
static uint32_t *new_leaf(builder *b, uint32_t node, uint32_t n)
{
    uint32_t *p = reserve(b->prims, &b->cap_prims, (uint64_t)b->n_prims + n, sizeof *p);
    if (!p)
        return NULL;
    b->prims = p;
    b->nodes[node] = (kd_node){ KD_LEAF, 0, 0.0, b->n_prims, n };
    b->n_prims += n;
    return p + b->nodes[node].first;
}

/* ---- exact mode: event lists ---------------------------------------------------------------- */

static int event_less(const event *a, const event *b)
{
    if (a->pos != b->pos)
        return a->pos < b->pos;
    if (a->type != b->type)
        return a->type < b->type;
    return a->prim < b->prim;
}

static int cmp_event(const void *x, const void *y)
{
    const event *a = x, *b = y;
    return event_less(b, a) - event_less(a, b);
}

/* Room for per_axis events on each axis (one spare, so that no size is 0). */
static int events_alloc(prim_set *s, size_t per_axis)
{
    for (int a = 0; a < 3; a++)
        if (!(s->ev[a] = malloc((per_axis + 1) * sizeof(event))))
            return -1;
    return 0;
}

static void add_events(prim_set *s, uint32_t id, const aabb *part)
{
    for (int a = 0; a < 3; a++) {
        event *e = s->ev[a] + s->n_ev[a];
        if (part->lo[a] == part->hi[a]) {
            e[0] = (event){ part->lo[a], id, EV_PLANAR };
            s->n_ev[a] += 1;
        } else {
            e[0] = (event){ part->lo[a], id, EV_START };
            e[1] = (event){ part->hi[a], id, EV_END };
            s->n_ev[a] += 2;
        }
    }
    s->n++;
}

static void events_sort(prim_set *s)
{
    for (int a = 0; a < 3; a++)
        qsort(s->ev[a], s->n_ev[a], sizeof(event), cmp_event);
}

/* Sweeps the events of axis k; candidates are the snapped event positions, and the counts at a
 * candidate q come from a second pointer that has passed every event below q. */
static void sweep_axis(const builder *b, const prim_set *s, const aabb *box, uint32_t k, split *best)
{
    const event *ev = s->ev[k];
    const uint32_t m = s->n_ev[k];
    const axis_terms t = terms_of(b, box, k);
    uint32_t below[EV_TYPES] = { 0 }, j = 0;
    double last = -INFINITY;
    for (uint32_t i = 0; i < m; i++) {
        if (i > 0 && ev[i].pos == ev[i - 1].pos)
            continue;
        const double q = snap(b, ev[i].pos);
        if (!(q > last) || !strictly_inside(box, k, q))
            continue;
        last = q;
        while (j < m && ev[j].pos < q)
            below[ev[j++].type]++;
        uint32_t at[EV_TYPES] = { 0 };
        while (j < m && ev[j].pos == q)
            at[ev[j++].type]++;
        const uint32_t nl = below[EV_START] + below[EV_PLANAR];
        const uint32_t nr = s->n - below[EV_END] - below[EV_PLANAR] - at[EV_END] - at[EV_PLANAR];
        consider(&t, q, nl, at[EV_PLANAR], nr, best);
        for (int e = 0; e < EV_TYPES; e++)
            below[e] += at[e];
    }
}

/* Sets b->side for the primitives of s from their events on the split axis: an end at or below
 * the plane means left only, a start at or above it right only, the rest straddles. */
static void classify(builder *b, const prim_set *s, const split *sp)
{
    const event *ev = s->ev[sp->axis];
    const uint32_t m = s->n_ev[sp->axis];
    for (uint32_t i = 0; i < m; i++)
        b->side[ev[i].prim] = SIDE_BOTH;
    for (uint32_t i = 0; i < m; i++) {
        const event *e = &ev[i];
        if (e->type == EV_PLANAR)
            b->side[e->prim] = (uint8_t)side_of(e->pos, e->pos, sp);
        else if (e->type == EV_END && e->pos <= sp->pos)
            b->side[e->prim] = SIDE_LEFT;
        else if (e->type == EV_START && e->pos >= sp->pos)
            b->side[e->prim] = SIDE_RIGHT;
    }
}

/* Starts the children l and r with the sorted events of the straddling primitives, clipped to
 * the child boxes (a straddler has exactly one start event on the split axis). */
static int clip_straddlers(const builder *b, const prim_set *s, const split *sp, const aabb *lb, const aabb *rb,
                           prim_set *l, prim_set *r)
{
    const event *ev = s->ev[sp->axis];
    const uint32_t m = s->n_ev[sp->axis];
    size_t nb = 0;
    for (uint32_t i = 0; i < m; i++)
        nb += ev[i].type == EV_START && b->side[ev[i].prim] == SIDE_BOTH;
    if (events_alloc(l, 2 * nb) || events_alloc(r, 2 * nb))
        return -1;
    for (uint32_t i = 0; i < m; i++) {
        if (ev[i].type != EV_START || b->side[ev[i].prim] != SIDE_BOTH)
            continue;
        aabb part;
        if (part_in_box(b, ev[i].prim, NULL, lb, &part))
            add_events(l, ev[i].prim, &part);
        if (part_in_box(b, ev[i].prim, NULL, rb, &part))
            add_events(r, ev[i].prim, &part);
    }
    events_sort(l);
    events_sort(r);
    return 0;
}

/* Merges sorted add[0..k) into sorted dst[0..m), which has room for m + k events. */
static void merge_events(event *dst, size_t m, const event *add, size_t k)
{
    size_t i = m, j = k, o = m + k;
    while (j > 0) {
        if (i > 0 && event_less(&add[j - 1], &dst[i - 1]))
            dst[--o] = dst[--i];
        else
            dst[--o] = add[--j];
    }
}

/* Adds to child c the events of the primitives of s that go only to side `want`. */
static int merge_side(const builder *b, const prim_set *s, int want, prim_set *c)
{
    for (int a = 0; a < 3; a++) {
        const event *src = s->ev[a];
        size_t keep = 0, m = 0;
        for (uint32_t i = 0; i < s->n_ev[a]; i++)
            keep += b->side[src[i].prim] == want;
        event *dst = malloc((keep + c->n_ev[a] + 1) * sizeof *dst);
        if (!dst)
            return -1;
        for (uint32_t i = 0; i < s->n_ev[a]; i++) {
            if (b->side[src[i].prim] != want)
                continue;
            dst[m++] = src[i];
            c->n += a == 0 && src[i].type != EV_END; /* one start or planar event per primitive */
        }
        merge_events(dst, m, c->ev[a], c->n_ev[a]);
        free(c->ev[a]);
        c->ev[a] = dst;
        c->n_ev[a] += (uint32_t)keep;
    }
    return 0;
}

static int split_events(builder *b, const prim_set *s, const split *sp, const aabb *lb, const aabb *rb,
                        prim_set *l, prim_set *r)
{
    classify(b, s, sp);
    if (clip_straddlers(b, s, sp, lb, rb, l, r))
        return -1;
    return merge_side(b, s, SIDE_LEFT, l) || merge_side(b, s, SIDE_RIGHT, r) ? -1 : 0;
}

/* Root set: bounds of every primitive (no clipping needed: they lie in the root box). */
static int root_events(const builder *b, prim_set *s, aabb *root)
{
    if (events_alloc(s, 2 * (size_t)b->src->count))
        return -1;
    for (uint32_t i = 0; i < b->src->count; i++) {
        const aabb bx = b->src->bounds(b->src->user, i);
        add_events(s, i, &bx);
        box_union(root, &bx);
    }
    events_sort(s);
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

/* Snapped bin boundaries of axis k strictly inside box, sorted and distinct, into b->cand. */
static uint32_t bin_planes(const builder *b, const aabb *box, uint32_t k)
{
    double *c = b->cand;
    const double w = (box->hi[k] - box->lo[k]) / b->p.bins;
    uint32_t m = 0;
    for (uint32_t j = 1; j < b->p.bins; j++) {
        const double q = snap(b, box->lo[k] + j * w);
        if (!strictly_inside(box, k, q))
            continue;
        uint32_t i = m++; /* insertion sort: O(1) per plane when quantize is monotone */
        for (; i > 0 && c[i - 1] > q; i--)
            c[i] = c[i - 1];
        c[i] = q;
    }
    uint32_t u = 0;
    for (uint32_t i = 0; i < m; i++)
        if (u == 0 || c[i] != c[u - 1])
            c[u++] = c[i];
    return u;
}

static int below(double c, double x, int inclusive) { return c < x || (inclusive && c == x); }

/* Number of planes c[0..m) below x (c < x), or at most x if inclusive: binary search. */
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

/* The same, trying first the bin of x, floor(f) (f >= 0: parts lie in the node box), which is
 * the answer unless snapping moved planes. */
static inline uint32_t rank_of(const double *c, uint32_t m, double x, int inclusive, double f)
{
    const uint32_t g = f < m ? (uint32_t)f : m;
    if ((g == 0 || below(c[g - 1], x, inclusive)) && (g == m || !below(c[g], x, inclusive)))
        return g;
    return rank_search(c, m, x, inclusive);
}

/* Exact counts at the bin planes of axis k. A primitive with rank s = #(planes <= lo) is left
 * of planes s, s+1, ...; with e = #(planes < hi) it is right of planes 0..e-1; a flat primitive
 * lying in plane s-1 is in neither and counted as planar there. */
static void binned_axis(const builder *b, const prim_set *s, const aabb *box, uint32_t k, split *best)
{
    const uint32_t m = bin_planes(b, box, k);
    if (m == 0)
        return;
    uint32_t *ns = b->counts, *ne = ns + m + 1, *np = ne + m + 1;
    memset(ns, 0, 3 * ((size_t)m + 1) * sizeof *ns);
    const double scale = (m + 1) / (box->hi[k] - box->lo[k]); /* planes per unit length */
    for (uint32_t i = 0; i < s->n; i++) {
        const double lo = s->ref[i].b.lo[k], hi = s->ref[i].b.hi[k];
        const uint32_t rs = rank_of(b->cand, m, lo, 1, (lo - box->lo[k]) * scale);
        ns[rs]++;
        ne[rank_of(b->cand, m, hi, 0, (hi - box->lo[k]) * scale)]++;
        if (lo == hi && rs > 0 && b->cand[rs - 1] == lo)
            np[rs - 1]++;
    }
    const axis_terms t = terms_of(b, box, k);
    uint32_t nl = 0, ended = 0;
    for (uint32_t j = 0; j < m; j++) {
        nl += ns[j];
        ended += ne[j];
        consider(&t, b->cand[j], nl, np[j], s->n - ended, best);
    }
}

/* Small nodes (SMALL_NODE): exact SAH over the snapped bounds of their primitives. */
static void small_axis(const builder *b, const prim_set *s, const aabb *box, uint32_t k, split *best)
{
    const axis_terms t = terms_of(b, box, k);
    for (uint32_t j = 0; j < 2 * s->n; j++) {
        const aabb *own = &s->ref[j / 2].b;
        const double q = snap(b, j % 2 ? own->hi[k] : own->lo[k]);
        if (!strictly_inside(box, k, q))
            continue;
        uint32_t nl = 0, np = 0, nr = 0;
        for (uint32_t i = 0; i < s->n; i++) {
            const uint32_t left = s->ref[i].b.lo[k] < q, right = s->ref[i].b.hi[k] > q;
            nl += left;
            nr += right;
            np += (left | right) == 0; /* lo >= q >= hi: lying in the plane */
        }
        consider(&t, q, nl, np, nr, best);
    }
}

/* Appends primitive pr to child c, clipped to box (NULL: it lies on one side, keep it as is). */
static void keep_ref(const builder *b, prim_set *c, const prim_ref *pr, const aabb *box)
{
    prim_ref out = *pr;
    if (!box || part_in_box(b, pr->id, &pr->b, box, &out.b))
        c->ref[c->n++] = out;
}

static int split_refs(const builder *b, const prim_set *s, const split *sp, const aabb *lb, const aabb *rb,
                      prim_set *l, prim_set *r)
{
    size_t nl = 0, nr = 0;
    for (uint32_t i = 0; i < s->n; i++) {
        const int side = side_of(s->ref[i].b.lo[sp->axis], s->ref[i].b.hi[sp->axis], sp);
        nl += side != SIDE_RIGHT;
        nr += side != SIDE_LEFT;
    }
    l->ref = malloc((nl + 1) * sizeof *l->ref);
    r->ref = malloc((nr + 1) * sizeof *r->ref);
    if (!l->ref || !r->ref)
        return -1;
    for (uint32_t i = 0; i < s->n; i++) {
        const prim_ref *pr = &s->ref[i];
        const int side = side_of(pr->b.lo[sp->axis], pr->b.hi[sp->axis], sp);
        if (side != SIDE_RIGHT)
            keep_ref(b, l, pr, side == SIDE_BOTH ? lb : NULL);
        if (side != SIDE_LEFT)
            keep_ref(b, r, pr, side == SIDE_BOTH ? rb : NULL);
    }
    return 0;
}

static int root_refs(const builder *b, prim_set *s, aabb *root)
{
    if (!(s->ref = malloc(((size_t)b->src->count + 1) * sizeof *s->ref)))
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
    for (int a = 0; a < 3; a++)
        free(s->ev[a]);
    free(s->ref);
    memset(s, 0, sizeof *s);
}

static int binned(const builder *b) { return b->p.bins > 0; }

static void find_split(const builder *b, const prim_set *s, const aabb *box, split *best)
{
    for (uint32_t k = 0; k < 3; k++) {
        if (!binned(b))
            sweep_axis(b, s, box, k, best);
        else if (s->n <= SMALL_NODE && 2 * s->n < b->p.bins - 1)
            small_axis(b, s, box, k, best);
        else
            binned_axis(b, s, box, k, best);
    }
}

/* Builds node `node` (already allocated) over s, which it frees. */
static int build_node(builder *b, uint32_t node, const aabb *box, prim_set *s, uint32_t depth)
{
    split best = { INFINITY, 0, 0.0, 0 };
    if (s->n > b->p.leaf_size && depth < b->max_depth)
        find_split(b, s, box, &best);
    if (!(best.cost < b->p.cost_intersection * s->n)) {
        const int rc = binned(b) ? leaf_from_refs(b, node, s) : leaf_from_events(b, node, s);
        set_free(s);
        return rc;
    }
    aabb lb = *box, rb = *box;
    lb.hi[best.axis] = rb.lo[best.axis] = best.pos;
    prim_set l = { 0 }, r = { 0 };
    uint32_t child = 0;
    int rc = binned(b) ? split_refs(b, s, &best, &lb, &rb, &l, &r) : split_events(b, s, &best, &lb, &rb, &l, &r);
    set_free(s); /* before recursing: the parent's lists are the largest */
    if (rc == 0)
        rc = add_nodes(b, 2, &child);
    if (rc != 0) {
        set_free(&l);
        set_free(&r);
        return -1;
    }
    b->nodes[node] = (kd_node){ best.axis, child, best.pos, 0, 0 };
    if (build_node(b, child, &lb, &l, depth + 1) != 0) {
        set_free(&r);
        return -1;
    }
    return build_node(b, child + 1, &rb, &r, depth + 1);
}

/* ---- statistics ----------------------------------------------------------------------------- */

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

typedef struct {
    const kd_tree *t;
    const kd_params *p;
    measure_kind kind;
    double root_measure;
    kd_stats st;
} walker;

static void walk(walker *w, uint32_t node, const aabb *box, uint32_t depth)
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
        w->st.sah_cost += w->p->cost_intersection * n->count * weight;
        return;
    }
    w->st.sah_cost += w->p->cost_traversal * weight;
    aabb lb = *box, rb = *box;
    lb.hi[n->axis] = rb.lo[n->axis] = n->split;
    walk(w, n->child, &lb, depth + 1);
    walk(w, n->child + 1, &rb, depth + 1);
}

static kd_stats tree_stats(const kd_tree *t, const kd_params *p)
{
    walker w = { t, p, MEASURE_UNIT, 1.0, { 0 } };
    if (half_area(&t->bounds) > 0)
        w.kind = MEASURE_AREA;
    else if (length(&t->bounds) > 0)
        w.kind = MEASURE_LENGTH;
    w.root_measure = measure(w.kind, &t->bounds);
    if (t->n_nodes > 0)
        walk(&w, 0, &t->bounds, 0);
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
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint32_t auto_depth(uint32_t count)
{
    const double d = count > 1 ? 8.0 + 1.3 * log2((double)count) : 8.0;
    return d >= 64.0 ? 64u : (uint32_t)lround(d);
}

/* p without the spare capacity of doubling; a failed shrink keeps p as it is. */
static void *shrink(void *p, size_t bytes)
{
    void *q = realloc(p, bytes);
    return q ? q : p;
}

/* Scratch arrays and the root primitive set. */
static int start(builder *b, prim_set *s, aabb *root)
{
    const aabb empty = { { INFINITY, INFINITY, INFINITY }, { -INFINITY, -INFINITY, -INFINITY } };
    *root = empty;
    if (binned(b)) {
        b->cand = malloc((size_t)b->p.bins * sizeof *b->cand);
        b->counts = malloc(3 * ((size_t)b->p.bins + 1) * sizeof *b->counts);
        if (!b->cand || !b->counts || root_refs(b, s, root))
            return -1;
    } else {
        if (b->src->count > UINT32_MAX / 2)
            return -1; /* 2 events per primitive and axis must fit in 32 bits */
        b->side = malloc((size_t)b->src->count + 1);
        if (!b->side || root_events(b, s, root))
            return -1;
    }
    if (b->src->count == 0)
        *root = (aabb){ { 0, 0, 0 }, { 0, 0, 0 } }; /* no primitives: a point at the origin */
    b->prims = reserve(NULL, &b->cap_prims, (uint64_t)b->src->count + 1, sizeof *b->prims);
    uint32_t first;
    return b->prims ? add_nodes(b, 1, &first) : -1;
}

int kd_build(const kd_source *src, const kd_params *p, kd_tree *out)
{
    const double t0 = now();
    memset(out, 0, sizeof *out);
    builder b = { .src = src, .p = *p };
    b.max_depth = p->max_depth ? p->max_depth : auto_depth(src->count);
    prim_set s = { 0 };
    aabb root;
    int rc = start(&b, &s, &root);
    if (rc == 0)
        rc = build_node(&b, 0, &root, &s, 0); /* frees s */
    set_free(&s);
    free(b.side);
    free(b.cand);
    free(b.counts);
    if (rc != 0) {
        free(b.nodes);
        free(b.prims);
        return -1;
    }
    *out = (kd_tree){ shrink(b.nodes, b.n_nodes * sizeof *b.nodes), b.n_nodes,
                      shrink(b.prims, ((size_t)b.n_prims + 1) * sizeof *b.prims), b.n_prims, root, { 0 } };
    out->stats = tree_stats(out, p);
    out->stats.build_seconds = now() - t0;
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

static void poly_add(polygon *p, const double v[3])
{
    if (p->n < CLIP_MAX)
        memcpy(p->v[p->n++], v, sizeof p->v[0]);
}

/* Point where segment in-out crosses x[axis] = d, computed from the inside end so that an edge
 * shared by two triangles gives the same point both ways; kept within the segment's bounds. */
static void crossing(const double in[3], const double out[3], int axis, double d, double p[3])
{
    const double t = (d - in[axis]) / (out[axis] - in[axis]);
    for (int k = 0; k < 3; k++) {
        const double x = in[k] + t * (out[k] - in[k]);
        p[k] = dmin(dmax(x, dmin(in[k], out[k])), dmax(in[k], out[k]));
    }
    p[axis] = d;
}

/* Keeps the part of src with x[axis] >= d (keep_above) or <= d; points on the plane are kept. */
static void clip_plane(const polygon *src, int axis, double d, int keep_above, polygon *dst)
{
    dst->n = 0;
    for (int i = 0; i < src->n; i++) {
        const double *a = src->v[i], *c = src->v[(i + 1) % src->n];
        const int ain = keep_above ? a[axis] >= d : a[axis] <= d;
        const int cin = keep_above ? c[axis] >= d : c[axis] <= d;
        if (ain)
            poly_add(dst, a);
        /* a crossing only between strict sides: a vertex on the plane is the crossing itself */
        if (ain != cin && a[axis] != d && c[axis] != d) {
            double p[3];
            crossing(ain ? a : c, ain ? c : a, axis, d, p);
            poly_add(dst, p);
        }
    }
}

int kd_clip_triangle(const double a[3], const double b[3], const double c[3], const aabb *box, aabb *out)
{
    polygon p[2];
    p[0].n = 3;
    memcpy(p[0].v[0], a, sizeof p[0].v[0]);
    memcpy(p[0].v[1], b, sizeof p[0].v[0]);
    memcpy(p[0].v[2], c, sizeof p[0].v[0]);
    int cur = 0;
    for (int plane = 0; plane < 6 && p[cur].n > 0; plane++) {
        const int axis = plane / 2, above = plane % 2 == 0;
        clip_plane(&p[cur], axis, above ? box->lo[axis] : box->hi[axis], above, &p[1 - cur]);
        cur = 1 - cur;
    }
    if (p[cur].n == 0)
        return 0;
    /* exact inside tests, crossings on their plane and within their edge: the polygon lies in box */
    for (int k = 0; k < 3; k++) {
        out->lo[k] = out->hi[k] = p[cur].v[0][k];
        for (int i = 1; i < p[cur].n; i++) {
            out->lo[k] = dmin(out->lo[k], p[cur].v[i][k]);
            out->hi[k] = dmax(out->hi[k], p[cur].v[i][k]);
        }
    }
    return 1;
}
