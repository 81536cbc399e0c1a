/* Per-pixel cost: see pixel_cost.h. */
#include "pixel_cost.h"

#include <string.h>

const char *const pc_names[PC_KINDS] = { "traversal_steps", "list_entries", "intersections", "transformations", "cycles" };
const char *const pc_units[PC_KINDS] = { "steps", "entries", "tests", "slots", "cycles" };

/* The masks a step may serve, read before it: both levels' walkers, since the level is only
 * meaningful once a packet is being traced (the mask is chosen after the step, by what it counted). */
typedef struct {
    uint32_t level, alive, need, entry[2], leaf[2];
    uint64_t before[PC_CYCLES];
} probe;

static void counts_of(const trace_counters *t, uint64_t n[PC_CYCLES])
{
    n[PC_TRAVERSAL_STEPS] = t->traversal_steps;
    n[PC_LIST_ENTRIES] = t->list_entries;
    n[PC_INTERSECTIONS] = t->intersections;
    n[PC_TRANSFORMATIONS] = t->transformations;
}

static void probe_take(const trace_state *s, const trace_counters *t, probe *p)
{
    p->level = s->level;
    p->alive = s->alive;
    p->need = s->need;
    for (int l = 0; l < 2; l++) {
        p->entry[l] = s->walk[l].cur.mask;
        p->leaf[l] = s->walk[l].leaf_mask;
    }
    counts_of(t, p->before);
}

static uint32_t served(const probe *p, int kind)
{
    const int l = p->level != 0;
    switch (kind) {
    case PC_TRAVERSAL_STEPS: return p->entry[l] & p->alive;
    case PC_LIST_ENTRIES: return p->leaf[l] & p->alive;
    default: return p->need;
    }
}

static uint32_t lanes(uint32_t mask) { return (mask & 1u) + (mask >> 1 & 1u) + (mask >> 2 & 1u) + (mask >> 3 & 1u); }

/* amount whole units split evenly over the lanes of mask (1..4 lanes: PC_UNIT / n is whole). */
static void split(pixel_cost cost[TRACE_PACKET], int kind, uint64_t amount, uint32_t mask)
{
    const uint64_t share = amount * (PC_UNIT / lanes(mask));
    for (int i = 0; i < TRACE_PACKET; i++)
        if (mask >> i & 1u)
            cost[i].v[kind] += share;
}

/* pc_step with costs; apart, so that pc_step without them is a jump to rgs_step (a frame takes some
 * 60 steps a pixel, and the probe's stack frame around each cost 1.6% of a room frame's
 * instructions) */
static __attribute__((noinline)) int step_costed(const uint32_t *mem, const rgs_config *cfg, rgs_block *b, unit_op *op,
                                                 rgs_counters *c, pixel_cost cost[TRACE_PACKET])
{
    probe p;
    probe_take(&b->trace, &c->trace, &p);
    const int more = rgs_step(mem, cfg, b, op, c);
    uint64_t after[PC_CYCLES];
    counts_of(&c->trace, after);
    for (int k = 0; k < PC_CYCLES; k++) {
        if (after[k] == p.before[k])
            continue;
        const uint32_t mask = served(&p, k) & 0xFu;
        split(cost, k, after[k] - p.before[k], mask ? mask : 1u); /* (never empty; lane 0 keeps sums exact) */
    }
    return more;
}

int pc_step(const uint32_t *mem, const rgs_config *cfg, rgs_block *b, unit_op *op, rgs_counters *c,
            pixel_cost cost[TRACE_PACKET])
{
    if (cost)
        return step_costed(mem, cfg, b, op, c, cost);
    return rgs_step(mem, cfg, b, op, c);
}

/* The driver of rgs_render_block, stepping through pc_step (hls/ cannot call into tb/). */
void pc_render_block(const uint32_t *mem, const rgs_config *cfg, uint32_t x0, uint32_t y0, uint32_t rgb[],
                     hit_record primary_hits[], rgs_counters *c, pixel_cost cost[TRACE_PACKET])
{
    rgs_block b;
    unit_op op;
    if (cost)
        memset(cost, 0, TRACE_PACKET * sizeof *cost);
    rgs_block_begin(mem, x0, y0, &b);
    for (uint32_t n = 0; n < RGS_STEP_LIMIT && pc_step(mem, cfg, &b, &op, c, cost); n++)
        ;
    if (primary_hits)
        memcpy(primary_hits, b.primary_hits, sizeof b.primary_hits);
    rgs_block_finish(&b, rgb);
}

static int inside(uint32_t x0, uint32_t y0, int i, uint32_t w, uint32_t h)
{
    return x0 + (uint32_t)(i & 1) < w && y0 + (uint32_t)(i >> 1) < h;
}

void pc_split_block(pixel_cost cost[TRACE_PACKET], int kind, uint64_t amount, uint32_t x0, uint32_t y0, uint32_t w,
                    uint32_t h)
{
    uint32_t mask = 0;
    for (int i = 0; i < TRACE_PACKET; i++)
        mask |= (uint32_t)inside(x0, y0, i, w, h) << i;
    split(cost, kind, amount, mask ? mask : 1u);
}

void pc_store_block(pixel_cost *costs, const pixel_cost cost[TRACE_PACKET], uint32_t x0, uint32_t y0, uint32_t w,
                    uint32_t h)
{
    for (int i = 0; i < TRACE_PACKET; i++)
        if (inside(x0, y0, i, w, h))
            costs[(size_t)(y0 + (uint32_t)(i >> 1)) * w + x0 + (uint32_t)(i & 1)] = cost[i];
}
