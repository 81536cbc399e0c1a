/*
 * Tests of the SAH kd-tree builder (host/kdtree) on random triangle soups, a tessellated sphere,
 * random boxes (binned mode) and degenerate inputs. Every tree is checked by check_tree():
 *
 *   structure  nodes[0] is the root, child > parent index, child + 1 < n_nodes, every node is
 *              reached exactly once, split planes lie strictly inside their node box, leaf ranges
 *              lie in prims, depth <= max_depth, and with quantize every split is a fixed point;
 *   leaves     with box L of a leaf and part = clip(i, L) (the source's clip, or box intersection):
 *              complete: if part reaches into the interior of L (on every axis where L has
 *                        extent, part.lo < L.hi - EPS and part.hi > L.lo + EPS: EPS allows for
 *                        rounding in clip()), i is in the leaf;
 *              sound:    if i is in the leaf, clip(i, L) is non-empty (it may only touch L: a
 *                        primitive lying in a split plane is kept on one side, and a primitive
 *                        touching a leaf at its face need not be listed there);
 *              no leaf lists a primitive twice; tree.bounds is the union of the bounds;
 *   stats      recounted from the tree (leaves, empty leaves, references, depth, largest leaf,
 *              SAH cost from the node boxes' surface areas) and sah_cost equal to kd_sah_cost.
 *
 * SAH quality is compared against an object-median baseline built here with the same node
 * layout; kd_sah_cost is checked against hand-computed values, kd_clip_triangle against
 * hand-computed polygons. Large builds, which use threads, must repeat bit for bit and equal the
 * single-threaded build.
 */
#define _GNU_SOURCE /* sched_setaffinity */
#include <sched.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kdtree.h"
#include "ugrid.h"

/* ---- inputs ------------------------------------------------------------------------------- */

typedef struct {
    double v[3][3];
} tri;

typedef struct {
    tri *t;
    uint32_t n;
} soup;

static uint64_t rng = 0x243F6A8885A308D3ull;

static void seed(uint64_t s) { rng = s * 0x9E3779B97F4A7C15ull + 1; }

static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

static aabb tri_bounds(const void *user, uint32_t i)
{
    const tri *t = &((const soup *)user)->t[i];
    aabb b;
    for (int k = 0; k < 3; k++) {
        b.lo[k] = fmin(t->v[0][k], fmin(t->v[1][k], t->v[2][k]));
        b.hi[k] = fmax(t->v[0][k], fmax(t->v[1][k], t->v[2][k]));
    }
    return b;
}

static int tri_clip(const void *user, uint32_t i, const aabb *box, aabb *out)
{
    const tri *t = &((const soup *)user)->t[i];
    return kd_clip_triangle(t->v[0], t->v[1], t->v[2], box, out);
}

static int tri_clip_split(const void *user, uint32_t i, const aabb *box, uint32_t axis, double pos, aabb out[2])
{
    const tri *t = &((const soup *)user)->t[i];
    return kd_clip_triangle_split(t->v[0], t->v[1], t->v[2], box, axis, pos, out);
}

static soup soup_new(uint32_t n)
{
    soup s = { calloc(n + 1u, sizeof(tri)), n };
    assert_non_null(s.t);
    return s;
}

/* Small random triangles in the unit cube, a few large ones across it. */
static soup random_soup(uint32_t n, uint64_t s)
{
    seed(s);
    soup r = soup_new(n);
    for (uint32_t i = 0; i < n; i++) {
        const double size = i % 50 == 0 ? 0.8 : 0.06;
        double c[3] = { urand(), urand(), urand() };
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++)
                r.t[i].v[v][k] = c[k] + size * (urand() - 0.5);
    }
    return r;
}

static void sphere_point(double theta, double phi, double p[3])
{
    p[0] = sin(theta) * cos(phi);
    p[1] = sin(theta) * sin(phi);
    p[2] = cos(theta);
}

/* UV sphere of radius 1; the triangles at the poles have zero area (two equal vertices). */
static soup sphere(uint32_t stacks, uint32_t slices)
{
    soup r = soup_new(2 * stacks * slices);
    const double pi = 3.14159265358979323846;
    uint32_t n = 0;
    for (uint32_t i = 0; i < stacks; i++)
        for (uint32_t j = 0; j < slices; j++) {
            double p[4][3];
            const double t0 = pi * i / stacks, t1 = pi * (i + 1) / stacks;
            const double f0 = 2 * pi * j / slices, f1 = 2 * pi * (j + 1) / slices;
            sphere_point(t0, f0, p[0]);
            sphere_point(t0, f1, p[1]);
            sphere_point(t1, f1, p[2]);
            sphere_point(t1, f0, p[3]);
            const int quad[2][3] = { { 0, 1, 2 }, { 0, 2, 3 } };
            for (int q = 0; q < 2; q++, n++)
                for (int v = 0; v < 3; v++)
                    memcpy(r.t[n].v[v], p[quad[q][v]], sizeof p[0]);
        }
    r.n = n;
    return r;
}

typedef struct {
    aabb *b;
    uint32_t n;
} box_set;

static aabb box_bounds(const void *user, uint32_t i) { return ((const box_set *)user)->b[i]; }

static box_set random_boxes(uint32_t n, uint64_t s)
{
    seed(s);
    box_set r = { calloc(n + 1u, sizeof(aabb)), n };
    assert_non_null(r.b);
    for (uint32_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            const double c = 100 * urand(), e = i % 10 == 0 ? 0 : 3 * urand(); /* some points */
            r.b[i].lo[k] = c - e;
            r.b[i].hi[k] = c + e;
        }
    return r;
}

static kd_source tri_source(const soup *s) { return (kd_source){ s->n, s, tri_bounds, tri_clip, tri_clip_split }; }
static kd_source box_source(const box_set *s) { return (kd_source){ s->n, s, box_bounds, NULL, NULL }; }

static double grid8(double x) { return round(x * 8.0) / 8.0; }
static double grid2(double x) { return round(x * 2.0) / 2.0; }

/* ---- checks ------------------------------------------------------------------------------- */

static int box_overlap(const aabb *a, const aabb *b, aabb *out)
{
    for (int k = 0; k < 3; k++) {
        out->lo[k] = fmax(a->lo[k], b->lo[k]);
        out->hi[k] = fmin(a->hi[k], b->hi[k]);
        if (out->lo[k] > out->hi[k])
            return 0;
    }
    return 1;
}

static double half_area_of(const aabb *b)
{
    const double x = b->hi[0] - b->lo[0], y = b->hi[1] - b->lo[1], z = b->hi[2] - b->lo[2];
    return x * y + y * z + z * x;
}

static int part_of(const kd_source *src, uint32_t i, const aabb *box, aabb *out)
{
    if (src->clip)
        return src->clip(src->user, i, box, out);
    const aabb b = src->bounds(src->user, i);
    return box_overlap(&b, box, out);
}

/* Clipping rounds: a triangle that only touches a leaf along an edge can come out of clip() as a
 * sliver a few ulps deep, depending on the box it was clipped to. So "reaching into the
 * interior" means by more than EPS (the scenes here have sizes 1 to 100). */
#define EPS 1e-9

static int reaches_interior(const aabb *part, const aabb *leaf)
{
    for (int k = 0; k < 3; k++)
        if (leaf->lo[k] < leaf->hi[k] && !(part->lo[k] < leaf->hi[k] - EPS && part->hi[k] > leaf->lo[k] + EPS))
            return 0;
    return 1;
}

static uint32_t expected_max_depth(const kd_source *src, const kd_params *p)
{
    if (p->max_depth)
        return p->max_depth;
    const int shallow = p->shallow_from && src->count >= p->shallow_from;
    const int binned = p->bins > 0 && src->count >= p->bins_from; /* a binned shallow tree: one level more */
    const double d = src->count > 1 ? (shallow ? 5.0 + binned : 8.0) + (shallow ? 1.0 : 1.3) * log2((double)src->count) : 8.0;
    return d >= 64 ? 64 : (uint32_t)lround(d);
}

typedef struct {
    const kd_source *src;
    const kd_params *p;
    const kd_tree *t;
    uint8_t *visited, *member;
    aabb *bounds; /* of every primitive, asked once */
    kd_stats st;  /* recounted */
} checker;

/* near: the primitives whose bounds overlap box (closed); the others do not touch the leaf. */
/* A flat leaf on a face of a box with volume (consider_face) lists the primitives lying in that
 * face; one that crosses the face only touches it along an edge or at a vertex, and a ray
 * meeting it there is in the neighbouring cell at the same distance (closed intervals), which
 * lists it. */
static int in_neighbour(const checker *c, uint32_t i, const aabb *leaf)
{
    for (int k = 0; k < 3; k++)
        if (leaf->lo[k] == leaf->hi[k] && c->t->bounds.lo[k] < c->t->bounds.hi[k] && c->bounds[i].lo[k] < c->bounds[i].hi[k])
            return 1;
    return 0;
}

