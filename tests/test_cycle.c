/*
 * Tests of the cycle-level model (tb/cycle): the image, the primary hits and every work counter
 * equal the functional mode's bit for bit for several scenes, thread counts and pipe counts; the
 * cycle count is deterministic (repeated runs, host thread counts, units stepped in reverse
 * order); caches: a second identical frame hits 100% when the cache holds the whole image, a
 * tiny cache misses, and the bytes over the port equal the misses times the line size (every kind,
 * shading too; an uncached kind moves exactly its words); the shading cache on a known pattern; more
 * threads per pipe hide latency (fewer cycles), and a slower memory costs cycles; every operation
 * is charged the latency of its kind.
 */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "cycle_sim.h"
#include "memimage.h"
#include "rgs.h"
#include "scenes.h"

enum { W = 40, H = 30 };

typedef struct {
    scene s;
    mi_builder *b;
    const uint32_t *mem;
    uint32_t words;
} image;

static void image_build(image *im, const char *name)
{
    char err[256];
    const scene_gen_params gp = { 1, 0 };
    assert_int_equal(scene_generator_find(name)->build(&im->s, &gp, err, sizeof err), 0);
    assert_int_equal(scene_evaluate(&im->s, 0.5, 0), 0);
    mi_params p;
    mi_params_default(&p);
    p.width = W;
    p.height = H;
    im->b = mi_build(&im->s, &p, err, sizeof err);
    assert_non_null(im->b);
    im->mem = mi_words(im->b, &im->words);
}

static void image_free(image *im)
{
    mi_free(im->b);
    scene_free(&im->s);
}

typedef struct {
    uint32_t rgb[W * H];
    hit_record hits[W * H];
    rgs_counters c;
} frame;

static void functional(const uint32_t *mem, const rgs_config *rc, frame *f)
{
    memset(f, 0, sizeof *f);
    for (uint32_t y = 0; y < H; y += 2)
        for (uint32_t x = 0; x < W; x += 2) {
            uint32_t rgb[4];
            hit_record h[4];
            rgs_render_block(mem, rc, x, y, rgb, h, &f->c);
            for (int i = 0; i < 4; i++) {
                f->rgb[(y + (uint32_t)(i >> 1)) * W + x + (uint32_t)(i & 1)] = rgb[i];
                f->hits[(y + (uint32_t)(i >> 1)) * W + x + (uint32_t)(i & 1)] = h[i];
            }
        }
}

static void cycle(cycle_sim *sim, const uint32_t *mem, const rgs_config *rc, frame *f, cycle_stats *st)
{
    memset(f, 0, sizeof *f);
    assert_int_equal(cycle_render(sim, mem, rc, f->rgb, f->hits, &f->c, st, NULL, NULL), 0);
}

static void cycle_with(const cycle_config *cfg, const uint32_t *mem, const rgs_config *rc, frame *f, cycle_stats *st)
{
    cycle_sim *sim = cycle_create(cfg);
    assert_non_null(sim);
    cycle(sim, mem, rc, f, st);
    cycle_free(sim);
}

static void assert_same_frame(const frame *a, const frame *b)
{
    assert_memory_equal(a->rgb, b->rgb, sizeof a->rgb);
    for (size_t i = 0; i < W * H; i++) {
        assert_int_equal(a->hits[i].instance, b->hits[i].instance);
        assert_int_equal(a->hits[i].triangle, b->hits[i].triangle);
        assert_int_equal(a->hits[i].t, b->hits[i].t);
    }
    assert_memory_equal(&a->c, &b->c, sizeof a->c);
}

static const rgs_config full = { 2, 1, TRAV_STACK };

