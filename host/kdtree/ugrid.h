/*
 * Uniform grid builder (host) for the grid traversal modes of the traversal unit (3D-DDA,
 * Purcell et al. 2002; two-level grids over instances, Adinetz and Berezin): the same abstract
 * primitives as the kd-tree builder (kd_source), about `density` cells per primitive with cubic-
 * ish cells, each cell listing every primitive that overlaps it, cells slightly widened (by
 * `widen`, a fraction of the largest coordinate) so that the device's rounded cell planes never
 * leave a primitive out of a cell a ray visits.
 */
#ifndef SAARCOR_UGRID_H
#define SAARCOR_UGRID_H

#include <stdint.h>

#include "kdtree.h"

#ifdef __cplusplus
extern "C" {
#endif

#define UGRID_MAX_AXIS 1023u      /* the device packs a cell index into 3 x 10 bits */
#define UGRID_MAX_CELLS (1u << 21)

typedef struct {
    double density; /* cells per primitive (default 2) */
    double widen;   /* cell widening, relative to the largest coordinate of the grid's box */
    /* Rounds a cell size up to a device value (NULL: none); pure. */
    double (*quantize_up)(double x);
} ugrid_params;

typedef struct {
    uint32_t n[3];
    double lo[3], size[3];      /* cell (i, j, k) spans lo + (i, j, k) * size .. + size */
    uint32_t *first, *count;    /* per cell, x fastest: its entries in prims */
    uint32_t *prims, n_prims;
} ugrid;

/* Builds a grid over box; 0, or -1 if memory ran out (out is then empty). */
int ugrid_build(const kd_source *src, const aabb *box, const ugrid_params *p, ugrid *out);

void ugrid_free(ugrid *g);

static inline uint32_t ugrid_cells(const ugrid *g) { return g->n[0] * g->n[1] * g->n[2]; }

#ifdef __cplusplus
}
#endif

#endif
