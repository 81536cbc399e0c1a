/* The numerical stability stress suite: see stress.h and docs/stress.md. */
#include "stress.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "f24_fast.h"
#include "geom.h"
#include "interrupt.h"
#include "isect_unit.h"
#include "memimage.h"
#include "rebase_unit.h"
#include "ref_bvh.h"
#include "ref_units.h"
#include "scenes.h"
#include "trace.h"
#include "xform_unit.h"

/* How a case passes, beyond the criteria every case has (no non-finite hit, deterministic). */
typedef enum { CRIT_BASE, CRIT_WATERTIGHT, CRIT_NO_ACNE, CRIT_AGREE, CRIT_DROPPED, CRIT_TRAVERSAL } crit;

typedef struct {
    double o[3], d[3], tmin, tmax;
    double target;   /* t at which the ray crosses the surface it was aimed at (INFINITY: anywhere) */
    uint32_t vertex; /* a mesh vertex of the aimed edge (STRESS_MULTI), UINT32_MAX if none */
} stress_ray;

typedef struct {
    scene s;
    mi_builder *b;
    const uint32_t *mem;
    ref_scene ref;
    uint32_t *adj_first, *adj;  /* mesh 0: vertex -> mesh triangles (CSR), for STRESS_MULTI */
    uint32_t *image_of;         /* mesh 0: mesh triangle -> image triangle (UINT32_MAX: dropped) */
} world;

typedef struct case_def case_def;
/* Builds w->s and fills at most n rays; returns the number of rays, or -1 (skip: no input). */
typedef int (*case_make)(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n);

struct case_def {
    const char *name, *what;
    uint32_t flags;
    crit criterion;
    case_make make;
    double param;
};

static double D(f24_t x) { return f24_fast_decode(x); }
static f24_t F(double x) { return f24_fast_encode(x); }

static void random_dir(geom_rng *r, double d[3])
{
    const double z = geom_range(r, -1, 1), phi = geom_range(r, 0, 2 * M_PI), s = sqrt(fmax(0, 1 - z * z));
    d[0] = s * cos(phi);
    d[1] = s * sin(phi);
    d[2] = z;
}

static void aim(stress_ray *ry, const double o[3], const double p[3])
{
    for (int k = 0; k < 3; k++) {
        ry->o[k] = o[k];
        ry->d[k] = p[k] - o[k];
    }
    ry->tmin = 0;
    ry->tmax = INFINITY;
    ry->target = 1;
    ry->vertex = UINT32_MAX;
}

/* ---- scenes -------------------------------------------------------------------------------- */

/* One mesh (moved out of m) placed by each of the n matrices (place NULL: once, untransformed). */
static int scene_of(geom_mesh *m, const affine *place, int n, scene *out)
{
    const affine id = affine_identity();
    if (!place) {
        place = &id;
        n = 1;
    }
    geom_scene g;
    char err[128];
    geom_scene_begin(&g, out);
    const uint32_t mesh = geom_add_mesh(&g, m, "stress");
    for (int i = 0; i < n; i++) {
        const uint32_t node = geom_add_node(&g, "stress", -1, mesh, NULL, NULL, NULL);
        if (!g.oom) {
            g.s->nodes[node].has_matrix = 1;
            g.s->nodes[node].matrix = place[i];
        }
    }
    return geom_scene_end(&g, err, sizeof err);
}

static affine diag(double sx, double sy, double sz, double tx, double ty, double tz)
{
    affine a = { { { sx, 0, 0, tx }, { 0, sy, 0, ty }, { 0, 0, sz, tz } } };
    return a;
}

/* Icosphere of radius 1 with every vertex moved radially by up to +-jitter (still closed). */
static void jittered_sphere(geom_mesh *m, uint32_t subdiv, double jitter, geom_rng *rng)
{
    geom_mesh_init(m);
    geom_sphere(m, NULL, subdiv, 0);
    for (uint32_t v = 0; v < m->nv; v++) {
        const double f = 1 + geom_range(rng, -jitter, jitter);
        for (int k = 0; k < 3; k++)
            m->pos[3 * v + k] = (float)(m->pos[3 * v + k] * f);
    }
}

static int sphere_scene(world *w, geom_rng *rng, const affine *place, double jitter)
{
    geom_mesh m;
    jittered_sphere(&m, 3, jitter, rng);
    return scene_of(&m, place, 1, &w->s);
}

/* ---- ray sets ------------------------------------------------------------------------------ */

/* Rays from a camera at `eye` towards random points of a disk of radius `r` around `c` (facing the eye). */
static void view_rays(geom_rng *rng, const double eye[3], const double c[3], double r, stress_ray *rays, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) {
        double p[3];
        for (int k = 0; k < 3; k++)
            p[k] = c[k] + r * geom_range(rng, -1, 1);
        aim(&rays[i], eye, p);
        rays[i].target = INFINITY;
    }
}

/* Rays aimed exactly at points of the edges (and, one in eight, at vertices) of instance 0, from
 * a distance `dist` along the face normal plus a random tilt: each must cross the surface at t <= 1. */
static void edge_rays(const world *w, geom_rng *rng, double dist, stress_ray *rays, uint32_t n)
{
    const scene_mesh *m = &w->s.meshes[w->s.instances[0].mesh];
    const affine *xf = &w->s.instances[0].world;
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t t = (uint32_t)(geom_rand(rng) * m->n_triangles), k = (uint32_t)(geom_rand(rng) * 3);
        const uint32_t ia = m->indices[3 * t + k], ib = m->indices[3 * t + (k + 1) % 3];
        double v[3][3], p[3], o[3], dir[3], e1[3], e2[3], nrm[3];
        for (int j = 0; j < 3; j++)
            affine_apply_point(xf, (const double[3]){ m->positions[3 * m->indices[3 * t + j]],
                                                      m->positions[3 * m->indices[3 * t + j] + 1],
                                                      m->positions[3 * m->indices[3 * t + j] + 2] },
                               v[j]);
        const double s = geom_rand(rng) < 0.125 ? 0 : geom_range(rng, 0.01, 0.99);
        for (int j = 0; j < 3; j++) {
            p[j] = v[k][j] + s * (v[(k + 1) % 3][j] - v[k][j]);
            e1[j] = v[1][j] - v[0][j];
            e2[j] = v[2][j] - v[0][j];
        }
        nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
        nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
        nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
        const double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        random_dir(rng, dir);
        for (int j = 0; j < 3; j++)
            o[j] = p[j] + dist * (nrm[j] / len + 0.5 * dir[j]);
        aim(&rays[i], o, p);
        rays[i].vertex = s == 0 ? ia : ib;
    }
}