/* Every scene, T in {1, 5, 64}, P in {1, 3}: the functional mode's bits and counters. */
static void same_bits_as_functional(void **state)
{
    (void)state;
    static const char *const names[] = { "cornell", "room", "plants", "terrain", "animated" };
    static frame ref, got;
    for (size_t k = 0; k < sizeof names / sizeof *names; k++) {
        image im;
        image_build(&im, names[k]);
        functional(im.mem, &full, &ref);
        const uint32_t threads[] = { 1, 5, 64 }, pipes[] = { 1, 3 };
        for (int t = 0; t < 3; t++)
            for (int p = 0; p < 2; p++) {
                cycle_config cfg;
                cycle_config_default(&cfg);
                cfg.threads_per_pipe = threads[t];
                cfg.pipes = pipes[p];
                cfg.tile = 8;
                cycle_stats st;
                cycle_with(&cfg, im.mem, &full, &got, &st);
                assert_same_frame(&ref, &got);
                assert_int_equal(st.blocks, (W / 2) * (H / 2));
                assert_true(st.cycles > 0);
            }
        image_free(&im);
    }
}

/* The same cycle count on every run, for 1, 2 and 4 host threads, and with the units stepped in
 * reverse order. */
static void deterministic(void **state)
{
    (void)state;
    static frame f;
    image im;
    image_build(&im, "room");
    cycle_config cfg;
    cycle_config_default(&cfg);
    cfg.pipes = 4;
    cfg.threads_per_pipe = 16;
    cfg.tile = 4;
    cycle_stats first, st;
    cycle_with(&cfg, im.mem, &full, &f, &first);
    const uint32_t host[] = { 1, 2, 4, 3 };
    for (int i = 0; i < 4; i++) {
        cfg.host_threads = host[i];
        cfg.reverse_order = i == 3;
        cycle_with(&cfg, im.mem, &full, &f, &st);
        assert_memory_equal(&first, &st, sizeof st);
    }
    image_free(&im);
}

/* A cache holding the whole image: the second identical frame hits 100%. A tiny cache misses;
 * the bytes over the port are misses x line size for every cached kind. */
static void caches(void **state)
{
    (void)state;
    static frame f;
    image im;
    image_build(&im, "cornell");
    cycle_config cfg;
    cycle_config_default(&cfg);
    for (int k = 0; k < MI_CACHED_KINDS; k++)
        cfg.mem.cache[k] = (cache_config){ 4 * 1024 * 1024, 16 };
    assert_true(im.words * 4u <= 4u * 1024 * 1024);
    cycle_sim *sim = cycle_create(&cfg);
    assert_non_null(sim);
    cycle_stats cold, warm;
    cycle(sim, im.mem, &full, &f, &cold);
    cycle(sim, im.mem, &full, &f, &warm);
    for (int k = 0; k < MI_CACHED_KINDS; k++) {
        assert_true(cold.mem.lookups[k] > 0);
        assert_true(cold.mem.hits[k] < cold.mem.lookups[k] || k == MEM_NODES); /* cornell: few nodes */
        assert_int_equal(warm.mem.hits[k], warm.mem.lookups[k]);
        assert_int_equal(warm.mem.bytes[k], 0);
    }
    assert_true(warm.cycles <= cold.cycles);
    cycle_flush(sim);
    cycle(sim, im.mem, &full, &f, &warm);
    assert_memory_equal(&cold.mem, &warm.mem, sizeof cold.mem); /* flushed: cold again */
    cycle_free(sim);

    for (int k = 0; k < MI_CACHED_KINDS; k++)
        cfg.mem.cache[k] = (cache_config){ 64, 16 };
    cycle_with(&cfg, im.mem, &full, &f, &cold);
    for (int k = 0; k < MI_CACHED_KINDS; k++) {
        const uint64_t misses = cold.mem.lookups[k] - cold.mem.hits[k];
        assert_true(misses > 0);
        assert_int_equal(cold.mem.bytes[k], misses * 16);
        assert_int_equal(cold.mem.requests[k], misses);
    }
    cfg.mem.cache[MEM_SHADING].size_bytes = 0; /* uncached: every word read goes over the port */
    cycle_with(&cfg, im.mem, &full, &f, &cold);
    assert_int_equal(cold.mem.bytes[MEM_SHADING], 4 * f.c.trace.words[MEM_SHADING]);
    assert_int_equal(cold.mem.lookups[MEM_SHADING], 0);
    image_free(&im);
}

