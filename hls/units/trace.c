/* Functional model of the ray tracing core for one packet: see trace.h. */
#include "trace.h"

#include "isect_unit.h"
#include "xform_unit.h"

#define MI_NODE_LEAF 3u     /* docs/memory-image.md: kd node word 0 = child << 2 | axis, or count << 2 | 3 */
#define STEP_LIMIT (1u << 24) /* bound of every walk (a valid tree has fewer nodes than this) */

/* Memory-image layout constants used by the core (docs/memory-image.md). */
enum {
    H_OBJECTS = 6, H_INSTANCES = 7, H_TOP_NODES = 11, H_SCENE_BOUNDS = 12, H_REGIONS = 18,
    R_OBJECTS = 5, R_INSTANCES = 8, R_TOP_NODES = 9, R_TOP_LISTS = 10,
    OBJ_WORDS = 16, O_NODES = 0, O_LISTS = 1, O_TRIANGLES = 2, O_BOUNDS = 8,
    INST_WORDS = 16, TRI_WORDS = 12,
};

typedef struct {
    uint32_t node, mask;
    f24_t tn[TRACE_PACKET], tf[TRACE_PACKET];
} trav_entry;

typedef struct {
    uint32_t nodes, lists; /* word addresses of the tree */
    trav_entry stack[TRACE_STACK];
    uint32_t sp;
    trav_entry cur;
    int have_cur;
    uint32_t leaf_first, leaf_count; /* list range of the leaf last returned */
} walker;

typedef struct {
    uint32_t key[TRACE_MAILBOX];
    uint32_t next;
} mailbox;

static uint32_t region_start(const uint32_t *mem, uint32_t r) { return mem[H_REGIONS + 2 * r]; }

static f24_t axis_of(f24_vec3 v, uint32_t k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }

static void mailbox_clear(mailbox *m)
{
mailbox_clear_loop:
    for (int i = 0; i < TRACE_MAILBOX; i++)
        m->key[i] = TRACE_NO_HIT;
    m->next = 0;
}

/* 1 if key was seen (skip it), else remembers it (round robin) and returns 0. */
static int mailbox_seen(mailbox *m, uint32_t key)
{
mailbox_search:
    for (int i = 0; i < TRACE_MAILBOX; i++)
        if (m->key[i] == key)
            return 1;
    m->key[m->next] = key;
    m->next = (m->next + 1) % TRACE_MAILBOX;
    return 0;
}

/* Slab test of ray (o, d) against a box of 6 fp24 words: narrows [tn, tf]. The sign bit of d
 * orders the slab distances, so that d = -0 behaves like a negative direction. */
static void clip_box(const uint32_t *box, f24_vec3 o, f24_vec3 d, f24_t *tn, f24_t *tf)
{
clip_axes:
    for (uint32_t k = 0; k < 3; k++) {
        const f24_t ok = axis_of(o, k), dk = axis_of(d, k);
        f24_t t0 = f24_div(f24_sub(box[k], ok), dk), t1 = f24_div(f24_sub(box[3 + k], ok), dk);
        if (f24_sign(dk)) {
            const f24_t s = t0;
            t0 = t1;
            t1 = s;
        }
        *tn = f24_max(*tn, t0);
        *tf = f24_min(*tf, t1);
    }
}

static void walker_start(walker *w, uint32_t nodes, uint32_t lists, uint32_t mask, const f24_t tn[], const f24_t tf[])
{
    w->nodes = nodes;
    w->lists = lists;
    w->sp = 0;
    w->have_cur = 1;
    w->cur.node = 0;
    w->cur.mask = mask;
walker_copy:
    for (int i = 0; i < TRACE_PACKET; i++) {
        w->cur.tn[i] = tn[i];
        w->cur.tf[i] = tf[i];
    }
}

