/*
 * Ray generation and shading unit (RGS, paper sections 2.2 and 3; contract: docs/shading.md).
 *
 * Ray generation goes through the transformation unit. Primary rays: the camera block holds O
 * and the columns U, V, W of T_init = [U V W; O] (docs/memory-image.md), so the direction of pixel
 * (x, y) is T_init (x + 1/2, y + 1/2, 1) and the origin O (perspective), or the origin
 * O + (x + 1/2) U + (y + 1/2) V and direction W (orthographic); a packet is a 2x2 pixel block,
 * whose rays share their origin. Secondary rays: T_R = [D^, N^, D^; O] (the corrected form of the
 * paper's matrix) applied to the initial rays of reflection (-e, 0, t^)/(1, -2c, 0), transparency
 * (e, 0, t^)/(1, 0, 0) and refraction (e, 0, t^)/(eta_r, mu, 0) with mu = -eta_r c - sqrt(k);
 * shadow rays from the hit point P = T_R (0, 0, t^) towards each light. The primary rays have RTL
 * (rtl/rgs_raygen.sv, bit-identical to rgs_primary): 29 cycles from block to packet, one ray per
 * cycle through the transformation unit, so a packet every 4 cycles (the cycle model's RB_GEN
 * charges TRACE_PACKET steps of kind OP_RAYGEN).
 *
 * Shading is fixed function: Phong-like (ambient + diffuse with interpolated normals + highlight
 * of exponent 2^k), base colour x bilinear texture, the scene's lights with shadow rays (the
 * host adds a default light if it has none), mirror reflection and transmission rays weighted by the material,
 * up to RGS_MAX_DEPTH levels. Geometry of shading (normals, cosines, directions) is fp24; all
 * colour arithmetic is integer Q12 (4096 = 1.0, saturating at 65535).
 *
 * State: per 2x2 pixel block (one thread of the DynRTP), the depth-first stack of pending ray
 * packets with their per-ray RGB weights, the colour accumulators, and the packet in flight with
 * its trace_state. Step (rgs_step): one operation of one unit. The functional driver
 * rgs_render_block runs a block's steps back to back; the cycle model (tb/cycle) times the same
 * steps, so both give the same bits.
 *
 * fp24 operators per shaded ray (datapath, shared across the steps): decoding the 3 vertex
 * normals of the compact shading record (shade_rec.h: per normal 3 int-to-fp24, 6 mul, 2 add,
 * 1 sqrt, 1 div; the three side by side, interpolated as lanes), normalization of D and N (2 sqrt,
 * 2 div), T_R steps on the transformation unit, per light 2 dot products (diffuse and
 * highlight cosines), the spot factor (1 div) and the float-to-Q12 converters. Each RGS operation
 * has its kind (OP_SURFACE, OP_LIGHT, OP_ACCUM) and the cycle model charges each the latency of its
 * pipelined RTL (rtl/rgs_units.sv's shared rgs_surface, rgs_light, rgs_accum, as measured by their
 * benches and tb_rgs_ctrl: docs/cycle-model.md's table), throughput one shaded ray per cycle (an
 * operation takes as many issue slots as it shades rays, at least 1).
 */
#ifndef SAARCOR_RGS_H
#define SAARCOR_RGS_H

#include "config.h"
#include "trace.h"

#define RGS_MAX_DEPTH SAARCOR_CFG_MAX_DEPTH       /* deepest secondary level the unit supports (8) */
#define RGS_STACK (RGS_MAX_DEPTH + 2)             /* pending packets of a depth-first ray tree */
#define RGS_MAX_PACKETS ((1u << (RGS_MAX_DEPTH + 1)) - 1u) /* packets of a full binary ray tree */
#define RGS_Q12_ONE 4096u
#define RGS_STEP_LIMIT (1u << 30) /* bound of the operations of one block */

enum { RAY_PRIMARY, RAY_SHADOW, RAY_REFLECTION, RAY_TRANSMISSION, RAY_KINDS };

typedef struct {
    uint32_t max_depth; /* secondary levels below the primary rays, 0 .. RGS_MAX_DEPTH */
    uint32_t shadows;   /* 0: every light is visible (no shadow rays) */
    uint32_t traversal; /* TRAV_* algorithm of the traversal unit (0: the paper's stack) */
} rgs_config;

typedef struct {
    trace_counters trace;
    uint64_t rays[RAY_KINDS]; /* rays traced, by kind */
    uint64_t dropped;         /* child packets not spawned because the ray stack was full */
} rgs_counters;

typedef struct {
    ray_packet rays;
    uint32_t weight[TRACE_PACKET][3]; /* Q12 RGB weight of each ray's contribution */
    uint32_t depth, kind;
} rgs_task;

/* What shading needs to know about a hit. */
typedef struct {
    int valid;
    f24_vec3 p, d, n;   /* hit point, unit ray direction, unit shading normal facing the ray */
    f24_affine tr;      /* T_R of the hit */
    f24_t t_hat;        /* hit distance along d */
    int entering;       /* the geometric normal faces against the ray */
    uint32_t mat;       /* address of the material record */
    int unlit;          /* KHR_materials_unlit: no light, the diffuse term weighs kd B alone */
    uint32_t base[3];   /* Q12 base colour: factor x vertex colour x bilinear texture sample */
    uint32_t emission[3]; /* Q12 emission: factor x bilinear sample of the emissive texture */
    uint32_t tint[3];   /* Q12 colour of reflection and highlight: 1 + metallic (base - 1) */
} surface;

