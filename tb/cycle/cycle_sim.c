/* Cycle-level model of the DynRTC: see cycle_sim.h and docs/cycle-model.md. */
#define _GNU_SOURCE
#include "cycle_sim.h"
#include "cycle_trace.h"
#include "pixel_cost.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "f24_record.h"

const char *const unit_names[UNIT_KINDS] = { "RGS", "transformation", "traversal", "list", "intersection" };
const char *const mem_kind_names[MEM_KINDS] = { "kd_nodes", "lists", "matrices", "shading" };
const char *const op_kind_names[OP_KINDS] = { "raygen", "xform", "instance", "shadow",  "children", "trav",
                                              "objclip", "list", "leaf",     "isect",   "surface",  "light", "accum" };

void cycle_config_default(cycle_config *c)
{
    memset(c, 0, sizeof *c);
    c->pipes = 1;
    c->threads_per_pipe = 32;
    /* Each kind of operation takes the latency of the RTL module(s) that do it when pipelined
     * (the operators' default stages add 6, mul 4, div 11, cmp 2, sqrt 9, cvt 3: >= 60 MHz on
     * iCE40; the RGS's units 1 more each for rgs_units' arbiter register, rtl/rgs_arb.sv) and what the DynRTP around them adds (a dependent read's cache hit, trace_thread's
     * states, the operations its thread issues that the C has inside one), measured per kind on
     * the DynRTP (tb_dynrtp's TB_DYNRTP_LOG); docs/cycle-model.md derives each. */
    c->latency[OP_RAYGEN] = 29;   /* rgs_arb's register 1, rgs_raygen: block register 1 + f24_from_i32 3 + xform_unit
                                   * 22 + packet 1, dynrtp's packet queue into the core 1 */
    c->latency[OP_XFORM] = 36;    /* trace_core's issue stage 1 (the operands from thread_ram), isect_rebased's origin
                                   * path (l = p.lo - C.lo, c = h + l: 2 add) + xform_unit 22; the triangle's record
                                   * through trace_core's word request stage 1 */
    c->latency[OP_INSTANCE] = 54; /* rebase_unit 25, then xform_wide 25 (the origins' chain), each after trace_core's
                                   * issue stage 1; the instance's and the object's records each through trace_core's
                                   * word request stage 1 */
    c->latency[OP_SHADOW] = 2;    /* rgs_light forms the shadow rays: its register to the trace port, dynrtp's packet
                                   * queue into the core 1 */
    c->latency[OP_CHILDREN] = 2;  /* rgs_spawn (in rgs_accum) forms the child rays: the stack's register, the packet
                                   * queue 1 */
    c->latency[OP_TRAV] = 44;     /* trace_core's issue FIFO 1 + trav_unit 38 (state and stack read, prune, queue,
                                   * trav_node 21, split and push, its node read answering in the next cycle) + 2
                                   * (the kd-node cache's hit: 3) + 3 (trace_thread's states from the result to the
                                   * next request) - the issue slot: 13 of it before its trav_node slot (trav_front
                                   * + node_read), 31 after; the scene clip: 6 slots, trav_clip's chain, the start */
    c->latency[OP_OBJCLIP] = 69;  /* trace_thread: the object's record (2 matrix cache lines), the mailboxes cleared
                                   * (a list unit operation, not waited for), the relative distances (an adder batch
                                   * after trace_core's issue stage), the clip (6 slots, trav_clip), the start (a
                                   * traversal operation of its own): the clip and the start 1 each through
                                   * trace_core's issue FIFO; the two records 1 each through its word request
                                   * stage */
    c->latency[OP_LIST] = 19;     /* trace_core's issue FIFO 1, list_unit 3, its word through dynrtp's registers and
                                   * the list cache (hit 3), trace_thread's request and result states */
    c->latency[OP_LEAF] = 48;     /* the list entry's 19, then rebase_unit 25 (a batch after trace_core's issue stage
                                   * 1) and its states */
    c->latency[OP_ISECT] = 36;    /* isect_rebased's second half: isect_unit 29 (div 11 + mul 4 + 2 add + cmp 2) +
                                   * best_t = t0 + t (add 6); + 1 since trace_core's output register (a packet's hits
                                   * a cycle later), fitted on subpass 32x24 at 8 threads (2026-11-29: 2.2% under the
                                   * RTL with 35) */
    c->latency[OP_SURFACE] = 221; /* rgs_arb's register 1, rgs_surface: the first hit's front reads (instance word,
                                   * object, record: 3 bursts of 1, 2 and 1 to 5 lines through the shading cache,
                                   * about 8, + 3: each burst's lines through dynrtp's answer register), rgs_normal
                                   * 90 (asked for from the second stage's registers, a cycle after the hit loads
                                   * there), rgs_frame 118 behind its arbiter's register 1 (one frame shared by the
                                   * surface units) */
    c->surface_hit = 40;          /* each further hit: the front's reads of it, one burst of lines after another, or
                                   * its normal's chain (rgs_normal 89: 88 before f24_from_i32's third stage) */
    c->surface_miss = 13;         /* a packet without hits: rgs_arb's register, rgs_surface's stages and queue,
                                   * nothing read */
    c->shade_hit = 5;             /* the RGS's mem_port's request queue 1 + the shading cache_read's hit 3 + dynrtp's
                                   * answer register 1 */
    c->trav_front = 9;            /* trace_core's issue FIFO 1, trav_unit's stages A to E 7 (the walker state's and
                                   * the stack's read, the prune's comparators 4, D, E), its queue 1: a clip's first
                                   * slab plane enters trav_node 9 cycles after the issue */
    c->node_read = 4;             /* a kd-tree entry's node: its request's queue 1, the kd-node cache's hit 3 */
    c->objclip_front = 24;        /* trace_thread's steps from an object clip's decision to the clip's issue (the
                                   * records, the mailboxes' clear, the relative distances: 19 + n for an identity
                                   * instance's n rays, measured on the RTL, 17 + n before the word request stage), so the 36 after its last slot are the
                                   * RTL's (the clip's 28, the start, the thread's states) */
    c->latency[OP_LIGHT] = 93;    /* rgs_arb's register 1 + rgs_light 87 (rgs_light_colour's 27 beside it) + rgs_ctrl's
                                   * state (LCALC 93) */
    c->latency[OP_ACCUM] = 69;    /* rgs_arb's register 1, rgs_accum: its operand's register 1 + rgs_spawn's 67 */
    c->tile = 16;
    c->epoch = 256;
    c->host_threads = 1;
    /* lines of one record: wider lines fetch neighbours a packet rarely visits next (docs/cycle-model.md) */
    c->mem.cache[MEM_NODES] = (cache_config){ 4096, 8 }; /* one kd node */
    c->mem.cache[MEM_LISTS] = (cache_config){ 2048, 4 }; /* one list entry */
    c->mem.cache[MEM_MATRICES] = (cache_config){ 6144, 4 * F24_TRIANGLE_RECORD_WORDS }; /* one line per triangle */
    c->mem.cache[MEM_SHADING] = (cache_config){ 4096, 16 };
    c->mem.latency = 10;
    c->mem.mbps = 1000.0;
    c->mem.clock_mhz = 90.0;
}

