/* Traversal unit, per-node decision: see trav_node.h. */
#include "trav_node.h"

static f24_t axis_of(f24_vec3 v, uint32_t k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }

/* The rays side by side, one lane each, as the datapath has them: every lane computes, the
 * entry's mask selects the results. */
F24Q_FN void trav_node_split(const trav_entry *e, uint32_t axis, f24_t split, const f24_vec3 o[], const f24_vec3 d[],
                             trav_entry *l, trav_entry *r, uint32_t *near_left)
{
    f24_t dk_bits[TRACE_PACKET], ok_bits[TRACE_PACKET], near_tf[TRACE_PACKET], far_tn[TRACE_PACKET];
split_axes:
    for (int i = 0; i < TRACE_PACKET; i++) {
        dk_bits[i] = axis_of(d[i], axis);
        ok_bits[i] = axis_of(o[i], axis);
    }
    const f24q dk = f24q_of(dk_bits), tn = f24q_of(e->tn), tf = f24q_of(e->tf);
    const f24q ts = f24q_div(f24q_sub(f24q_splat(split), f24q_of(ok_bits)), dk);
    const f24q near_tfq = f24q_min(tf, ts), far_tnq = f24q_max(tn, ts);
    f24q_bits(near_tfq, near_tf);
    f24q_bits(far_tnq, far_tn);
    const uint32_t in = e->mask, left = ~f24q_sign(dk) & in; /* -0 counts as negative */
    const uint32_t near_ok = in & f24q_le(tn, near_tfq), far_ok = in & f24q_le(far_tnq, tf);
    l->mask = (left & near_ok) | (~left & far_ok);
    r->mask = (left & far_ok) | (~left & near_ok);
    *near_left = left;
split_rays: /* as masks (all ones or zero per ray), so that the lanes' selects need no branch */
    for (int i = 0; i < TRACE_PACKET; i++) {
        const uint32_t on = 0u - (in >> i & 1u), lft = 0u - (left >> i & 1u);
        const f24_t ntn = e->tn[i] & on, ntf = near_tf[i] & on, ftn = far_tn[i] & on, ftf = e->tf[i] & on;
        l->tn[i] = (ntn & lft) | (ftn & ~lft);
        l->tf[i] = (ntf & lft) | (ftf & ~lft);
        r->tn[i] = (ftn & lft) | (ntn & ~lft);
        r->tf[i] = (ftf & lft) | (ntf & ~lft);
    }
}