static void check_leaf(checker *c, const kd_node *n, const aabb *box, const uint32_t *near, uint32_t n_near)
{
    const kd_source *src = c->src;
    assert_true((uint64_t)n->first + n->count <= c->t->n_prims);
    for (uint32_t e = 0; e < n->count; e++) {
        const uint32_t id = c->t->prims[n->first + e];
        assert_true(id < src->count);
        assert_int_equal(c->member[id], 0); /* listed once */
        c->member[id] = 1;
        aabb part;
        if (!box_overlap(&c->bounds[id], box, &part))
            fail_msg("leaf lists primitive %u, which does not touch the leaf", id);
    }
    for (uint32_t k = 0; k < n_near; k++) {
        const uint32_t i = near[k];
        aabb part;
        const int touches = box_overlap(&c->bounds[i], box, &part) && part_of(src, i, box, &part);
        if (touches && reaches_interior(&part, box) && !in_neighbour(c, i, box) && !c->member[i])
            fail_msg("primitive %u reaches into a leaf that does not list it", i);
        if (c->member[i] && !touches)
            fail_msg("leaf lists primitive %u, which does not touch the leaf", i);
    }
    for (uint32_t e = 0; e < n->count; e++)
        c->member[c->t->prims[n->first + e]] = 0;
    c->st.n_leaves++;
    c->st.n_empty_leaves += n->count == 0;
    c->st.references += n->count;
    if (n->count > c->st.max_leaf_count)
        c->st.max_leaf_count = n->count;
}

/* The primitives of near[0..n) whose bounds overlap box, into out. */
static uint32_t near_box(const checker *c, const uint32_t *near, uint32_t n, const aabb *box, uint32_t *out)
{
    uint32_t k = 0;
    for (uint32_t e = 0; e < n; e++) {
        aabb part;
        if (box_overlap(&c->bounds[near[e]], box, &part))
            out[k++] = near[e];
    }
    return k;
}

/* near: the primitives whose bounds overlap box (a leaf needs to look at no others). */
static void check_node(checker *c, uint32_t index, const aabb *box, uint32_t depth, const uint32_t *near, uint32_t n_near)
{
    assert_true(index < c->t->n_nodes);
    assert_int_equal(c->visited[index], 0);
    c->visited[index] = 1;
    if (depth > c->st.depth)
        c->st.depth = depth;
    const kd_node *n = &c->t->nodes[index];
    const double root = half_area_of(&c->t->bounds); /* the recount covers roots with area only */
    const double weight = root > 0 ? half_area_of(box) / root : 0;
    if (n->axis == KD_LEAF) {
        check_leaf(c, n, box, near, n_near);
        c->st.sah_cost += c->p->cost_intersection * n->count * weight;
        return;
    }
    c->st.sah_cost += c->p->cost_traversal * weight;
    assert_true(n->axis < 3);
    assert_true(n->child > index);
    assert_true(n->child + 1 < c->t->n_nodes);
    /* strictly inside, or on a face of a box with extent (a flat cell for the primitives lying in
     * that face, consider_face) */
    assert_true(n->split >= box->lo[n->axis] && n->split <= box->hi[n->axis] && box->lo[n->axis] < box->hi[n->axis]);
    if (c->p->quantize)
        assert_true(c->p->quantize(n->split) == n->split);
    aabb lb = *box, rb = *box;
    lb.hi[n->axis] = rb.lo[n->axis] = n->split;
    uint32_t *sub = malloc((n_near + 1u) * sizeof *sub);
    assert_non_null(sub);
    check_node(c, n->child, &lb, depth + 1, sub, near_box(c, near, n_near, &lb, sub));
    check_node(c, n->child + 1, &rb, depth + 1, sub, near_box(c, near, n_near, &rb, sub));
    free(sub);
}

/* All invariants of the file comment; stats only for trees from kd_build. */
static void check_tree_opt(const kd_source *src, const kd_params *p, const kd_tree *t, int stats)
{
    assert_true(t->n_nodes >= 1);
    checker c = { src, p, t, calloc(t->n_nodes, 1), calloc(src->count + 1u, 1),
                  calloc(src->count + 1u, sizeof(aabb)), { 0 } };
    assert_non_null(c.visited);
    assert_non_null(c.member);
    assert_non_null(c.bounds);
    aabb u = { { INFINITY, INFINITY, INFINITY }, { -INFINITY, -INFINITY, -INFINITY } };
    for (uint32_t i = 0; i < src->count; i++) {
        c.bounds[i] = src->bounds(src->user, i);
        for (int k = 0; k < 3; k++) {
            u.lo[k] = fmin(u.lo[k], c.bounds[i].lo[k]);
            u.hi[k] = fmax(u.hi[k], c.bounds[i].hi[k]);
        }
    }
    for (int k = 0; k < 3 && src->count > 0; k++) {
        assert_true(t->bounds.lo[k] == u.lo[k]);
        assert_true(t->bounds.hi[k] == u.hi[k]);
    }
    uint32_t *near = malloc((src->count + 1u) * sizeof *near);
    assert_non_null(near);
    for (uint32_t i = 0; i < src->count; i++)
        near[i] = i;
    check_node(&c, 0, &t->bounds, 0, near, near_box(&c, near, src->count, &t->bounds, near));
    free(near);
    for (uint32_t i = 0; i < t->n_nodes; i++)
        assert_int_equal(c.visited[i], 1); /* every node reached */
    assert_true(c.st.depth <= expected_max_depth(src, p));
    assert_true(c.st.references == t->n_prims);
    if (stats) {
        assert_int_equal(t->stats.n_leaves, c.st.n_leaves);
        assert_int_equal(t->stats.n_empty_leaves, c.st.n_empty_leaves);
        assert_int_equal(t->stats.depth, c.st.depth);
        assert_true(t->stats.references == c.st.references);
        assert_int_equal(t->stats.max_leaf_count, c.st.max_leaf_count);
        assert_float_equal(t->stats.sah_cost, kd_sah_cost(t, p), 1e-9 * (1 + t->stats.sah_cost));
        if (half_area_of(&t->bounds) > 0) /* else: length ratios, checked by hand in sah_cost_by_hand */
            assert_float_equal(t->stats.sah_cost, c.st.sah_cost, 1e-9 * (1 + t->stats.sah_cost));
        assert_true(t->stats.build_seconds >= 0);
    }
    free(c.visited);
    free(c.member);
    free(c.bounds);
}

static void check_tree(const kd_source *src, const kd_params *p, const kd_tree *t) { check_tree_opt(src, p, t, 1); }

static void build_and_check(const kd_source *src, const kd_params *p)
{
    kd_tree t;
    assert_int_equal(kd_build(src, p, &t), 0);
    check_tree(src, p, &t);
    kd_free(&t);
}

static kd_params params(uint32_t bins, double (*quantize)(double))
{
    kd_params p;
    kd_params_default(&p);
    p.bins = bins;
    p.quantize = quantize;
    return p;
}

/* ---- median-split baseline ------------------------------------------------------------------ */

typedef struct {
    const kd_source *src;
    kd_node *nodes;
    uint32_t n_nodes, cap_nodes;
    uint32_t *prims;
    uint32_t n_prims, cap_prims;
} median_tree;