/* Vertex k of mesh triangle t of instance 0, in world space. */
static void world_vertex(const world *w, uint32_t t, int k, double out[3])
{
    const scene_mesh *m = &w->s.meshes[w->s.instances[0].mesh];
    const float *p = &m->positions[3 * (size_t)m->indices[3 * (size_t)t + (size_t)k]];
    affine_apply_point(&w->s.instances[0].world, (const double[3]){ p[0], p[1], p[2] }, out);
}

static void unit_normal(const double v[3][3], double n[3])
{
    const double e1[3] = { v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2] },
                 e2[3] = { v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2] };
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int j = 0; j < 3; j++)
        n[j] /= len;
}

/* The triangle other than t of instance 0 with an edge from a to b (UINT32_MAX: none, a border). */
static uint32_t neighbour(const world *w, uint32_t t, const double a[3], const double b[3])
{
    const scene_mesh *m = &w->s.meshes[w->s.instances[0].mesh];
    for (uint32_t s = 0; s < m->n_triangles; s++) {
        int found = 0;
        for (int k = 0; k < 3 && s != t; k++) {
            double v[3];
            world_vertex(w, s, k, v);
            found += (v[0] == a[0] && v[1] == a[1] && v[2] == a[2]) || (v[0] == b[0] && v[1] == b[1] && v[2] == b[2]);
        }
        if (found == 2)
            return s;
    }
    return UINT32_MAX;
}

/* Rays aimed at interior points of shared edges of instance 0 at grazing angles, from `dist`
 * away: 0.25 .. 4 degrees below both triangles' planes and along the edge, so that the ray meets
 * the surface first at the aimed point, at t = 1. A flat mesh is approached from either side and
 * half of the rays turn up to 45 degrees off the edge in the plane; a closed convex one (centred
 * at instance 0's origin) from outside, along the edge only (a turn would leave a plane of the
 * pair). A ray that misses the flat mesh, or meets the closed one only on its far side, went
 * through a crack between the two triangles. At 0.25 degrees the units' t on the same fp24 ray
 * differs from the reference's by up to 5e-4 (t' = -O'z / D'z with D'z small), so a closed
 * mesh's crossing counts by t = 1.002 (x 1.001, the criterion's own slack): a ray through a crack
 * meets its far side beyond t = 1 + 2 sin(0.25 degrees) / dist, 1.004 from 2 radii. */
static void crack_rays(const world *w, geom_rng *rng, double dist, int closed, stress_ray *rays, uint32_t n)
{
    const double *c = (const double[3]){ w->s.instances[0].world.m[0][3], w->s.instances[0].world.m[1][3],
                                         w->s.instances[0].world.m[2][3] };
    const scene_mesh *m = &w->s.meshes[w->s.instances[0].mesh];
    for (uint32_t i = 0; i < n;) {
        const uint32_t t = (uint32_t)(geom_rand(rng) * m->n_triangles), k = (uint32_t)(geom_rand(rng) * 3);
        double v[3][3], nv[3][3], nt[3], nn[3], e[3], side[3], p[3], o[3], d[3];
        for (int j = 0; j < 3; j++)
            world_vertex(w, t, j, v[j]);
        const double *a = v[k], *b = v[(k + 1) % 3];
        const uint32_t s = neighbour(w, t, a, b);
        if (s == UINT32_MAX)
            continue;
        for (int j = 0; j < 3; j++)
            world_vertex(w, s, j, nv[j]);
        unit_normal(v, nt);
        unit_normal(nv, nn);
        const double f = geom_range(rng, 0.05, 0.95), el = geom_range(rng, 0.25, 4) * M_PI / 180;
        const double az = !closed && (i & 1) ? geom_range(rng, -M_PI / 4, M_PI / 4) : 0;
        double en = 0, mid[3];
        for (int j = 0; j < 3; j++) {
            e[j] = b[j] - a[j];
            en += e[j] * e[j];
            p[j] = a[j] + f * e[j];
        }
        const double out = nt[0] * (p[0] - c[0]) + nt[1] * (p[1] - c[1]) + nt[2] * (p[2] - c[2]);
        const double up = closed ? (out < 0 ? -1 : 1) : geom_rand(rng) < 0.5 ? 1 : -1;
        const double same = nt[0] * nn[0] + nt[1] * nn[1] + nt[2] * nn[2] < 0 ? -1 : 1; /* the neighbour alike */
        for (int j = 0; j < 3; j++)
            mid[j] = nt[j] + same * nn[j];
        en = sqrt(en);
        const double ml = sqrt(mid[0] * mid[0] + mid[1] * mid[1] + mid[2] * mid[2]);
        side[0] = mid[1] * e[2] - mid[2] * e[1];
        side[1] = mid[2] * e[0] - mid[0] * e[2];
        side[2] = mid[0] * e[1] - mid[1] * e[0];
        for (int j = 0; j < 3; j++) /* towards the surface from the side `up` of both planes */
            d[j] = cos(el) * (cos(az) * e[j] / en + sin(az) * side[j] / (ml * en)) - up * sin(el) * mid[j] / ml;
        for (int j = 0; j < 3; j++)
            o[j] = p[j] - dist * d[j];
        aim(&rays[i], o, p);
        rays[i++].target = closed ? 1.002 : INFINITY;
    }
}

/* ---- the cases ----------------------------------------------------------------------------- */

