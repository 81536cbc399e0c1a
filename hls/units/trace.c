/*
 * The ray tracing core for one packet (see trace.h): the router that moves a packet between the
 * units along the paper's paths b..f, one unit operation per trace_step. The units' work is in
 * their own files: the traversal unit in trav_unit.c (scene and object clips, the walk; its
 * algorithms behind trav_algo.h, its per-node datapath trav_node.c), the mailboxed list unit in
 * list_unit.c, the transformation unit's datapath in xform_unit.c and the intersection unit's in
 * isect_unit.c. This file decides which operation comes next, reads the memory image's
 * descriptors (instances, objects, triangle transformations) for them, and holds the core's
 * transformation and intersection operations (op_inst_xform, op_tri_xform, op_tri_isect), which
 * apply those stateless datapaths to the rays that need them.
 */
#include "trace.h"

#include "isect_unit.h"
#include "list_unit.h"
#include "rebase_unit.h"
#include "trace_ops.h"
#include "trav_unit.h"
#include "xform_unit.h"

/* Memory-image layout constants used by the core (docs/memory-image.md). */
enum {
    H_FORMAT = 2, H_OBJECTS = 6, H_INSTANCES = 7, H_TOP_NODES = 11, H_SCENE_BOUNDS = 12, H_REGIONS = 18,
    R_OBJECTS = 5, R_CAMERA = 6, R_INSTANCES = 8, R_TOP_NODES = 9, R_TOP_LISTS = 10, R_TOP_GRID = 11,
    CAM_PROFILE = 3, OBJ_WORDS = 16, O_NODES = 0, O_LISTS = 1, O_TRIANGLES = 2, O_BOUNDS = 8, O_GRID = 14,
    INST_WORDS = F24_INSTANCE_RECORD_WORDS, INST_READ = 17, INST_FLAGS = 13, INST_IDENTITY = 1, INST_T_LO = 14,
    OBJ_READ = 14,
    TRI_WORDS = F24_TRIANGLE_RECORD_WORDS,
};

/* Next operation of a packet. */
enum { TP_SCENE_CLIP, TP_WALK, TP_LIST, TP_INST_XFORM, TP_INST_CLIP, TP_TRI_XFORM, TP_TRI_ISECT, TP_DONE };

static uint32_t region_start(const uint32_t *mem, uint32_t r) { return mem[H_REGIONS + 2 * r]; }

static uint32_t trav_algo(uint32_t flags) { return flags >> TRACE_TRAV_SHIFT & TRACE_TRAV_MASK; }

/* Words of an object descriptor the transformation unit reads: with a grid algorithm, also the
 * grid's address. */
static uint32_t obj_read(uint32_t flags) { return OBJ_READ + (trav_algo(flags) >= TRAV_GRID ? 1u : 0u); }

static uint32_t accel_of(const uint32_t *mem) { return mem[H_FORMAT] >> ACCEL_SHIFT; }

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

/* ---- the operations ------------------------------------------------------------------------ */

/* trace_step runs one of these per call, most often the walk's (op_walk, inlined into it); the
 * simulation build keeps the others out of line (F24_SIM_NOINLINE), so that a walk step does not
 * pay the registers and stack frame of all of them. */

/* The one object of a PROFILE_SINGLE_OBJECT scene: the packet goes straight to its
 * transformation, as the one-leaf top-level tree would send it. With PROFILE_IDENTITY that
 * transformation is wiring (xform_identity gives the bits xform_point/xform_vector give for an
 * identity whose zeros may be signed), the instance and object descriptor are read with the
 * scene clip, and the packet goes on to the object's bounds (path b). The top level holds no further entries, so the packet is done when
 * the object is. */
static void enter_single_object(const uint32_t *mem, trace_state *s, uint32_t mask, const f24_t tn[], unit_op *op,
                                trace_counters *c)
{
    const uint32_t ia = region_start(mem, R_INSTANCES);
    s->inst = mem[region_start(mem, R_TOP_LISTS) + mem[region_start(mem, R_TOP_NODES) + 1]]; /* its one-leaf list */
    s->need = mask;
    s->walk[0].leaf_count = s->walk[0].k = 0;
scene_entry:
    for (int i = 0; i < TRACE_PACKET; i++)
        s->walk[0].leaf_tn[i] = tn[i]; /* where the instance's rays enter, as a top-level leaf would say */
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
        s->o_lo[i] = s->d_lo[i] = (f24_vec3){ 0, 0, 0 };
        s->t0[i] = 0;
    }
    s->phase = TP_INST_CLIP;
}

