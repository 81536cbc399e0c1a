/*
 * Traversal unit, stack family (docs/traversal.md; interface trav_algo.h): the packet walks the
 * kd-tree as a whole, near child first (by the packet's first ray), the far child of a split that
 * both sides need waiting on a stack of w->cap entries: the paper's stack (TRACE_STACK = 64, paper
 * section 3; the prototype kept 64 per thread), the short stack (TRACE_SHORT_STACK = 4, Horn et
 * al. 2007), kd-restart and push-down (no stack). A full stack drops its oldest entry, and a
 * stack that runs dry after a drop restarts (trav_restart.c); with push-down (short stack,
 * push-down) a node that the whole packet passes on one side only becomes the restart point while
 * nothing waits.
 *
 * Per step one kd-tree entry: the prune (4 comparators), the node read (2 words), and at an inner
 * node the per-node datapath (trav_node.h: 4 sub, 4 div, per ray min, max, 2 compares); latency
 * and throughput those of the traversal unit (trav_unit.h: 21 cycles, one entry per cycle).
 * State per level: TRACE_STACK entries of a node index, mask and 4 intervals.
 */
#include "trace_ops.h"
#include "trav_algo.h"
#include "trav_node.h"

/* Pushes the far child; a full stack drops its oldest entry (a restart will cover it). */
static void walker_push(trav_walker *w, const trav_entry *far)
{
    if (w->cap == 0) {
        w->lost = 1;
        return;
    }
    if (w->sp == w->cap) {
    stack_shift:
        for (uint32_t i = 0; i + 1 < TRACE_STACK; i++)
            if (i + 1 < w->sp)
                w->stack[i] = w->stack[i + 1];
        w->sp--;
        w->lost = 1;
    }
    trav_entry_copy(&w->stack[w->sp++], far);
}

/* An inner node: both children for the rays that need them (trav_node_split_held); the far side of
 * the packet's first ray waits on the stack. With push-down, a node that the whole packet
 * passes through on one side only becomes the new restart point while nothing waits. */
F24Q_INLINE void walker_split(trav_walker *w, uint32_t w0, f24_t split)
{
    const uint32_t axis = w0 & 3u, child = w0 >> TRAV_NODE_CHILD_SHIFT, empty = w0 >> 2 & 3u;
    trav_entry l, r;
    uint32_t near_left;
    trav_node_split_held(&w->cur, axis, split, &w->rays, &l, &r, &near_left);
    /* a side that is an empty leaf is not stored: no ray goes there (no step for an empty cell) */
    l.mask &= bit(empty, 0) ? 0u : 0xFu;
    r.mask &= bit(empty, 1) ? 0u : 0xFu;
    l.node = child;
    r.node = child + (bit(empty, 0) ? 0u : 1u);
    trav_restart_drop_done(w, &l);
    trav_restart_drop_done(w, &r);
    /* the packet follows its first ray, near side first; after a restart, the first ray that
     * still needs a child, into the child it needs (so that it advances every pass) */
    const uint32_t lead = w->pass ? l.mask | r.mask : w->cur.mask;
    int first = 0;
first_ray:
    while (first < TRACE_PACKET - 1 && !bit(lead, first))
        first++;
    uint32_t first_near_left = bit(near_left, first);
    if (w->pass && !bit(first_near_left ? l.mask : r.mask, first))
        first_near_left = !first_near_left;
    if (l.mask && r.mask) {
        walker_push(w, first_near_left ? &r : &l);
        trav_entry_copy(&w->cur, first_near_left ? &l : &r);
    } else {
        trav_entry_copy(&w->cur, l.mask ? &l : &r);
        if (w->push_down && w->sp == 0 && !w->lost)
            trav_entry_copy(&w->root, &w->cur);
    }
}

/* One kd-tree entry: prune the rays whose closest hit lies before it, then read the node and
 * split, or report a leaf (its list range). Afterwards, if the entry is used up, the next one is
 * popped (or, the stack empty after a drop, the walk restarts); !w->have_cur then means the tree
 * is done. Returns 1 at a leaf with entries. */
/* The rays of entry e still alive whose closest hit does not lie before it (4 comparators, side
 * by side: every lane compares, the mask keeps the entry's). */
F24Q_INLINE uint32_t entry_rays(const trav_entry *e, const f24_t best_t[], uint32_t alive)
{
    return e->mask & alive & ~f24q_lt(f24q_of(best_t), f24h_get(&e->tn));
}

/* Where each ray of the leaf at entry e enters it, for the list and rebase units. */
F24Q_INLINE void leaf_entry(trav_walker *w, const trav_entry *e) { f24h_words(&e->tn, w->leaf_tn); }

F24Q_FN int trav_stack_step(trav_walker *w, const uint32_t *mem, const f24_t best_t[], uint32_t alive, unit_op *op,
                    trace_counters *c)
{
    trav_entry *e = &w->cur;
    int leaf = 0;
    e->mask = entry_rays(e, best_t, alive); /* rays done (any hit found) leave the packet */
    if (!e->mask && w->sp > 0) {
        /* an entry all of whose rays found their hit before it is dropped and the next one taken
         * in the same step (a second read port of the stack memory): the walk is the same, the
         * step that would only find it done is saved */
        *e = w->stack[--w->sp];
        e->mask = entry_rays(e, best_t, alive);
    }
    w->root.mask &= alive;
    if (!e->mask) {
        w->have_cur = 0;
    } else {
        const uint32_t a = w->nodes + 2 * e->node, w0 = mem[a], w1 = mem[a + 1];
        op_read(op, c, MEM_NODES, a, 2);
        if ((w0 & 3u) == TRAV_NODE_LEAF) {
            w->have_cur = 0;
            w->leaf_first = w1;
            w->leaf_count = w0 >> 2;
            w->leaf_mask = e->mask;
            w->k = 0;
            leaf_entry(w, e);
            c->leaves++;
            leaf = w->leaf_count != 0;
            trav_restart_leaf(w, e);
        } else {
            c->traversal_steps++;
            walker_split(w, w0, w1);
        }
    }
    if (!w->have_cur && w->sp > 0) {
        w->cur = w->stack[--w->sp];
        w->have_cur = 1;
    } else if (!w->have_cur && w->lost) {
        trav_restart(w, best_t);
    }
    return leaf;
}