static int make_inside(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)c, (void)shared;
    if (sphere_scene(w, rng, NULL, 0.02) != 0)
        return 0;
    for (uint32_t i = 0; i < n; i++) {
        double o[3], d[3];
        random_dir(rng, o);
        random_dir(rng, d);
        const double r = 0.5 * cbrt(geom_rand(rng));
        for (int k = 0; k < 3; k++)
            o[k] *= r;
        aim(&rays[i], o, (const double[3]){ o[0] + d[0], o[1] + d[1], o[2] + d[2] });
        rays[i].target = INFINITY;
    }
    return (int)n;
}

static int make_edges_ico(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)shared;
    geom_mesh m;
    jittered_sphere(&m, (uint32_t)c->param, 0.05, rng);
    if (scene_of(&m, NULL, 0, &w->s) != 0)
        return 0;
    edge_rays(w, rng, 2.0, rays, n);
    return (int)n;
}

static int make_edges_lathe(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)c, (void)shared;
    enum { RINGS = 17 };
    double profile[RINGS][2];
    for (int k = 0; k < RINGS; k++) {
        const double a = M_PI * (k / (RINGS - 1.0) - 0.5);
        profile[k][0] = k == 0 || k == RINGS - 1 ? 0 : cos(a);
        profile[k][1] = sin(a);
    }
    geom_mesh m;
    geom_mesh_init(&m);
    const affine xf = geom_trs(0.3, -0.2, 0.1, 1, 1, 0, 0.4, 1, 1, 1);
    geom_lathe(&m, &xf, (const double(*)[2])profile, RINGS, 48, 0);
    if (scene_of(&m, NULL, 0, &w->s) != 0)
        return 0;
    edge_rays(w, rng, 2.0, rays, n);
    return (int)n;
}

static int make_edges_file(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)c;
    char path[512], err[256];
    snprintf(path, sizeof path, "%s/bunny.glb", shared ? shared : "");
    if (!shared || scene_load_gltf(path, &w->s, err, sizeof err) != 0 || w->s.n_instances == 0)
        return -1;
    edge_rays(w, rng, 0.05, rays, n);
    return (int)n;
}

/* A unit sphere moved by param along (1, 0.6, -0.3), seen from 4 units away. */
/* A flat quad of two triangles (param 0: rays at its diagonal from 2 away), a flat 32 x 32 grid
 * of 2048 (param: the distance in its sizes), tilted and moved off the axes so that vertices
 * round in every coordinate. */
static int make_cracks_flat(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)shared;
    geom_mesh m;
    geom_mesh_init(&m);
    const affine xf = geom_trs(0.31, -0.17, 0.23, 1, 2, 3, 0.7, 1, 1, 1);
    const uint32_t cells = c->param == 0 ? 1 : 32;
    geom_grid(&m, &xf, cells, cells, NULL, 0, NULL, NULL);
    if (scene_of(&m, NULL, 0, &w->s) != 0)
        return 0;
    crack_rays(w, rng, c->param == 0 ? 2 : c->param, 0, rays, n);
    return (int)n;
}

/* A closed icosphere (5120 triangles, radius 1, convex) at the origin, seen from param radii
 * (from far away a ray through a crack would meet the far side at about the same t: the small-far
 * cases aim at edges from there at steeper angles). */
static int make_cracks_sphere(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)shared;
    geom_mesh m;
    geom_mesh_init(&m);
    geom_sphere(&m, NULL, 4, 0);
    if (scene_of(&m, NULL, 0, &w->s) != 0)
        return 0;
    crack_rays(w, rng, c->param, 1, rays, n);
    return (int)n;
}

static int make_far(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)shared;
    const double cx = c->param, cy = 0.6 * c->param, cz = -0.3 * c->param;
    const affine place = diag(1, 1, 1, cx, cy, cz);
    if (sphere_scene(w, rng, &place, 0.02) != 0)
        return 0;
    view_rays(rng, (const double[3]){ cx + 0.3, cy + 0.2, cz + 4 }, (const double[3]){ cx, cy, cz }, 1.2, rays, n);
    return (int)n;
}

/* The sphere's vertices scaled by param (the mesh itself, identity instance), the view alike. */
static int make_scale(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)shared;
    geom_mesh m;
    jittered_sphere(&m, 3, 0.02, rng);
    for (uint32_t v = 0; v < 3 * m.nv; v++)
        m.pos[v] = (float)(m.pos[v] * c->param);
    if (scene_of(&m, NULL, 0, &w->s) != 0)
        return 0;
    const double s = c->param;
    view_rays(rng, (const double[3]){ 0.3 * s, 0.2 * s, 4 * s }, (const double[3]){ 0, 0, 0 }, 1.2 * s, rays, n);
    return (int)n;
}

/* Two triangles of a 1 x param strip (a needle of aspect 1/param), or (param < 0) one cap
 * triangle whose apex lies |param| above its base: rays aimed at interior points, at the same
 * height as their origin so that the fp24 ray meets the point it was aimed at. */
static int make_sliver(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)shared;
    const double h = fabs(c->param);
    geom_mesh m;
    geom_mesh_init(&m);
    const double a[3] = { -0.5, 0, 0 }, b[3] = { 0.5, 0, 0 }, p2[3] = { 0.5, h, 0 }, p3[3] = { -0.5, h, 0 }, apex[3] = { 0.1, h, 0 };
    const uint32_t va = geom_vertex(&m, a, NULL, 0, 0), vb = geom_vertex(&m, b, NULL, 0, 0);
    if (c->param > 0) {
        const uint32_t vc = geom_vertex(&m, p2, NULL, 0, 0), vd = geom_vertex(&m, p3, NULL, 0, 0);
        geom_tri(&m, va, vb, vc, 0);
        geom_tri(&m, va, vc, vd, 0);
    } else {
        geom_tri(&m, va, vb, geom_vertex(&m, apex, NULL, 0, 0), 0);
    }
    if (scene_of(&m, NULL, 0, &w->s) != 0)
        return 0;
    for (uint32_t i = 0; i < n; i++) {
        /* a point strictly inside (for the cap: below the line from the base to the apex) */
        const double x = geom_range(rng, -0.45, 0.45), fy = geom_range(rng, 0.1, 0.9);
        const double top = c->param > 0 ? h : h * (x < 0.1 ? (x + 0.5) / 0.6 : (0.5 - x) / 0.4);
        /* slanted in x only: a slant across the strip would be rounded in fp24 by more than the
         * strip's height (2^-18 of it, 8e-7 at 0.2) and meet every ray at one edge of it */
        const double p[3] = { x, fy * top, 0 }, o[3] = { x + 0.3, p[1], 1 };
        aim(&rays[i], o, p);
    }
    return (int)n;
}