static int cmp_double(const void *x, const void *y)
{
    const double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

static void *grow(void *p, uint32_t *cap, uint32_t need, size_t size)
{
    if (need <= *cap)
        return p;
    *cap = 2 * need;
    p = realloc(p, *cap * size);
    assert_non_null(p);
    return p;
}

/* Primitives of ids[0..n) whose part in the child box goes there: reaching below the plane
 * (left) or above it (right); primitives lying in the plane go left, as the builder may do. */
static uint32_t median_side(const median_tree *m, const uint32_t *ids, uint32_t n, const aabb *child, int axis,
                            double split, int left, uint32_t *out)
{
    uint32_t k = 0;
    for (uint32_t i = 0; i < n; i++) {
        aabb part;
        if (!part_of(m->src, ids[i], child, &part))
            continue;
        const int flat_in_plane = part.lo[axis] == split && part.hi[axis] == split;
        if (left ? part.lo[axis] < split || flat_in_plane : part.hi[axis] > split)
            out[k++] = ids[i];
    }
    return k;
}

/* Split position: the median of the primitive centres on the longest axis (else the middle). */
static double median_split(const median_tree *m, const aabb *box, const uint32_t *ids, uint32_t n, int axis)
{
    double split = 0.5 * (box->lo[axis] + box->hi[axis]);
    if (n == 0)
        return split;
    double *c = malloc(n * sizeof *c);
    assert_non_null(c);
    for (uint32_t i = 0; i < n; i++) {
        aabb part;
        c[i] = part_of(m->src, ids[i], box, &part) ? 0.5 * (part.lo[axis] + part.hi[axis]) : split;
    }
    qsort(c, n, sizeof *c, cmp_double);
    if (c[n / 2] > box->lo[axis] && c[n / 2] < box->hi[axis])
        split = c[n / 2];
    free(c);
    return split;
}

static void median_build(median_tree *m, uint32_t node, const aabb *box, uint32_t *ids, uint32_t n, uint32_t depth)
{
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (box->hi[k] - box->lo[k] > box->hi[axis] - box->lo[axis])
            axis = k;
    const double split = median_split(m, box, ids, n, axis);
    aabb lb = *box, rb = *box;
    lb.hi[axis] = rb.lo[axis] = split;
    uint32_t *l = malloc((n + 1u) * sizeof *l), *r = malloc((n + 1u) * sizeof *r);
    assert_non_null(l);
    assert_non_null(r);
    const uint32_t nl = median_side(m, ids, n, &lb, axis, split, 1, l);
    const uint32_t nr = median_side(m, ids, n, &rb, axis, split, 0, r);
    if (n <= 2 || depth >= 16 || !(split > box->lo[axis] && split < box->hi[axis]) || (nl == n && nr == n)) {
        m->prims = grow(m->prims, &m->cap_prims, m->n_prims + n + 1, sizeof *m->prims);
        m->nodes[node] = (kd_node){ KD_LEAF, 0, 0, m->n_prims, n };
        memcpy(m->prims + m->n_prims, ids, n * sizeof *ids);
        m->n_prims += n;
    } else {
        const uint32_t child = m->n_nodes;
        m->n_nodes += 2;
        m->nodes = grow(m->nodes, &m->cap_nodes, m->n_nodes, sizeof *m->nodes);
        m->nodes[node] = (kd_node){ (uint32_t)axis, child, split, 0, 0 };
        median_build(m, child, &lb, l, nl, depth + 1);
        median_build(m, child + 1, &rb, r, nr, depth + 1);
    }
    free(l);
    free(r);
}

/* The baseline over the same input and root box. */
static kd_tree median_tree_build(const kd_source *src, const aabb *root)
{
    median_tree m = { src, NULL, 1, 0, NULL, 0, 0 };
    m.nodes = grow(NULL, &m.cap_nodes, 1, sizeof *m.nodes);
    uint32_t *ids = malloc((src->count + 1u) * sizeof *ids);
    assert_non_null(ids);
    for (uint32_t i = 0; i < src->count; i++)
        ids[i] = i;
    median_build(&m, 0, root, ids, src->count, 0);
    free(ids);
    kd_tree t = { m.nodes, m.n_nodes, m.prims, m.n_prims, *root, { 0 } };
    return t;
}

/* ---- tests: invariants on realistic inputs -------------------------------------------------- */

static void soup_exact(void **state)
{
    (void)state;
    for (uint64_t s = 1; s <= 3; s++) {
        soup so = random_soup(1500, s);
        const kd_source src = tri_source(&so);
        const kd_params p = params(0, NULL);
        build_and_check(&src, &p);
        free(so.t);
    }
}

static void sphere_exact(void **state)
{
    (void)state;
    soup so = sphere(24, 48);
    const kd_source src = tri_source(&so);
    kd_params p = params(0, NULL);
    build_and_check(&src, &p);
    p.leaf_size = 4;
    p.max_depth = 6;
    build_and_check(&src, &p);
    free(so.t);
}

/* Exact mode without a clip function: box primitives, intersection as the clip. */
static void boxes_exact(void **state)
{
    (void)state;
    box_set bs = random_boxes(1500, 7);
    const kd_source src = box_source(&bs);
    const kd_params p = params(0, NULL);
    build_and_check(&src, &p);
    free(bs.b);
}

static void boxes_binned(void **state)
{
    (void)state;
    const uint32_t bins[] = { 1, 2, 8, 32 };
    box_set bs = random_boxes(2000, 11);
    const kd_source src = box_source(&bs);
    for (size_t i = 0; i < sizeof bins / sizeof bins[0]; i++) {
        const kd_params p = params(bins[i], NULL);
        build_and_check(&src, &p);
    }
    free(bs.b);
}

/* Binned mode with a clip function (allowed by the API, though the top level has none). */
static void soup_binned(void **state)
{
    (void)state;
    soup so = random_soup(1500, 5);
    const kd_source src = tri_source(&so);
    const kd_params p = params(16, NULL);
    build_and_check(&src, &p);
    free(so.t);
}

/* Binned nodes above exact_max primitives, exact subtrees below (the bottom level's default):
 * valid trees, with and without snapping, and an SAH cost close to exact mode's. The sphere has
 * odd stack and slice counts: no vertex lies on the middle planes the bins put through it. (A
 * triangle touching a bin plane only at a vertex can come out of clip() as a point in the plane,
 * by rounding, and then sit in a flat cell on that plane that clipping to the cell itself
 * misses: harmless, one test too many, but check_leaf's soundness is exact.) */
static void soup_hybrid(void **state)
{
    (void)state;
    soup so = random_soup(3000, 6), sp = sphere(23, 47);
    const kd_source srcs[] = { tri_source(&so), tri_source(&sp) };
    for (size_t i = 0; i < 2; i++)
        for (int q = 0; q < 2; q++) {
            kd_params p = params(64, q ? grid8 : NULL);
            p.exact_max = 128;
            kd_tree t, e;
            assert_int_equal(kd_build(&srcs[i], &p, &t), 0);
            check_tree(&srcs[i], &p, &t);
            const kd_params exact = params(0, p.quantize);
            assert_int_equal(kd_build(&srcs[i], &exact, &e), 0);
            assert_true(kd_sah_cost(&t, &p) < 1.05 * kd_sah_cost(&e, &exact));
            kd_free(&t);
            kd_free(&e);
        }
    free(so.t);
    free(sp.t);
}

static void assert_same_tree(const kd_tree *a, const kd_tree *b);

/* bins_from picks the mode per tree: a tree of at least bins_from primitives is binned (and, when
 * shallow, one level deeper), a smaller one is exact throughout, the same tree as exact mode's. */
static void bins_from_per_tree(void **state)
{
    (void)state;
    soup so = random_soup(3000, 31);
    const kd_source src = tri_source(&so);
    kd_params binned = params(128, grid8), exact = params(0, grid8);
    binned.exact_max = 48;
    binned.shallow_from = exact.shallow_from = 1000;
    kd_params at = binned, above = binned;
    at.bins_from = 3000;
    above.bins_from = 3001;
    assert_int_equal(kd_depth_bound(&binned, 3000), 18); /* round(6 + log2 3000) */
    assert_int_equal(kd_depth_bound(&at, 3000), 18);
    assert_int_equal(kd_depth_bound(&above, 3000), 17); /* round(5 + log2 3000), exact's */
    kd_tree b, a, x, e;
    assert_int_equal(kd_build(&src, &binned, &b), 0);
    assert_int_equal(kd_build(&src, &at, &a), 0);
    assert_int_equal(kd_build(&src, &above, &x), 0);
    assert_int_equal(kd_build(&src, &exact, &e), 0);
    check_tree(&src, &binned, &b);
    assert_same_tree(&b, &a);
    assert_same_tree(&e, &x);
    assert_true(b.n_nodes != e.n_nodes || memcmp(b.nodes, e.nodes, b.n_nodes * sizeof *b.nodes) != 0);
    kd_free(&b);
    kd_free(&a);
    kd_free(&x);
    kd_free(&e);
    free(so.t);
}

/* bin_size sets a binned node's bins from its primitives: n / bin_size, at least KD_MIN_BINS (or
 * bins if fewer) and at most bins. A bin_size no node reaches gives every node the fewest bins,
 * the tree of 32 bins throughout; with bins under KD_MIN_BINS, every node gets bins; a bin_size
 * between gives the root and the nodes near it more bins than those below: a tree of its own,
 * valid, and not one of the two fixed counts'. */
static void bins_per_node_size(void **state)
{
    (void)state;
    soup so = random_soup(3000, 41);
    const kd_source src = tri_source(&so);
    kd_params fewest = params(256, NULL), sixteen = params(16, NULL), mixed = params(128, NULL);
    fewest.bin_size = UINT32_MAX;
    sixteen.bin_size = 16;
    mixed.bin_size = 16; /* the root: 187 bins, capped at 128; below 512 primitives: 32 */
    const kd_params p32 = params(32, NULL), p16 = params(16, NULL), p128 = params(128, NULL);
    kd_tree f, t32, s, t16, m, t128;
    assert_int_equal(kd_build(&src, &fewest, &f), 0);
    assert_int_equal(kd_build(&src, &p32, &t32), 0);
    assert_int_equal(kd_build(&src, &sixteen, &s), 0);
    assert_int_equal(kd_build(&src, &p16, &t16), 0);
    assert_int_equal(kd_build(&src, &mixed, &m), 0);
    assert_int_equal(kd_build(&src, &p128, &t128), 0);
    assert_same_tree(&f, &t32);
    assert_same_tree(&s, &t16);
    check_tree(&src, &mixed, &m);
    assert_true(m.n_nodes != t32.n_nodes || memcmp(m.nodes, t32.nodes, m.n_nodes * sizeof *m.nodes) != 0);
    assert_true(m.n_nodes != t128.n_nodes || memcmp(m.nodes, t128.nodes, m.n_nodes * sizeof *m.nodes) != 0);
    kd_free(&f);
    kd_free(&t32);
    kd_free(&s);
    kd_free(&t16);
    kd_free(&m);
    kd_free(&t128);
    free(so.t);
}

/* ---- tests: quantized planes ---------------------------------------------------------------- */

static void quantized(void **state)
{
    (void)state;
    soup so = random_soup(1500, 21), sp = sphere(16, 32);
    box_set bs = random_boxes(1500, 22);
    const kd_source srcs[] = { tri_source(&so), tri_source(&sp), box_source(&bs) };
    for (size_t i = 0; i < 3; i++) {
        const kd_params exact = params(0, grid8), binned = params(32, grid8), coarse = params(0, grid2);
        build_and_check(&srcs[i], &exact);
        build_and_check(&srcs[i], &binned);
        build_and_check(&srcs[i], &coarse);
    }
    free(so.t);
    free(sp.t);
    free(bs.b);
}

/* A quantizer that is not monotone (but, like any rounding, maps onto its fixed points) must
 * not break the tree: 1/8 steps whose index is a multiple of 3, everything else to 0.5. */
static double scramble(double x)
{
    const long k = lround(x * 8.0);
    return k % 3 == 0 ? (double)k / 8.0 : 0.5;
}

static void non_monotone_quantize(void **state)
{
    (void)state;
    soup so = random_soup(800, 23);
    const kd_source src = tri_source(&so);
    const kd_params exact = params(0, scramble), binned = params(32, scramble);
    build_and_check(&src, &exact);
    build_and_check(&src, &binned);
    free(so.t);
}

/* ---- tests: SAH quality ----------------------------------------------------------------------- */

static void compare_with_median(const kd_source *src, const kd_params *p)
{
    kd_tree t;
    assert_int_equal(kd_build(src, p, &t), 0);
    kd_tree m = median_tree_build(src, &t.bounds);
    check_tree_opt(src, p, &m, 0); /* the baseline is a valid tree too */
    const double sah = kd_sah_cost(&t, p), median = kd_sah_cost(&m, p);
    assert_true(sah <= median);
    assert_true(sah < 0.9 * median);
    kd_free(&t);
    free(m.nodes);
    free(m.prims);
}

static void sah_beats_median(void **state)
{
    (void)state;
    soup so = random_soup(2000, 31), sp = sphere(24, 48);
    box_set bs = random_boxes(2000, 32);
    const kd_source soup_src = tri_source(&so), sphere_src = tri_source(&sp), box_src = box_source(&bs);
    const kd_params exact = params(0, NULL), binned = params(32, NULL);
    compare_with_median(&soup_src, &exact);
    compare_with_median(&sphere_src, &exact);
    compare_with_median(&box_src, &exact);
    compare_with_median(&box_src, &binned);
    compare_with_median(&soup_src, &binned);
    free(so.t);
    free(sp.t);
    free(bs.b);
}

/* The root split against a brute-force search over every candidate plane of the mode: the
 * snapped primitive bounds (exact mode, and binned mode for nodes of at most 16 primitives with
 * fewer bounds than bin planes), else the snapped bin planes; counts by definition, primitives
 * lying in the plane tried on both sides. Boxes on a coarse grid give ties, flat boxes and
 * duplicates. */
static double cost_of(const kd_params *p, const aabb *box, int axis, double q, uint32_t nl, uint32_t nr)
{
    aabb l = *box, r = *box;
    l.hi[axis] = r.lo[axis] = q;
    const double c = p->cost_traversal +
                     p->cost_intersection * (half_area_of(&l) * nl + half_area_of(&r) * nr) / half_area_of(box);
    return nl == 0 || nr == 0 ? c * (1 - p->empty_bonus) : c;
}

static double brute_force_best(const box_set *bs, const kd_params *p, const aabb *root)
{
    const int own = p->bins == 0 || (bs->n <= 16 && 2 * bs->n < p->bins - 1);
    double best = INFINITY;
    for (int axis = 0; axis < 3; axis++) {
        const double w = (root->hi[axis] - root->lo[axis]) / p->bins;
        for (uint32_t c = 0; c < (own ? 2 * bs->n : p->bins - 1); c++) {
            const aabb *b = &bs->b[c / 2];
            double q = own ? (c % 2 ? b->hi[axis] : b->lo[axis]) : root->lo[axis] + (c + 1) * w;
            q = p->quantize ? p->quantize(q) : q;
            const int face = p->bins == 0 && root->lo[axis] < root->hi[axis] && (q == root->lo[axis] || q == root->hi[axis]);
            if (!(q > root->lo[axis] && q < root->hi[axis]) && !face)
                continue;
            uint32_t nl = 0, np = 0, nr = 0;
            for (uint32_t i = 0; i < bs->n; i++) {
                const double lo = bs->b[i].lo[axis], hi = bs->b[i].hi[axis];
                nl += lo < q;
                nr += hi > q;
                np += lo == q && hi == q;
            }
            if (face) { /* exact mode: the primitives lying in a face of the root may get a flat cell */
                if (np)
                    best = fmin(best, q == root->lo[axis] ? cost_of(p, root, axis, q, np, bs->n - np)
                                                          : cost_of(p, root, axis, q, bs->n - np, np));
                continue;
            }
            best = fmin(best, cost_of(p, root, axis, q, nl + np, nr));
            best = fmin(best, cost_of(p, root, axis, q, nl, nr + np));
        }
    }
    return best;
}

static void root_split_is_optimal(void **state)
{
    (void)state;
    seed(71);
    box_set bs = { calloc(64, sizeof(aabb)), 0 };
    for (int trial = 0; trial < 600; trial++) {
        const int mode = trial % 3; /* exact, binned with bin planes, binned small node */
        bs.n = mode == 2 ? 2 + (uint32_t)(urand() * 15) : mode == 1 ? 20 + (uint32_t)(urand() * 40)
                                                                   : 2 + (uint32_t)(urand() * 60);
        for (uint32_t i = 0; i < bs.n; i++)
            for (int k = 0; k < 3; k++) {
                const double a = floor(urand() * 17) / 4, e = urand() < 0.3 ? 0 : floor(urand() * 5) / 4;
                bs.b[i].lo[k] = a;
                bs.b[i].hi[k] = a + e;
            }
        const kd_source src = box_source(&bs);
        const uint32_t bins[3] = { 0, 8, 64 };
        kd_params p = params(bins[mode], trial % 2 ? grid2 : NULL);
        p.max_depth = 1;
        kd_tree t;
        assert_int_equal(kd_build(&src, &p, &t), 0);
        check_tree(&src, &p, &t);
        const double best = brute_force_best(&bs, &p, &t.bounds), leaf = p.cost_intersection * bs.n;
        if (fabs(best - leaf) > 1e-9) {
            assert_int_equal(t.n_nodes, best < leaf ? 3 : 1);
            if (best < leaf) {
                const kd_node *r = &t.nodes[0];
                const double got = cost_of(&p, &t.bounds, (int)r->axis, r->split, t.nodes[r->child].count,
                                           t.nodes[r->child + 1].count);
                assert_float_equal(got, best, 1e-9);
            }
        }
        kd_free(&t);
    }
    free(bs.b);
}

/* ---- tests: degenerate inputs ----------------------------------------------------------------- */

static void empty_and_single(void **state)
{
    (void)state;
    soup so = random_soup(1, 41);
    for (uint32_t bins = 0; bins <= 32; bins += 32) {
        const kd_params p = params(bins, grid8);
        for (uint32_t n = 0; n <= 1; n++) {
            const kd_source src = { n, &so, tri_bounds, tri_clip, NULL };
            kd_tree t;
            assert_int_equal(kd_build(&src, &p, &t), 0);
            check_tree(&src, &p, &t);
            assert_int_equal(t.n_nodes, 1);
            assert_int_equal(t.nodes[0].axis, KD_LEAF);
            assert_int_equal(t.nodes[0].count, n);
            assert_int_equal(t.stats.n_empty_leaves, n == 0);
            kd_free(&t);
        }
    }
    free(so.t);
}

static void identical_boxes(void **state)
{
    (void)state;
    box_set bs = { calloc(1000, sizeof(aabb)), 1000 };
    for (int zero = 0; zero < 2; zero++) { /* zero: all boxes are the same point */
        for (uint32_t i = 0; i < bs.n; i++)
            bs.b[i] = (aabb){ { 1, 2, 3 }, { zero ? 1 : 4, zero ? 2 : 5, zero ? 3 : 6 } };
        const kd_source src = box_source(&bs);
        for (uint32_t bins = 0; bins <= 32; bins += 32) {
            const kd_params p = params(bins, NULL);
            kd_tree t;
            assert_int_equal(kd_build(&src, &p, &t), 0);
            check_tree(&src, &p, &t);
            assert_int_equal(t.n_nodes, 1); /* no plane lies strictly inside */
            assert_int_equal(t.stats.max_leaf_count, 1000);
            kd_free(&t);
        }
    }
    free(bs.b);
}

/* Positions -0 and +0 are equal: the root's event lists (sorted by an integer key of the position)
 * order their events by type and primitive, as at any other position. A leaf lists its primitives
 * in the order of their events on x; no plane can separate these boxes. */
static void signed_zero_positions(void **state)
{
    (void)state;
    box_set bs = { calloc(4, sizeof(aabb)), 4 };
    for (uint32_t i = 0; i < bs.n; i++)
        bs.b[i] = (aabb){ { i % 2 ? -0.0 : 0.0, 0, 0 }, { 1, 1, 1 } };
    const kd_source src = box_source(&bs);
    const kd_params p = params(0, NULL);
    kd_tree t;
    assert_int_equal(kd_build(&src, &p, &t), 0);
    check_tree(&src, &p, &t);
    assert_int_equal(t.n_nodes, 1);
    for (uint32_t i = 0; i < bs.n; i++)
        assert_int_equal(t.prims[i], i);
    kd_free(&t);
    free(bs.b);
}

/* Many copies of a few triangles, and of random boxes. */
static void duplicates(void **state)
{
    (void)state;
    soup base = random_soup(5, 43), so = soup_new(600);
    for (uint32_t i = 0; i < so.n; i++)
        so.t[i] = base.t[i % base.n];
    box_set bs = random_boxes(600, 44);
    for (uint32_t i = 0; i < bs.n; i++)
        bs.b[i] = bs.b[i % 7];
    const kd_source tsrc = tri_source(&so), bsrc = box_source(&bs);
    for (uint32_t bins = 0; bins <= 32; bins += 32) {
        const kd_params p = params(bins, NULL);
        build_and_check(&tsrc, &p);
        build_and_check(&bsrc, &p);
    }
    free(base.t);
    free(so.t);
    free(bs.b);
}

/* Triangles all in the plane z = 0.5: the root box is flat. */
static void all_in_one_plane(void **state)
{
    (void)state;
    soup so = random_soup(1000, 45);
    for (uint32_t i = 0; i < so.n; i++)
        for (int v = 0; v < 3; v++)
            so.t[i].v[v][2] = 0.5;
    const kd_source src = tri_source(&so);
    for (uint32_t bins = 0; bins <= 32; bins += 32) {
        const kd_params p = params(bins, grid8);
        build_and_check(&src, &p);
    }
    free(so.t);
}

/* Axis-aligned cubes (12 triangles each, every one flat in a face plane on the quantization grid)
 * plus a grid of triangles in z = 0.5 and one triangle across it, so that the planes holding
 * many flat triangles are split candidates. */
static soup planar_scene(void)
{
    soup so = soup_new(12 * 64 + 200 + 1);
    uint32_t n = 0;
    for (int c = 0; c < 64; c++) {
        const double o[3] = { (c % 4) * 0.25, (c / 4 % 4) * 0.25, (c / 16) * 0.25 }, s = 0.125;
        for (int axis = 0; axis < 3; axis++)
            for (int face = 0; face < 2; face++) {
                const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                double q[4][3];
                for (int corner = 0; corner < 4; corner++) {
                    q[corner][axis] = o[axis] + face * s;
                    q[corner][u] = o[u] + ((corner == 1 || corner == 2) ? s : 0);
                    q[corner][v] = o[v] + (corner >= 2 ? s : 0);
                }
                const int tris[2][3] = { { 0, 1, 2 }, { 0, 2, 3 } };
                for (int t = 0; t < 2; t++, n++)
                    for (int k = 0; k < 3; k++)
                        memcpy(so.t[n].v[k], q[tris[t][k]], sizeof q[0]);
            }
    }
    for (int i = 0; i < 200; i++, n++) {
        const double x = (i % 20) / 20.0, y = (i / 20) / 10.0;
        const double t[3][3] = { { x, y, 0.5 }, { x + 0.05, y, 0.5 }, { x, y + 0.1, 0.5 } };
        memcpy(so.t[n].v, t, sizeof t);
    }
    const double across[3][3] = { { 0.1, 0.1, 0 }, { 0.9, 0.2, 1 }, { 0.2, 0.9, 0.7 } };
    memcpy(so.t[n++].v, across, sizeof across);
    so.n = n;
    return so;
}

static void planar_in_candidate_planes(void **state)
{
    (void)state;
    soup so = planar_scene();
    const kd_source src = tri_source(&so);
    double (*quant[])(double) = { NULL, grid8 };
    for (int q = 0; q < 2; q++)
        for (uint32_t bins = 0; bins <= 32; bins += 32) {
            const kd_params p = params(bins, quant[q]);
            build_and_check(&src, &p);
        }
    free(so.t);
}

/* Zero-area triangles: points and segments, some repeated, some on the box faces. */
static void zero_area_triangles(void **state)
{
    (void)state;
    seed(47);
    soup so = soup_new(600);
    for (uint32_t i = 0; i < so.n; i++) {
        const double a[3] = { urand(), urand(), urand() }, d[3] = { urand() - 0.5, urand() - 0.5, 0 };
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++)
                so.t[i].v[v][k] = i % 3 == 0 ? a[k] : a[k] + 0.1 * v * d[k]; /* point or segment */
        if (i % 5 == 0)
            so.t[i] = so.t[i - i % 10];
    }
    const kd_source src = tri_source(&so);
    for (uint32_t bins = 0; bins <= 32; bins += 32) {
        build_and_check(&src, &(kd_params){ 1.0, 1.5, 0.2, 0, 1, bins, NULL, 1, 0, 0, 0, 0, NULL, 0, 0 });
        build_and_check(&src, &(kd_params){ 1.0, 1.5, 0.2, 0, 1, bins, grid8, 1, 0, 0, 0, 0, NULL, 0, 0 });
        build_and_check(&src, &(kd_params){ 1.0, 1.5, 0.2, 0, 1, bins, grid8, 1, 0, 16, 0, 0, NULL, 0, 0 });
    }
    free(so.t);
}

