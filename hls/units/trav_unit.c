/* Traversal unit: clip operations, walk start and dispatch to the algorithms; see trav_unit.h. */
#include "trav_unit.h"

#include "trace_ops.h"
#include "trav_algo.h"
#include "trav_node.h"

/* Slab test of the rays in mask (o, d) against a box of 6 fp24 words, the rays side by side as
 * the unit's per-ray operators are: narrows their [tn, tf] and returns the rays in mask whose
 * interval is not empty. The sign bit of d orders the slab distances, so that d = -0 behaves like
 * a negative direction. Rays outside mask keep their tn and tf. */
static F24Q_FN uint32_t clip_box(const uint32_t *box, const f24_vec3 o[], const f24_vec3 d[], uint32_t mask,
                                 f24_t tn[TRACE_PACKET], f24_t tf[TRACE_PACKET])
{
    f24q n = f24q_of(tn), f = f24q_of(tf);
    f24_t ok[3][TRACE_PACKET], dk[3][TRACE_PACKET]; /* the rays' components by axis, read once */
    const f24_t lo[F24Q_LANES] = { box[0], box[1], box[2], 0 }, hi[F24Q_LANES] = { box[3], box[4], box[5], 0 };
    const f24q loq = f24q_of(lo), hiq = f24q_of(hi); /* the box's planes, each broadcast to the rays */
clip_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        ok[0][i] = o[i].x, ok[1][i] = o[i].y, ok[2][i] = o[i].z;
        dk[0][i] = d[i].x, dk[1][i] = d[i].y, dk[2][i] = d[i].z;
    }
clip_axes:
    for (uint32_t k = 0; k < 3; k++) {
        const f24q okq = f24q_of(ok[k]), dkq = f24q_of(dk[k]);
        const f24q t0 = f24q_div(f24q_sub(f24q_broadcast(loq, (int)k), okq), dkq),
                   t1 = f24q_div(f24q_sub(f24q_broadcast(hiq, (int)k), okq), dkq);
        const uint32_t negative = f24q_sign(dkq);
        n = f24q_max(n, f24q_select(negative, t1, t0));
        f = f24q_min(f, f24q_select(negative, t0, t1));
    }
    f24_t nb[TRACE_PACKET], fb[TRACE_PACKET];
    f24q_bits(n, nb);
    f24q_bits(f, fb);
clip_results:
    for (int i = 0; i < TRACE_PACKET; i++) {
        tn[i] = bit(mask, i) ? nb[i] : tn[i];
        tf[i] = bit(mask, i) ? fb[i] : tf[i];
    }
    return mask & f24q_le(n, f);
}

uint32_t trav_scene_clip(const uint32_t *bounds, const ray_packet *rays, f24_t tn[TRACE_PACKET], f24_t tf[TRACE_PACKET])
{
scene_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        tn[i] = rays->tmin[i];
        tf[i] = rays->tmax[i];
    }
    return clip_box(bounds, rays->o, rays->d, rays->active, tn, tf);
}

uint32_t trav_object_clip(const uint32_t *bounds, const f24_vec3 o[], const f24_vec3 d[], const f24_t tmin[],
                          const f24_t best_t[], uint32_t need, f24_t tn[TRACE_PACKET], f24_t tf[TRACE_PACKET])
{
object_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        tn[i] = bit(need, i) ? tmin[i] : F24_POS_INF;
        tf[i] = bit(need, i) ? best_t[i] : 0;
    }
    return clip_box(bounds, o, d, need, tn, tf);
}

/* The walker's state for every algorithm: the rays and their intervals at the root, the stack
 * (its capacity by algorithm: 0 for the stackless ones) and the restart state. */
static F24Q_FN void walker_init(trav_walker *w, uint32_t nodes, uint32_t lists, uint32_t mask, const f24_t tn[], const f24_t tf[],
                        uint32_t algo)
{
    w->nodes = nodes;
    w->lists = lists;
    w->sp = 0;
    w->have_cur = 1;
    w->cur.node = 0;
    w->cur.mask = mask;
    /* the leaf fields too, though no walk reads them before it finds a leaf: the walker's whole state
     * is what --capture-unit-io records, and a capture must not depend on the memory it was made in */
    w->leaf_first = w->leaf_count = w->leaf_mask = w->k = 0;
    w->algo = algo;
    w->cap = algo == TRAV_STACK ? TRACE_STACK : algo == TRAV_SHORT_STACK ? TRACE_SHORT_STACK : 0;
    w->push_down = algo == TRAV_SHORT_STACK || algo == TRAV_PUSH_DOWN;
    w->lost = w->pass = 0;
    f24h_of(&w->cur.tn, tn);
    f24h_of(&w->cur.tf, tf);
walker_copy:
    for (int i = 0; i < TRACE_PACKET; i++) {
        w->t_exit[i] = tn[i];
        w->leaf_tn[i] = 0;
    }
    trav_entry_copy(&w->root, &w->cur);
}

void trav_start(trav_walker *w, const uint32_t *mem, uint32_t asked, uint32_t accel, uint32_t nodes, uint32_t lists,
                uint32_t grid, uint32_t mask, const f24_t tn[], const f24_t tf[], const f24_vec3 o[], const f24_vec3 d[],
                unit_op *op, trace_counters *c)
{
    uint32_t algo = asked < TRAV_ROPES && !(accel & ACCEL_COMPACT) ? asked : TRAV_STACK;
    if (asked == TRAV_ROPES && (accel & ACCEL_ROPES) && !(accel & ACCEL_COMPACT))
        algo = TRAV_ROPES;
    if (asked >= TRAV_GRID && grid != TRACE_NO_HIT)
        algo = TRAV_GRID;
    walker_init(w, nodes, lists, mask, tn, tf, algo);
    if (algo < TRAV_ROPES)
        trav_rays_of(&w->rays, o, d); /* the stack family's splits read the rays as held */
    else if (algo == TRAV_ROPES)
        trav_ropes_start(w);
    else if (algo == TRAV_GRID)
        trav_grid_start(w, mem, grid, o, d, op, c);
}

int trav_walk(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[], const f24_t best_t[],
              uint32_t alive, unit_op *op, trace_counters *c)
{
    op_set(op, OP_TRAV, 1);
    if (w->algo == TRAV_ROPES)
        return trav_ropes_step(w, mem, o, d, best_t, alive, op, c);
    if (w->algo == TRAV_GRID)
        return trav_grid_step(w, mem, o, d, best_t, alive, op, c);
    return trav_stack_step(w, mem, best_t, alive, op, c);
}
