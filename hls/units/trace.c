/* The ray tracing core for one packet, as a state machine of unit operations: see trace.h. */
#include "trace.h"

#include "isect_unit.h"
#include "trace_ops.h"
#include "trav_cursor.h"
#include "trav_node.h"
#include "xform_unit.h"

/* docs/memory-image.md: kd node word 0 = count << 2 | 3 (leaf), or child << 4 | empty << 2 | axis */
#define MI_NODE_LEAF 3u
#define NODE_CHILD_SHIFT 4

/* Memory-image layout constants used by the core (docs/memory-image.md). */
enum {
    H_FORMAT = 2, H_OBJECTS = 6, H_INSTANCES = 7, H_TOP_NODES = 11, H_SCENE_BOUNDS = 12, H_REGIONS = 18,
    R_OBJECTS = 5, R_CAMERA = 6, R_INSTANCES = 8, R_TOP_NODES = 9, R_TOP_LISTS = 10, R_TOP_GRID = 11,
    CAM_PROFILE = 3, OBJ_WORDS = 16, O_NODES = 0, O_LISTS = 1, O_TRIANGLES = 2, O_BOUNDS = 8, O_GRID = 14,
    INST_WORDS = 16, INST_READ = 14, INST_FLAGS = 13, INST_IDENTITY = 1, OBJ_READ = 14,
    TRI_WORDS = F24_AFFINE_RECORD_WORDS,
};

/* Next operation of a packet. */
enum { TP_SCENE_CLIP, TP_WALK, TP_LIST, TP_INST_XFORM, TP_INST_CLIP, TP_TRI_XFORM, TP_TRI_ISECT, TP_DONE };

static uint32_t region_start(const uint32_t *mem, uint32_t r) { return mem[H_REGIONS + 2 * r]; }

static uint32_t trav_algo(uint32_t flags) { return flags >> TRACE_TRAV_SHIFT & TRACE_TRAV_MASK; }

/* Words of an object descriptor the transformation unit reads: with a grid algorithm, also the
 * grid's address. */
static uint32_t obj_read(uint32_t flags) { return OBJ_READ + (trav_algo(flags) >= TRAV_GRID ? 1u : 0u); }

static uint32_t count_rays(uint32_t mask) { return bit(mask, 0) + bit(mask, 1) + bit(mask, 2) + bit(mask, 3); }

static void mailbox_clear(trace_mailbox *m)
{
mailbox_clear_loop:
    for (int i = 0; i < TRACE_MAILBOX; i++)
        m->key[i] = TRACE_NO_HIT;
    m->next = 0;
}

/* 1 if key was seen (skip it), else remembers it (round robin) and returns 0. */
static int mailbox_seen(trace_mailbox *m, uint32_t key)
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

/* ---- traversal unit ------------------------------------------------------------------------ */

static void walker_start(trav_walker *w, uint32_t nodes, uint32_t lists, uint32_t mask, const f24_t tn[], const f24_t tf[],
                         uint32_t algo)
{
    w->nodes = nodes;
    w->lists = lists;
    w->sp = 0;
    w->have_cur = 1;
    w->cur.node = 0;
    w->cur.mask = mask;
    w->leaf_count = w->k = 0;
    w->algo = algo;
    w->cap = algo == TRAV_STACK ? TRACE_STACK : algo == TRAV_SHORT_STACK ? TRACE_SHORT_STACK : 0;
    w->push_down = algo == TRAV_SHORT_STACK || algo == TRAV_PUSH_DOWN;
    w->lost = w->pass = 0;
walker_copy:
    for (int i = 0; i < TRACE_PACKET; i++) {
        w->cur.tn[i] = tn[i];
        w->cur.tf[i] = tf[i];
        w->t_exit[i] = tn[i];
    }
    w->root = w->cur;
}

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
    w->stack[w->sp++] = *far;
}

/* After a restart, a cell that ends where a ray's last leaf ended was visited already. */
static void drop_done_cells(const trav_walker *w, trav_entry *e)
{
    if (!w->pass)
        return;
done_cells:
    for (int i = 0; i < TRACE_PACKET; i++)
        if (bit(e->mask, i) && f24_le(e->tf[i], w->t_exit[i]))
            e->mask &= ~(1u << i);
}

/* An inner node: both children for the rays that need them (trav_node_split); the far side of
 * the packet's first ray waits on the stack. With push-down, a node that the whole packet
 * passes through on one side only becomes the new restart point while nothing waits. */
