/* Cursor walkers of the traversal unit (ropes, uniform grid): see trav_cursor.h. */
#include "trav_cursor.h"

#include "trace_ops.h"

#define NODE_LEAF 3u

static uint32_t grid_axis(uint32_t at, uint32_t k) { return at >> (GRID_AXIS_BITS * k) & GRID_MAX_AXIS; }

/* The ray's coordinate on axis k at distance t. */
static f24_t point_on(f24_vec3 o, f24_vec3 d, f24_t t, uint32_t k) { return f24_add(axis_of(o, k), f24_mul(axis_of(d, k), t)); }

/* The rays at the position of the packet's first walking ray (its index in *lead). */
static uint32_t cursor_group(const trav_walker *w, int *lead)
{
    *lead = 0;
lead_ray:
    while (*lead < TRACE_PACKET - 1 && !bit(w->cur.mask, *lead))
        (*lead)++;
    uint32_t g = 0;
group_rays:
    for (int i = 0; i < TRACE_PACKET; i++)
        if (bit(w->cur.mask, i) && w->at[i] == w->at[*lead])
            g |= 1u << i;
    return g;
}

/* Where a ray leaves a cell whose planes in the ray's direction are far[]: the distance and the
 * axis (3: it never leaves, a zero or NaN direction). */
static uint32_t cell_exit(const f24_t far[3], f24_vec3 o, f24_vec3 d, f24_t *t)
{
    uint32_t axis = 3;
    *t = F24_POS_INF;
exit_axes:
    for (uint32_t k = 0; k < 3; k++) {
        const f24_t dk = axis_of(d, k);
        if (f24_is_zero(dk) || f24_is_nan(dk))
            continue;
        const f24_t tk = f24_div(f24_sub(far[k], axis_of(o, k)), dk);
        if (f24_lt(tk, *t)) {
            *t = tk;
            axis = k;
        }
    }
    return axis;
}

/* Moves ray i on to its next position at distance t, or ends its walk (no next position, or its
 * interval ends there). */
static void cursor_advance(trav_walker *w, int i, uint32_t next, int has_next, f24_t t)
{
    if (!has_next || !f24_lt(t, w->cur.tf[i])) {
        w->cur.mask &= ~(1u << i);
        return;
    }
    w->at[i] = next;
    w->cur.tn[i] = f24_max(w->cur.tn[i], t);
}

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
        const int32_t i = f24_to_i32(f24_mul(f24_sub(point_on(o, d, t, k), w->grid_lo[k]), w->grid_inv[k]));
        const uint32_t last = w->grid_n[k] - 1;
        at |= (i < 0 ? 0u : (uint32_t)i > last ? last : (uint32_t)i) << (GRID_AXIS_BITS * k);
    }
    return at;
}

void cursor_start(trav_walker *w, const uint32_t *mem, uint32_t grid, const f24_vec3 o[], const f24_vec3 d[],
                  unit_op *op, trace_counters *c)
{
    if (w->algo == TRAV_GRID) {
        grid_load(w, mem, grid);
        op_read(op, c, MEM_NODES, grid, GRID_WORDS);
    }
start_rays:
    for (int i = 0; i < TRACE_PACKET; i++)
        w->at[i] = w->algo == TRAV_GRID && bit(w->cur.mask, i) ? grid_cell_of(w, o[i], d[i], w->cur.tn[i]) : 0;
}

/* An inner node: each ray of the group moves to the child holding its entry point (a ray in the
 * plane goes the way it points). */
static void ropes_inner(trav_walker *w, uint32_t group, uint32_t w0, f24_t split, const f24_vec3 o[], const f24_vec3 d[])
{
    const uint32_t axis = w0 & 3u, child = w0 >> 4; /* ropes images store every node: no empty bits */
descend_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!bit(group, i))
            continue;
        const f24_t p = point_on(o[i], d[i], w->cur.tn[i], axis);
        const int left = f24_lt(p, split) || (!f24_lt(split, p) && f24_sign(axis_of(d[i], axis)));
        w->at[i] = child + (left ? 0u : 1u);
    }
}

/* A leaf: each ray of the group follows the rope of the face it leaves by. */
static void ropes_leaf(trav_walker *w, const uint32_t *mem, uint32_t group, uint32_t rec, const f24_vec3 o[],
                       const f24_vec3 d[])
{
leave_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!bit(group, i))
            continue;
        f24_t far[3], t;
    far_planes:
        for (uint32_t k = 0; k < 3; k++)
            far[k] = mem[rec + (f24_sign(axis_of(d[i], k)) ? k : 3 + k)] & F24_MASK;
        const uint32_t axis = cell_exit(far, o[i], d[i], &t);
        const uint32_t rope = axis < 3 ? mem[rec + 6 + 2 * axis + (f24_sign(axis_of(d[i], axis)) ? 0u : 1u)] : TRACE_NO_HIT;
        cursor_advance(w, i, rope, rope != TRACE_NO_HIT, t);
    }
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
        const uint32_t axis = cell_exit(far, o[i], d[i], &t);
        const uint32_t ik = axis < 3 ? grid_axis(w->at[i], axis) : 0u, down = axis < 3 && f24_sign(axis_of(d[i], axis));
        const int inside = axis < 3 && (down ? ik > 0 : ik + 1 < w->grid_n[axis]);
        const uint32_t shift = GRID_AXIS_BITS * (axis < 3 ? axis : 0u);
        cursor_advance(w, i, down ? w->at[i] - (1u << shift) : w->at[i] + (1u << shift), inside, t);
    }
}

/* The group's list (leaf or cell) for the list unit. */
static int cursor_list(trav_walker *w, uint32_t group, uint32_t first, uint32_t count, trace_counters *c)
{
    w->leaf_first = first;
    w->leaf_count = count;
    w->leaf_mask = group;
    w->k = 0;
    c->leaves++;
    return count != 0;
}

int cursor_step(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[], const f24_t best_t[],
                uint32_t alive, unit_op *op, trace_counters *c)
{
    int leaf = 0;
    op_set(op, UNIT_TRAV, 1);
    w->cur.mask &= alive;
prune:
    for (int i = 0; i < TRACE_PACKET; i++)
        if (bit(w->cur.mask, i) && f24_lt(best_t[i], w->cur.tn[i]))
            w->cur.mask &= ~(1u << i);
    int lead;
    const uint32_t group = cursor_group(w, &lead);
    if (group && w->algo == TRAV_GRID) {
        const uint32_t at = w->at[lead];
        const uint32_t a = w->nodes + 2 * (grid_axis(at, 0) + w->grid_n[0] * (grid_axis(at, 1) + w->grid_n[1] * grid_axis(at, 2)));
        op_read(op, c, MEM_NODES, a, 2);
        leaf = cursor_list(w, group, mem[a], mem[a + 1], c);
        grid_leave(w, group, o, d);
    } else if (group) {
        const uint32_t a = w->nodes + 2 * w->at[lead], w0 = mem[a], w1 = mem[a + 1];
        op_read(op, c, MEM_NODES, a, 2);
        if ((w0 & 3u) == NODE_LEAF) {
            op_read(op, c, MEM_NODES, w->lists + w1 - ROPE_WORDS, ROPE_WORDS);
            leaf = cursor_list(w, group, w1, w0 >> 2, c);
            ropes_leaf(w, mem, group, w->lists + w1 - ROPE_WORDS, o, d);
        } else {
            c->traversal_steps++;
            ropes_inner(w, group, w0, w1 & F24_MASK, o, d);
        }
    }
    w->have_cur = w->cur.mask != 0;
    return leaf;
}
