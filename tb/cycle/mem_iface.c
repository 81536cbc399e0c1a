/* Memory interface of one DynRTP: see mem_iface.h. */
#include "mem_iface.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FX 65536u

int mem_iface_init(mem_iface *m, const mem_config *cfg)
{
    memset(m, 0, sizeof *m);
    m->cfg = *cfg;
    m->fx_per_byte = (uint64_t)llround(cfg->clock_mhz / cfg->mbps * FX);
    for (int k = 0; k < MI_CACHED_KINDS; k++) {
        dm_cache *c = &m->cache[k];
        c->line_bytes = cfg->cache[k].line_bytes;
        c->lines = cfg->cache[k].size_bytes / (c->line_bytes ? c->line_bytes : 1);
        if (!c->lines)
            continue;
        c->tag = calloc(c->lines, sizeof *c->tag);
        c->valid_at = calloc(c->lines, sizeof *c->valid_at);
        if (!c->tag || !c->valid_at) {
            mem_iface_free(m);
            return -1;
        }
    }
    return 0;
}

void mem_iface_free(mem_iface *m)
{
    for (int k = 0; k < MI_CACHED_KINDS; k++) {
        free(m->cache[k].tag);
        free(m->cache[k].valid_at);
        m->cache[k].tag = NULL;
        m->cache[k].valid_at = NULL;
    }
}

void mem_iface_flush(mem_iface *m)
{
    for (int k = 0; k < MI_CACHED_KINDS; k++)
        if (m->cache[k].lines)
            memset(m->cache[k].tag, 0, m->cache[k].lines * sizeof *m->cache[k].tag);
}

void mem_iface_new_frame(mem_iface *m)
{
    for (int k = 0; k < MI_CACHED_KINDS; k++)
        if (m->cache[k].lines)
            memset(m->cache[k].valid_at, 0, m->cache[k].lines * sizeof *m->cache[k].valid_at);
    m->port_free = 0;
    memset(m->answer_at, 0, sizeof m->answer_at);
    memset(&m->stats, 0, sizeof m->stats);
}

/* One transfer of n bytes over the port, requested at cycle now: the cycle its data arrives. It
 * starts the cycle after at the earliest (rtl/mem_port.sv: each requester's queue). */
static uint64_t port_transfer(mem_iface *m, uint32_t kind, uint64_t bytes, uint64_t now)
{
    const uint64_t start = m->port_free > (now + 1) * FX ? m->port_free : (now + 1) * FX;
    m->port_free = start + bytes * m->fx_per_byte;
    m->stats.bytes[kind] += bytes;
    m->stats.requests[kind]++;
    return (m->port_free + FX - 1) / FX + m->cfg.latency;
}

uint64_t mem_iface_read(mem_iface *m, uint32_t kind, uint32_t word_addr, uint32_t words, uint64_t now)
{
    if (kind >= MI_CACHED_KINDS || !m->cache[kind].lines) {
        const uint64_t at = port_transfer(m, kind, 4ull * words, now);
        if (m->probe)
            m->probe(m->probe_arg, kind, MI_UNCACHED, now, at);
        return at;
    }
    dm_cache *c = &m->cache[kind];
    const uint64_t first = 4ull * word_addr / c->line_bytes, last = (4ull * (word_addr + words) - 1) / c->line_bytes;
    uint64_t ready = now;
    for (uint64_t line = first; line <= last; line++) {
        const uint32_t i = (uint32_t)(line % c->lines);
        const int hit = c->tag[i] == line + 1;
        m->stats.lookups[kind]++;
        m->stats.hits[kind] += (uint64_t)hit;
        if (!hit) {
            c->tag[i] = line + 1;
            c->valid_at[i] = port_transfer(m, kind, c->line_bytes, now);
        }
        const uint64_t at = c->valid_at[i] > now ? c->valid_at[i] : now;
        if (m->probe)
            m->probe(m->probe_arg, kind, hit ? MI_HIT : MI_MISS, now, at);
        ready = at > ready ? at : ready;
    }
    /* rtl/cache_read.sv answers in request order: a read after a miss waits for the miss's line */
    ready = m->answer_at[kind] > ready ? m->answer_at[kind] : ready;
    m->answer_at[kind] = ready;
    return ready;
}