/* Child intervals of one ray at an inner node: near = [tn, min(tf, ts)], far = [max(tn, ts), tf]. */
static void split_ray(const trav_entry *e, int i, f24_t ts, int near_is_left, trav_entry *l, trav_entry *r)
{
    trav_entry *nearc = near_is_left ? l : r, *farc = near_is_left ? r : l;
    nearc->tn[i] = e->tn[i];
    nearc->tf[i] = f24_min(e->tf[i], ts);
    farc->tn[i] = f24_max(e->tn[i], ts);
    farc->tf[i] = e->tf[i];
    if (f24_le(l->tn[i], l->tf[i]))
        l->mask |= 1u << i;
    if (f24_le(r->tn[i], r->tf[i]))
        r->mask |= 1u << i;
}

/* Advances to the next leaf that some ray of the packet needs; 0 when the tree is done.
 * best_t: each ray's closest hit so far (rays whose hit lies before a node skip it). */
static int walker_next_leaf(walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[],
                            const f24_t best_t[], trace_counters *c)
{
walk:
    for (uint32_t step = 0; step < STEP_LIMIT; step++) {
        if (!w->have_cur) {
            if (w->sp == 0)
                return 0;
            w->cur = w->stack[--w->sp];
            w->have_cur = 1;
        }
        trav_entry *e = &w->cur;
    prune:
        for (int i = 0; i < TRACE_PACKET; i++)
            if ((e->mask >> i & 1u) && f24_lt(best_t[i], e->tn[i]))
                e->mask &= ~(1u << i);
        if (!e->mask) {
            w->have_cur = 0;
            continue;
        }
        const uint32_t w0 = mem[w->nodes + 2 * e->node], w1 = mem[w->nodes + 2 * e->node + 1];
        c->words[MEM_NODES] += 2;
        if ((w0 & 3u) == MI_NODE_LEAF) {
            w->have_cur = 0;
            w->leaf_first = w1;
            w->leaf_count = w0 >> 2;
            c->leaves++;
            return 1;
        }
        c->traversal_steps++;
        const uint32_t axis = w0 & 3u, child = w0 >> 2;
        trav_entry l = { child, 0, { 0 }, { 0 } }, r = { child + 1, 0, { 0 }, { 0 } };
        int first_near_left = -1;
    split_rays:
        for (int i = 0; i < TRACE_PACKET; i++) {
            if (!(e->mask >> i & 1u))
                continue;
            const f24_t dk = axis_of(d[i], axis);
            const f24_t ts = f24_div(f24_sub(w1, axis_of(o[i], axis)), dk);
            const int near_left = !f24_sign(dk);
            if (first_near_left < 0)
                first_near_left = near_left;
            split_ray(e, i, ts, near_left, &l, &r);
        }
        if (l.mask && r.mask && w->sp < TRACE_STACK) {
            w->stack[w->sp++] = first_near_left ? r : l; /* the far side of the packet's first ray */
            w->cur = first_near_left ? l : r;
        } else {
            w->cur = l.mask ? l : r; /* (a full stack cannot occur: depth <= 64 = TRACE_STACK) */
        }
    }
    return 0;
}


