/* Two-level BVH and watertight ray/triangle test in binary64: see ref_bvh.h. */
#include "ref_bvh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LEAF_SIZE 4
#define STACK 128 /* median splits keep the depth below log2(n) + small; 2^64 primitives need 64 */

typedef struct {
    double lo[3], hi[3], c[3];
} prim_box;

void ref_vertex(const scene_mesh *m, uint32_t t, int k, double out[3])
{
    const float *p = &m->positions[3 * (size_t)m->indices[3 * t + (uint32_t)k]];
    out[0] = p[0];
    out[1] = p[1];
    out[2] = p[2];
}

static void box_empty(double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
}

static void box_grow(double lo[3], double hi[3], const double a[3], const double b[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = fmin(lo[k], a[k]);
        hi[k] = fmax(hi[k], b[k]);
    }
}

static const prim_box *sort_boxes;
static int sort_axis;
static int by_centre(const void *a, const void *b)
{
    const double x = sort_boxes[*(const uint32_t *)a].c[sort_axis], y = sort_boxes[*(const uint32_t *)b].c[sort_axis];
    return (x > y) - (x < y);
}

/* Median split on the longest centroid extent; iterative over a work list (no recursion needed
 * on the host, but it keeps deep trees off the C stack). Not thread-safe (qsort's comparator
 * state): builds run before rendering starts. */
static int bvh_build(ref_bvh *b, const prim_box *boxes, uint32_t n)
{
    memset(b, 0, sizeof *b);
    b->prims = malloc((n ? n : 1) * sizeof *b->prims);
    b->nodes = malloc((2 * (size_t)n + 1) * sizeof *b->nodes);
    uint32_t *work = malloc((2 * (size_t)n + 1) * sizeof *work);
    if (!b->prims || !b->nodes || !work) {
        free(work);
        return -1;
    }
    for (uint32_t i = 0; i < n; i++)
        b->prims[i] = i;
    b->nodes[0] = (ref_node){ .first = 0, .count = n };
    b->n_nodes = 1;
    uint32_t top = 0;
    work[top++] = 0;
    sort_boxes = boxes;
    while (top) {
        ref_node *nd = &b->nodes[work[--top]];
        double clo[3], chi[3];
        box_empty(nd->lo, nd->hi);
        box_empty(clo, chi);
        for (uint32_t i = nd->first; i < nd->first + nd->count; i++) {
            box_grow(nd->lo, nd->hi, boxes[b->prims[i]].lo, boxes[b->prims[i]].hi);
            box_grow(clo, chi, boxes[b->prims[i]].c, boxes[b->prims[i]].c);
        }
        if (nd->count <= LEAF_SIZE)
            continue;
        sort_axis = 0;
        for (int k = 1; k < 3; k++)
            if (chi[k] - clo[k] > chi[sort_axis] - clo[sort_axis])
                sort_axis = k;
        qsort(b->prims + nd->first, nd->count, sizeof *b->prims, by_centre);
        const uint32_t half = nd->count / 2, first = nd->first, count = nd->count;
        const uint32_t l = b->n_nodes;
        b->nodes[l] = (ref_node){ .first = first, .count = half };
        b->nodes[l + 1] = (ref_node){ .first = first + half, .count = count - half };
        b->n_nodes += 2;
        nd->first = l;
        nd->count = 0;
        work[top++] = l;
        work[top++] = l + 1;
    }
    free(work);
    return 0;
}

static void bvh_free(ref_bvh *b)
{
    free(b->nodes);
    free(b->prims);
}

/* Slab test: the entry distance, or INFINITY if the box is missed within [tmin, tmax). */
static double box_hit(const ref_node *n, const double o[3], const double inv[3], double tmin, double tmax)
{
    for (int k = 0; k < 3; k++) {
        double t0 = (n->lo[k] - o[k]) * inv[k], t1 = (n->hi[k] - o[k]) * inv[k];
        if (t0 > t1) {
            const double s = t0;
            t0 = t1;
            t1 = s;
        }
        if (isnan(t0)) /* 0 * inf: the origin lies on the slab's plane and the ray runs in it */
            t0 = -INFINITY, t1 = INFINITY;
        tmin = fmax(tmin, t0);
        tmax = fmin(tmax, t1);
    }
    return tmin <= tmax ? tmin : INFINITY;
}

/* Watertight ray/triangle test (Woop, Benthin, Wald 2013) in double. */
typedef struct {
    int kx, ky, kz;
    double sx, sy, sz;
} wt_ray;

static wt_ray wt_prepare(const double d[3])
{
    wt_ray w;
    w.kz = fabs(d[0]) > fabs(d[1]) ? (fabs(d[0]) > fabs(d[2]) ? 0 : 2) : (fabs(d[1]) > fabs(d[2]) ? 1 : 2);
    w.kx = (w.kz + 1) % 3;
    w.ky = (w.kx + 1) % 3;
    if (d[w.kz] < 0) {
        const int s = w.kx;
        w.kx = w.ky;
        w.ky = s;
    }
    w.sx = d[w.kx] / d[w.kz];
    w.sy = d[w.ky] / d[w.kz];
    w.sz = 1.0 / d[w.kz];
    return w;
}

