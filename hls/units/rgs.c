/* Ray generation and shading unit: see rgs.h and docs/shading.md. */
#include "rgs.h"

#include "rgs_ops.h"
#include "trace_ops.h"
#include "xform_unit.h"

enum {
    H_LIGHTS = 10, H_SCENE_BOUNDS = 12, R_CAMERA = 6, R_LIGHTS = 7, LIGHT_WORDS = 16, MAX_LIGHTS = 64, CAM_WORDS = 16,
};

#define Q12_AMBIENT 614u   /* 0.15 */
#define EPS_SHIFT 10       /* e = 2^-10 x the largest extent of the scene bounds */



/* ---- fp24 vector helpers ------------------------------------------------------------------ */

f24_vec3 rgs_reflect(f24_vec3 d, f24_vec3 n)
{
    const f24_affine m = t_r((f24_vec3){ 0, 0, 0 }, d, n);
    const f24_t c = rgs_dot3(n, d);
    return xform_vector(&m, (f24_vec3){ F24_ONE, f24_neg(f24_add(c, c)), 0 });
}

#if SAARCOR_CFG_REFRACTION
int rgs_refract(f24_vec3 d, f24_vec3 n, f24_t eta_r, f24_vec3 *out)
{
    const f24_t c = rgs_dot3(n, d);
    const f24_t k = f24_sub(F24_ONE, f24_mul(f24_mul(eta_r, eta_r), f24_sub(F24_ONE, f24_mul(c, c))));
    if (f24_lt(k, 0))
        return 0; /* total internal reflection */
    const f24_t mu = f24_sub(f24_neg(f24_mul(eta_r, c)), f24_sqrt(k));
    const f24_affine m = t_r((f24_vec3){ 0, 0, 0 }, d, n);
    *out = xform_vector(&m, (f24_vec3){ eta_r, mu, 0 });
    return 1;
}
#endif

/* ---- ray generation -------------------------------------------------------------------------- */

void rgs_image_size(const uint32_t *mem, uint32_t *width, uint32_t *height)
{
    const uint32_t cam = region_start(mem, R_CAMERA);
    *width = mem[cam + 1];
    *height = mem[cam + 2];
}

void rgs_primary(const uint32_t *mem, uint32_t x0, uint32_t y0, ray_packet *rp)
{
    const uint32_t cam = region_start(mem, R_CAMERA), kind = mem[cam], w = mem[cam + 1], h = mem[cam + 2];
    f24_affine t; /* T_init: columns U V W, translation O */
camera_matrix:
    for (int r = 0; r < 3; r++) {
        t.m[r][0] = mem[cam + 7 + (uint32_t)r];
        t.m[r][1] = mem[cam + 10 + (uint32_t)r];
        t.m[r][2] = mem[cam + 13 + (uint32_t)r];
        t.m[r][3] = mem[cam + 4 + (uint32_t)r];
    }
    const f24_vec3 origin = { mem[cam + 4], mem[cam + 5], mem[cam + 6] };
    const f24_t half = rgs_ratio(1, 2);
    rp->active = 0;
block_pixels:
    for (int i = 0; i < TRACE_PACKET; i++) {
        const uint32_t x = x0 + (uint32_t)(i & 1), y = y0 + (uint32_t)(i >> 1);
        const f24_vec3 p = { f24_mul(f24_from_i32((int32_t)(2 * x + 1)), half),
                             f24_mul(f24_from_i32((int32_t)(2 * y + 1)), half), F24_ONE };
        if (SAARCOR_CFG_ORTHOGRAPHIC && kind == 1) { /* orthographic: O + x U + y V, direction W */
            const f24_vec3 p2 = { p.x, p.y, 0 };
            rp->o[i] = xform_point(&t, p2);
            rp->d[i] = (f24_vec3){ t.m[0][2], t.m[1][2], t.m[2][2] };
        } else {
            rp->o[i] = origin;
            rp->d[i] = xform_vector(&t, p);
        }
        rp->tmin[i] = 0;
        rp->tmax[i] = F24_POS_INF;
        if (x < w && y < h)
            rp->active |= 1u << i;
    }
}


/* ---- lights ----------------------------------------------------------------------------------- */


static uint32_t at_least_one(uint32_t n) { return n ? n : 1u; }


/* ---- shading steps ---------------------------------------------------------------------------- */

/* RGS: the surfaces of the traced packet (normals, texture samples, T_R); ambient light. */
static void op_surfaces(const uint32_t *mem, rgs_block *b, unit_op *op, rgs_counters *c)
{
    c->rays[b->cur.kind] += count_rays(b->cur.rays.active);
    op_set(op, OP_SURFACE, at_least_one(count_rays(b->cur.rays.active)));
    rgs_surfaces(mem, &b->cur.rays, b->trace.hits, b->sf, op, &c->trace);
surface_state:
    for (int i = 0; i < TRACE_PACKET; i++) {
        op->hits += b->sf[i].valid;
        b->k_of[i] = b->sf[i].valid ? rgs_mat_k(&mem[b->sf[i].mat]) : 0u;
        for (int k = 0; k < 3; k++) {
            b->diffuse[i][k] = b->sf[i].unlit ? RGS_Q12_ONE : Q12_AMBIENT; /* unlit: kd B alone */
            b->highlight[i][k] = 0;
        }
    }
    b->light = 0;
    b->phase = RB_LIGHT;
}