/* Boxes on a line (root box of zero area) and of zero extent in one axis. */
static void thin_roots(void **state)
{
    (void)state;
    box_set bs = random_boxes(500, 49);
    for (uint32_t i = 0; i < bs.n; i++)
        for (int k = 1; k < 3; k++)
            bs.b[i].lo[k] = bs.b[i].hi[k] = 0;
    const kd_source src = box_source(&bs);
    for (uint32_t bins = 0; bins <= 32; bins += 32) {
        const kd_params p = params(bins, NULL);
        kd_tree t;
        assert_int_equal(kd_build(&src, &p, &t), 0);
        check_tree(&src, &p, &t);
        assert_true(t.n_nodes > 1); /* length ratios still make splitting worthwhile */
        assert_true(isfinite(t.stats.sah_cost));
        kd_free(&t);
    }
    free(bs.b);
}

/* ---- tests: parallel build -------------------------------------------------------------------- */

/* Boxes like the instances of a top level: centres uniform in [0, 100]^3, half-sizes 0.2 .. 1.7. */
static box_set instance_boxes(uint32_t n, uint64_t s)
{
    seed(s);
    box_set r = { calloc(n + 1u, sizeof(aabb)), n };
    assert_non_null(r.b);
    for (uint32_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            const double c = 100 * urand(), e = 0.2 + 1.5 * urand();
            r.b[i].lo[k] = c - e;
            r.b[i].hi[k] = c + e;
        }
    return r;
}