/* Next operation of a block (rgs_block.phase, rgs_step; rtl/rgs_ctrl.sv has a state per phase). */
enum { RB_GEN, RB_NEXT, RB_TRACE, RB_SURFACES, RB_LIGHT, RB_SHADOW_GEN, RB_SHADOW_TRACE, RB_ACCUM, RB_CHILD_GEN, RB_DONE };

/* A 2x2 pixel block's thread: its ray tree, the packet in flight and its shading state. */
typedef struct {
    rgs_task stack[RGS_STACK];
    uint32_t sp, packets;           /* pending packets; packets started */
    rgs_task cur;                   /* the packet being traced and shaded */
    trace_state trace;              /* the core's state of the packet (or shadow packet) in flight */
    uint32_t acc[TRACE_PACKET][3];  /* Q12 pixel colours */
    f24_t eps;                      /* ray offset e (docs/shading.md) */
    uint32_t phase, n_lights, light, children;
    uint32_t profile;               /* the image's PROFILE_* skip bits (trace.h) */
    uint32_t trav_flags;            /* the traversal algorithm as trace flags (rgs_config.traversal) */
    surface sf[TRACE_PACKET];       /* the surfaces of cur */
    uint32_t k_of[TRACE_PACKET];    /* their highlight exponents */
    uint32_t diffuse[TRACE_PACKET][3], highlight[TRACE_PACKET][3]; /* light gathered so far */
    ray_packet shadow;              /* the current light's shadow rays and their weights */
    uint32_t diff[TRACE_PACKET], spec[TRACE_PACKET], colour[3];
    hit_record primary_hits[TRACE_PACKET];
} rgs_block;

/* Primary rays of the 2x2 block with top-left pixel (x0, y0); pixels outside the image are
 * inactive. */
void rgs_primary(const uint32_t *mem, uint32_t x0, uint32_t y0, ray_packet *rp);

/* Starts the ray tree of a block with its primary packet (no unit operation yet). */
void rgs_block_begin(const uint32_t *mem, uint32_t x0, uint32_t y0, rgs_block *b);

/* What one phase of rgs_step did: issued a unit operation, changed phase without one (the next
 * phase follows in the same step), or found the block done. */
enum { RGS_STEP_OP, RGS_STEP_ON, RGS_STEP_END };

/* rgs_step's phases of the RGS's own (every one but a packet's tracing, rgs.c). */
int rgs_phase(const uint32_t *mem, const rgs_config *cfg, rgs_block *b, unit_op *op, rgs_counters *c);

/* A packet traced to its end: the primary packet's hits kept, a shadow packet's light added (rgs.c). */
int rgs_packet_done(rgs_block *b);

/* Performs the block's next operation on one unit (the RGS itself, or through trace_step the
 * core's units) and describes it in op; returns 0 when the block is done. Operations of the RGS:
 * primary ray generation (transformation unit, path a), the surfaces of a traced packet, one
 * light (its shadow packet; shadow ray generation on the transformation unit), accumulation and
 * child packets (T_R steps on the transformation unit).
 * Inline, so that the loop of the step driver (rgs_render_block, tb/cycle's pc_render_block) takes a
 * packet in flight's next core operation, most of a frame's steps, without a call and stack frame
 * of rgs_step's own (room 256x192: 3.2 of 3.4 million steps). */
static inline int rgs_step(const uint32_t *mem, const rgs_config *cfg, rgs_block *b, unit_op *op, rgs_counters *c)
{
rgs_route:
    for (int guard = 0; guard < 4; guard++) { /* transitions without a unit operation, then one operation */
        int did;
        if (b->phase == RB_TRACE || (SAARCOR_CFG_SHADOWS && b->phase == RB_SHADOW_TRACE))
            did = trace_step(mem, &b->trace, op, &c->trace) ? RGS_STEP_OP : rgs_packet_done(b);
        else
            did = rgs_phase(mem, cfg, b, op, c);
        if (did != RGS_STEP_ON)
            return did == RGS_STEP_OP;
    }
    return 0;
}

/* 0xRRGGBB of the block's pixels. */
void rgs_block_finish(const rgs_block *b, uint32_t rgb[]);

/* Functional mode: the whole ray tree of one block; primary_hits (may be NULL) gets the primary
 * rays' hits. */
void rgs_render_block(const uint32_t *mem, const rgs_config *cfg, uint32_t x0, uint32_t y0, uint32_t rgb[],
                      hit_record primary_hits[], rgs_counters *c);

/* Image size of the camera block. */
void rgs_image_size(const uint32_t *mem, uint32_t *width, uint32_t *height);

/* Secondary-ray directions of docs/shading.md for unit d and unit n facing the ray (n.d <= 0):
 * the mirror direction, and the refracted direction for eta_r = n_from / n_to through T_R
 * (returns 0 on total internal reflection). Exposed for the tests of the derivation. */
f24_vec3 rgs_reflect(f24_vec3 d, f24_vec3 n);
int rgs_refract(f24_vec3 d, f24_vec3 n, f24_t eta_r, f24_vec3 *out);

#endif