/* The shading cache on a known pattern (64 bytes, 16-byte lines: 4 lines, word w in line w / 4
 * at index (w / 4) % 4): misses fill whole lines, a read spanning two lines looks up both, a line
 * 64 bytes further evicts, a hit while the line is in flight waits for its arrival, and a hit
 * after a miss waits for the miss's answer (answers in request order). */
static void shading_cache_pattern(void **state)
{
    (void)state;
    mem_config cfg = { .latency = 10, .mbps = 1000, .clock_mhz = 90 };
    cfg.cache[MEM_SHADING] = (cache_config){ 64, 16 };
    mem_iface m;
    assert_int_equal(mem_iface_init(&m, &cfg), 0);
    const uint64_t fill = mem_iface_read(&m, MEM_SHADING, 0, 4, 0); /* line 0: miss */
    assert_true(fill > 10);
    assert_int_equal(mem_iface_read(&m, MEM_SHADING, 1, 2, 0), fill); /* in flight: waits for it */
    const uint64_t second = mem_iface_read(&m, MEM_SHADING, 3, 2, fill); /* lines 0 (hit) and 1 (miss) */
    assert_true(second > fill);
    assert_int_equal(mem_iface_read(&m, MEM_SHADING, 4, 1, fill), second); /* line 1 in flight */
    assert_int_equal(mem_iface_read(&m, MEM_SHADING, 2, 1, 1000), 1000); /* arrived: a hit costs nothing */
    const uint64_t evict = mem_iface_read(&m, MEM_SHADING, 16, 1, 1000); /* line 4 evicts line 0 */
    assert_true(evict > 1000);
    /* answers leave in request order (rtl/cache_read.sv): a hit after the miss waits for it */
    assert_int_equal(mem_iface_read(&m, MEM_SHADING, 4, 1, 1001), evict); /* line 1: a hit */
    mem_iface_read(&m, MEM_SHADING, 0, 1, 1000);  /* miss again */
    assert_int_equal(m.stats.lookups[MEM_SHADING], 9);
    assert_int_equal(m.stats.hits[MEM_SHADING], 5);
    assert_int_equal(m.stats.requests[MEM_SHADING], 4);
    assert_int_equal(m.stats.bytes[MEM_SHADING], 4 * 16);
    assert_int_equal(m.stats.lookups[MEM_NODES], 0); /* the other kinds are untouched */
    mem_iface_free(&m);
}

/* Latency hiding: 32 threads take far fewer cycles than 1; a slow memory port costs cycles;
 * usage never exceeds the issue slots. */
static void threads_hide_latency(void **state)
{
    (void)state;
    static frame f;
    image im;
    image_build(&im, "room");
    cycle_config cfg;
    cycle_config_default(&cfg);
    cycle_stats one, many, slow;
    cfg.threads_per_pipe = 1;
    cycle_with(&cfg, im.mem, &full, &f, &one);
    cfg.threads_per_pipe = 32;
    cycle_with(&cfg, im.mem, &full, &f, &many);
    assert_true(many.cycles * 4 < one.cycles);
    for (int u = 0; u < UNIT_KINDS; u++)
        assert_true(many.busy[u] <= many.cycles);
    cfg.mem.mbps = 20;
    cycle_with(&cfg, im.mem, &full, &f, &slow);
    assert_true(slow.cycles > many.cycles);
    image_free(&im);
}