/* Two overlapping coplanar squares in one mesh: rays straight down onto the overlap. */
static int make_coplanar(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)c, (void)shared;
    geom_mesh m;
    geom_mesh_init(&m);
    const affine s1 = geom_trs(0, 0, 0, 1, 0, 0, M_PI / 2, 2, 1, 2), s2 = geom_trs(0.3, 0.1, 0, 1, 0, 0, M_PI / 2, 2, 1, 2);
    geom_grid(&m, &s1, 1, 1, NULL, 0, NULL, NULL);
    geom_grid(&m, &s2, 1, 1, NULL, 0, NULL, NULL);
    if (scene_of(&m, NULL, 0, &w->s) != 0)
        return 0;
    for (uint32_t i = 0; i < n; i++) {
        const double p[3] = { geom_range(rng, -0.6, 0.9), geom_range(rng, -0.8, 0.9), 0 }, o[3] = { p[0], p[1], 2 };
        aim(&rays[i], o, p);
    }
    return (int)n;
}

/* The sphere instanced with an extreme matrix: param 0 non-uniform scale 1e-4 .. 1e4, 1 shear,
 * 2 mirror (negative determinant); rays from outside towards its centre region. */
static int make_instance(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)shared;
    static const affine mats[3] = {
        { { { 1e-4, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1e4, 0 } } },
        { { { 1, 8, 0, 0.5 }, { 0, 1, 0, 0 }, { 0, -5, 1, 0 } } },
        { { { -1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 } } },
    };
    const affine *m = &mats[(int)c->param];
    if (sphere_scene(w, rng, m, 0.02) != 0)
        return 0;
    for (uint32_t i = 0; i < n; i++) {
        double u[3], d[3], p[3], o[3];
        random_dir(rng, u);
        random_dir(rng, d);
        for (int k = 0; k < 3; k++)
            u[k] *= 1.3 * cbrt(geom_rand(rng));
        affine_apply_point(m, u, p);  /* a point in (or near) the instance */
        affine_apply_vector(m, d, o); /* from outside: 4 object radii away */
        for (int k = 0; k < 3; k++)
            o[k] = p[k] + 4 * o[k];
        aim(&rays[i], o, p);
        rays[i].target = INFINITY;
    }
    return (int)n;
}

/* Small triangles seen from far away (issue 18, docs/numerics.md): a closed jittered icosphere of
 * 5120 triangles (edges about 0.06 of its radius) as an instance scaled by param and moved by
 * 3 param (1, 2, 3) (param 0: the mesh itself, untransformed), with rays aimed at its edges and
 * vertices from 10^4 of its radii: a triangle then measures about 2^-18 of the distance to the
 * ray's origin, beyond fp24's 17 bits, so every ray relies on the rebased origin. */
static int make_small_far(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)shared;
    const double s = c->param == 0 ? 1 : c->param;
    const affine place = diag(s, s, s, 3 * s, 6 * s, 9 * s);
    geom_mesh m;
    jittered_sphere(&m, 4, 0.02, rng);
    if (scene_of(&m, c->param == 0 ? NULL : &place, c->param == 0 ? 0 : 1, &w->s) != 0)
        return 0;
    edge_rays(w, rng, 1e4 * s, rays, n);
    return (int)n;
}

/* The room scene; rays whose origins lie in the top-level split planes with the direction
 * component along the split axis +0 or -0. */
static int make_split_planes(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)c, (void)shared;
    char err[128];
    const scene_gen_params gp = { 1, 0 };
    if (scene_generator_find("room")->build(&w->s, &gp, err, sizeof err) != 0)
        return 0;
    mi_params p;
    mi_params_default(&p);
    mi_builder *b = mi_build(&w->s, &p, err, sizeof err);
    if (!b)
        return 0;
    uint32_t nw;
    const uint32_t *mem = mi_words(b, &nw), *nodes = mem + mem[MI_H_REGION_TABLE + 2 * MI_R_TOP_NODES];
    const uint32_t *box = mem + MI_H_SCENE_BOUNDS;
    uint32_t k = 0;
    for (uint32_t i = 0; i < n; i++) {
        do
            k = (k + 1) % mem[MI_H_TOP_NODES];
        while ((nodes[2 * k] & 3u) == 3u);
        const uint32_t axis = nodes[2 * k] & 3u;
        for (uint32_t j = 0; j < 3; j++) {
            const double lo = D(box[j]), hi = D(box[3 + j]);
            rays[i].o[j] = j == axis ? D(nodes[2 * k + 1]) : lo + geom_range(rng, 0.1, 0.9) * (hi - lo);
            rays[i].d[j] = j == axis ? (i & 1 ? -0.0 : 0.0) : geom_range(rng, -1, 1);
        }
        rays[i].tmin = 0;
        rays[i].tmax = rays[i].target = INFINITY;
        rays[i].vertex = UINT32_MAX;
    }
    mi_free(b);
    return (int)n;
}

/* A unit cube; rays lying in the planes of its faces (direction component 0 along the normal). */
static int make_face_planes(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)c, (void)shared;
    geom_mesh m;
    geom_mesh_init(&m);
    geom_box(&m, NULL, 0);
    if (scene_of(&m, NULL, 0, &w->s) != 0)
        return 0;
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t axis = i % 3;
        for (uint32_t j = 0; j < 3; j++) {
            rays[i].o[j] = j == axis ? (i & 8 ? 0.5 : -0.5) : geom_range(rng, -2, 2);
            rays[i].d[j] = j == axis ? (i & 16 ? -0.0 : 0.0) : geom_range(rng, -1, 1);
        }
        rays[i].tmin = 0;
        rays[i].tmax = rays[i].target = INFINITY;
        rays[i].vertex = UINT32_MAX;
    }
    return (int)n;
}

