/*
 * Ropes of a kd-tree (Popov et al. 2007, "Stackless KD-Tree Traversal for High Performance GPU Ray
 * Tracing"): for every leaf its box and, per face, the smallest node on the other side that
 * still covers the whole face ("optimized ropes": a rope is pushed down the neighbour's subtree
 * while one child covers the face), so that a ray leaving a leaf descends as little as possible.
 */
#include "kdtree.h"

/* The rope of face f of box pushed down from node r while one of its children covers the face. */
static uint32_t rope_down(const kd_tree *t, uint32_t r, int f, const aabb *box)
{
    while (r != KD_NO_ROPE && t->nodes[r].axis != KD_LEAF) {
        const kd_node *n = &t->nodes[r];
        const uint32_t k = n->axis;
        if (k == (uint32_t)f / 2)
            r = n->child + ((f & 1) ? 0u : 1u); /* the neighbour's child that touches the face */
        else if (box->hi[k] <= n->split)
            r = n->child;
        else if (box->lo[k] >= n->split)
            r = n->child + 1;
        else
            break;
    }
    return r;
}

static void ropes_node(const kd_tree *t, uint32_t n, const aabb *box, const uint32_t parent[6], kd_rope *out)
{
    uint32_t rope[6];
    for (int f = 0; f < 6; f++)
        rope[f] = rope_down(t, parent[f], f, box);
    const kd_node *nd = &t->nodes[n];
    if (nd->axis == KD_LEAF) {
        out[n].box = *box;
        for (int f = 0; f < 6; f++)
            out[n].rope[f] = rope[f];
        return;
    }
    const uint32_t k = nd->axis;
    aabb lo = *box, hi = *box;
    lo.hi[k] = nd->split;
    hi.lo[k] = nd->split;
    uint32_t r[6];
    for (int f = 0; f < 6; f++)
        r[f] = rope[f];
    r[2 * k + 1] = nd->child + 1;
    ropes_node(t, nd->child, &lo, r, out);
    r[2 * k + 1] = rope[2 * k + 1];
    r[2 * k] = nd->child;
    ropes_node(t, nd->child + 1, &hi, r, out);
}

void kd_ropes(const kd_tree *t, const aabb *root, kd_rope *out)
{
    const uint32_t none[6] = { KD_NO_ROPE, KD_NO_ROPE, KD_NO_ROPE, KD_NO_ROPE, KD_NO_ROPE, KD_NO_ROPE };
    if (t->n_nodes)
        ropes_node(t, 0, root, none, out);
}
