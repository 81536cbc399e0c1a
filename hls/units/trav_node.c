/* Traversal unit, per-node decision: see trav_node.h. */
#include "trav_node.h"

static f24_t axis_of(f24_vec3 v, uint32_t k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }

void trav_node_split(const trav_entry *e, uint32_t axis, f24_t split, const f24_vec3 o[], const f24_vec3 d[],
                     trav_entry *l, trav_entry *r, uint32_t *near_left)
{
    l->mask = r->mask = 0;
    *near_left = 0;
split_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        l->tn[i] = l->tf[i] = r->tn[i] = r->tf[i] = 0;
        if (!(e->mask >> i & 1u))
            continue;
        const f24_t dk = axis_of(d[i], axis);
        const f24_t ts = f24_div(f24_sub(split, axis_of(o[i], axis)), dk);
        const int left = !f24_sign(dk);
        trav_entry *nearc = left ? l : r, *farc = left ? r : l;
        nearc->tn[i] = e->tn[i];
        nearc->tf[i] = f24_min(e->tf[i], ts);
        farc->tn[i] = f24_max(e->tn[i], ts);
        farc->tf[i] = e->tf[i];
        if (f24_le(l->tn[i], l->tf[i]))
            l->mask |= 1u << i;
        if (f24_le(r->tn[i], r->tf[i]))
            r->mask |= 1u << i;
        *near_left |= (uint32_t)left << i;
    }
}