/* Rays passing the sphere's silhouette within +-param of its radius. */
static int make_grazing(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)shared;
    geom_mesh m;
    geom_mesh_init(&m);
    geom_sphere(&m, NULL, 5, 0);
    if (scene_of(&m, NULL, 0, &w->s) != 0)
        return 0;
    for (uint32_t i = 0; i < n; i++) {
        const double a = geom_range(rng, 0, 2 * M_PI), r = 1 + geom_range(rng, -c->param, c->param);
        const double o[3] = { r * cos(a), r * sin(a), 5 }, p[3] = { r * cos(a), r * sin(a), 0 };
        aim(&rays[i], o, p);
        rays[i].target = INFINITY;
    }
    return (int)n;
}

/* Rays leaving the sphere's surface outwards from the units' own hit points (as shadow rays do,
 * docs/shading.md): tmin = param x the RGS epsilon e = 2^-10 x the scene extent. */
static int make_acne(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)shared;
    if (sphere_scene(w, rng, NULL, 0) != 0) /* convex: nothing can be hit on the way out */
        return 0;
    char err[128];
    mi_params p;
    mi_params_default(&p);
    mi_builder *b = mi_build(&w->s, &p, err, sizeof err);
    if (!b)
        return 0;
    uint32_t nw, k = 0;
    const uint32_t *mem = mi_words(b, &nw);
    if (mi_validate(mem, nw, err, sizeof err) != 0) { /* the device model reads only validated images */
        mi_free(b);
        return 0;
    }
    const double eps = 2.0 / 1024 * c->param;
    trace_counters tc;
    memset(&tc, 0, sizeof tc);
    while (k < n) {
        ray_packet rp = { .active = 1 };
        double o[3], d[3];
        random_dir(rng, o);
        for (int j = 0; j < 3; j++)
            d[j] = -o[j] + 0.3 * geom_range(rng, -1, 1);
        rp.o[0] = (f24_vec3){ F(3 * o[0]), F(3 * o[1]), F(3 * o[2]) };
        rp.d[0] = (f24_vec3){ F(d[0]), F(d[1]), F(d[2]) };
        rp.tmin[0] = 0;
        rp.tmax[0] = F24_POS_INF;
        hit_record h[TRACE_PACKET];
        trace_packet(mem, &rp, h, &tc);
        if (h[0].instance == TRACE_NO_HIT)
            continue;
        /* the hit point with the units' arithmetic, and a direction in the outward hemisphere of
         * the hit triangle's plane (the polyhedron is convex: nothing lies beyond that plane) */
        const f24_vec3 q = { f24_add(rp.o[0].x, f24_mul(h[0].t, rp.d[0].x)), f24_add(rp.o[0].y, f24_mul(h[0].t, rp.d[0].y)),
                             f24_add(rp.o[0].z, f24_mul(h[0].t, rp.d[0].z)) };
        const scene_mesh *sm = &w->s.meshes[0];
        uint32_t si, mt;
        mi_hit_source(b, h[0].instance, h[0].triangle, &si, &mt);
        double v[3][3], nrm[3], dir[3];
        for (int j = 0; j < 3; j++)
            ref_vertex(sm, mt, j, v[j]);
        const double e1[3] = { v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2] },
                     e2[3] = { v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2] };
        nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
        nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
        nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
        const double out = nrm[0] * v[0][0] + nrm[1] * v[0][1] + nrm[2] * v[0][2] < 0 ? -1 : 1; /* away from the centre */
        random_dir(rng, dir);
        const double side = out * (dir[0] * nrm[0] + dir[1] * nrm[1] + dir[2] * nrm[2]);
        for (int j = 0; j < 3; j++) {
            rays[k].o[j] = D((&q.x)[j]);
            rays[k].d[j] = side < 0 ? -dir[j] : dir[j];
        }
        rays[k].tmin = eps;
        rays[k].tmax = rays[k].target = INFINITY;
        rays[k].vertex = UINT32_MAX;
        k++;
    }
    mi_free(b);
    return (int)n;
}

/* A sphere 10^4 away; directions scaled to length param (t scales by 1 / param). */
static int make_long(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)shared;
    const affine place = diag(50, 50, 50, 0, 0, -1e4);
    if (sphere_scene(w, rng, &place, 0.02) != 0)
        return 0;
    view_rays(rng, (const double[3]){ 0, 0, 0 }, (const double[3]){ 0, 0, -1e4 }, 60, rays, n);
    for (uint32_t i = 0; i < n; i++) {
        const double len = sqrt(rays[i].d[0] * rays[i].d[0] + rays[i].d[1] * rays[i].d[1] + rays[i].d[2] * rays[i].d[2]);
        for (int k = 0; k < 3; k++)
            rays[i].d[k] *= c->param / len;
    }
    return (int)n;
}

/* Rays with NaN or Inf in their origin, direction, tmin or tmax, at the sphere. */
static int make_nan_rays(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)c, (void)shared;
    if (sphere_scene(w, rng, NULL, 0.02) != 0)
        return 0;
    view_rays(rng, (const double[3]){ 0.3, 0.2, 4 }, (const double[3]){ 0, 0, 0 }, 1.2, rays, n);
    const double bad[3] = { NAN, INFINITY, -INFINITY };
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t slot = i % 8, v = (i / 8) % 3;
        if (slot < 3)
            rays[i].o[slot] = bad[v];
        else if (slot < 6)
            rays[i].d[slot - 3] = bad[v];
        else if (slot == 6)
            rays[i].tmin = bad[v];
        else
            rays[i].tmax = bad[v];
    }
    return (int)n;
}

/* The sphere with one NaN and one Inf vertex: the host must drop their triangles (or refuse). */
static int make_nan_geometry(const case_def *c, const char *shared, geom_rng *rng, world *w, stress_ray *rays, uint32_t n)
{
    (void)c, (void)shared;
    geom_mesh m;
    jittered_sphere(&m, 3, 0.02, rng);
    m.pos[0] = NAN;
    m.pos[3 * 7 + 1] = INFINITY;
    if (scene_of(&m, NULL, 0, &w->s) != 0)
        return 0;
    view_rays(rng, (const double[3]){ 0.3, 0.2, 4 }, (const double[3]){ 0, 0, 0 }, 1.2, rays, n);
    return (int)n;
}