static void walker_split(trav_walker *w, uint32_t w0, f24_t split, const f24_vec3 o[], const f24_vec3 d[])
{
    const uint32_t axis = w0 & 3u, child = w0 >> NODE_CHILD_SHIFT, empty = w0 >> 2 & 3u;
    trav_entry l, r;
    uint32_t near_left;
    trav_node_split(&w->cur, axis, split, o, d, &l, &r, &near_left);
    /* a side that is an empty leaf is not stored: no ray goes there (no step for an empty cell) */
    l.mask &= bit(empty, 0) ? 0u : 0xFu;
    r.mask &= bit(empty, 1) ? 0u : 0xFu;
    l.node = child;
    r.node = child + (bit(empty, 0) ? 0u : 1u);
    drop_done_cells(w, &l);
    drop_done_cells(w, &r);
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
        w->cur = first_near_left ? l : r;
    } else {
        w->cur = l.mask ? l : r;
        if (w->push_down && w->sp == 0 && !w->lost)
            w->root = w->cur;
    }
}

/* The stack ran dry after dropping entries: walk down again from the restart point with every
 * ray's interval from where its last leaf ended. A ray is done for good when nothing is left of
 * its interval or its closest hit lies before the rest. */
static void walker_restart(trav_walker *w, const f24_t best_t[])
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

/* One kd-tree entry: prune the rays whose closest hit lies before it, then read the node and
 * split, or report a leaf (its list range). Afterwards, if the entry is used up, the next one is
 * popped (or, the stack empty after a drop, the walk restarts); !w->have_cur then means the tree
 * is done. Returns 1 at a leaf with entries. */
static int walker_step(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[], const f24_t best_t[],
                       uint32_t alive, unit_op *op, trace_counters *c)
{
    trav_entry *e = &w->cur;
    int leaf = 0;
    op_set(op, UNIT_TRAV, 1);
    e->mask &= alive; /* rays done (any hit found) leave the packet */
    w->root.mask &= alive;
prune:
    for (int i = 0; i < TRACE_PACKET; i++)
        if (bit(e->mask, i) && f24_lt(best_t[i], e->tn[i]))
            e->mask &= ~(1u << i);
    if (!e->mask) {
        w->have_cur = 0;
    } else {
        const uint32_t a = w->nodes + 2 * e->node, w0 = mem[a], w1 = mem[a + 1];
        op_read(op, c, MEM_NODES, a, 2);
        if ((w0 & 3u) == MI_NODE_LEAF) {
            w->have_cur = 0;
            w->leaf_first = w1;
            w->leaf_count = w0 >> 2;
            w->leaf_mask = e->mask;
            w->k = 0;
            c->leaves++;
            leaf = w->leaf_count != 0;
        leaf_exit: /* only a leaf that continues a ray's covered segment extends it: in a packet a
                     ray may meet its cells in another order than the first ray */
            for (int i = 0; i < TRACE_PACKET && w->cap < TRACE_STACK; i++) /* the stack never restarts */
                if (bit(e->mask, i) && f24_le(e->tn[i], w->t_exit[i]))
                    w->t_exit[i] = f24_max(w->t_exit[i], e->tf[i]);
        } else {
            c->traversal_steps++;
            walker_split(w, w0, w1, o, d);
        }
    }
    if (!w->have_cur && w->sp > 0) {
        w->cur = w->stack[--w->sp];
        w->have_cur = 1;
    } else if (!w->have_cur && w->lost) {
        walker_restart(w, best_t);
    }
    return leaf;
}

/* Starts the walk of a level (tree at nodes/lists, or the grid header at grid, TRACE_NO_HIT for
 * none) with the algorithm asked for where the image holds its structure, else the stack. */
static void level_start(const uint32_t *mem, trav_walker *w, uint32_t flags, uint32_t nodes, uint32_t lists, uint32_t grid,
                        uint32_t mask, const f24_t tn[], const f24_t tf[], const f24_vec3 o[], const f24_vec3 d[],
                        unit_op *op, trace_counters *c)
{
    const uint32_t asked = trav_algo(flags), accel = mem[H_FORMAT] >> ACCEL_SHIFT;
    uint32_t algo = asked < TRAV_ROPES ? asked : TRAV_STACK;
    if (asked == TRAV_ROPES && (accel & ACCEL_ROPES))
        algo = TRAV_ROPES;
    if (asked >= TRAV_GRID && grid != TRACE_NO_HIT)
        algo = TRAV_GRID;
    walker_start(w, nodes, lists, mask, tn, tf, algo);
    if (algo >= TRAV_ROPES)
        cursor_start(w, mem, grid, o, d, op, c);
}

