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
        const f24w dk = f24w_of(axis_of(d[i], axis)), tn = f24w_of(e->tn[i]), tf = f24w_of(e->tf[i]);
        const f24w ts = f24w_div(f24w_sub(f24w_of(split), f24w_of(axis_of(o[i], axis))), dk);
        const f24w near_tf = f24w_min(tf, ts), far_tn = f24w_max(tn, ts);
        const int left = !f24w_sign(dk);
        trav_entry *nearc = left ? l : r, *farc = left ? r : l;
        nearc->tn[i] = e->tn[i];
        nearc->tf[i] = f24w_bits(near_tf);
        farc->tn[i] = f24w_bits(far_tn);
        farc->tf[i] = e->tf[i];
        nearc->mask |= (uint32_t)f24w_le(tn, near_tf) << i;
        farc->mask |= (uint32_t)f24w_le(far_tn, tf) << i;
        *near_left |= (uint32_t)left << i;
    }
}