#define WT STRESS_MUST_HIT
static const case_def cases[] = {
    { "inside-sphere", "rays from inside a closed jittered icosphere (1280 triangles), all directions", WT, CRIT_WATERTIGHT, make_inside, 0 },
    { "edges-ico0", "rays aimed exactly at edges and vertices of a jittered icosahedron (20 triangles)", WT | STRESS_MULTI, CRIT_WATERTIGHT, make_edges_ico, 0 },
    { "edges-ico2", "the same on a jittered icosphere, 2 subdivisions (320 triangles)", WT | STRESS_MULTI, CRIT_WATERTIGHT, make_edges_ico, 2 },
    { "edges-ico4", "the same, 4 subdivisions (5120 triangles)", WT | STRESS_MULTI, CRIT_WATERTIGHT, make_edges_ico, 4 },
    { "edges-lathe", "the same on a tessellated UV sphere (48 x 16, tilted)", WT | STRESS_MULTI, CRIT_WATERTIGHT, make_edges_lathe, 0 },
    { "edges-bunny", "the same on the shared bunny.glb (not closed: rays may pass its holes only before t = 1)", WT | STRESS_MULTI, CRIT_WATERTIGHT, make_edges_file, 0 },
    { "cracks-quad", "a flat quad of two triangles: rays along its diagonal at 0.25 .. 4 degrees", WT, CRIT_WATERTIGHT, make_cracks_flat, 0 },
    { "cracks-grid", "a flat 32 x 32 grid (2048 triangles): rays at its inner edges at grazing angles, from 2 sizes", WT, CRIT_WATERTIGHT, make_cracks_flat, 2 },
    { "cracks-grid-far", "... from 10^3 of its sizes", WT, CRIT_WATERTIGHT, make_cracks_flat, 1e3 },
    { "cracks-sphere", "a closed icosphere (5120 triangles): rays along its edges at grazing angles, from 2 radii", WT, CRIT_WATERTIGHT, make_cracks_sphere, 2 },
    { "far-1e2", "a unit sphere 10^2 from the origin, camera 4 units from it", 0, CRIT_AGREE, make_far, 1e2 },
    { "far-1e3", "... 10^3 from the origin", 0, CRIT_AGREE, make_far, 1e3 },
    { "far-1e4", "... 10^4 from the origin", 0, CRIT_AGREE, make_far, 1e4 },
    { "far-1e5", "... 10^5 from the origin", 0, CRIT_AGREE, make_far, 1e5 },
    { "far-1e6", "... 10^6 from the origin", 0, CRIT_AGREE, make_far, 1e6 },
    { "far-1e7", "... 10^7 from the origin", 0, CRIT_AGREE, make_far, 1e7 },
    { "scale-1e-4", "the sphere's vertices scaled by 10^-4 (and the view)", 0, CRIT_AGREE, make_scale, 1e-4 },
    { "scale-1e4", "the sphere's vertices scaled by 10^4 (and the view)", 0, CRIT_AGREE, make_scale, 1e4 },
    { "sliver-1e2", "two triangles of a 1 x 10^-2 strip, rays at interior points", WT, CRIT_WATERTIGHT, make_sliver, 1e-2 },
    { "sliver-1e4", "... 1 x 10^-4 strip (aspect 10^4)", WT, CRIT_WATERTIGHT, make_sliver, 1e-4 },
    { "sliver-1e6", "... 1 x 10^-6 strip (aspect 10^6)", WT, CRIT_WATERTIGHT, make_sliver, 1e-6 },
    { "cap-1e-5", "a nearly degenerate triangle, apex 10^-5 above its base of length 1", WT, CRIT_WATERTIGHT, make_sliver, -1e-5 },
    { "coplanar", "two overlapping coplanar squares, rays onto the overlap", WT, CRIT_WATERTIGHT, make_coplanar, 0 },
    { "inst-scale", "sphere instance scaled 10^-4, 1, 10^4 along x, y, z", 0, CRIT_AGREE, make_instance, 0 },
    { "inst-shear", "sphere instance sheared (factors 8 and -5)", 0, CRIT_AGREE, make_instance, 1 },
    { "inst-mirror", "sphere instance mirrored (determinant -1)", 0, CRIT_AGREE, make_instance, 2 },
    { "small-far", "a closed icosphere of 5120 triangles, its edges and vertices aimed at from 10^4 radii away", WT | STRESS_MULTI, CRIT_WATERTIGHT, make_small_far, 0 },
    { "small-inst-1e-3", "the same as an instance scaled by 10^-3 (and moved), aimed at from 10^4 of its radii", WT | STRESS_MULTI, CRIT_WATERTIGHT, make_small_far, 1e-3 },
    { "small-inst-1", "... an instance of scale 1 (moved)", WT | STRESS_MULTI, CRIT_WATERTIGHT, make_small_far, 1 },
    { "small-inst-1e3", "... an instance scaled by 10^3", WT | STRESS_MULTI, CRIT_WATERTIGHT, make_small_far, 1e3 },
    { "split-planes", "room: origins in top-level split planes, direction +-0 along the axis (against brute force)", STRESS_BRUTE, CRIT_TRAVERSAL, make_split_planes, 0 },
    { "face-planes", "cube: rays lying in the planes of its faces", 0, CRIT_BASE, make_face_planes, 0 },
    { "grazing", "rays passing a fine sphere's silhouette within +-10^-3 of its radius", 0, CRIT_BASE, make_grazing, 1e-3 },
    { "acne-eps", "rays leaving the sphere outwards from the units' hit points, tmin = e (RGS)", STRESS_MUST_MISS, CRIT_NO_ACNE, make_acne, 1 },
    { "acne-0", "the same with tmin = 0: shows what the epsilon e is for", STRESS_MUST_MISS, CRIT_BASE, make_acne, 0 },
    { "long-short-d", "a sphere 10^4 away, direction length 10^-3 (t ~ 10^7)", 0, CRIT_AGREE, make_long, 1e-3 },
    { "long-long-d", "the same with direction length 10^3 (t ~ 10)", 0, CRIT_AGREE, make_long, 1e3 },
    { "nan-rays", "rays with NaN/+-Inf in origin, direction, tmin or tmax", 0, CRIT_BASE, make_nan_rays, 0 },
    { "nan-geometry", "the sphere with a NaN and an Inf vertex (their triangles must be dropped)", 0, CRIT_DROPPED, make_nan_geometry, 0 },
};
#undef WT