/* Traversal unit: clip the packet to the scene bounds; rays that miss them never enter traversal. */
static F24_SIM_NOINLINE void op_scene_clip(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    f24_t tn[TRACE_PACKET], tf[TRACE_PACKET];
    op_set(op, OP_TRAV, TRAV_CLIP_SLOTS);
    const uint32_t mask = trav_scene_clip(&mem[H_SCENE_BOUNDS], &s->rays, tn, tf);
    if (!mask || mem[H_INSTANCES] == 0) {
        s->phase = TP_DONE;
        return;
    }
    if (!SAARCOR_CFG_TOP_LEVEL || (s->flags & TRACE_SKIP_TOP)) {
        enter_single_object(mem, s, mask, tn, op, c);
        return;
    }
    const int top_grid = trav_algo(s->flags) == TRAV_GRID2 && (accel_of(mem) & ACCEL_TOP_GRID);
    trav_start(&s->walk[0], mem, trav_algo(s->flags), accel_of(mem), region_start(mem, R_TOP_NODES),
               region_start(mem, R_TOP_LISTS), top_grid ? region_start(mem, R_TOP_GRID) : TRACE_NO_HIT, mask, tn, tf,
               s->rays.o, s->rays.d, op, c);
    s->phase = TP_WALK;
}

/* Traversal unit: one kd-tree entry of the current level. */
static void op_walk(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    const int top = s->level == 0;
    trav_walk(&s->walk[s->level], mem, top ? s->rays.o : s->o, top ? s->rays.d : s->d, top ? s->best_t : s->best_rel,
              s->alive, op, c);
    route_after_list(s);
}

/* Rebase unit, as the list unit opens a bottom-level leaf: each ray of the leaf gets its origin
 * moved to where it enters the leaf (rebase_unit.h), one issue slot per ray; the operation then
 * ends with the rebase unit's pipeline (OP_LEAF). */
static void rebase_leaf(trace_state *s, unit_op *op)
{
    const trav_walker *w = &s->walk[1];
    const uint32_t rays = w->leaf_mask & s->alive;
    op->slots += count_rays(rays);
    if (rays)
        op->kind = OP_LEAF;
    rebase_rays(rays, s->o, s->o_lo, s->d, s->d_lo, w->leaf_tn, s->p, s->te);
}

/* List unit: one entry of the current leaf (an instance at the top level, a triangle below). */
static F24_SIM_NOINLINE void op_list(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    uint32_t key;
    const int opens = s->level == 1 && s->walk[1].k == 0;
    s->need = list_unit_entry(mem, &s->walk[s->level], s->box[s->level], s->alive, &key, op, c);
    if (opens)
        rebase_leaf(s, op);
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
 * would give), and the traversal unit clips them to the object at once, in the same operation.
 * Any other moves each ray's origin to where it enters the top-level leaf (the rebase unit, in
 * front of this one) and maps it in the wide mode: the object-space ray in double words whose
 * high words the traversal walks with are then the exact ray to about the object's size times
 * 2^-(M+1), not the distance's (docs/numerics.md). Rebased origins differ per ray: two steps each. */
static F24_SIM_NOINLINE void op_inst_xform(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    const uint32_t ia = region_start(mem, R_INSTANCES) + INST_WORDS * s->inst;
    const f24_affine w2o = f24_affine_load(mem, ia);
    const int identity = mem[ia + INST_FLAGS] & INST_IDENTITY;
    s->obj = region_start(mem, R_OBJECTS) + OBJ_WORDS * mem[ia + 12];
    op_set(op, identity ? OP_OBJCLIP : OP_INSTANCE, identity ? TRAV_CLIP_SLOTS : 2u * count_rays(s->need));
    op_read(op, c, MEM_MATRICES, ia, INST_READ);  /* matrix, object index, flags, translation low words */
    op_read(op, c, MEM_MATRICES, s->obj, obj_read(s->flags)); /* object descriptor: tree, triangles, bounds */
    c->transformations += identity ? 0u : op->slots;
    const f24_vec3 t_lo = { mem[ia + INST_T_LO] & F24_MASK, mem[ia + INST_T_LO + 1] & F24_MASK,
                            mem[ia + INST_T_LO + 2] & F24_MASK };
    if (!identity) {
        xform_enter_rays(&w2o, t_lo, s->need, s->rays.o, s->rays.d, s->walk[0].leaf_tn, s->o, s->o_lo, s->d, s->d_lo,
                         s->t0);
    } else {
    wiring_rays:
        for (int i = 0; i < TRACE_PACKET; i++) {
            if (!bit(s->need, i))
                continue;
            s->o[i] = xform_identity(&w2o, s->rays.o[i], 1);
            s->d[i] = xform_identity(&w2o, s->rays.d[i], 0);
            s->o_lo[i] = s->d_lo[i] = (f24_vec3){ 0, 0, 0 };
            s->t0[i] = 0;
        }
    }
    s->phase = TP_INST_CLIP;
    if (identity)
        inst_clip(mem, s, op, c);
}