void rgs_counters_add(rgs_counters *sum, const rgs_counters *c)
{
    sum->trace.traversal_steps += c->trace.traversal_steps;
    sum->trace.leaves += c->trace.leaves;
    sum->trace.list_entries += c->trace.list_entries;
    sum->trace.mailbox_skips += c->trace.mailbox_skips;
    sum->trace.transformations += c->trace.transformations;
    sum->trace.intersections += c->trace.intersections;
    for (int k = 0; k < MEM_KINDS; k++)
        sum->trace.words[k] += c->trace.words[k];
    for (int k = 0; k < RAY_KINDS; k++)
        sum->rays[k] += c->rays[k];
    sum->dropped += c->dropped;
}

/* ---- one pipe ------------------------------------------------------------------------------ */

/* TH_FRONT: the thread's own steps before its operation joins the unit's queue (op_front) */
enum { TH_IDLE, TH_MEMORY, TH_FRONT, TH_QUEUED, TH_UNIT };

/* A thread's packet in the core for the CYCLE_LOG file (docs/cycle-model.md): the cycle its first
 * core operation was decided, its core operations and issue slots by kind, and its thread-cycles
 * waiting for memory (by data type) and queued (by unit) */
typedef struct {
    int in_core;
    uint64_t in, wait_mem[MEM_KINDS], wait_unit[UNIT_KINDS];
    uint32_t ops[OP_KINDS], slots[OP_KINDS];
} packet_log;

typedef struct {
    rgs_block blk;
    unit_op op;
    uint32_t state, x0, y0, wait_kind;
    uint64_t since; /* cycle the current state began */
    uint64_t began; /* cycle it took its block (per-pixel cycles) */
    uint64_t node_at; /* its traversal operation can take trav_node's first slot from this cycle on */
    uint32_t light_held; /* the light record its block controller holds (rgs_ctrl; UINT32_MAX: none) */
    pixel_cost cost[TRACE_PACKET]; /* its block's per-pixel cost so far (if kept) */
    packet_log pkt;      /* its packet in the core (CYCLE_LOG only) */
} thread;

/* A unit's input queue as the RTL scheduler holds it (rtl/thread_sched.sv): one ready bit per
 * thread, any number set per cycle, and a round-robin pointer: the unit issues the first ready
 * thread at or after the pointer, which then moves past it. */
typedef struct {
    uint64_t *ready; /* bit t of word t / 64: thread t waits for the unit */
    uint32_t count, ptr;
} ready_set;

#define TILE_QUEUE 2

typedef struct {
    const uint32_t *mem;
    const rgs_config *rcfg;
    const cycle_config *cfg;
    uint32_t width, height, *pixels;
    uint32_t rx0, ry0, rx1, ry1; /* the region rendered: tiles are numbered within it */
    hit_record *hits;
    pixel_cost *costs; /* per pixel (NULL: not kept) */
    thread *th;
    ready_set queue[UNIT_KINDS];
    uint64_t free_at[UNIT_KINDS]; /* a unit's issue is free from this cycle on */
    uint32_t *trav_q, trav_head, trav_n; /* the traversal unit's queue: its operations in issue order (a ring) */
    uint64_t trav_free;                  /* trav_node's slots are free from this cycle on */
    uint64_t shade_port_free; /* the RGS's line port to the shading cache is free from this cycle on */
    uint64_t *heap; /* events: cycle << 16 | thread, min first */
    uint32_t heap_n;
    uint32_t tiles[TILE_QUEUE], n_tiles; /* tile queue filled by the controller */
    uint32_t tile_block, cur_tile, have_tile;
    uint32_t *arrived, n_arrived; /* threads whose results arrive this cycle */
    uint64_t now, last_event;
    uint32_t active; /* threads holding a block */
    mem_iface mi;
    rgs_counters counters;
    cycle_stats st;
    trace_pipe *tp; /* waveform recorder (NULL: none) */
    cycle_sched_probe probe; /* scheduler events (NULL: none) */
    void *probe_arg;
    FILE *log;        /* CYCLE_LOG (NULL: none) */
    uint64_t packets; /* packets begun, numbered for the log */
    uint32_t index;   /* the pipe's number */
    int in_cycle;     /* a ready thread joins the set in a cycle's commit: the unit sees it next cycle */
} pipe_state;