static double to_float(double x) { return (double)(float)x; }

/* kd_build on one thread: the builder uses as many threads as the caller may use CPUs. */
static void build_serial(const kd_source *src, const kd_params *p, kd_tree *t)
{
    cpu_set_t all, one;
    assert_int_equal(sched_getaffinity(0, sizeof all, &all), 0);
    CPU_ZERO(&one);
    for (int c = 0; c < CPU_SETSIZE; c++)
        if (CPU_ISSET(c, &all)) {
            CPU_SET(c, &one);
            break;
        }
    assert_int_equal(sched_setaffinity(0, sizeof one, &one), 0);
    const int rc = kd_build(src, p, t);
    assert_int_equal(sched_setaffinity(0, sizeof all, &all), 0);
    assert_int_equal(rc, 0);
}

static void assert_same_tree(const kd_tree *a, const kd_tree *b)
{
    assert_int_equal(a->n_nodes, b->n_nodes);
    assert_int_equal(a->n_prims, b->n_prims);
    assert_memory_equal(a->nodes, b->nodes, a->n_nodes * sizeof *a->nodes);
    assert_memory_equal(a->prims, b->prims, a->n_prims * sizeof *a->prims);
    assert_memory_equal(&a->bounds, &b->bounds, sizeof a->bounds);
    assert_int_equal(a->stats.n_leaves, b->stats.n_leaves);
    assert_int_equal(a->stats.n_empty_leaves, b->stats.n_empty_leaves);
    assert_int_equal(a->stats.depth, b->stats.depth);
    assert_true(a->stats.references == b->stats.references);
    assert_int_equal(a->stats.max_leaf_count, b->stats.max_leaf_count);
    assert_memory_equal(&a->stats.sah_cost, &b->stats.sah_cost, sizeof(double)); /* to the bit */
}

/* A large build runs on several threads (given several cores), which build subtrees concurrently
 * and merge them. The tree must not depend on their timing: repeated builds are bit-identical,
 * and identical to the single-threaded build (one CPU, or kd_params.threads). Binned boxes (the top level), triangles binned with
 * exact subtrees (the bottom level) and triangles in exact mode. */
static void parallel_deterministic(void **state)
{
    (void)state;
    box_set inst = instance_boxes(20000, 71), mixed = random_boxes(5000, 72); /* mixed: 10% points */
    soup so = random_soup(6000, 73);
    kd_params hybrid = params(32, grid8), exact = params(0, to_float);
    hybrid.exact_max = 64;
    const struct {
        kd_source src;
        kd_params p;
    } cases[] = { { box_source(&inst), params(32, to_float) }, { box_source(&mixed), params(32, grid8) },
                  { tri_source(&so), hybrid }, { tri_source(&so), exact } };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        kd_tree first, t;
        assert_int_equal(kd_build(&cases[i].src, &cases[i].p, &first), 0);
        check_tree(&cases[i].src, &cases[i].p, &first);
        for (int rep = 0; rep < 4; rep++) {
            assert_int_equal(kd_build(&cases[i].src, &cases[i].p, &t), 0);
            assert_same_tree(&first, &t);
            kd_free(&t);
        }
        build_serial(&cases[i].src, &cases[i].p, &t);
        assert_same_tree(&first, &t);
        kd_free(&t);
        for (uint32_t threads = 1; threads <= 3; threads += 2) { /* kd_params.threads, whatever the CPUs */
            kd_params q = cases[i].p;
            q.threads = threads;
            assert_int_equal(kd_build(&cases[i].src, &q, &t), 0);
            assert_same_tree(&first, &t);
            kd_free(&t);
        }
        kd_free(&first);
    }
    free(inst.b);
    free(mixed.b);
    free(so.t);
}