/* ---- routing between the units (paths b..f) -------------------------------------------------- */

/* Where a packet goes after a list entry of the given level, or after its walk found no leaf:
 * the next entry, the next kd-tree entry, or back up / done. */
static void route_after_list(trace_state *s)
{
route_levels:
    for (int guard = 0; guard < 2; guard++) {
        const trav_walker *w = &s->walk[s->level];
        if (!s->alive) {
            s->phase = TP_DONE; /* every ray has its hit (any-hit tracing) */
            return;
        }
        if (w->k < w->leaf_count) {
            s->phase = TP_LIST;
            return;
        }
        if (w->have_cur) {
            s->phase = TP_WALK;
            return;
        }
        if (s->level == 0) {
            s->phase = TP_DONE;
            return;
        }
        s->level = 0; /* the object is done: back to the top-level list */
    }
}

/* The rays of the current leaf that a list entry still needs: each ray's mailbox of that level
 * (at the top level, an instance already visited gave the ray its closest hit in it). */
static uint32_t list_need(trace_state *s, uint32_t key, trace_counters *c)
{
    uint32_t need = 0;
mailbox_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!bit(s->walk[s->level].leaf_mask & s->alive, i))
            continue;
        if (mailbox_seen(&s->box[s->level][i], key))
            c->mailbox_skips++;
        else
            need |= 1u << i;
    }
    return need;
}

/* Issue slots of the transformation unit for the rays in mask: origin and direction each, or one
 * shared origin step if all their origins are equal. */
static uint32_t xform_slots(const f24_vec3 o[], uint32_t mask)
{
    int first = -1, shared = 1;
same_origin:
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!bit(mask, i))
            continue;
        if (first < 0)
            first = i;
        else if (o[i].x != o[first].x || o[i].y != o[first].y || o[i].z != o[first].z)
            shared = 0;
    }
    const uint32_t n = count_rays(mask);
    return shared ? n + 1 : 2 * n;
}

/* ---- the operations ------------------------------------------------------------------------ */

/* The one object of a PROFILE_SINGLE_OBJECT scene: the packet goes straight to its
 * transformation, as the one-leaf top-level tree would send it. With PROFILE_IDENTITY that
 * transformation is wiring (xform_identity gives the bits xform_point/xform_vector give for an
 * identity whose zeros may be signed), the instance and object descriptor are read with the
 * scene clip, and the packet goes on to the object's bounds (path b). The top level holds no further entries, so the packet is done when
 * the object is. */
static void enter_single_object(const uint32_t *mem, trace_state *s, uint32_t mask, unit_op *op, trace_counters *c)
{
    const uint32_t ia = region_start(mem, R_INSTANCES);
    s->inst = mem[region_start(mem, R_TOP_LISTS) + mem[region_start(mem, R_TOP_NODES) + 1]]; /* its one-leaf list */
    s->need = mask;
    s->walk[0].leaf_count = s->walk[0].k = 0;
    if (!(s->flags & TRACE_IDENTITY)) {
        s->phase = TP_INST_XFORM;
        return;
    }
    const f24_affine w2o = f24_affine_load(mem, ia + INST_WORDS * s->inst);
    s->obj = region_start(mem, R_OBJECTS) + OBJ_WORDS * mem[ia + INST_WORDS * s->inst + 12];
    op_read(op, c, MEM_MATRICES, ia + INST_WORDS * s->inst, INST_READ); /* the signs of its zeros */
    op_read(op, c, MEM_MATRICES, s->obj, obj_read(s->flags));
identity_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        s->o[i] = xform_identity(&w2o, s->rays.o[i], 1);
        s->d[i] = xform_identity(&w2o, s->rays.d[i], 0);
    }
    s->phase = TP_INST_CLIP;
}

