/* Uniform grid builder: see ugrid.h. Two passes over the primitives (count, then fill). */
#include "ugrid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Cells per axis: about density * count cells of roughly equal sides (a flat axis gets one). */
static void grid_resolution(const aabb *box, uint32_t count, double density, uint32_t n[3])
{
    double ext[3], big = 0;
    for (int k = 0; k < 3; k++) {
        ext[k] = box->hi[k] - box->lo[k];
        big = fmax(big, ext[k]);
    }
    double vol = 1;
    for (int k = 0; k < 3; k++)
        vol *= fmax(ext[k], big * 1e-3);
    const double cells = fmin(fmax(density * count, 1.0), UGRID_MAX_CELLS);
    const double per_unit = big > 0 ? cbrt(cells / vol) : 0;
    for (int k = 0; k < 3; k++) {
        const double m = ceil(ext[k] * per_unit);
        n[k] = m < 1 ? 1u : m > UGRID_MAX_AXIS ? UGRID_MAX_AXIS : (uint32_t)m;
    }
    while ((uint64_t)n[0] * n[1] * n[2] > UGRID_MAX_CELLS)
        for (int k = 0; k < 3; k++)
            n[k] = n[k] > 1 ? n[k] - n[k] / 8 - 1 : 1;
}

/* Cell range [c0, c1] of [lo, hi] on axis k, clamped to the grid. */
static void cell_range(const ugrid *g, int k, double lo, double hi, uint32_t *c0, uint32_t *c1)
{
    const double a = floor((lo - g->lo[k]) / g->size[k]), b = floor((hi - g->lo[k]) / g->size[k]);
    const double last = g->n[k] - 1;
    *c0 = (uint32_t)(a < 0 ? 0 : a > last ? last : a);
    *c1 = (uint32_t)(b < 0 ? 0 : b > last ? last : b);
}

/* Visits the cells primitive i overlaps (fill: records it), returns how many. */
static uint32_t prim_cells(const kd_source *src, uint32_t i, ugrid *g, double widen, int fill)
{
    const aabb b = src->bounds(src->user, i);
    uint32_t c0[3], c1[3], n = 0;
    for (int k = 0; k < 3; k++)
        cell_range(g, k, b.lo[k] - widen, b.hi[k] + widen, &c0[k], &c1[k]);
    for (uint32_t z = c0[2]; z <= c1[2]; z++)
        for (uint32_t y = c0[1]; y <= c1[1]; y++)
            for (uint32_t x = c0[0]; x <= c1[0]; x++) {
                const uint32_t xyz[3] = { x, y, z };
                aabb cell, part;
                for (int k = 0; k < 3; k++) {
                    cell.lo[k] = g->lo[k] + xyz[k] * g->size[k] - widen;
                    cell.hi[k] = g->lo[k] + (xyz[k] + 1) * g->size[k] + widen;
                }
                if (src->clip && !src->clip(src->user, i, &cell, &part))
                    continue;
                const uint32_t c = x + g->n[0] * (y + g->n[1] * z);
                if (fill)
                    g->prims[g->first[c] + g->count[c]] = i;
                g->count[c]++;
                n++;
            }
    return n;
}

void ugrid_free(ugrid *g)
{
    free(g->first);
    free(g->count);
    free(g->prims);
    memset(g, 0, sizeof *g);
}

int ugrid_build(const kd_source *src, const aabb *box, const ugrid_params *p, ugrid *out)
{
    memset(out, 0, sizeof *out);
    grid_resolution(box, src->count, p->density, out->n);
    double big = 0;
    for (int k = 0; k < 3; k++) {
        out->lo[k] = box->lo[k];
        const double ext = box->hi[k] - box->lo[k];
        double s = ext > 0 ? ext / out->n[k] : 1.0;
        s = p->quantize_up ? p->quantize_up(s) : s;
        while (out->lo[k] + out->n[k] * s < box->hi[k]) /* cover the box despite the rounding */
            s = p->quantize_up ? p->quantize_up(s * (1 + 1e-7)) : s * (1 + 1e-12);
        out->size[k] = s;
        big = fmax(big, fmax(fabs(box->lo[k]), fabs(box->hi[k])));
    }
    const double widen = p->widen * big;
    const uint32_t cells = ugrid_cells(out);
    out->first = calloc(cells, sizeof *out->first);
    out->count = calloc(cells, sizeof *out->count);
    if (!out->first || !out->count)
        goto oom;
    uint64_t total = 0;
    for (uint32_t i = 0; i < src->count; i++)
        total += prim_cells(src, i, out, widen, 0);
    if (total > UINT32_MAX / 2)
        goto oom;
    out->prims = malloc((total + 1) * sizeof *out->prims);
    if (!out->prims)
        goto oom;
    out->n_prims = (uint32_t)total;
    for (uint32_t c = 0, at = 0; c < cells; c++) {
        out->first[c] = at;
        at += out->count[c];
        out->count[c] = 0;
    }
    for (uint32_t i = 0; i < src->count; i++)
        prim_cells(src, i, out, widen, 1);
    return 0;
oom:
    ugrid_free(out);
    return -1;
}