/* A source's clip_split gives the halves' parts as clip does, so the trees are the same with and
 * without it: exact mode (the straddlers' events) and binned mode (the straddling references). */
static void clip_split_same_trees(void **state)
{
    (void)state;
    soup so = random_soup(3000, 75);
    kd_params hybrid = params(32, grid8), exact = params(0, to_float);
    hybrid.exact_max = 64;
    const kd_params ps[] = { exact, hybrid, params(32, grid8) };
    kd_source with = tri_source(&so), without = with;
    without.clip_split = NULL;
    for (size_t i = 0; i < sizeof ps / sizeof ps[0]; i++) {
        kd_tree a, b;
        assert_int_equal(kd_build(&with, &ps[i], &a), 0);
        assert_int_equal(kd_build(&without, &ps[i], &b), 0);
        assert_same_tree(&a, &b);
        kd_free(&a);
        kd_free(&b);
    }
    free(so.t);
}

/* kd_build_many builds several trees on one pool of threads, a thread done with one tree taking
 * subtrees of the others: every tree must be the one kd_build makes, on any number of threads,
 * with the small and empty ones among them; a tree over its node budget fails alone. */
static void build_many_same_trees(void **state)
{
    (void)state;
    box_set inst = instance_boxes(4000, 71), mixed = random_boxes(2000, 72), few = random_boxes(40, 74);
    soup so = random_soup(2000, 73);
    kd_params hybrid = params(32, grid8), exact = params(0, to_float);
    hybrid.exact_max = 64;
    enum { N = 6 };
    /* the largest last: the threads done with the others take its subtrees */
    const kd_source src[N] = { box_source(&few), tri_source(&so), { 0, NULL, NULL, NULL, NULL }, box_source(&mixed),
                               tri_source(&so), box_source(&inst) };
    kd_params p[N] = { exact, hybrid, exact, params(32, grid8), exact, params(32, to_float) };
    kd_tree alone[N], many[N];
    for (int i = 0; i < N; i++)
        assert_int_equal(kd_build(&src[i], &p[i], &alone[i]), 0);
    for (uint32_t threads = 0; threads <= 3; threads++) { /* 0: all CPUs */
        int rc[N];
        assert_int_equal(kd_build_many(src, p, N, threads, many, rc), 0);
        for (int i = 0; i < N; i++) {
            assert_int_equal(rc[i], 0);
            assert_same_tree(&alone[i], &many[i]);
            kd_free(&many[i]);
        }
        assert_int_equal(kd_build_many(src + N - 1, p + N - 1, 1, threads, many, rc), 0); /* one tree */
        assert_int_equal(rc[0], 0);
        assert_same_tree(&alone[N - 1], &many[0]);
        kd_free(&many[0]);
    }
    kd_params limited[N];
    memcpy(limited, p, sizeof limited);
    limited[1].max_nodes = alone[1].n_nodes - 1;
    int rc[N];
    assert_int_equal(kd_build_many(src, limited, N, 2, many, rc), 0);
    for (int i = 0; i < N; i++) {
        assert_int_equal(rc[i], i == 1 ? KD_TOO_MANY_NODES : 0);
        if (i != 1)
            assert_same_tree(&alone[i], &many[i]);
        kd_free(&many[i]);
        kd_free(&alone[i]);
    }
    free(inst.b);
    free(mixed.b);
    free(few.b);
    free(so.t);
}

/* ---- tests: parameters ---------------------------------------------------------------------- */

static void parameters(void **state)
{
    (void)state;
    soup so = random_soup(1000, 51);
    const kd_source src = tri_source(&so);
    kd_params p = params(0, NULL);
    kd_tree t;

    p.leaf_size = so.n; /* never split */
    assert_int_equal(kd_build(&src, &p, &t), 0);
    assert_int_equal(t.n_nodes, 1);
    kd_free(&t);

    p = params(0, NULL);
    p.cost_traversal = 1e9; /* splitting never pays */
    assert_int_equal(kd_build(&src, &p, &t), 0);
    assert_int_equal(t.n_nodes, 1);
    kd_free(&t);

    /* a larger empty-space bonus cuts off more empty space */
    uint32_t empty[2];
    for (int i = 0; i < 2; i++) {
        p = params(0, NULL);
        p.empty_bonus = i ? 0.9 : 0.0;
        assert_int_equal(kd_build(&src, &p, &t), 0);
        check_tree(&src, &p, &t);
        empty[i] = t.stats.n_empty_leaves;
        kd_free(&t);
    }
    assert_true(empty[1] > empty[0]);

    for (uint32_t d = 1; d <= 3; d++) {
        p = params(d == 2 ? 32 : 0, NULL);
        p.max_depth = d;
        assert_int_equal(kd_build(&src, &p, &t), 0);
        check_tree(&src, &p, &t);
        assert_int_equal(t.stats.depth, d);
        kd_free(&t);
    }

    /* deterministic: the same input gives the same tree */
    kd_tree a, b;
    p = params(0, grid8);
    assert_int_equal(kd_build(&src, &p, &a), 0);
    assert_int_equal(kd_build(&src, &p, &b), 0);
    assert_int_equal(a.n_nodes, b.n_nodes);
    assert_int_equal(a.n_prims, b.n_prims);
    assert_memory_equal(a.nodes, b.nodes, a.n_nodes * sizeof *a.nodes);
    assert_memory_equal(a.prims, b.prims, a.n_prims * sizeof *a.prims);
    kd_free(&a);
    kd_free(&b);
    kd_free(&b); /* freeing twice is harmless: kd_free leaves an empty tree */
    free(so.t);
}

static void defaults(void **state)
{
    (void)state;
    kd_params p;
    memset(&p, 0xAB, sizeof p);
    kd_params_default(&p);
    assert_float_equal(p.cost_traversal, 1.0, 0);
    assert_float_equal(p.cost_intersection, 1.5, 0);
    assert_float_equal(p.empty_bonus, 0.2, 0);
    assert_int_equal(p.max_depth, 0);
    assert_int_equal(p.leaf_size, 1);
    assert_int_equal(p.bins, 0);
    assert_null(p.quantize);
    assert_int_equal(p.exact_max, 0);
    assert_int_equal(p.bins_from, 0);
}

/* Exact mode counts events in 32 bits: a source of 2^32 - 1 primitives is refused before anything
 * is allocated or asked, with -1 and an empty tree. */
static aabb never_called(const void *user, uint32_t i)
{
    (void)user;
    (void)i;
    fail_msg("bounds() called");
    return (aabb){ { 0, 0, 0 }, { 0, 0, 0 } };
}

static void too_many_primitives(void **state)
{
    (void)state;
    const kd_source src = { UINT32_MAX, NULL, never_called, NULL, NULL };
    const kd_params p = params(0, NULL);
    kd_tree t;
    memset(&t, 0x5A, sizeof t);
    assert_int_equal(kd_build(&src, &p, &t), -1);
    assert_null(t.nodes);
    assert_null(t.prims);
    assert_int_equal(t.n_nodes, 0);
    assert_int_equal(t.n_prims, 0);
    kd_free(&t);
}

/* The node limit (kd_params.max_nodes) stops a build before the nodes are allocated: a budget
 * of exactly the tree's node count builds the same tree, one node less fails with
 * KD_TOO_MANY_NODES and an empty tree, on all CPUs and on one, in every mode; with a counter
 * shared by several builds (kd_params.shared_nodes) the limit bounds them together. */
static void node_limit(void **state)
{
    (void)state;
    soup so = random_soup(3000, 91);
    box_set inst = instance_boxes(5000, 92);
    kd_params hybrid = params(32, grid8);
    hybrid.exact_max = 64;
    const struct {
        kd_source src;
        kd_params p;
    } cases[] = { { tri_source(&so), params(0, to_float) }, { tri_source(&so), hybrid },
                  { box_source(&inst), params(32, to_float) } };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        kd_tree free_tree, t;
        assert_int_equal(kd_build(&cases[i].src, &cases[i].p, &free_tree), 0);
        kd_params p = cases[i].p;
        p.max_nodes = free_tree.n_nodes;
        assert_int_equal(kd_build(&cases[i].src, &p, &t), 0);
        assert_same_tree(&free_tree, &t);
        kd_free(&t);
        build_serial(&cases[i].src, &p, &t);
        assert_same_tree(&free_tree, &t);
        kd_free(&t);
        p.max_nodes = free_tree.n_nodes - 1;
        memset(&t, 0x5A, sizeof t);
        assert_int_equal(kd_build(&cases[i].src, &p, &t), KD_TOO_MANY_NODES);
        assert_null(t.nodes);
        assert_int_equal(t.n_nodes, 0);
        /* a counter shared by two builds: the budget of both trees is enough, one node less not */
        for (uint64_t less = 0; less <= 1; less++) {
            uint64_t shared = 0;
            p.shared_nodes = &shared;
            p.max_nodes = 2 * (uint64_t)free_tree.n_nodes - less;
            assert_int_equal(kd_build(&cases[i].src, &p, &t), 0);
            kd_free(&t);
            assert_int_equal(kd_build(&cases[i].src, &p, &t), less ? KD_TOO_MANY_NODES : 0);
            assert_true(less || shared == p.max_nodes);
            kd_free(&t);
        }
        kd_free(&free_tree);
    }
    free(so.t);
    free(inst.b);
}