static void heap_push(pipe_state *p, uint64_t cycle, uint32_t t)
{
    uint64_t *h = p->heap, v = cycle << 16 | t;
    uint32_t i = p->heap_n++;
    while (i > 0 && h[(i - 1) / 2] > v) {
        h[i] = h[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    h[i] = v;
}

static uint64_t heap_pop(pipe_state *p)
{
    uint64_t *h = p->heap, top = h[0], v = h[--p->heap_n];
    uint32_t i = 0;
    for (;;) {
        uint32_t c = 2 * i + 1;
        if (c >= p->heap_n)
            break;
        if (c + 1 < p->heap_n && h[c + 1] < h[c])
            c++;
        if (h[c] >= v)
            break;
        h[i] = h[c];
        i = c;
    }
    h[i] = v;
    return top;
}

static uint32_t ready_words(uint32_t threads) { return (threads + 63) / 64; }

static void ready_set_add(ready_set *q, uint32_t id)
{
    q->ready[id / 64] |= 1ull << (id % 64);
    q->count++;
}

/* The first ready thread at or after the pointer, cyclically (the queue is not empty). */
static uint32_t ready_first(const ready_set *q, uint32_t threads)
{
    const uint32_t n = ready_words(threads), w0 = q->ptr / 64;
    const uint64_t at_or_after = q->ready[w0] & (~0ull << (q->ptr % 64));
    if (at_or_after)
        return w0 * 64 + (uint32_t)__builtin_ctzll(at_or_after);
    for (uint32_t k = 1; k <= n; k++) {
        const uint32_t w = (w0 + k) % n;
        if (q->ready[w])
            return w * 64 + (uint32_t)__builtin_ctzll(q->ready[w]);
    }
    return 0; /* not reached: count > 0 */
}

static void ready_set_take(ready_set *q, uint32_t id, uint32_t threads)
{
    q->ready[id / 64] &= ~(1ull << (id % 64));
    q->count--;
    q->ptr = (id + 1) % threads;
}

/* The cycles an operation holds its unit's issue: the traversal unit takes an operation a cycle
 * (trace_core's issue FIFO, trav_unit's queue), its trav_node slots come later (trav_slot); the
 * other units are held for all its slots (a batch's ray steps, one a cycle; rays shaded). */
static uint32_t issue_slots(const unit_op *op) { return op_kind_unit(op->kind) == UNIT_TRAV ? 1u : op->slots; }

/* Thread id joins unit u's queue. */
static void enqueue(pipe_state *p, int u, uint32_t id)
{
    ready_set_add(&p->queue[u], id);
    if (p->probe)
        p->probe(p->probe_arg, p->index, SCHED_READY, p->now + (p->in_cycle ? 1u : 0u), (uint32_t)u, id,
                 issue_slots(&p->th[id].op));
    if (p->tp)
        trace_queue(p->tp, u, p->now, p->queue[u].count);
}

/* Thread-cycles of the state being left. */
static void leave_state(pipe_state *p, thread *t)
{
    const uint64_t d = p->now - t->since;
    switch (t->state) {
    case TH_MEMORY:
        p->st.thread_cycles[ST_MEMORY] += d;
        p->st.wait_mem[t->wait_kind] += d;
        t->pkt.wait_mem[t->wait_kind] += d;
        break;
    case TH_QUEUED:
        p->st.thread_cycles[ST_UNIT_QUEUE] += d;
        p->st.wait_unit[op_kind_unit(t->op.kind)] += d;
        t->pkt.wait_unit[op_kind_unit(t->op.kind)] += d;
        break;
    case TH_FRONT:
    case TH_UNIT: p->st.thread_cycles[ST_UNIT_BUSY] += d; break;
    default: p->st.thread_cycles[ST_NO_WORK] += d; break;
    }
    t->since = p->now;
}

/* The next 2x2 block of the pipe's tiles, 0 if it has none now. */
static int next_block(pipe_state *p, uint32_t *x0, uint32_t *y0)
{
    const uint32_t tile = p->cfg->tile, per_row = tile / 2, tiles_x = (p->rx1 - p->rx0 + tile - 1) / tile;
tile_blocks:
    for (;;) {
        if (!p->have_tile) {
            if (!p->n_tiles)
                return 0;
            p->cur_tile = p->tiles[0];
            memmove(p->tiles, p->tiles + 1, --p->n_tiles * sizeof *p->tiles);
            p->have_tile = 1;
            p->tile_block = 0;
            p->st.tiles++;
        }
        if (p->tile_block >= per_row * per_row) {
            p->have_tile = 0;
            continue;
        }
        const uint32_t tx = p->cur_tile % tiles_x, ty = p->cur_tile / tiles_x, b = p->tile_block++;
        *x0 = p->rx0 + tx * tile + 2 * (b % per_row);
        *y0 = p->ry0 + ty * tile + 2 * (b / per_row);
        if (*x0 < p->rx1 && *y0 < p->ry1)
            return 1; /* (blocks beyond the region's edge are skipped) */
    }
}

static void finish_block(pipe_state *p, thread *t)
{
    uint32_t rgb[TRACE_PACKET];
    rgs_block_finish(&t->blk, rgb);
    for (int i = 0; i < TRACE_PACKET; i++) {
        const uint32_t x = t->x0 + (uint32_t)(i & 1), y = t->y0 + (uint32_t)(i >> 1);
        if (x >= p->width || y >= p->height)
            continue;
        p->pixels[(size_t)y * p->width + x] = rgb[i];
        if (p->hits)
            p->hits[(size_t)y * p->width + x] = t->blk.primary_hits[i];
    }
    if (p->costs) {
        pc_split_block(t->cost, PC_CYCLES, p->now - t->began, t->x0, t->y0, p->width, p->height);
        pc_store_block(p->costs, t->cost, t->x0, t->y0, p->width, p->height);
    }
    p->st.blocks++;
}

/* An operation of the core (trace_step's), not of the RGS (the ray generation, shadow and child
 * rays, the surfaces, lights and accumulation) */
static int core_op(uint32_t kind)
{
    return kind < OP_SURFACE && kind != OP_RAYGEN && kind != OP_SHADOW && kind != OP_CHILDREN;
}

/* CYCLE_LOG: thread id has decided its next operation (none: the block is done). A core operation
 * after an RGS one begins a packet; an RGS operation after core ones ends it, with a line
 * "P number thread cycle_in cycle_out", per kind of operation (OP_*) its count and issue slots (as
 * tb_dynrtp's TB_DYNRTP_LOG), then its thread-cycles waiting for memory per data type and queued
 * per unit. */
static void log_packet(pipe_state *p, uint32_t id, int core_op)
{
    thread *t = &p->th[id];
    if (core_op && !t->pkt.in_core) {
        memset(&t->pkt, 0, sizeof t->pkt);
        t->pkt.in_core = 1;
        t->pkt.in = p->now;
    } else if (!core_op && t->pkt.in_core) {
        t->pkt.in_core = 0;
        char line[1024]; /* one write per line: the pipes' host threads share the file */
        int n = snprintf(line, sizeof line, "P %llu %u %llu %llu", (unsigned long long)p->packets++,
                         p->index * p->cfg->threads_per_pipe + id, (unsigned long long)t->pkt.in,
                         (unsigned long long)p->now);
        for (int k = 0; k < OP_KINDS; k++)
            n += snprintf(line + n, sizeof line - (size_t)n, " %u %u", t->pkt.ops[k], t->pkt.slots[k]);
        for (int k = 0; k < MEM_KINDS; k++)
            n += snprintf(line + n, sizeof line - (size_t)n, " %llu", (unsigned long long)t->pkt.wait_mem[k]);
        for (int u = 0; u < UNIT_KINDS; u++)
            n += snprintf(line + n, sizeof line - (size_t)n, " %llu", (unsigned long long)t->pkt.wait_unit[u]);
        fprintf(p->log, "%s\n", line);
    }
    if (core_op) {
        t->pkt.ops[t->op.kind]++;
        t->pkt.slots[t->op.kind] += t->op.slots;
    }
}

/* The cycles of a thread's own steps before its operation joins the unit's queue, a part of its
 * latency: an object clip's (trace_thread reads the object's record, clears the mailboxes and
 * computes the relative distances, then raises the clip), none for the others. */
static uint32_t op_front(const cycle_config *cfg, const unit_op *op)
{
    if (op->kind != OP_OBJCLIP)
        return 0;
    return cfg->objclip_front < cfg->latency[op->kind] ? cfg->objclip_front : cfg->latency[op->kind];
}

/* Thread id's operation (its memory data there) joins its unit's queue, after its own steps. */
static void join_unit(pipe_state *p, uint32_t id)
{
    thread *t = &p->th[id];
    const uint32_t front = op_front(p->cfg, &t->op);
    if (front) {
        t->state = TH_FRONT;
        heap_push(p, p->now + front, id);
        return;
    }
    t->state = TH_QUEUED;
    enqueue(p, (int)op_kind_unit(t->op.kind), id);
}

/* A thread's result has arrived (or it is idle): it decides its next operation, reads that
 * operation's memory blocks, and waits for them or joins the unit's queue. */
static void advance_thread(pipe_state *p, uint32_t id)
{
    thread *t = &p->th[id];
    leave_state(p, t);
next_op:
    while (t->state == TH_IDLE || !pc_step(p->mem, p->rcfg, &t->blk, &t->op, &p->counters, p->costs ? t->cost : NULL)) {
        if (p->log && t->state != TH_IDLE)
            log_packet(p, id, 0);
        if (t->state != TH_IDLE) { /* the block is done */
            finish_block(p, t);
            p->active--;
            t->state = TH_IDLE;
        }
        if (!next_block(p, &t->x0, &t->y0))
            return;
        rgs_block_begin(p->mem, t->x0, t->y0, &t->blk);
        memset(t->cost, 0, sizeof t->cost);
        t->began = p->now;
        p->active++;
        t->state = TH_QUEUED; /* holds a block from here on */
    }
    if (p->log)
        log_packet(p, id, core_op(t->op.kind));
    uint64_t ready = p->now;
    for (uint32_t r = 0; r < t->op.n_reads; r++) {
        const uint64_t at = mem_iface_read(&p->mi, t->op.read[r].kind, t->op.read[r].addr, t->op.read[r].words, p->now);
        if (at > ready) {
            ready = at;
            t->wait_kind = t->op.read[r].kind;
        }
    }
    if (ready > p->now) {
        t->state = TH_MEMORY;
        heap_push(p, ready, id);
    } else {
        join_unit(p, id);
    }
}

/* advance_thread, and the threads in flight it may have changed for the waveform. */
static void advance(pipe_state *p, uint32_t id)
{
    advance_thread(p, id);
    if (p->tp)
        trace_threads(p->tp, p->now, p->active);
}

static int cmp_u32(const void *a, const void *b)
{
    const uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* The cycles from an operation's last issue slot to its result: its kind's latency; a surface
 * operation's hits pass rgs_surface's front stage one after another (its reads, each burst after
 * the one its address comes from), so each hit after the first adds surface_hit, while its misses
 * pass in a cycle each: a packet without hits takes surface_miss. */
static uint32_t op_latency(const cycle_config *cfg, const unit_op *op)
{
    if (op->kind != OP_SURFACE)
        return cfg->latency[op->kind];
    return op->hits ? cfg->latency[OP_SURFACE] + (op->hits - 1) * cfg->surface_hit : cfg->surface_miss;
}

uint64_t cycle_shading_lines(const cycle_config *cfg, const unit_op *op)
{
    const uint64_t lw = cfg->mem.cache[MEM_SHADING].line_bytes >= 8 ? cfg->mem.cache[MEM_SHADING].line_bytes / 4 : 1;
    uint64_t lines = 0;
    for (uint32_t r = 0; r < op->n_reads; r++)
        if (op->read[r].kind == MEM_SHADING && op->read[r].words)
            lines += (op->read[r].addr % lw + op->read[r].words + lw - 1) / lw;
    return lines;
}

/* Takes `lines` cycles of the RGS's line port to the shading cache from its first free cycle at
 * or after now, and returns that cycle: the RGS's block controllers share one port, a line a
 * cycle (rtl/dynrtp.sv: mem_port onto the shading cache_read, a 16-byte line a response). */
static uint64_t shade_port_take(pipe_state *p, uint64_t lines)
{
    const uint64_t start = p->shade_port_free > p->now ? p->shade_port_free : p->now;
    p->shade_port_free = start + lines;
    p->st.shade_port_wait += start - p->now;
    return start;
}

/* The cycle the RGS operation t issues now starts its work. A surface reads all its lines
 * through the port as its front and back go (its latency counts their bursts), so it starts when
 * the port has taken the lines of the operations before it. A light: rgs_ctrl reads the light's
 * record (S_LREC, a line a cycle) before rgs_light starts, unless it holds that light's record
 * from its last light operation (a scene of one light reads it once per controller); its few
 * lines do not wait for the surfaces' booked before it: dynrtp merges the controllers' record
 * reads and the surface units' reads round robin a line at a time (u_rgs_reads), so they go
 * between those, and the surfaces issued after it start that many cycles later. Others: now. */
static uint64_t rgs_start(pipe_state *p, thread *t)
{
    const unit_op *op = &t->op;
    if (op->kind == OP_SURFACE)
        return shade_port_take(p, cycle_shading_lines(p->cfg, op));
    if (op->kind != OP_LIGHT || !op->n_reads || op->read[0].addr == t->light_held)
        return p->now;
    t->light_held = op->read[0].addr;
    const uint64_t lines = cycle_shading_lines(p->cfg, op);
    p->shade_port_free = (p->shade_port_free > p->now ? p->shade_port_free : p->now) + lines;
    return p->now + p->cfg->shade_hit + lines - 1;
}

/* The cycles from a traversal operation's issue to its first trav_node slot with nothing ahead
 * of it (trav_unit's stages, and the node's words for a kd-tree entry that reads one): a part of
 * its latency, at most what its own steps before the issue (op_front) left. */
static uint32_t node_lead(const cycle_config *cfg, const unit_op *op)
{
    const uint32_t left = cfg->latency[op->kind] - op_front(cfg, op);
    uint32_t e = cfg->trav_front;
    for (uint32_t r = 0; r < op->n_reads; r++)
        if (op->read[r].kind == MEM_NODES) {
            e += cfg->node_read;
            break;
        }
    return e < left ? e : left;
}

/* Thread id's operation takes its `slots` cycles of its unit's datapath from now on (the
 * issue's, trav_node's for the traversal): busy, the waveform, and its result `after` cycles
 * after its work's last slot (work from `start`: now, or when the RGS's line port has taken it). */
static void occupy(pipe_state *p, uint32_t id, uint64_t start, uint32_t after)
{
    const thread *t = &p->th[id];
    const int u = (int)op_kind_unit(t->op.kind);
    p->st.busy[u] += t->op.slots;
    if (p->tp)
        trace_busy(p->tp, u, p->now, id, t->op.slots);
    heap_push(p, start + t->op.slots - 1 + after, id);
}

/* The traversal unit's queue, in issue order: thread id's operation can enter trav_node from
 * `at` on. */
static void trav_push(pipe_state *p, uint32_t id, uint64_t at)
{
    p->th[id].node_at = at;
    const uint32_t slot = p->trav_head + p->trav_n++, cap = p->cfg->threads_per_pipe;
    p->trav_q[slot < cap ? slot : slot - cap] = id; /* a ring: at < 2 cap, no division on the hot path */
}

/* The queue's head, if it can take trav_node's slots now (UINT32_MAX: none). */
static uint32_t trav_slot(const pipe_state *p)
{
    if (!p->trav_n || p->trav_free > p->now)
        return UINT32_MAX;
    const uint32_t id = p->trav_q[p->trav_head];
    return p->th[id].node_at <= p->now ? id : UINT32_MAX;
}

/* Unit u issues thread id's operation now. */
static void issue_op(pipe_state *p, int u, uint32_t id)
{
    const uint32_t cap = p->cfg->threads_per_pipe;
    thread *t = &p->th[id];
    ready_set_take(&p->queue[u], id, cap);
    leave_state(p, t);
    t->state = TH_UNIT;
    p->free_at[u] = p->now + issue_slots(&t->op);
    p->st.ops[u]++;
    if (p->probe)
        p->probe(p->probe_arg, p->index, SCHED_ISSUE, p->now, (uint32_t)u, id, issue_slots(&t->op));
    if (p->tp) {
        trace_issue(p->tp, u, p->now);
        trace_queue(p->tp, u, p->now, p->queue[u].count);
    }
    if (u == UNIT_TRAV)
        trav_push(p, id, p->now + node_lead(p->cfg, &t->op));
    else
        occupy(p, id, rgs_start(p, t), op_latency(p->cfg, &t->op));
}

/* One cycle: compute (each unit picks its issue, trav_node its operation, from the current
 * state), then commit. */
static void pipe_cycle(pipe_state *p)
{
    const uint32_t cap = p->cfg->threads_per_pipe;
    uint32_t issue[UNIT_KINDS];
    for (int k = 0; k < UNIT_KINDS; k++) { /* phase 1: decisions from the current state only */
        const int u = p->cfg->reverse_order ? UNIT_KINDS - 1 - k : k;
        issue[u] = p->queue[u].count && p->free_at[u] <= p->now ? ready_first(&p->queue[u], cap) : UINT32_MAX;
    }
    const uint32_t slot = trav_slot(p);
    p->n_arrived = 0;
    while (p->heap_n && p->heap[0] >> 16 == p->now) /* results and memory data arriving now */
        p->arrived[p->n_arrived++] = (uint32_t)(heap_pop(p) & 0xFFFFu);
    for (int u = 0; u < UNIT_KINDS; u++) /* phase 2: commit, in a fixed order */
        if (issue[u] != UINT32_MAX)
            issue_op(p, u, issue[u]);
    if (slot != UINT32_MAX) {
        const unit_op *op = &p->th[slot].op;
        p->trav_head = p->trav_head + 1 == cap ? 0 : p->trav_head + 1;
        p->trav_n--;
        p->trav_free = p->now + op->slots;
        occupy(p, slot, p->now, op_latency(p->cfg, op) - op_front(p->cfg, op) - node_lead(p->cfg, op));
    }
    qsort(p->arrived, p->n_arrived, sizeof *p->arrived, cmp_u32);
    p->in_cycle = 1;
    for (uint32_t i = 0; i < p->n_arrived; i++) {
        thread *t = &p->th[p->arrived[i]];
        if (t->state == TH_MEMORY) { /* data is here: join the unit's queue */
            leave_state(p, t);
            join_unit(p, p->arrived[i]);
        } else if (t->state == TH_FRONT) {
            leave_state(p, t);
            t->state = TH_QUEUED;
            enqueue(p, (int)op_kind_unit(t->op.kind), p->arrived[i]);
        } else {
            advance(p, p->arrived[i]);
        }
    }
    p->in_cycle = 0;
    if (p->n_arrived)
        p->last_event = p->now;
}

static uint64_t max_u64(uint64_t a, uint64_t b) { return a > b ? a : b; }

/* The first cycle from p->now on at which anything can happen (UINT64_MAX: nothing pending). */
static uint64_t next_cycle(const pipe_state *p)
{
    uint64_t n = p->heap_n ? p->heap[0] >> 16 : UINT64_MAX;
    for (int u = 0; u < UNIT_KINDS; u++)
        if (p->queue[u].count) {
            const uint64_t f = max_u64(p->free_at[u], p->now);
            n = f < n ? f : n;
        }
    if (p->trav_n) {
        const uint64_t f = max_u64(max_u64(p->th[p->trav_q[p->trav_head]].node_at, p->trav_free), p->now);
        n = f < n ? f : n;
    }
    return n;
}

/* Idle threads take blocks from the tile queue (the controller has just refilled it), in
 * thread order, as a commit at the end of the previous cycle. */
static void wake_idle(pipe_state *p)
{
    for (uint32_t i = 0; i < p->cfg->threads_per_pipe && (p->n_tiles || p->have_tile); i++)
        if (p->th[i].state == TH_IDLE)
            advance(p, i);
}

/* Runs the pipe's cycles from p->now up to `until` (exclusive), skipping cycles in which
 * nothing can happen. */
static void pipe_run(pipe_state *p, uint64_t until)
{
    wake_idle(p);
cycles:
    for (;;) {
        const uint64_t n = next_cycle(p);
        if (n >= until) {
            p->now = until;
            return;
        }
        p->now = n;
        pipe_cycle(p);
        p->now = n + 1;
    }
}

static int pipe_busy(const pipe_state *p) { return p->active || p->n_tiles || p->have_tile; }

/* ---- the DynRTC: pipes, controller, host threads ------------------------------------------------ */

struct cycle_sim {
    cycle_config cfg;
    pipe_state *pipes;
    pixel_cost *costs;
    cycle_trace *trace;
    FILE *log; /* the per-packet log: the file CYCLE_LOG names in the environment (NULL: none) */
};

void cycle_set_costs(cycle_sim *s, pixel_cost *costs) { s->costs = costs; }

void cycle_set_sched_probe(cycle_sim *s, cycle_sched_probe probe, void *arg)
{
    for (uint32_t i = 0; i < s->cfg.pipes; i++) {
        s->pipes[i].probe = probe;
        s->pipes[i].probe_arg = arg;
    }
}

void cycle_set_trace(cycle_sim *s, cycle_trace *tr)
{
    s->trace = tr;
    for (uint32_t i = 0; i < s->cfg.pipes; i++) {
        pipe_state *p = &s->pipes[i];
        p->tp = tr ? cycle_trace_pipe(tr, i) : NULL;
        p->mi.probe = tr ? trace_mem : NULL;
        p->mi.probe_arg = p->tp;
    }
}

cycle_sim *cycle_create(const cycle_config *cfg)
{
    cycle_sim *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    s->cfg = *cfg;
    s->pipes = calloc(cfg->pipes, sizeof *s->pipes);
    const char *log = getenv("CYCLE_LOG");
    s->log = log ? fopen(log, "w") : NULL;
    int ok = s->pipes != NULL && (!log || s->log);
    for (uint32_t i = 0; ok && i < cfg->pipes; i++) {
        pipe_state *p = &s->pipes[i];
        const uint32_t n = cfg->threads_per_pipe;
        p->cfg = &s->cfg;
        p->index = i;
        p->log = s->log;
        p->th = calloc(n, sizeof *p->th);
        p->heap = calloc(n, sizeof *p->heap);
        p->arrived = calloc(n, sizeof *p->arrived);
        p->trav_q = calloc(n, sizeof *p->trav_q);
        ok = p->th && p->heap && p->arrived && p->trav_q && mem_iface_init(&p->mi, &cfg->mem) == 0;
        for (int u = 0; ok && u < UNIT_KINDS; u++)
            ok = (p->queue[u].ready = calloc(ready_words(n), sizeof(uint64_t))) != NULL;
    }
    if (!ok) {
        cycle_free(s);
        return NULL;
    }
    return s;
}

void cycle_free(cycle_sim *s)
{
    if (!s)
        return;
    for (uint32_t i = 0; s->pipes && i < s->cfg.pipes; i++) {
        pipe_state *p = &s->pipes[i];
        free(p->th);
        free(p->heap);
        free(p->arrived);
        free(p->trav_q);
        for (int u = 0; u < UNIT_KINDS; u++)
            free(p->queue[u].ready);
        mem_iface_free(&p->mi);
    }
    if (s->log)
        fclose(s->log);
    free(s->pipes);
    free(s);
}

void cycle_flush(cycle_sim *s)
{
    for (uint32_t i = 0; i < s->cfg.pipes; i++)
        mem_iface_flush(&s->pipes[i].mi);
}

/* Host threads: worker w simulates pipes w, w + n, ... of each epoch between two barriers. The
 * barriers are set up for the threads that did start, before any of them uses them (the gate). */
typedef struct {
    cycle_sim *sim;
    uint32_t workers, ready;
    pthread_mutex_t lock;
    pthread_cond_t gate;
    pthread_barrier_t start, done;
    uint64_t until;
    int stop;
} host_pool;

typedef struct {
    host_pool *pool;
    uint32_t worker;
} worker_arg;

static void run_share(cycle_sim *s, uint32_t worker, uint32_t workers, uint64_t until)
{
    for (uint32_t i = worker; i < s->cfg.pipes; i += workers)
        pipe_run(&s->pipes[i], until);
}

static void *worker_main(void *arg)
{
    worker_arg *w = arg;
    host_pool *h = w->pool;
    pthread_mutex_lock(&h->lock);
    while (!h->ready)
        pthread_cond_wait(&h->gate, &h->lock);
    pthread_mutex_unlock(&h->lock);
    for (;;) {
        pthread_barrier_wait(&h->start);
        if (h->stop)
            return NULL;
        run_share(h->sim, w->worker, h->workers, h->until);
        pthread_barrier_wait(&h->done);
    }
}

/* Tops up each pipe's tile queue, in pipe order. */
static void controller_refill(cycle_sim *s, uint32_t *next_tile, uint32_t n_tiles)
{
    for (uint32_t i = 0; i < s->cfg.pipes; i++) {
        pipe_state *p = &s->pipes[i];
        while (p->n_tiles < TILE_QUEUE && *next_tile < n_tiles)
            p->tiles[p->n_tiles++] = (*next_tile)++;
    }
}

static void pipe_reset(pipe_state *p, const uint32_t *mem, const rgs_config *rcfg, const uint32_t region[4],
                       uint32_t *pixels, hit_record *hits, pixel_cost *costs)
{
    p->mem = mem;
    p->rcfg = rcfg;
    rgs_image_size(mem, &p->width, &p->height);
    p->rx0 = region[0];
    p->ry0 = region[1];
    p->rx1 = region[2] < p->width ? region[2] : p->width;
    p->ry1 = region[3] < p->height ? region[3] : p->height;
    p->pixels = pixels;
    p->hits = hits;
    p->costs = costs;
    for (uint32_t i = 0; i < p->cfg->threads_per_pipe; i++)
        p->th[i] = (thread){ .state = TH_IDLE, .light_held = UINT32_MAX };
    for (int u = 0; u < UNIT_KINDS; u++) {
        p->queue[u].count = p->queue[u].ptr = 0;
        memset(p->queue[u].ready, 0, ready_words(p->cfg->threads_per_pipe) * sizeof(uint64_t));
        p->free_at[u] = 0;
    }
    p->shade_port_free = p->trav_free = 0;
    p->trav_head = p->trav_n = 0;
    p->heap_n = p->n_tiles = p->have_tile = p->active = 0;
    p->now = p->last_event = 0;
    memset(&p->counters, 0, sizeof p->counters);
    memset(&p->st, 0, sizeof p->st);
    mem_iface_new_frame(&p->mi);
    if (p->probe)
        p->probe(p->probe_arg, p->index, SCHED_FRAME, 0, 0, p->cfg->threads_per_pipe, 0);
}

void cycle_stats_add(cycle_stats *sum, const cycle_stats *s)
{
    for (int u = 0; u < UNIT_KINDS; u++) {
        sum->busy[u] += s->busy[u];
        sum->ops[u] += s->ops[u];
        sum->wait_unit[u] += s->wait_unit[u];
    }
    for (int k = 0; k < ST_KINDS; k++)
        sum->thread_cycles[k] += s->thread_cycles[k];
    for (int k = 0; k < MEM_KINDS; k++) {
        sum->wait_mem[k] += s->wait_mem[k];
        sum->mem.lookups[k] += s->mem.lookups[k];
        sum->mem.hits[k] += s->mem.hits[k];
        sum->mem.bytes[k] += s->mem.bytes[k];
        sum->mem.requests[k] += s->mem.requests[k];
    }
    sum->shade_port_wait += s->shade_port_wait;
    sum->blocks += s->blocks;
    sum->tiles += s->tiles;
}

static void collect(cycle_sim *s, rgs_counters *counters, cycle_stats *st)
{
    memset(counters, 0, sizeof *counters);
    memset(st, 0, sizeof *st);
    st->pipe_cycles_min = UINT64_MAX;
    for (uint32_t i = 0; i < s->cfg.pipes; i++) {
        pipe_state *p = &s->pipes[i];
        const uint64_t end = p->last_event + 1;
        for (uint32_t t = 0; t < s->cfg.threads_per_pipe; t++) { /* close the books at the pipe's end */
            p->now = end;
            leave_state(p, &p->th[t]);
        }
        rgs_counters_add(counters, &p->counters);
        st->pipe_cycles_max = end > st->pipe_cycles_max ? end : st->pipe_cycles_max;
        st->pipe_cycles_min = end < st->pipe_cycles_min ? end : st->pipe_cycles_min;
        cycle_stats pipe = p->st;
        pipe.mem = p->mi.stats; /* the pipe's memory interface keeps its own books */
        cycle_stats_add(st, &pipe);
    }
    st->cycles = st->pipe_cycles_max;
}

int cycle_render(cycle_sim *s, const uint32_t *mem, const rgs_config *rcfg, uint32_t *pixels, hit_record *hits,
                 rgs_counters *counters, cycle_stats *stats, cycle_progress_fn progress, void *arg)
{
    const uint32_t all[4] = { 0, 0, UINT32_MAX, UINT32_MAX };
    return cycle_render_region(s, mem, rcfg, all, pixels, hits, counters, stats, progress, arg);
}

int cycle_render_region(cycle_sim *s, const uint32_t *mem, const rgs_config *rcfg, const uint32_t region[4],
                        uint32_t *pixels, hit_record *hits, rgs_counters *counters, cycle_stats *stats,
                        cycle_progress_fn progress, void *arg)
{
    for (uint32_t i = 0; i < s->cfg.pipes; i++)
        pipe_reset(&s->pipes[i], mem, rcfg, region, pixels, hits, s->costs);
    const pipe_state *p0 = &s->pipes[0];
    const uint32_t width = p0->rx1 > p0->rx0 ? p0->rx1 - p0->rx0 : 0, height = p0->ry1 > p0->ry0 ? p0->ry1 - p0->ry0 : 0;
    const uint32_t tile = s->cfg.tile, n_tiles = ((width + tile - 1) / tile) * ((height + tile - 1) / tile);
    const uint64_t all_blocks = (uint64_t)((width + 1) / 2) * ((height + 1) / 2);
    const uint32_t want = s->cfg.host_threads < s->cfg.pipes ? s->cfg.host_threads : s->cfg.pipes;
    pthread_t *tid = calloc(want ? want : 1, sizeof *tid);
    worker_arg *wa = calloc(want ? want : 1, sizeof *wa);
    host_pool h = { .sim = s, .workers = 1 };
    if (!tid || !wa) {
        free(tid);
        free(wa);
        return -1;
    }
    pthread_mutex_init(&h.lock, NULL);
    pthread_cond_init(&h.gate, NULL);
    for (uint32_t i = 1; i < want; i++) {
        wa[i] = (worker_arg){ &h, i };
        if (pthread_create(&tid[i], NULL, worker_main, &wa[i]) != 0)
            break; /* fewer host threads: the same result, later */
        h.workers++;
    }
    pthread_barrier_init(&h.start, NULL, h.workers);
    pthread_barrier_init(&h.done, NULL, h.workers);
    pthread_mutex_lock(&h.lock);
    h.ready = 1;
    pthread_cond_broadcast(&h.gate);
    pthread_mutex_unlock(&h.lock);
    uint32_t next_tile = 0;
    int stopped = 0;
epochs:
    for (;;) {
        controller_refill(s, &next_tile, n_tiles);
        int busy = 0;
        uint64_t blocks = 0;
        for (uint32_t i = 0; i < s->cfg.pipes; i++) {
            busy |= pipe_busy(&s->pipes[i]);
            blocks += s->pipes[i].st.blocks;
        }
        if (!busy)
            break;
        if (progress && (stopped = progress(blocks, all_blocks, arg)) != 0)
            break; /* the host threads wait at the start barrier: released below with stop */
        h.until += s->cfg.epoch;
        pthread_barrier_wait(&h.start);
        run_share(s, 0, h.workers, h.until);
        pthread_barrier_wait(&h.done);
        if (s->trace)
            cycle_trace_epoch(s->trace, h.until);
    }
    h.stop = 1;
    pthread_barrier_wait(&h.start);
    for (uint32_t i = 1; i < h.workers; i++)
        pthread_join(tid[i], NULL);
    pthread_barrier_destroy(&h.start);
    pthread_barrier_destroy(&h.done);
    pthread_cond_destroy(&h.gate);
    pthread_mutex_destroy(&h.lock);
    free(tid);
    free(wa);
    if (stopped)
        return 1;
    if (s->trace)
        cycle_trace_epoch(s->trace, UINT64_MAX);
    collect(s, counters, stats);
    return 0;
}