/* Traversal unit: clip the packet to the scene bounds; rays that miss them never enter traversal. */
static void op_scene_clip(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    f24_t tn[TRACE_PACKET], tf[TRACE_PACKET];
    uint32_t mask = s->rays.active;
    op_set(op, UNIT_TRAV, 1);
scene_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        tn[i] = s->rays.tmin[i];
        tf[i] = s->rays.tmax[i];
        if (bit(mask, i))
            clip_box(&mem[H_SCENE_BOUNDS], s->rays.o[i], s->rays.d[i], &tn[i], &tf[i]);
        if (!f24_le(tn[i], tf[i]))
            mask &= ~(1u << i);
    }
    if (!mask || mem[H_INSTANCES] == 0) {
        s->phase = TP_DONE;
        return;
    }
    if (!SAARCOR_CFG_TOP_LEVEL || (s->flags & TRACE_SKIP_TOP)) {
        enter_single_object(mem, s, mask, op, c);
        return;
    }
    const int top_grid = trav_algo(s->flags) == TRAV_GRID2 && (mem[H_FORMAT] >> ACCEL_SHIFT & ACCEL_TOP_GRID);
    level_start(mem, &s->walk[0], s->flags, region_start(mem, R_TOP_NODES), region_start(mem, R_TOP_LISTS),
                top_grid ? region_start(mem, R_TOP_GRID) : TRACE_NO_HIT, mask, tn, tf, s->rays.o, s->rays.d, op, c);
    s->phase = TP_WALK;
}

/* Traversal unit: one kd-tree entry of the current level. */
static void op_walk(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    const int top = s->level == 0;
    trav_walker *w = &s->walk[s->level];
    if (w->algo >= TRAV_ROPES)
        cursor_step(w, mem, top ? s->rays.o : s->o, top ? s->rays.d : s->d, s->best_t, s->alive, op, c);
    else
        walker_step(w, mem, top ? s->rays.o : s->o, top ? s->rays.d : s->d, s->best_t, s->alive, op, c);
    route_after_list(s);
}

/* List unit: one entry of the current leaf (an instance at the top level, a triangle below). */
static void op_list(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    trav_walker *w = &s->walk[s->level];
    const uint32_t a = w->lists + w->leaf_first + w->k, key = mem[a];
    op_set(op, UNIT_LIST, 1);
    op_read(op, c, MEM_LISTS, a, 1);
    c->list_entries++;
    w->k++;
    s->need = list_need(s, key, c);
    if (!s->need) {
        route_after_list(s);
        return;
    }
    if (s->level == 0) {
        s->inst = key;
        s->phase = TP_INST_XFORM;
    } else {
        s->tri = key;
        s->phase = TP_TRI_XFORM;
    }
}

static void inst_clip(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c);

/* Transformation unit: the rays that need an instance into its object space (path d). An
 * instance flagged as the identity (static geometry the host merged into world space) needs no
 * transformation: its rays pass through as wiring (xform_identity, the bits the transformation
 * would give), and the traversal unit clips them to the object at once, in the same operation. */
static void op_inst_xform(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    const uint32_t ia = region_start(mem, R_INSTANCES) + INST_WORDS * s->inst;
    const f24_affine w2o = f24_affine_load(mem, ia);
    const int identity = mem[ia + INST_FLAGS] & INST_IDENTITY;
    s->obj = region_start(mem, R_OBJECTS) + OBJ_WORDS * mem[ia + 12];
    op_set(op, identity ? UNIT_TRAV : UNIT_XFORM, identity ? 1u : xform_slots(s->rays.o, s->need));
    op_read(op, c, MEM_MATRICES, ia, INST_READ);  /* matrix, object index and flags */
    op_read(op, c, MEM_MATRICES, s->obj, obj_read(s->flags)); /* object descriptor: tree, triangles, bounds */
    c->transformations += identity ? 0u : op->slots;
to_object_space:
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!bit(s->need, i))
            continue;
        s->o[i] = identity ? xform_identity(&w2o, s->rays.o[i], 1) : xform_point(&w2o, s->rays.o[i]);
        s->d[i] = identity ? xform_identity(&w2o, s->rays.d[i], 0) : xform_vector(&w2o, s->rays.d[i]);
    }
    s->phase = TP_INST_CLIP;
    if (identity)
        inst_clip(mem, s, op, c);
}

/* Traversal unit: clip the object-space rays to the object's bounds and start its tree (path b). */
static void op_inst_clip(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    op_set(op, UNIT_TRAV, 1);
    inst_clip(mem, s, op, c);
}

