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

void trav_restart_drop_done(const trav_walker *w, trav_entry *e)
{
    if (!w->pass)
        return;
done_cells:
    for (int i = 0; i < TRACE_PACKET; i++)
        if (bit(e->mask, i) && f24_le(e->tf[i], w->t_exit[i]))
            e->mask &= ~(1u << i);
}

void trav_restart_leaf(trav_walker *w, const trav_entry *e)
{
leaf_exit: /* only a leaf that continues a ray's covered segment extends it: in a packet a ray may
              meet its cells in another order than the first ray */
    for (int i = 0; i < TRACE_PACKET && w->cap < TRACE_STACK; i++) /* the stack never restarts */
        if (bit(e->mask, i) && f24_le(e->tn[i], w->t_exit[i]))
            w->t_exit[i] = f24_max(w->t_exit[i], e->tf[i]);
}

/* A ray is done for good when nothing is left of its interval or its closest hit lies before
 * the rest. */
void trav_restart(trav_walker *w, const f24_t best_t[])
{
    trav_entry e = w->root;
    w->lost = 0;
    w->pass++;
restart_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        e.tn[i] = f24_max(e.tn[i], w->t_exit[i]);
        w->t_exit[i] = e.tn[i]; /* before the restart point's cell the ray has nothing left */
        if (bit(e.mask, i) && (!f24_lt(e.tn[i], e.tf[i]) || f24_lt(best_t[i], e.tn[i])))
            e.mask &= ~(1u << i);
    }
    w->root.mask = e.mask;
    w->cur = e;
    w->have_cur = e.mask != 0;
}