/* Traversal unit: clip the object-space rays to the object's bounds and start its tree (path b). */
static F24_SIM_NOINLINE void op_inst_clip(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    op_set(op, OP_OBJCLIP, TRAV_CLIP_SLOTS);
    inst_clip(mem, s, op, c);
}

/* The distances of the rays that need the instance from where they entered it (t0): the 4 rays
 * side by side, as the traversal unit's subtractors compute them. */
static F24Q_FN void relative_distances(trace_state *s)
{
    const f24q t0 = f24q_of(s->t0);
    f24_t best[TRACE_PACKET], tmin[TRACE_PACKET];
    f24q_bits(f24q_sub(f24q_of(s->best_t), t0), best);
    f24q_bits(f24q_sub(f24q_of(s->rays.tmin), t0), tmin);
relative_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        s->best_rel[i] = bit(s->need, i) ? best[i] : s->best_rel[i];
        s->tmin_rel[i] = bit(s->need, i) ? tmin[i] : s->tmin_rel[i];
    }
}

static void inst_clip(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    f24_t tn[TRACE_PACKET], tf[TRACE_PACKET];
    list_mailboxes_clear(s->box[1]); /* a new visit of an instance: its triangles anew */
    relative_distances(s);
    const uint32_t mask =
        trav_object_clip(&mem[s->obj + O_BOUNDS], s->o, s->d, s->tmin_rel, s->best_rel, s->need, tn, tf);
    if (!mask) {
        route_after_list(s);
        return;
    }
    s->tris = mem[s->obj + O_TRIANGLES];
    const int grid = accel_of(mem) & ACCEL_GRID;
    trav_start(&s->walk[1], mem, trav_algo(s->flags), accel_of(mem), mem[s->obj + O_NODES], mem[s->obj + O_LISTS],
               grid ? mem[s->obj + O_GRID] : TRACE_NO_HIT, mask, tn, tf, s->o, s->d, op, c);
    s->level = 1;
    s->phase = TP_WALK;
}

/* Transformation unit: the directions of the rays that need a triangle into its unit-triangle
 * space (path e), one step per ray; their rebased origins go through the triangle's matrix in the
 * intersection unit (isect_unit.h), since no two rays of a packet share one. The transformed rays
 * are computed with the intersection below, which needs them only then. */
static F24_SIM_NOINLINE void op_tri_xform(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    const uint32_t a = s->tris + TRI_WORDS * s->tri;
    s->tx = f24_triangle_load(mem, a);
    op_set(op, OP_XFORM, count_rays(s->need));
    op_read(op, c, MEM_MATRICES, a, TRI_WORDS);
    c->transformations += op->slots;
    s->phase = TP_TRI_ISECT;
}

/* Intersection unit: one ray per slot; closest hits back to the traversal (path f). */
static F24_SIM_NOINLINE void op_tri_isect(trace_state *s, unit_op *op, trace_counters *c)
{
    op_set(op, OP_ISECT, count_rays(s->need));
    isect_result r[TRACE_PACKET];
    isect_unit_packet(&s->tx, s->need, s->p, s->te, s->d, s->tmin_rel, s->best_rel, r);
isect_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!bit(s->need, i))
            continue;
        c->intersections++;
        if (r[i].hit) {
            s->best_rel[i] = r[i].t;
            s->best_t[i] = f24_add(s->t0[i], r[i].t); /* back to the distance from the ray's origin */
            s->hits[i] = (hit_record){ s->inst, s->tri, s->best_t[i], r[i].u, r[i].v, r[i].cos_n };
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
        s->best_t[i] = s->best_rel[i] = rays->tmax[i];
        s->tmin_rel[i] = rays->tmin[i];
        s->t0[i] = 0;
    }
    list_mailboxes_clear(s->box[0]);
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