static void inst_clip(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    f24_t tn[TRACE_PACKET], tf[TRACE_PACKET];
    uint32_t mask = s->need;
object_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        tn[i] = F24_POS_INF;
        tf[i] = 0;
        mailbox_clear(&s->box[1][i]);
        if (!bit(mask, i))
            continue;
        tn[i] = s->rays.tmin[i];
        tf[i] = s->best_t[i];
        clip_box(&mem[s->obj + O_BOUNDS], s->o[i], s->d[i], &tn[i], &tf[i]);
        if (!f24_le(tn[i], tf[i]))
            mask &= ~(1u << i);
    }
    if (!mask) {
        route_after_list(s);
        return;
    }
    s->tris = mem[s->obj + O_TRIANGLES];
    const int grid = mem[H_FORMAT] >> ACCEL_SHIFT & ACCEL_GRID;
    level_start(mem, &s->walk[1], s->flags, mem[s->obj + O_NODES], mem[s->obj + O_LISTS],
                grid ? mem[s->obj + O_GRID] : TRACE_NO_HIT, mask, tn, tf, s->o, s->d, op, c);
    s->level = 1;
    s->phase = TP_WALK;
}

/* Transformation unit: the rays that need a triangle into its unit-triangle space (path e). The
 * transformed rays are computed with the intersection below, which needs them only then. */
static void op_tri_xform(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    const uint32_t a = s->tris + TRI_WORDS * s->tri;
    s->tx = f24_affine_load_record(mem, a);
    op_set(op, UNIT_XFORM, xform_slots(s->o, s->need));
    op_read(op, c, MEM_MATRICES, a, TRI_WORDS);
    c->transformations += op->slots;
    s->phase = TP_TRI_ISECT;
}

/* Intersection unit: one ray per slot; closest hits back to the traversal (path f). */
static void op_tri_isect(trace_state *s, unit_op *op, trace_counters *c)
{
    op_set(op, UNIT_ISECT, count_rays(s->need));
isect_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!bit(s->need, i))
            continue;
        const isect_result r = isect_unit_transformed(&s->tx, s->o[i], s->d[i], s->rays.tmin[i], s->best_t[i]);
        c->intersections++;
        if (r.hit) {
            s->best_t[i] = r.t;
            s->hits[i] = (hit_record){ s->inst, s->tri, r.t, r.u, r.v, r.cos_n };
            if (s->flags & TRACE_ANY_HIT)
                s->alive &= ~(1u << i);
        }
    }
    route_after_list(s);
}

uint32_t trace_profile(const uint32_t *mem) { return mem[region_start(mem, R_CAMERA) + CAM_PROFILE]; }

uint32_t trace_flags_of(uint32_t profile, int shadow)
{
    return (profile & PROFILE_SINGLE_OBJECT ? TRACE_SKIP_TOP : 0u) |
           ((profile & (PROFILE_SINGLE_OBJECT | PROFILE_IDENTITY)) == (PROFILE_SINGLE_OBJECT | PROFILE_IDENTITY)
                ? TRACE_IDENTITY : 0u) |
           (shadow && (profile & PROFILE_ANY_HIT) ? TRACE_ANY_HIT : 0u);
}

void trace_begin(const ray_packet *rays, uint32_t flags, trace_state *s)
{
    s->rays = *rays;
    s->flags = flags;
    s->alive = rays->active;
    s->phase = TP_SCENE_CLIP;
    s->level = 0;
    s->walk[0].have_cur = s->walk[1].have_cur = 0;
init_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        s->hits[i] = (hit_record){ TRACE_NO_HIT, TRACE_NO_HIT, F24_POS_INF, 0, 0, 0 };
        s->best_t[i] = rays->tmax[i];
        mailbox_clear(&s->box[0][i]);
    }
}

int trace_step(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    switch (s->phase) {
    case TP_SCENE_CLIP: op_scene_clip(mem, s, op, c); return 1;
    case TP_WALK: op_walk(mem, s, op, c); return 1;
    case TP_LIST: op_list(mem, s, op, c); return 1;
    case TP_INST_XFORM: op_inst_xform(mem, s, op, c); return 1;
    case TP_INST_CLIP: op_inst_clip(mem, s, op, c); return 1;
    case TP_TRI_XFORM: op_tri_xform(mem, s, op, c); return 1;
    case TP_TRI_ISECT: op_tri_isect(s, op, c); return 1;
    default: return 0;
    }
}

void trace_packet(const uint32_t *mem, const ray_packet *rays, hit_record hits[TRACE_PACKET], trace_counters *c)
{
    trace_state s;
    unit_op op;
    trace_begin(rays, trace_flags_of(trace_profile(mem), 0), &s);
packet_ops:
    for (uint32_t n = 0; n < TRACE_STEP_LIMIT && trace_step(mem, &s, &op, c); n++)
        ;
copy_hits:
    for (int i = 0; i < TRACE_PACKET; i++)
        hits[i] = s.hits[i];
}
