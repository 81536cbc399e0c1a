/*
 * Traversal unit, ropes (Popov et al. 2007; docs/traversal.md, interface trav_algo.h, shared
 * cursor machinery trav_cursor.h): a kd-tree whose leaves carry their box and, per face, a rope
 * to the smallest node beyond it; no stack. At an inner node each ray of the group moves to the
 * child holding its entry point (1 mul, 1 add, 1 compare per ray); at a leaf, after the list unit
 * has its entries, each ray leaves by the nearest far plane of the box and follows that face's
 * rope (3 sub, 3 div, 2 compares per ray). One node per step and packet; latency and throughput
 * those of the traversal unit (trav_unit.h). Memory: a rope record of ROPE_WORDS before each
 * leaf's list entries (docs/memory-image.md), read with the leaf.
 */
#include "trace_ops.h"
#include "trav_algo.h"
#include "trav_cursor.h"

/* Rope record: leaf box lo xyz, hi xyz (fp24), ropes -x +x -y +y -z +z (node or TRACE_NO_HIT). */
#define ROPE_WORDS 12

/* A ray that leaves this many leaves in a row without moving on (exit t not beyond its entry) is
 * done. Why: ropes and boxes that the validator accepts but that lead a ray in a circle (a fuzzed
 * image: tests/fuzz/regress/memimage/rope-cycle.bin) would otherwise hold the unit for
 * TRACE_STEP_LIMIT steps; in a consistent tree only the cells around an edge or corner the ray
 * passes exactly through (at most 8) are left without moving on. */
#define ROPE_STALL_LIMIT 16

void trav_ropes_start(trav_walker *w)
{
start_rays:
    for (int i = 0; i < TRACE_PACKET; i++)
        w->at[i] = w->stalls[i] = 0;
}

/* An inner node: each ray of the group moves to the child holding its entry point (a ray in the
 * plane goes the way it points). */
static void ropes_inner(trav_walker *w, uint32_t group, uint32_t w0, f24_t split, const f24_vec3 o[], const f24_vec3 d[])
{
    const uint32_t axis = w0 & 3u, child = w0 >> TRAV_NODE_CHILD_SHIFT; /* ropes images store every node */
descend_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!bit(group, i))
            continue;
        const f24_t p = cursor_point_on(o[i], d[i], f24h_lane(&w->cur.tn, i), axis);
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
        const uint32_t axis = cursor_cell_exit(far, o[i], d[i], &t);
        const uint32_t rope = axis < 3 ? mem[rec + 6 + 2 * axis + (f24_sign(axis_of(d[i], axis)) ? 0u : 1u)] : TRACE_NO_HIT;
        w->stalls[i] = f24_lt(f24h_lane(&w->cur.tn, i), t) ? 0u : w->stalls[i] + 1u;
        cursor_advance(w, i, rope, rope != TRACE_NO_HIT && w->stalls[i] <= ROPE_STALL_LIMIT, t);
    }
}

int trav_ropes_step(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[], const f24_t best_t[],
                    uint32_t alive, unit_op *op, trace_counters *c)
{
    int leaf = 0, lead;
    const uint32_t group = cursor_group(w, best_t, alive, &lead);
    if (group) {
        const uint32_t a = w->nodes + 2 * w->at[lead], w0 = mem[a], w1 = mem[a + 1];
        op_read(op, c, MEM_NODES, a, 2);
        if ((w0 & 3u) == TRAV_NODE_LEAF) {
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