/* Adds the light of the current light source to the rays in visible. */
static void add_light(rgs_block *b, uint32_t visible)
{
add_light_rays:
    for (int i = 0; i < TRACE_PACKET; i++)
        if (visible >> i & 1u)
            rgs_add_light(b->diffuse[i], b->highlight[i], b->diff[i], b->spec[i], b->colour);
}

/* RGS: the next light's weights and its shadow packet; unoccluded light is added at once. */
static void op_light(const uint32_t *mem, const rgs_config *cfg, rgs_block *b, unit_op *op, rgs_counters *c)
{
    const uint32_t at = region_start(mem, R_LIGHTS) + LIGHT_WORDS * b->light;
    const uint32_t *l = &mem[at];
    rgs_light_packet(l, b->sf, b->eps, &b->shadow, b->diff, b->spec, b->k_of);
    rgs_light_colour(l, b->colour);
    op_set(op, OP_LIGHT, at_least_one(count_rays(b->shadow.active)));
    shade_read(op, &c->trace, at, LIGHT_WORDS);
    if (SAARCOR_CFG_SHADOWS && cfg->shadows && b->shadow.active) {
        b->phase = RB_SHADOW_GEN;
        return;
    }
    add_light(b, b->shadow.active);
    b->light++;
}

#if SAARCOR_CFG_SHADOWS
/* Transformation unit: shadow rays generated (T_shadow), n + 1 steps: they share the light. */
static void op_shadow_gen(rgs_block *b, unit_op *op, rgs_counters *c)
{
    op_set(op, OP_SHADOW, count_rays(b->shadow.active) + 1u);
    c->rays[RAY_SHADOW] += count_rays(b->shadow.active);
    trace_begin(&b->shadow, trace_flags_of(b->profile, 1) | b->trav_flags, &b->trace);
    b->phase = RB_SHADOW_TRACE;
}

/* The shadow packet is traced: light reaches the rays that hit nothing. */
static void shadow_done(rgs_block *b)
{
    uint32_t visible = b->shadow.active;
blocked_rays:
    for (int i = 0; i < TRACE_PACKET; i++)
        if (b->trace.hits[i].instance != TRACE_NO_HIT)
            visible &= ~(1u << i);
    add_light(b, visible);
    b->light++;
    b->phase = RB_LIGHT;
}
#endif

/* ---- the ray tree of a block ----------------------------------------------------------------- */

static void push(rgs_block *b, const rgs_task *t, rgs_counters *c)
{
    if (b->sp < RGS_STACK)
        b->stack[b->sp++] = *t;
    else
        c->dropped++; /* cannot happen for depth <= RGS_MAX_DEPTH: the stack holds a full tree's path */
}

void rgs_block_begin(const uint32_t *mem, uint32_t x0, uint32_t y0, rgs_block *b)
{
    f24_t extent = 0;
scene_extent:
    for (uint32_t k = 0; k < 3; k++)
        extent = f24_max(extent, f24_sub(mem[H_SCENE_BOUNDS + 3 + k], mem[H_SCENE_BOUNDS + k]));
    b->eps = f24_div(extent, f24_from_i32(1 << EPS_SHIFT));
    b->sp = 0;
    b->phase = RB_GEN;
    b->packets = 0;
    b->n_lights = mem[H_LIGHTS] < MAX_LIGHTS ? mem[H_LIGHTS] : MAX_LIGHTS;
    b->profile = trace_profile(mem);
    rgs_task t;
    rgs_primary(mem, x0, y0, &t.rays);
    t.depth = 0;
    t.kind = RAY_PRIMARY;
init_block:
    for (int i = 0; i < TRACE_PACKET; i++)
        for (int k = 0; k < 3; k++) {
            t.weight[i][k] = RGS_Q12_ONE;
            b->acc[i][k] = 0;
        }
    b->stack[b->sp++] = t;
}


static void task_init(rgs_task *t, uint32_t depth, uint32_t kind)
{
    t->rays.active = 0;
    t->depth = depth;
    t->kind = kind;
task_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        t->rays.o[i] = t->rays.d[i] = (f24_vec3){ 0, 0, 0 };
        t->rays.tmin[i] = 0;
        t->rays.tmax[i] = F24_POS_INF;
        for (int k = 0; k < 3; k++)
            t->weight[i][k] = 0;
    }
}