/* ---- tests: SAH cost and stats by hand -------------------------------------------------------- */

static void sah_cost_by_hand(void **state)
{
    (void)state;
    kd_params p = params(0, NULL);
    kd_node nodes[3] = {
        { 0, 1, 1.0, 0, 0 },
        { KD_LEAF, 0, 0, 0, 1 },
        { KD_LEAF, 0, 0, 1, 2 },
    };
    uint32_t prims[3] = { 0, 1, 2 };
    /* box 2 x 1 x 1: half areas 5 (root) and 3 (each child) */
    kd_tree t = { nodes, 3, prims, 3, { { 0, 0, 0 }, { 2, 1, 1 } }, { 0 } };
    assert_float_equal(kd_sah_cost(&t, &p), 1.0 + 1.5 * (1 * 0.6 + 2 * 0.6), 1e-12);
    /* flat root 2 x 1 x 0: half areas 2 and 1 */
    t.bounds.hi[2] = 0;
    assert_float_equal(kd_sah_cost(&t, &p), 1.0 + 1.5 * (1 * 0.5 + 2 * 0.5), 1e-12);
    /* root on a segment of length 2 (zero area): length ratios */
    t.bounds.hi[1] = 0;
    nodes[0].split = 0.5;
    assert_float_equal(kd_sah_cost(&t, &p), 1.0 + 1.5 * (1 * 0.25 + 2 * 0.75), 1e-12);
    /* a single leaf over a point */
    kd_node leaf = { KD_LEAF, 0, 0, 0, 3 };
    kd_tree point = { &leaf, 1, prims, 3, { { 1, 1, 1 }, { 1, 1, 1 } }, { 0 } };
    assert_float_equal(kd_sah_cost(&point, &p), 1.5 * 3, 1e-12);
    kd_tree none = { 0 };
    assert_float_equal(kd_sah_cost(&none, &p), 0.0, 0);
}

/* Two unit boxes far apart: the builder cuts the empty space between them. */
static void two_boxes_by_hand(void **state)
{
    (void)state;
    aabb b[2] = { { { 0, 0, 0 }, { 1, 1, 1 } }, { { 9, 0, 0 }, { 10, 1, 1 } } };
    box_set bs = { b, 2 };
    const kd_source src = box_source(&bs);
    for (uint32_t bins = 0; bins <= 10; bins += 10) {
        kd_params p = params(bins, NULL);
        p.leaf_size = 0;
        kd_tree t;
        assert_int_equal(kd_build(&src, &p, &t), 0);
        check_tree(&src, &p, &t);
        assert_int_equal(t.nodes[0].axis, 0);
        assert_true(t.nodes[0].split >= 1 && t.nodes[0].split <= 9);
        assert_int_equal(t.stats.references, 2);
        assert_int_equal(t.stats.n_leaves, t.n_nodes / 2 + 1);
        kd_free(&t);
    }
}

/* ---- tests: triangle clipping ----------------------------------------------------------------- */

static void expect_box(const aabb *got, double x0, double y0, double z0, double x1, double y1, double z1)
{
    const double want[6] = { x0, y0, z0, x1, y1, z1 };
    for (int k = 0; k < 3; k++) {
        assert_float_equal(got->lo[k], want[k], 1e-12);
        assert_float_equal(got->hi[k], want[3 + k], 1e-12);
    }
}

static void clip_triangle_cases(void **state)
{
    (void)state;
    const aabb unit = { { 0, 0, 0 }, { 1, 1, 1 } };
    aabb out;
    { /* inside: its own bounds */
        const double a[3] = { 0.1, 0.2, 0.3 }, b[3] = { 0.9, 0.2, 0.4 }, c[3] = { 0.5, 0.8, 0.6 };
        assert_int_equal(kd_clip_triangle(a, b, c, &unit, &out), 1);
        expect_box(&out, 0.1, 0.2, 0.3, 0.9, 0.8, 0.6);
    }
    { /* outside, though its bounds overlap the box: x + y >= 2 misses [0,0.9]^2 */
        const double a[3] = { 2, 0, 0.5 }, b[3] = { 0, 2, 0.5 }, c[3] = { 2, 2, 0.5 };
        const aabb box = { { 0, 0, 0 }, { 0.9, 0.9, 1 } };
        assert_int_equal(kd_clip_triangle(a, b, c, &box, &out), 0);
    }
    { /* corner cut: x + y <= 2 inside [0.5, 3]^2 is the triangle (0.5,0.5) (1.5,0.5) (0.5,1.5) */
        const double a[3] = { 0, 0, 0 }, b[3] = { 2, 0, 0 }, c[3] = { 0, 2, 0 };
        const aabb box = { { 0.5, 0.5, -1 }, { 3, 3, 1 } };
        assert_int_equal(kd_clip_triangle(a, b, c, &box, &out), 1);
        expect_box(&out, 0.5, 0.5, 0, 1.5, 1.5, 0);
    }
    { /* tilted, in the plane z = x + y: inside z in [0.5, 1] of the unit box */
        const double a[3] = { 0, 0, 0 }, b[3] = { 2, 0, 2 }, c[3] = { 0, 2, 2 };
        const aabb box = { { 0, 0, 0.5 }, { 1, 1, 1 } };
        assert_int_equal(kd_clip_triangle(a, b, c, &box, &out), 1);
        expect_box(&out, 0, 0, 0.5, 1, 1, 1);
    }
    { /* a big triangle covering the slab: the box face square remains */
        const double a[3] = { -10, -10, 0.25 }, b[3] = { 30, -10, 0.25 }, c[3] = { -10, 30, 0.25 };
        assert_int_equal(kd_clip_triangle(a, b, c, &unit, &out), 1);
        expect_box(&out, 0, 0, 0.25, 1, 1, 0.25);
    }
    { /* lying in the face plane z = 1 */
        const double a[3] = { 0, 0, 1 }, b[3] = { 1, 0, 1 }, c[3] = { 0, 1, 1 };
        assert_int_equal(kd_clip_triangle(a, b, c, &unit, &out), 1);
        expect_box(&out, 0, 0, 1, 1, 1, 1);
    }
    { /* in the face plane and reaching beyond it */
        const double a[3] = { -1, -1, 0 }, b[3] = { 3, -1, 0 }, c[3] = { -1, 3, 0 };
        assert_int_equal(kd_clip_triangle(a, b, c, &unit, &out), 1);
        expect_box(&out, 0, 0, 0, 1, 1, 0);
    }
    { /* touching the box in one corner only */
        const double a[3] = { 1, 1, 1 }, b[3] = { 2, 1, 1 }, c[3] = { 1, 2, 1 };
        assert_int_equal(kd_clip_triangle(a, b, c, &unit, &out), 1);
        expect_box(&out, 1, 1, 1, 1, 1, 1);
    }
    { /* just outside a face */
        const double a[3] = { 0, 0, 1.001 }, b[3] = { 1, 0, 1.001 }, c[3] = { 0, 1, 1.5 };
        assert_int_equal(kd_clip_triangle(a, b, c, &unit, &out), 0);
    }
    { /* degenerate: a point inside and a point outside */
        const double p[3] = { 0.5, 0.25, 0.75 }, q[3] = { 1.5, 0.25, 0.75 };
        assert_int_equal(kd_clip_triangle(p, p, p, &unit, &out), 1);
        expect_box(&out, 0.5, 0.25, 0.75, 0.5, 0.25, 0.75);
        assert_int_equal(kd_clip_triangle(q, q, q, &unit, &out), 0);
    }
    { /* degenerate: a segment through the box */
        const double a[3] = { -1, 0.5, 0.5 }, b[3] = { 2, 0.5, 0.5 }, c[3] = { 0.5, 0.5, 0.5 };
        assert_int_equal(kd_clip_triangle(a, b, c, &unit, &out), 1);
        expect_box(&out, 0, 0.5, 0.5, 1, 0.5, 0.5);
    }
    { /* a flat box: the triangle's line through z = 0.5 within x, y in [0, 1] */
        const double a[3] = { 0, 0, 0 }, b[3] = { 1, 0, 1 }, c[3] = { 0, 1, 0 };
        const aabb box = { { 0, 0, 0.5 }, { 1, 1, 0.5 } };
        assert_int_equal(kd_clip_triangle(a, b, c, &box, &out), 1);
        expect_box(&out, 0.5, 0, 0.5, 0.5, 0.5, 0.5);
    }
}

/* Random triangles against random boxes: the clipped bounds lie in both the box and the
 * triangle's bounds, and contain every sampled triangle point that lies in the box. */