/* Every operation is charged the latency of its kind (trace.h OP_*): with one thread nothing
 * overlaps (the thread waits for each operation's reads and result before the next), so one more
 * cycle of kind k's latency adds exactly the frame's operations of kind k, counted here by stepping
 * the blocks as the functional mode does. A surface operation is charged its latency only when a
 * ray hit: one more cycle of surface_hit adds a cycle per hit after its first (rgs_surface's front
 * reads the hits in turn), one more of surface_miss a cycle per surface operation without a hit
 * (its misses pass rgs_surface in a cycle each). */
/* Steps every block of the frame as the functional mode does, handing each operation to visit. */
static void for_each_op(const image *im, void (*visit)(const unit_op *op, void *ctx), void *ctx)
{
    for (uint32_t y = 0; y < H; y += 2)
        for (uint32_t x = 0; x < W; x += 2) {
            static rgs_block b;
            unit_op op;
            rgs_counters c = { 0 };
            rgs_block_begin(im->mem, x, y, &b);
            while (rgs_step(im->mem, &full, &b, &op, &c))
                visit(&op, ctx);
        }
}

typedef struct {
    uint64_t count[OP_KINDS], further_hits, misses; /* count[OP_SURFACE]: the surface operations with a hit */
} kind_counts;

static void count_kind(const unit_op *op, void *ctx)
{
    kind_counts *k = ctx;
    const int miss = op->kind == OP_SURFACE && op->hits == 0;
    k->count[op->kind] += !miss;
    k->misses += miss;
    k->further_hits += op->kind == OP_SURFACE && op->hits ? op->hits - 1 : 0;
}

/* One more cycle of each latency adds the cycles kind_counts predicts; `every_kind`: the scene has
 * operations of every kind and surfaces with several hits. Returns the surfaces without a hit. */
static uint64_t check_latencies(const char *name, int every_kind)
{
    static frame f;
    image im;
    image_build(&im, name);
    kind_counts ops = { { 0 }, 0, 0 };
    for_each_op(&im, count_kind, &ops);
    cycle_config cfg;
    cycle_config_default(&cfg);
    cfg.threads_per_pipe = 1;
    cycle_stats base, more;
    cycle_with(&cfg, im.mem, &full, &f, &base);
    for (int k = 0; k < OP_KINDS; k++) {
        assert_true(!every_kind || ops.count[k] > 0); /* the room: instances, leaves, shadows, children */
        cfg.latency[k]++;
        cycle_with(&cfg, im.mem, &full, &f, &more);
        cfg.latency[k]--;
        assert_int_equal(more.cycles - base.cycles, ops.count[k]);
    }
    assert_true(!every_kind || ops.further_hits > 0);
    uint32_t *extra[2] = { &cfg.surface_hit, &cfg.surface_miss };
    const uint64_t want[2] = { ops.further_hits, ops.misses };
    for (int e = 0; e < 2; e++) {
        ++*extra[e];
        cycle_with(&cfg, im.mem, &full, &f, &more);
        --*extra[e];
        assert_int_equal(more.cycles - base.cycles, want[e]);
    }
    image_free(&im);
    return ops.misses;
}

static void latency_per_kind(void **state)
{
    (void)state;
    check_latencies("room", 1);
    assert_true(check_latencies("cornell", 0) > 0); /* rays past the box: packets without a hit */
}

/* rgs_ctrl holds the record of its last light and reads another light's before rgs_light starts:
 * with one thread, one more cycle of the shading cache's hit adds a cycle per light operation
 * whose light differs from the one before it: once per frame in cornell (one light), every light
 * operation in the room (2 lights, each packet's in turn). */
typedef struct {
    uint64_t lights, reads;
    uint32_t held;
} light_reads;

static void count_light_read(const unit_op *op, void *ctx)
{
    light_reads *l = ctx;
    if (op->kind != OP_LIGHT)
        return;
    l->lights++;
    l->reads += op->read[0].addr != l->held;
    l->held = op->read[0].addr;
}