static int wt_triangle(const wt_ray *w, const double o[3], const double a[3], const double b[3], const double c[3],
                       double tmin, double tmax, double *t, double *u, double *v)
{
    const double A[3] = { a[0] - o[0], a[1] - o[1], a[2] - o[2] }, B[3] = { b[0] - o[0], b[1] - o[1], b[2] - o[2] },
                 C[3] = { c[0] - o[0], c[1] - o[1], c[2] - o[2] };
    const double ax = A[w->kx] - w->sx * A[w->kz], ay = A[w->ky] - w->sy * A[w->kz];
    const double bx = B[w->kx] - w->sx * B[w->kz], by = B[w->ky] - w->sy * B[w->kz];
    const double cx = C[w->kx] - w->sx * C[w->kz], cy = C[w->ky] - w->sy * C[w->kz];
    const double U = cx * by - cy * bx, V = ax * cy - ay * cx, W = bx * ay - by * ax;
    if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0))
        return 0;
    const double det = U + V + W;
    if (det == 0)
        return 0;
    const double T = w->sz * (U * A[w->kz] + V * B[w->kz] + W * C[w->kz]) / det;
    if (!(T >= tmin && T < tmax))
        return 0;
    *t = T;
    *u = U / det;
    *v = V / det;
    return 1;
}

/* Closest (or, with any != 0, first) hit in one mesh, object-space ray. */
static int mesh_hit(const scene_mesh *m, const ref_bvh *b, const double o[3], const double d[3], double tmin,
                    double *tmax, ref_hit *hit, int any)
{
    if (!b->n_nodes)
        return 0;
    const double inv[3] = { 1.0 / d[0], 1.0 / d[1], 1.0 / d[2] };
    const wt_ray w = wt_prepare(d);
    uint32_t stack[STACK], sp = 0;
    int found = 0;
    stack[sp++] = 0;
    while (sp) {
        const ref_node *n = &b->nodes[stack[--sp]];
        if (box_hit(n, o, inv, tmin, *tmax) == INFINITY)
            continue;
        if (n->count == 0) {
            if (sp + 2 <= STACK) {
                stack[sp++] = n->first + 1;
                stack[sp++] = n->first;
            }
            continue;
        }
        for (uint32_t i = n->first; i < n->first + n->count; i++) {
            double a[3], bb[3], c[3], t, u, v;
            const uint32_t tri = b->prims[i];
            ref_vertex(m, tri, 0, a);
            ref_vertex(m, tri, 1, bb);
            ref_vertex(m, tri, 2, c);
            if (wt_triangle(&w, o, a, bb, c, tmin, *tmax, &t, &u, &v)) {
                *tmax = t;
                hit->triangle = tri;
                hit->t = t;
                hit->u = u;
                hit->v = v;
                found = 1;
                if (any)
                    return 1;
            }
        }
    }
    return found;
}

static int trace(const ref_scene *r, const double o[3], const double d[3], double tmin, double tmax, ref_hit *hit, int any)
{
    hit->instance = UINT32_MAX;
    if (!r->top.n_nodes)
        return 0;
    const double inv[3] = { 1.0 / d[0], 1.0 / d[1], 1.0 / d[2] };
    uint32_t stack[STACK], sp = 0;
    stack[sp++] = 0;
    while (sp) {
        const ref_node *n = &r->top.nodes[stack[--sp]];
        if (box_hit(n, o, inv, tmin, tmax) == INFINITY)
            continue;
        if (n->count == 0) {
            if (sp + 2 <= STACK) {
                stack[sp++] = n->first + 1;
                stack[sp++] = n->first;
            }
            continue;
        }
        for (uint32_t i = n->first; i < n->first + n->count; i++) {
            const uint32_t inst = r->top.prims[i];
            const scene_instance *si = &r->s->instances[inst];
            double oo[3], od[3];
            affine_apply_point(&r->w2o[inst], o, oo);
            affine_apply_vector(&r->w2o[inst], d, od);
            if (mesh_hit(&r->s->meshes[si->mesh], &r->meshes[si->mesh].bvh, oo, od, tmin, &tmax, hit, any)) {
                hit->instance = inst;
                if (any)
                    return 1;
            }
        }
    }
    return hit->instance != UINT32_MAX;
}

int ref_intersect(const ref_scene *r, const double o[3], const double d[3], double tmin, double tmax, ref_hit *hit)
{
    return trace(r, o, d, tmin, tmax, hit, 0);
}

int ref_occluded(const ref_scene *r, const double o[3], const double d[3], double tmin, double tmax)
{
    ref_hit h;
    return trace(r, o, d, tmin, tmax, &h, 1);
}