/* ---- measuring ----------------------------------------------------------------------------- */

static int world_build(world *w, uint32_t flags)
{
    mi_params p;
    mi_params_default(&p);
    p.memory_bytes = 256u << 20;
    char err[256];
    w->b = mi_build(&w->s, &p, err, sizeof err);
    if (!w->b)
        return -1;
    uint32_t n;
    w->mem = mi_words(w->b, &n);
    if (mi_validate(w->mem, n, err, sizeof err) != 0) /* the device model reads only validated images */
        return -1;
    if (ref_scene_build(&w->ref, &w->s) != 0)
        return -1;
    if (!(flags & STRESS_MULTI))
        return 0;
    /* vertex -> triangle adjacency of mesh 0 and its image triangles (instance 0 is its only one) */
    const scene_mesh *m = &w->s.meshes[0];
    const uint32_t obj = w->mem[w->mem[MI_H_REGION_TABLE + 2 * MI_R_INSTANCES] + 12];
    w->adj_first = calloc(m->n_vertices + 1, sizeof *w->adj_first);
    w->adj = malloc(3 * (size_t)m->n_triangles * sizeof *w->adj);
    w->image_of = malloc((size_t)m->n_triangles * sizeof *w->image_of);
    if (!w->adj_first || !w->adj || !w->image_of)
        return -1;
    for (uint32_t i = 0; i < 3 * m->n_triangles; i++)
        w->adj_first[m->indices[i] + 1]++;
    for (uint32_t v = 0; v < m->n_vertices; v++)
        w->adj_first[v + 1] += w->adj_first[v];
    uint32_t *fill = calloc(m->n_vertices, sizeof *fill);
    if (!fill)
        return -1;
    for (uint32_t i = 0; i < 3 * m->n_triangles; i++)
        w->adj[w->adj_first[m->indices[i]] + fill[m->indices[i]]++] = i / 3;
    free(fill);
    for (uint32_t t = 0; t < m->n_triangles; t++)
        w->image_of[t] = UINT32_MAX;
    const uint32_t *od = w->mem + w->mem[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS] + MI_OBJECT_WORDS * obj;
    for (uint32_t t = 0; t < od[MI_O_N_TRIANGLES]; t++) {
        uint32_t si, mt;
        mi_hit_source(w->b, 0, t, &si, &mt); /* image instance 0 is the mesh's only one */
        if (mt < m->n_triangles)
            w->image_of[mt] = t;
    }
    return 0;
}

static void world_free(world *w)
{
    if (w->b) {
        ref_scene_free(&w->ref);
        mi_free(w->b);
    }
    free(w->adj_first);
    free(w->adj);
    free(w->image_of);
    scene_free(&w->s);
}

/* Triangles around the aimed vertex that the units' transformation and intersection accept
 * near t = 1 (instance 0, no traversal): more than one is a double hit. */
static uint32_t accepting(const world *w, const ray_packet *rp, int k, uint32_t vertex)
{
    const uint32_t *mem = w->mem, ia = mem[MI_H_REGION_TABLE + 2 * MI_R_INSTANCES];
    const uint32_t *od = mem + mem[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS] + MI_OBJECT_WORDS * mem[ia + 12];
    f24_vec3x2 o, d;
    ref_units_to_object(mem, ia, rp->o[k], rp->d[k], &o, &d);
    const f24_vec3x2 p = rebase_origin(o, d, F24_ONE); /* where a leaf around the vertex would move it */
    uint32_t n = 0;
    for (uint32_t j = w->adj_first[vertex]; j < w->adj_first[vertex + 1]; j++) {
        const uint32_t t = w->image_of[w->adj[j]];
        if (t == UINT32_MAX)
            continue;
        const f24_triangle tx = f24_triangle_load(mem, od[MI_O_TRIANGLES] + MI_TRIANGLE_WORDS * t);
        const isect_result r = isect_unit_rebased(&tx, p, F24_ONE, d.hi, 0, F24_POS_INF);
        n += r.hit && fabs(D(r.t) - 1) < 1e-2;
    }
    return n;
}

/* How far a hit lies inside its triangle: the smallest of u, v and 1 - u - v. */
static double graze_margin(const isect_result *r)
{
    return fmin(fmin(D(r->u), D(r->v)), 1 - D(r->u) - D(r->v));
}

static int finite_hit(const hit_record *h, double tmin, double tmax)
{
    const double t = D(h->t);
    return isfinite(t) && isfinite(D(h->u)) && isfinite(D(h->v)) && t >= tmin && t < tmax;
}