/* RGS: the shaded colours accumulate into the pixels; the child packets are pushed. */
static void op_accumulate(const uint32_t *mem, const rgs_config *cfg, rgs_block *b, unit_op *op, rgs_counters *c)
{
    rgs_task refl, trans;
    const uint32_t depth = b->cur.depth + 1;
    const int children = SAARCOR_CFG_SECONDARY && depth <= cfg->max_depth && depth <= RGS_MAX_DEPTH &&
                         !(b->profile & PROFILE_NO_SECONDARY);
    task_init(&refl, depth, RAY_REFLECTION);
    task_init(&trans, depth, RAY_TRANSMISSION);
    op_set(op, OP_ACCUM, at_least_one(count_rays(b->cur.rays.active)));
    const uint32_t spawn = (children ? RGS_SPAWN_ON : 0u) | ((b->profile & PROFILE_LIVE_CHILDREN) ? RGS_SPAWN_LIVE : 0u);
    b->children = rgs_accumulate_rays(mem, b->sf, b->cur.rays.active, b->cur.weight, b->diffuse, b->highlight, b->eps,
                                      spawn, b->acc, &refl, &trans);
    if (trans.rays.active)
        push(b, &trans, c);
    if (refl.rays.active)
        push(b, &refl, c);
    b->phase = b->children ? RB_CHILD_GEN : RB_NEXT;
}

/* The next pending packet starts tracing (no unit operation), or the block is done. */
static void next_packet(rgs_block *b)
{
    if (b->sp == 0 || b->packets >= RGS_MAX_PACKETS) {
        b->phase = RB_DONE;
        return;
    }
    b->cur = b->stack[--b->sp];
    b->packets++;
    trace_begin(&b->cur.rays, trace_flags_of(b->profile, 0) | b->trav_flags, &b->trace);
    b->phase = RB_TRACE;
}

int rgs_packet_done(rgs_block *b)
{
#if SAARCOR_CFG_SHADOWS
    if (b->phase == RB_SHADOW_TRACE) {
        shadow_done(b);
        return RGS_STEP_ON;
    }
#endif
    if (b->packets == 1) {
    primary_hits:
        for (int i = 0; i < TRACE_PACKET; i++)
            b->primary_hits[i] = b->trace.hits[i];
    }
    b->phase = RB_SURFACES;
    return RGS_STEP_ON;
}

int rgs_phase(const uint32_t *mem, const rgs_config *cfg, rgs_block *b, unit_op *op, rgs_counters *c)
{
    switch (b->phase) {
    case RB_GEN: /* transformation unit: primary rays T_init, one step per ray (the shared origin, or an
                  * orthographic packet's shared direction, is a camera word: rtl/rgs_raygen.sv); camera block */
        b->trav_flags = cfg->traversal << TRACE_TRAV_SHIFT;
        op_set(op, OP_RAYGEN, TRACE_PACKET);
        shade_read(op, &c->trace, region_start(mem, R_CAMERA), CAM_WORDS);
        b->phase = RB_NEXT;
        return RGS_STEP_OP;
    case RB_NEXT: next_packet(b); return RGS_STEP_ON;
    case RB_SURFACES: op_surfaces(mem, b, op, c); return RGS_STEP_OP;
    case RB_LIGHT:
        if (b->light >= b->n_lights) {
            b->phase = RB_ACCUM;
            return RGS_STEP_ON;
        }
        op_light(mem, cfg, b, op, c);
        return RGS_STEP_OP;
#if SAARCOR_CFG_SHADOWS
    case RB_SHADOW_GEN: op_shadow_gen(b, op, c); return RGS_STEP_OP;
#endif
    case RB_ACCUM: op_accumulate(mem, cfg, b, op, c); return RGS_STEP_OP;
    case RB_CHILD_GEN: /* transformation unit: T_R steps for the back, ahead and mirror vectors */
        op_set(op, OP_CHILDREN, 3 * b->children);
        b->phase = RB_NEXT;
        return RGS_STEP_OP;
    default: return RGS_STEP_END;
    }
}

void rgs_block_finish(const rgs_block *b, uint32_t rgb[])
{
pixels:
    for (int i = 0; i < TRACE_PACKET; i++) {
        rgb[i] = 0;
        for (int k = 0; k < 3; k++) {
            const uint32_t v = (b->acc[i][k] * 255u + 2048u) >> 12;
            rgb[i] |= (v < 255u ? v : 255u) << (16 - 8 * k);
        }
    }
}

void rgs_render_block(const uint32_t *mem, const rgs_config *cfg, uint32_t x0, uint32_t y0, uint32_t rgb[],
                      hit_record primary_hits[], rgs_counters *c)
{
    rgs_block b;
    unit_op op;
    rgs_block_begin(mem, x0, y0, &b);
block_ops:
    for (uint32_t n = 0; n < RGS_STEP_LIMIT && rgs_step(mem, cfg, &b, &op, c); n++)
        ;
    if (primary_hits)
        for (int i = 0; i < TRACE_PACKET; i++)
            primary_hits[i] = b.primary_hits[i];
    rgs_block_finish(&b, rgb);
}
