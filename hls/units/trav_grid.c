/*
 * Traversal unit, uniform grids with 3D-DDA (Purcell et al. 2002, Amanatides and Woo 1987;
 * docs/traversal.md, interface trav_algo.h, shared cursor machinery trav_cursor.h): per object
 * under the top-level kd-tree (grid), or also over the instances (grid2: a two-level grid,
 * Adinetz and Berezin); no stack. The start cell comes from the ray's entry point times the
 * inverse cell size, clamped into the grid (3 mul, 6 add, 3 float-to-int per ray); per cell the
 * three far planes lo + (i + 1) size are recomputed from the cell index, so no error accumulates
 * along the ray (3 int-to-float, 3 mul, 6 add, 3 div, 2 compares per ray), and the ray steps
 * across the nearest. One cell per step and packet; latency and throughput those of the traversal
 * unit (trav_unit.h). Memory: a grid header of GRID_WORDS words (read at the start), cells of 2
 * words {first, count} into the grid's own lists (docs/memory-image.md).
 */
#include "trace_ops.h"
#include "trav_algo.h"
#include "trav_cursor.h"

/* Grid header: lo xyz, cell size xyz, 1 / size xyz (fp24), cells per axis (3), cells, lists,
 * list length (read by the validator only). */
enum { G_LO = 0, G_SIZE = 3, G_INV = 6, G_N = 9, G_CELLS = 12, G_LISTS = 13, GRID_WORDS = 14 };
#define GRID_AXIS_BITS 10 /* cell index x | y << 10 | z << 20: at most 1023 cells per axis */
#define GRID_MAX_AXIS ((1u << GRID_AXIS_BITS) - 1u)

static uint32_t grid_axis(uint32_t at, uint32_t k) { return at >> (GRID_AXIS_BITS * k) & GRID_MAX_AXIS; }

static void grid_load(trav_walker *w, const uint32_t *mem, uint32_t grid)
{
grid_header:
    for (uint32_t k = 0; k < 3; k++) {
        w->grid_lo[k] = mem[grid + G_LO + k] & F24_MASK;
        w->grid_size[k] = mem[grid + G_SIZE + k] & F24_MASK;
        w->grid_inv[k] = mem[grid + G_INV + k] & F24_MASK;
        w->grid_n[k] = mem[grid + G_N + k];
    }
    w->nodes = mem[grid + G_CELLS];
    w->lists = mem[grid + G_LISTS];
}

/* The cell of the ray's entry point, clamped into the grid (rounding may put it a cell out). */
static uint32_t grid_cell_of(const trav_walker *w, f24_vec3 o, f24_vec3 d, f24_t t)
{
    uint32_t at = 0;
cell_axes:
    for (uint32_t k = 0; k < 3; k++) {
        const int32_t i = f24_to_i32(f24_mul(f24_sub(cursor_point_on(o, d, t, k), w->grid_lo[k]), w->grid_inv[k]));
        const uint32_t last = w->grid_n[k] - 1;
        at |= (i < 0 ? 0u : (uint32_t)i > last ? last : (uint32_t)i) << (GRID_AXIS_BITS * k);
    }
    return at;
}

void trav_grid_start(trav_walker *w, const uint32_t *mem, uint32_t grid, const f24_vec3 o[], const f24_vec3 d[],
                     unit_op *op, trace_counters *c)
{
    grid_load(w, mem, grid);
    op_read(op, c, MEM_NODES, grid, GRID_WORDS);
start_rays:
    for (int i = 0; i < TRACE_PACKET; i++)
        w->at[i] = bit(w->cur.mask, i) ? grid_cell_of(w, o[i], d[i], f24h_lane(&w->cur.tn, i)) : 0;
}

/* A cell: each ray of the group steps to the neighbour across the nearest far plane. */
static void grid_leave(trav_walker *w, uint32_t group, const f24_vec3 o[], const f24_vec3 d[])
{
grid_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!bit(group, i))
            continue;
        f24_t far[3], t;
    grid_planes:
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t up = f24_sign(axis_of(d[i], k)) ? 0u : 1u;
            far[k] = f24_add(w->grid_lo[k], f24_mul(f24_from_i32((int32_t)(grid_axis(w->at[i], k) + up)), w->grid_size[k]));
        }
        const uint32_t axis = cursor_cell_exit(far, o[i], d[i], &t);
        const uint32_t ik = axis < 3 ? grid_axis(w->at[i], axis) : 0u, down = axis < 3 && f24_sign(axis_of(d[i], axis));
        const int inside = axis < 3 && (down ? ik > 0 : ik + 1 < w->grid_n[axis]);
        const uint32_t shift = GRID_AXIS_BITS * (axis < 3 ? axis : 0u);
        cursor_advance(w, i, down ? w->at[i] - (1u << shift) : w->at[i] + (1u << shift), inside, t);
    }
}

int trav_grid_step(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[], const f24_t best_t[],
                   uint32_t alive, unit_op *op, trace_counters *c)
{
    int leaf = 0, lead;
    const uint32_t group = cursor_group(w, best_t, alive, &lead);
    if (group) {
        const uint32_t at = w->at[lead];
        const uint32_t a = w->nodes + 2 * (grid_axis(at, 0) + w->grid_n[0] * (grid_axis(at, 1) + w->grid_n[1] * grid_axis(at, 2)));
        op_read(op, c, MEM_NODES, a, 2);
        leaf = cursor_list(w, group, mem[a], mem[a + 1], c);
        grid_leave(w, group, o, d);
    }
    w->have_cur = w->cur.mask != 0;
    return leaf;
}
