/* Traversal unit, per-node decision: see trav_node.h. */
#include "trav_node.h"

F24Q_FN void trav_rays_of(trav_rays *rays, const f24_vec3 o[], const f24_vec3 d[])
{
    f24_t c[6][TRACE_PACKET];
rays_axes:
    for (int i = 0; i < TRACE_PACKET; i++) {
        c[0][i] = o[i].x, c[1][i] = o[i].y, c[2][i] = o[i].z;
        c[3][i] = d[i].x, c[4][i] = d[i].y, c[5][i] = d[i].z;
    }
rays_held:
    for (int k = 0; k < 3; k++) {
        f24h_of(&rays->o[k], c[k]);
        f24h_of(&rays->d[k], c[3 + k]);
    }
}

/* The rays side by side, one lane each, as the datapath has them: every lane computes, the
 * entry's mask selects the results. The axis picks the rays' components (axis 3, never an inner
 * node's, reads z). */
F24Q_FN void trav_node_split_held(const trav_entry *e, uint32_t axis, f24_t split, const trav_rays *rays,
                                  trav_entry *l, trav_entry *r, uint32_t *near_left)
{
    const uint32_t k = axis < 2 ? axis : 2u;
    const f24q dk = f24h_get(&rays->d[k]), ok = f24h_get(&rays->o[k]), tn = f24h_get(&e->tn), tf = f24h_get(&e->tf);
    const f24q ts = f24q_div(f24q_sub(f24q_splat(split), ok), dk);
    const f24q near_tf = f24q_min(tf, ts), far_tn = f24q_max(tn, ts);
    const uint32_t in = e->mask, left = ~f24q_sign(dk) & in; /* -0 counts as negative */
    const uint32_t near_ok = in & f24q_le(tn, near_tf), far_ok = in & f24q_le(far_tn, tf);
    l->mask = (left & near_ok) | (~left & far_ok);
    r->mask = (left & far_ok) | (~left & near_ok);
    *near_left = left;
    /* the rays outside the mask get [0, 0]; inside, the left child is the near one where left */
    const f24q zero = f24q_splat(0u);
    const f24q ntn = f24q_select(in, tn, zero), ntf = f24q_select(in, near_tf, zero),
               ftn = f24q_select(in, far_tn, zero), ftf = f24q_select(in, tf, zero);
    f24h_put(&l->tn, f24q_select(left, ntn, ftn));
    f24h_put(&l->tf, f24q_select(left, ntf, ftf));
    f24h_put(&r->tn, f24q_select(left, ftn, ntn));
    f24h_put(&r->tf, f24q_select(left, ftf, ntf));
}

void trav_node_split(const trav_entry *e, uint32_t axis, f24_t split, const f24_vec3 o[], const f24_vec3 d[],
                     trav_entry *l, trav_entry *r, uint32_t *near_left)
{
    trav_rays rays;
    trav_rays_of(&rays, o, d);
    trav_node_split_held(e, axis, split, &rays, l, r, near_left);
}
