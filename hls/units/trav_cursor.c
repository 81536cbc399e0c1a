/* Traversal unit, what the cursor walkers (ropes, grid) share: see trav_cursor.h. */
#include "trav_cursor.h"

#include "trace_ops.h"

f24_t cursor_point_on(f24_vec3 o, f24_vec3 d, f24_t t, uint32_t k) { return f24_add(axis_of(o, k), f24_mul(axis_of(d, k), t)); }

/* The rays whose closest hit lies before their position (4 comparators, side by side). */
static F24Q_FN uint32_t pruned(const trav_walker *w, const f24_t best_t[])
{
    return f24q_lt(f24q_of(best_t), f24h_get(&w->cur.tn));
}

uint32_t cursor_group(trav_walker *w, const f24_t best_t[], uint32_t alive, int *lead)
{
    w->cur.mask &= alive & ~pruned(w, best_t);
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

uint32_t cursor_cell_exit(const f24_t far[3], f24_vec3 o, f24_vec3 d, f24_t *t)
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

void cursor_advance(trav_walker *w, int i, uint32_t next, int has_next, f24_t t)
{
    if (!has_next || !f24_lt(t, f24h_lane(&w->cur.tf, i))) {
        w->cur.mask &= ~(1u << i);
        return;
    }
    w->at[i] = next;
    f24h_set_lane(&w->cur.tn, i, f24_max(f24h_lane(&w->cur.tn, i), t));
}

int cursor_list(trav_walker *w, uint32_t group, uint32_t first, uint32_t count, trace_counters *c)
{
    w->leaf_first = first;
    w->leaf_count = count;
    w->leaf_mask = group;
    w->k = 0;
    f24h_words(&w->cur.tn, w->leaf_tn);
    c->leaves++;
    return count != 0;
}