/* A triangle the reference keeps: finite vertices, non-zero area. */
static int usable_triangle(const scene_mesh *m, uint32_t t, prim_box *pb)
{
    double v[3][3];
    box_empty(pb->lo, pb->hi);
    for (int k = 0; k < 3; k++) {
        ref_vertex(m, t, k, v[k]);
        if (!isfinite(v[k][0]) || !isfinite(v[k][1]) || !isfinite(v[k][2]))
            return 0;
        box_grow(pb->lo, pb->hi, v[k], v[k]);
    }
    const double e1[3] = { v[0][0] - v[2][0], v[0][1] - v[2][1], v[0][2] - v[2][2] },
                 e2[3] = { v[1][0] - v[2][0], v[1][1] - v[2][1], v[1][2] - v[2][2] };
    const double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0] };
    for (int k = 0; k < 3; k++)
        pb->c[k] = 0.5 * (pb->lo[k] + pb->hi[k]);
    return n[0] != 0 || n[1] != 0 || n[2] != 0;
}

static int mesh_build(ref_mesh *rm, const scene_mesh *m)
{
    prim_box *boxes = malloc((m->n_triangles ? m->n_triangles : 1) * sizeof *boxes);
    if (!boxes)
        return -1;
    uint32_t n = 0;
    uint32_t *ids = malloc((m->n_triangles ? m->n_triangles : 1) * sizeof *ids);
    if (!ids) {
        free(boxes);
        return -1;
    }
    for (uint32_t t = 0; t < m->n_triangles; t++)
        if (usable_triangle(m, t, &boxes[n]))
            ids[n++] = t;
    const int rc = bvh_build(&rm->bvh, boxes, n);
    for (uint32_t i = 0; rc == 0 && i < n; i++)
        rm->bvh.prims[i] = ids[rm->bvh.prims[i]]; /* build indices -> mesh triangles */
    if (n == 0)
        rm->bvh.n_nodes = 0;
    free(ids);
    free(boxes);
    return rc;
}

/* World box of an instance: its mesh's root box through the object-to-world matrix. */
static void instance_box(const ref_scene *r, uint32_t i, prim_box *pb)
{
    const ref_bvh *b = &r->meshes[r->s->instances[i].mesh].bvh;
    box_empty(pb->lo, pb->hi);
    for (int c = 0; c < 8; c++) {
        const double p[3] = { c & 1 ? b->nodes[0].hi[0] : b->nodes[0].lo[0], c & 2 ? b->nodes[0].hi[1] : b->nodes[0].lo[1],
                              c & 4 ? b->nodes[0].hi[2] : b->nodes[0].lo[2] };
        double w[3];
        affine_apply_point(&r->s->instances[i].world, p, w);
        box_grow(pb->lo, pb->hi, w, w);
    }
    for (int k = 0; k < 3; k++)
        pb->c[k] = 0.5 * (pb->lo[k] + pb->hi[k]);
}

int ref_scene_build(ref_scene *r, const scene *s)
{
    memset(r, 0, sizeof *r);
    r->s = s;
    r->meshes = calloc(s->n_meshes + 1, sizeof *r->meshes);
    r->w2o = calloc(s->n_instances + 1, sizeof *r->w2o);
    r->usable = calloc(s->n_instances + 1, 1);
    prim_box *boxes = calloc(s->n_instances + 1, sizeof *boxes);
    uint32_t *ids = calloc(s->n_instances + 1, sizeof *ids);
    if (!r->meshes || !r->w2o || !r->usable || !boxes || !ids)
        goto fail;
    for (uint32_t m = 0; m < s->n_meshes; m++)
        if (mesh_build(&r->meshes[m], &s->meshes[m]) != 0)
            goto fail;
    uint32_t n = 0;
    box_empty(r->lo, r->hi);
    for (uint32_t i = 0; i < s->n_instances; i++) {
        if (!r->meshes[s->instances[i].mesh].bvh.n_nodes || !affine_invert(&s->instances[i].world, &r->w2o[i]))
            continue;
        r->usable[i] = 1;
        instance_box(r, i, &boxes[n]);
        box_grow(r->lo, r->hi, boxes[n].lo, boxes[n].hi);
        ids[n++] = i;
    }
    if (bvh_build(&r->top, boxes, n) != 0)
        goto fail;
    for (uint32_t i = 0; i < n; i++)
        r->top.prims[i] = ids[r->top.prims[i]];
    if (n == 0)
        r->top.n_nodes = 0;
    free(boxes);
    free(ids);
    return 0;
fail:
    free(boxes);
    free(ids);
    ref_scene_free(r);
    return -1;
}

void ref_scene_free(ref_scene *r)
{
    if (r->meshes && r->s)
        for (uint32_t m = 0; m < r->s->n_meshes; m++)
            bvh_free(&r->meshes[m].bvh);
    bvh_free(&r->top);
    free(r->meshes);
    free(r->w2o);
    free(r->usable);
    memset(r, 0, sizeof *r);
}
