/*
 * Traversal unit, the restart of the stack walkers that drop entries (docs/traversal.md;
 * interface trav_algo.h): kd-restart (Foley and Sugerman 2005) and push-down (Horn et al. 2007),
 * which keep no stack, and the short stack (Horn et al. 2007), which drops its oldest entry when
 * full. When the walk runs out of entries after a drop, it walks down again from the restart
 * point (the root, or the push-down node) with each ray's interval starting at t_exit, where the
 * last leaf that continued the ray's covered segment ended, and excludes the cells that end
 * there. A ray whose closest hit lies before its t_exit leaves the restart point's mask for good.
 *
 * No operation of its own: the restart happens within a traversal unit step (trav_stack.c; its
 * latency and throughput, trav_unit.h). Operators per ray: at a leaf 1 comparator and 1 max
 * (t_exit), per child of an inner node after a restart 1 comparator, per restart 1 max and 2
 * comparators. State per level: the restart entry and 4 t_exit.
 */
#include "trace_ops.h"
#include "trav_algo.h"

/* per ray 1 comparator, side by side */
F24Q_FN uint32_t trav_restart_done(const trav_walker *w, const trav_entry *e)
{
    return f24q_le(f24h_get(&e->tf), f24q_of(w->t_exit));
}

F24Q_FN void trav_restart_leaf(trav_walker *w, const trav_entry *e)
{
    if (w->cap >= TRACE_STACK)
        return; /* the stack never restarts */
    /* only a leaf that continues a ray's covered segment extends it: in a packet a ray may meet
     * its cells in another order than the first ray */
    const f24q t_exit = f24q_of(w->t_exit);
    const uint32_t extends = e->mask & f24q_le(f24h_get(&e->tn), t_exit);
    f24_t ends[TRACE_PACKET];
    f24q_bits(f24q_max(t_exit, f24h_get(&e->tf)), ends);
leaf_exit:
    for (int i = 0; i < TRACE_PACKET; i++)
        w->t_exit[i] = bit(extends, i) ? ends[i] : w->t_exit[i];
}

/* A ray is done for good when nothing is left of its interval or its closest hit lies before
 * the rest. */
F24Q_FN void trav_restart(trav_walker *w, const f24_t best_t[])
{
    trav_entry e = w->root;
    w->lost = 0;
    w->pass++;
    const f24q tn = f24q_max(f24h_get(&e.tn), f24q_of(w->t_exit));
    f24h_put(&e.tn, tn);
    f24q_bits(tn, w->t_exit); /* before the restart point's cell the ray has nothing left */
    e.mask &= f24q_lt(tn, f24h_get(&e.tf)) & ~f24q_lt(f24q_of(best_t), tn);
    w->root.mask = e.mask;
    w->cur = e;
    w->have_cur = e.mask != 0;
}