static void light_record_held(void **state)
{
    (void)state;
    static frame f;
    const char *const scenes[2] = { "cornell", "room" };
    for (int k = 0; k < 2; k++) {
        image im;
        image_build(&im, scenes[k]);
        light_reads l = { 0, 0, UINT32_MAX };
        for_each_op(&im, count_light_read, &l);
        const uint64_t lights = l.lights, reads = l.reads;
        assert_true(k == 0 ? reads == 1 && lights > 1 : reads == lights);
        cycle_config cfg;
        cycle_config_default(&cfg);
        cfg.threads_per_pipe = 1;
        cycle_stats base, more;
        cycle_with(&cfg, im.mem, &full, &f, &base);
        cfg.shade_hit++;
        cycle_with(&cfg, im.mem, &full, &f, &more);
        assert_int_equal(more.cycles - base.cycles, reads);
        image_free(&im);
    }
}

/* The RGS's block controllers share one line port to the shading cache: one thread never waits
 * for it (its last surface's words are read long before its next), 8 threads do. */
static void shading_port_shared(void **state)
{
    (void)state;
    static frame f;
    image im;
    image_build(&im, "cornell");
    cycle_config cfg;
    cycle_config_default(&cfg);
    cycle_stats one, eight;
    cfg.threads_per_pipe = 1;
    cycle_with(&cfg, im.mem, &full, &f, &one);
    cfg.threads_per_pipe = 8;
    cycle_with(&cfg, im.mem, &full, &f, &eight);
    assert_int_equal(one.shade_port_wait, 0);
    assert_true(eight.shade_port_wait > 0);
    image_free(&im);
}

/* The RGS's port carries the shading cache's lines: a read of n words from word address a takes
 * ceil((a mod 4 + n) / 4) of its 16-byte lines (a light's 16 words 4 or 5, a word 1, none 0), other
 * kinds none; 8-byte lines take twice as many. */
static void shading_port_lines(void **state)
{
    (void)state;
    cycle_config cfg;
    cycle_config_default(&cfg);
    unit_op op = { 0 };
    const uint32_t reads[][3] = { { MEM_SHADING, 64, 16 }, { MEM_SHADING, 65, 16 }, { MEM_SHADING, 7, 1 },
                                  { MEM_SHADING, 9, 0 }, { MEM_MATRICES, 0, 10 }, { MEM_SHADING, 3, 2 } };
    const uint64_t lines16[] = { 4, 5, 1, 0, 0, 2 }, lines8[] = { 8, 9, 1, 0, 0, 2 };
    for (uint32_t k = 0; k < sizeof reads / sizeof reads[0]; k++) {
        op.n_reads = 1;
        op.read[0].kind = reads[k][0], op.read[0].addr = reads[k][1], op.read[0].words = reads[k][2];
        cfg.mem.cache[MEM_SHADING].line_bytes = 16;
        assert_int_equal(cycle_shading_lines(&cfg, &op), lines16[k]);
        cfg.mem.cache[MEM_SHADING].line_bytes = 8;
        assert_int_equal(cycle_shading_lines(&cfg, &op), lines8[k]);
    }
    op.n_reads = 3; /* an operation's reads add up */
    for (uint32_t k = 0; k < 3; k++)
        op.read[k].kind = reads[k][0], op.read[k].addr = reads[k][1], op.read[k].words = reads[k][2];
    cfg.mem.cache[MEM_SHADING].line_bytes = 16;
    assert_int_equal(cycle_shading_lines(&cfg, &op), 4 + 5 + 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(same_bits_as_functional),
        cmocka_unit_test(deterministic),
        cmocka_unit_test(caches),
        cmocka_unit_test(shading_cache_pattern),
        cmocka_unit_test(threads_hide_latency),
        cmocka_unit_test(latency_per_kind),
        cmocka_unit_test(light_record_held),
        cmocka_unit_test(shading_port_shared),
        cmocka_unit_test(shading_port_lines),
    };
    return cmocka_run_group_tests_name("cycle model (tb/cycle)", tests, NULL, NULL);
}