/* One ray of a packet: the units' hit h against the reference on the same (fp24) ray. */
static void judge(const world *w, const ray_packet *rp, int k, const hit_record *h, const stress_ray *ry, uint32_t flags,
                  stress_result *r, double *t_err, uint64_t *n_err)
{
    const double o[3] = { D(rp->o[k].x), D(rp->o[k].y), D(rp->o[k].z) }, d[3] = { D(rp->d[k].x), D(rp->d[k].y), D(rp->d[k].z) };
    const double tmin = D(rp->tmin[k]), tmax = D(rp->tmax[k]);
    ref_hit rh;
    const int uh = h->instance != TRACE_NO_HIT;
    const int rhit = isfinite(o[0] + o[1] + o[2] + d[0] + d[1] + d[2]) && tmin == tmin && tmax == tmax &&
                     ref_intersect(&w->ref, o, d, tmin, tmax, &rh);
    const double t = D(h->t);
    r->rays++;
    r->unit_hits += uh;
    r->ref_hits += rhit;
    r->agree += uh == rhit;
    r->bad += uh && !finite_hit(h, tmin, tmax);
    if (uh && rhit && rh.t > 0)
        t_err[(*n_err)++] = fabs(t - rh.t) / rh.t;
    /* a leak: the reference finds the surface crossing the ray was aimed at, the units do not */
    const double reach = ry->target * (1 + 1e-3);
    if (flags & STRESS_MUST_HIT)
        r->leaks += rhit && rh.t <= reach && !(uh && t <= reach);
    if (flags & STRESS_MUST_MISS)
        r->acne += uh;
    if (flags & STRESS_BRUTE) {
        isect_result bf;
        const f24_t b = ref_units_closest(w->mem, rp->o[k], rp->d[k], rp->tmin[k], rp->tmax[k], &bf);
        /* the traversal lost a surface: it missed, or its hit lies clearly behind the closest,
         * one that brute force meets off its edges: where it grazes an edge, whether the units
         * accept it depends on the point the origin was moved to, a leaf's entry for the
         * traversal and the plane for brute force (ref_units.h) */
        const int bh = b != rp->tmax[k] && graze_margin(&bf) > ldexp(1.0, -F24_MAN_BITS / 2);
        r->traversal += bh && (!uh || D(h->t) > D(b) * (1 + 1e-3));
    }
    if ((flags & STRESS_MULTI) && ry->vertex != UINT32_MAX)
        r->multi += accepting(w, rp, k, ry->vertex) > 1;
}

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void shoot(const world *w, const stress_ray *rays, uint32_t n, uint32_t flags, stress_result *r)
{
    double *t_err = malloc((n + 1) * sizeof *t_err);
    uint64_t n_err = 0;
    trace_counters c;
    memset(&c, 0, sizeof c);
    for (uint32_t i = 0; i < n && t_err; i += TRACE_PACKET) {
        ray_packet rp;
        memset(&rp, 0, sizeof rp);
        for (uint32_t k = 0; k < TRACE_PACKET && i + k < n; k++) {
            const stress_ray *ry = &rays[i + k];
            rp.o[k] = (f24_vec3){ F(ry->o[0]), F(ry->o[1]), F(ry->o[2]) };
            rp.d[k] = (f24_vec3){ F(ry->d[0]), F(ry->d[1]), F(ry->d[2]) };
            rp.tmin[k] = F(ry->tmin);
            rp.tmax[k] = F(ry->tmax);
            rp.active |= 1u << k;
        }
        hit_record h[TRACE_PACKET], again[TRACE_PACKET];
        trace_packet(w->mem, &rp, h, &c);
        trace_packet(w->mem, &rp, again, &c);
        for (uint32_t k = 0; k < TRACE_PACKET && i + k < n; k++) {
            r->nondeterministic += memcmp(&h[k], &again[k], sizeof h[k]) != 0;
            judge(w, &rp, (int)k, &h[k], &rays[i + k], flags, r, t_err, &n_err);
        }
    }
    if (t_err && n_err) {
        qsort(t_err, n_err, sizeof *t_err, by_value);
        r->t_err_p99 = t_err[(uint64_t)floor(0.99 * (double)(n_err - 1))];
        r->t_err_max = t_err[n_err - 1];
    }
    free(t_err);
}

static int judge_case(const case_def *c, const stress_result *r)
{
    if (r->bad || r->nondeterministic)
        return 0;
    switch (c->criterion) {
    case CRIT_WATERTIGHT: return r->leaks == 0;
    case CRIT_NO_ACNE: return r->acne == 0;
    case CRIT_AGREE: return r->agree >= 0.99 * (double)r->rays && r->t_err_p99 <= 1e-2;
    case CRIT_DROPPED: return r->build_failed || r->dropped >= 2;
    case CRIT_TRAVERSAL: return r->traversal == 0;
    default: return 1;
    }
}

static const char *criterion_text(crit c)
{
    static const char *const text[] = { "no non-finite hit, deterministic", "+ no leak (every ray hits by t = 1)",
                                        "+ no hit (no acne)", "+ hit agreement >= 99%, p99 t error <= 1e-2",
                                        "+ bad triangles dropped (or the scene refused)",
                                        "+ no surface lost: no miss or hit behind the brute-force closest hit" };
    return text[c];
}

/* 1 if name contains one of the comma-separated parts of filter (NULL: every name). */
static int selected(const char *name, const char *filter)
{
    if (!filter)
        return 1;
    char part[64];
    for (const char *p = filter; *p;) {
        const size_t n = strcspn(p, ",");
        snprintf(part, sizeof part, "%.*s", (int)(n < sizeof part ? n : sizeof part - 1), p);
        if (n && strstr(name, part))
            return 1;
        p += n + (p[n] == ',');
    }
    return 0;
}

/* The description fields of a result. */
static void describe(const case_def *c, stress_result *r)
{
    memset(r, 0, sizeof *r);
    r->name = c->name;
    r->what = c->what;
    r->criterion = criterion_text(c->criterion);
    r->flags = c->flags;
}

int stress_describe(stress_result *results, int max)
{
    int n = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0] && n < max; i++)
        describe(&cases[i], &results[n++]);
    return n;
}

int stress_run(const char *filter, uint32_t rays, const char *shared, stress_result *results, int max)
{
    int count = 0;
    stress_ray *buf = malloc((size_t)rays * sizeof *buf);
    if (!buf)
        return -1;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0] && count < max && !interrupt_signal(); i++) {
        const case_def *c = &cases[i];
        if (!selected(c->name, filter))
            continue;
        stress_result *r = &results[count];
        describe(c, r);
        world w;
        memset(&w, 0, sizeof w);
        geom_rng rng;
        geom_rng_seed(&rng, 2004, i);
        const int n = c->make(c, shared, &rng, &w, buf, rays);
        if (n < 0) {
            world_free(&w);
            continue; /* its input is missing */
        }
        if (n == 0 || world_build(&w, c->flags) != 0) {
            r->build_failed = 1;
        } else {
            r->dropped = mi_get_stats(w.b)->degenerate_triangles;
            shoot(&w, buf, (uint32_t)n, c->flags, r);
        }
        r->pass = judge_case(c, r);
        world_free(&w);
        count++;
    }
    free(buf);
    return count;
}
