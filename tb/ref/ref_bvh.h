/*
 * Reference ray tracing in binary64: the geometry half of `saarcor reference`, independent of
 * the hardware (no kd-trees, no memory image, no fp24). A two-level bounding volume hierarchy
 * over the evaluated scene: one BVH per mesh over its object-space triangles, one over the
 * instances' world boxes; rays go into object space through the inverse of each instance's
 * object-to-world matrix. Triangles are tested with the watertight algorithm of Woop, Benthin
 * and Wald (JCGT 2013), so rays through shared edges and vertices of a closed mesh never slip
 * through. Closest hit and any hit (shadow rays).
 */
#ifndef SAARCOR_REF_BVH_H
#define SAARCOR_REF_BVH_H

#include <stdint.h>

#include "scene.h"

typedef struct {
    double lo[3], hi[3];
    uint32_t first, count; /* leaf: primitives [first, first + count); inner: count 0, children first, first + 1 */
} ref_node;

typedef struct {
    ref_node *nodes;
    uint32_t *prims;
    uint32_t n_nodes;
} ref_bvh;

typedef struct {
    ref_bvh bvh;               /* over the mesh's non-degenerate triangles */
} ref_mesh;

typedef struct {
    const scene *s;
    ref_mesh *meshes;          /* per scene mesh */
    affine *w2o;               /* per scene instance: world to object */
    uint8_t *usable;           /* per scene instance: invertible and non-empty */
    ref_bvh top;               /* over instances */
    double lo[3], hi[3];       /* world bounds of all instances */
} ref_scene;

typedef struct {
    uint32_t instance;         /* scene instance, UINT32_MAX for a miss */
    uint32_t triangle;         /* index in the mesh (primitives concatenated) */
    double t, u, v;            /* u: weight of A, v: weight of B */
} ref_hit;

/* Builds the hierarchy of the evaluated scene (kept by pointer). 0, or -1 if memory ran out. */
int ref_scene_build(ref_scene *r, const scene *s);
void ref_scene_free(ref_scene *r);

/* Closest hit with t in [tmin, tmax); returns 1 on a hit. */
int ref_intersect(const ref_scene *r, const double o[3], const double d[3], double tmin, double tmax, ref_hit *hit);

/* 1 if anything is hit with t in [tmin, tmax). */
int ref_occluded(const ref_scene *r, const double o[3], const double d[3], double tmin, double tmax);

/* Vertex k of triangle t of mesh m, object space. */
void ref_vertex(const scene_mesh *m, uint32_t t, int k, double out[3]);

#endif