static void clip_triangle_random(void **state)
{
    (void)state;
    seed(61);
    for (int it = 0; it < 20000; it++) {
        double v[3][3];
        aabb box;
        for (int k = 0; k < 3; k++) {
            for (int j = 0; j < 3; j++)
                v[j][k] = urand();
            const double x = urand(), y = urand();
            box.lo[k] = fmin(x, y);
            box.hi[k] = fmax(x, y);
        }
        aabb out;
        const int hit = kd_clip_triangle(v[0], v[1], v[2], &box, &out);
        for (uint32_t axis = 0; axis < 3; axis++) { /* the split clip: each half as kd_clip_triangle */
            const double pos = box.lo[axis] + urand() * (box.hi[axis] - box.lo[axis]);
            aabb half[2] = { box, box }, part[2], one;
            half[0].hi[axis] = half[1].lo[axis] = pos;
            const int in = kd_clip_triangle_split(v[0], v[1], v[2], &box, axis, pos, part);
            for (int c = 0; c < 2; c++) {
                const int alone = kd_clip_triangle(v[0], v[1], v[2], &half[c], &one);
                assert_int_equal(in >> c & 1, alone);
                if (alone)
                    assert_memory_equal(&part[c], &one, sizeof one);
            }
        }
        for (int s = 0; s < 30; s++) {
            double u = urand(), w = urand();
            if (u + w > 1) {
                u = 1 - u;
                w = 1 - w;
            }
            double p[3];
            int inside = 1;
            for (int k = 0; k < 3; k++) {
                p[k] = v[0][k] + u * (v[1][k] - v[0][k]) + w * (v[2][k] - v[0][k]);
                inside = inside && p[k] >= box.lo[k] && p[k] <= box.hi[k];
            }
            if (!inside)
                continue;
            assert_int_equal(hit, 1);
            for (int k = 0; k < 3; k++)
                assert_true(p[k] >= out.lo[k] - 1e-12 && p[k] <= out.hi[k] + 1e-12);
        }
        if (!hit)
            continue;
        for (int k = 0; k < 3; k++) {
            assert_true(out.lo[k] >= box.lo[k] && out.hi[k] <= box.hi[k] && out.lo[k] <= out.hi[k]);
            assert_true(out.lo[k] >= fmin(v[0][k], fmin(v[1][k], v[2][k])));
            assert_true(out.hi[k] <= fmax(v[0][k], fmax(v[1][k], v[2][k])));
        }
    }
}

/* ---- ropes and uniform grids ---------------------------------------------------------------- */

/* Every node's box, from the root box down. */
static void node_boxes(const kd_tree *t, uint32_t n, const aabb *box, aabb *out)
{
    out[n] = *box;
    const kd_node *nd = &t->nodes[n];
    if (nd->axis == KD_LEAF)
        return;
    aabb lo = *box, hi = *box;
    lo.hi[nd->axis] = hi.lo[nd->axis] = nd->split;
    node_boxes(t, nd->child, &lo, out);
    node_boxes(t, nd->child + 1, &hi, out);
}

/* Every leaf's rope record holds its box; a face on the root box has no rope; any other face's
 * rope names a node that starts at the face and covers all of it, and that cannot be pushed
 * further down (its split, if any, cuts through the face). */
static void ropes_cover_faces(void **state)
{
    (void)state;
    soup s = random_soup(3000, 17);
    const kd_source src = tri_source(&s);
    const kd_params p = params(0, grid8);
    kd_tree t;
    assert_int_equal(kd_build(&src, &p, &t), 0);
    aabb *box = calloc(t.n_nodes, sizeof *box);
    kd_rope *r = calloc(t.n_nodes, sizeof *r);
    assert_non_null(box);
    assert_non_null(r);
    node_boxes(&t, 0, &t.bounds, box);
    kd_ropes(&t, &t.bounds, r);
    uint32_t faces = 0, inner_targets = 0;
    for (uint32_t n = 0; n < t.n_nodes; n++) {
        if (t.nodes[n].axis != KD_LEAF)
            continue;
        assert_memory_equal(&r[n].box, &box[n], sizeof(aabb));
        for (int f = 0; f < 6; f++) {
            const int k = f / 2, up = f & 1;
            const double plane = up ? box[n].hi[k] : box[n].lo[k];
            const uint32_t q = r[n].rope[f];
            if (plane == (up ? t.bounds.hi[k] : t.bounds.lo[k])) {
                assert_int_equal(q, KD_NO_ROPE);
                continue;
            }
            assert_true(q < t.n_nodes);
            faces++;
            assert_true((up ? box[q].lo[k] : box[q].hi[k]) == plane);
            for (int j = 0; j < 3; j++)
                if (j != k)
                    assert_true(box[q].lo[j] <= box[n].lo[j] && box[n].hi[j] <= box[q].hi[j]);
            if (t.nodes[q].axis != KD_LEAF) {
                const uint32_t a = t.nodes[q].axis;
                inner_targets++;
                assert_true(a != (uint32_t)k && box[n].lo[a] < t.nodes[q].split && t.nodes[q].split < box[n].hi[a]);
            }
        }
    }
    print_message("ropes: %u leaves' inner faces, %u ropes to inner nodes\n", faces, inner_targets);
    assert_true(faces > 1000);
    free(box);
    free(r);
    kd_free(&t);
    free(s.t);
}

/* A grid lists every triangle in every cell its part inside the cell touches (checked against
 * clipping each triangle to each cell), and only triangles that touch the widened cell; it has
 * about density cells per triangle and covers the box. */
static void grid_lists_overlapping_cells(void **state)
{
    (void)state;
    soup s = random_soup(400, 23);
    const kd_source src = tri_source(&s);
    const aabb box = { { -0.5, -0.5, -0.5 }, { 1.5, 1.5, 1.5 } };
    const ugrid_params gp = { 2.0, 1e-6, NULL };
    ugrid g;
    assert_int_equal(ugrid_build(&src, &box, &gp, &g), 0);
    const uint32_t cells = ugrid_cells(&g);
    assert_true(cells >= 400 && cells <= 4 * 2 * 400);
    uint64_t listed = 0;
    for (int k = 0; k < 3; k++)
        assert_true(g.lo[k] + g.n[k] * g.size[k] >= box.hi[k]);
    for (uint32_t z = 0; z < g.n[2]; z++)
        for (uint32_t y = 0; y < g.n[1]; y++)
            for (uint32_t x = 0; x < g.n[0]; x++) {
                const uint32_t c = x + g.n[0] * (y + g.n[1] * z), xyz[3] = { x, y, z };
                aabb cell, wide, part;
                for (int k = 0; k < 3; k++) {
                    cell.lo[k] = g.lo[k] + xyz[k] * g.size[k];
                    cell.hi[k] = cell.lo[k] + g.size[k];
                    wide.lo[k] = cell.lo[k] - 2 * gp.widen * 1.5;
                    wide.hi[k] = cell.hi[k] + 2 * gp.widen * 1.5;
                }
                for (uint32_t i = 0; i < s.n; i++) {
                    int in = 0;
                    for (uint32_t e = 0; e < g.count[c]; e++)
                        in |= g.prims[g.first[c] + e] == i;
                    if (kd_clip_triangle(s.t[i].v[0], s.t[i].v[1], s.t[i].v[2], &cell, &part))
                        assert_true(in);
                    if (in)
                        assert_true(kd_clip_triangle(s.t[i].v[0], s.t[i].v[1], s.t[i].v[2], &wide, &part));
                }
                listed += g.count[c];
            }
    assert_int_equal(listed, g.n_prims);
    print_message("grid: %ux%ux%u cells, %u references for %u triangles\n", g.n[0], g.n[1], g.n[2], g.n_prims, s.n);
    ugrid_free(&g);
    free(s.t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(soup_exact),
        cmocka_unit_test(sphere_exact),
        cmocka_unit_test(boxes_exact),
        cmocka_unit_test(boxes_binned),
        cmocka_unit_test(soup_binned),
        cmocka_unit_test(soup_hybrid),
        cmocka_unit_test(bins_from_per_tree),
        cmocka_unit_test(bins_per_node_size),
        cmocka_unit_test(quantized),
        cmocka_unit_test(non_monotone_quantize),
        cmocka_unit_test(sah_beats_median),
        cmocka_unit_test(root_split_is_optimal),
        cmocka_unit_test(empty_and_single),
        cmocka_unit_test(identical_boxes),
        cmocka_unit_test(build_many_same_trees),
        cmocka_unit_test(clip_split_same_trees),
        cmocka_unit_test(duplicates),
        cmocka_unit_test(all_in_one_plane),
        cmocka_unit_test(planar_in_candidate_planes),
        cmocka_unit_test(zero_area_triangles),
        cmocka_unit_test(thin_roots),
        cmocka_unit_test(parallel_deterministic),
        cmocka_unit_test(parameters),
        cmocka_unit_test(defaults),
        cmocka_unit_test(too_many_primitives),
        cmocka_unit_test(node_limit),
        cmocka_unit_test(sah_cost_by_hand),
        cmocka_unit_test(two_boxes_by_hand),
        cmocka_unit_test(signed_zero_positions),
        cmocka_unit_test(clip_triangle_cases),
        cmocka_unit_test(clip_triangle_random),
        cmocka_unit_test(ropes_cover_faces),
        cmocka_unit_test(grid_lists_overlapping_cells),
    };
    return cmocka_run_group_tests_name("kdtree", tests, NULL, NULL);
}