/* The bottom level of one instance for the rays in mask (in world space). */
static void trace_instance(const uint32_t *mem, const ray_packet *rays, uint32_t inst, uint32_t mask, hit_record hits[],
                           f24_t best_t[], trace_counters *c)
{
    const uint32_t ia = region_start(mem, R_INSTANCES) + INST_WORDS * inst;
    const f24_affine w2o = f24_affine_load(mem, ia);
    const uint32_t obj = region_start(mem, R_OBJECTS) + OBJ_WORDS * mem[ia + 12];
    c->words[MEM_MATRICES] += 13 + 9; /* instance: matrix and object index; object descriptor */
    f24_vec3 o[TRACE_PACKET], d[TRACE_PACKET];
    f24_t tn[TRACE_PACKET], tf[TRACE_PACKET];
    mailbox box[TRACE_PACKET];
to_object_space:
    for (int i = 0; i < TRACE_PACKET; i++) {
        tn[i] = F24_POS_INF;
        tf[i] = 0;
        mailbox_clear(&box[i]);
        if (!(mask >> i & 1u))
            continue;
        o[i] = xform_point(&w2o, rays->o[i]);
        d[i] = xform_vector(&w2o, rays->d[i]);
        c->transformations += 2;
        tn[i] = rays->tmin[i];
        tf[i] = best_t[i];
        clip_box(&mem[obj + O_BOUNDS], o[i], d[i], &tn[i], &tf[i]);
        if (!f24_le(tn[i], tf[i]))
            mask &= ~(1u << i);
    }
    if (!mask)
        return;
    walker w;
    walker_start(&w, mem[obj + O_NODES], mem[obj + O_LISTS], mask, tn, tf);
    const uint32_t tris = mem[obj + O_TRIANGLES];
bottom_leaves:
    while (walker_next_leaf(&w, mem, o, d, best_t, c)) {
        const trav_entry *e = &w.cur;
    bottom_list:
        for (uint32_t k = 0; k < w.leaf_count; k++) {
            const uint32_t tri = mem[w.lists + w.leaf_first + k];
            c->list_entries++;
            c->words[MEM_LISTS]++;
            const f24_affine tx = f24_affine_load(mem, tris + TRI_WORDS * tri);
            c->words[MEM_MATRICES] += TRI_WORDS;
        bottom_rays:
            for (int i = 0; i < TRACE_PACKET; i++) {
                if (!(e->mask >> i & 1u))
                    continue;
                if (mailbox_seen(&box[i], tri)) {
                    c->mailbox_skips++;
                    continue;
                }
                const isect_result r = isect_unit_triangle(xform_point(&tx, o[i]), xform_vector(&tx, d[i]),
                                                           rays->tmin[i], best_t[i]);
                c->transformations += 2;
                c->intersections++;
                if (r.hit) {
                    best_t[i] = r.t;
                    hits[i] = (hit_record){ inst, tri, r.t, r.u, r.v, r.cos_n };
                }
            }
        }
    }
}

void trace_packet(const uint32_t *mem, const ray_packet *rays, hit_record hits[TRACE_PACKET], trace_counters *c)
{
    f24_t best_t[TRACE_PACKET], tn[TRACE_PACKET], tf[TRACE_PACKET];
    uint32_t mask = rays->active;
    mailbox seen[TRACE_PACKET];
init_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        hits[i] = (hit_record){ TRACE_NO_HIT, TRACE_NO_HIT, F24_POS_INF, 0, 0, 0 };
        best_t[i] = rays->tmax[i];
        tn[i] = rays->tmin[i];
        tf[i] = rays->tmax[i];
        mailbox_clear(&seen[i]);
        if (mask >> i & 1u)
            clip_box(&mem[H_SCENE_BOUNDS], rays->o[i], rays->d[i], &tn[i], &tf[i]);
        if (!f24_le(tn[i], tf[i]))
            mask &= ~(1u << i); /* misses the scene: never enters traversal */
    }
    if (!mask || mem[H_INSTANCES] == 0)
        return;
    walker w;
    walker_start(&w, region_start(mem, R_TOP_NODES), region_start(mem, R_TOP_LISTS), mask, tn, tf);
top_leaves:
    while (walker_next_leaf(&w, mem, rays->o, rays->d, best_t, c)) {
        const trav_entry *e = &w.cur;
    top_list:
        for (uint32_t k = 0; k < w.leaf_count; k++) {
            const uint32_t inst = mem[w.lists + w.leaf_first + k];
            uint32_t need = 0;
            c->list_entries++;
            c->words[MEM_LISTS]++;
        top_mailbox:
            for (int i = 0; i < TRACE_PACKET; i++) {
                if (!(e->mask >> i & 1u))
                    continue;
                if (mailbox_seen(&seen[i], inst))
                    c->mailbox_skips++; /* the instance already gave this ray its closest hit */
                else
                    need |= 1u << i;
            }
            if (need)
                trace_instance(mem, rays, inst, need, hits, best_t, c);
        }
    }
}
