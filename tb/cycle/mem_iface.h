/*
 * Memory interface of one DynRTP (paper section 3, "Memory interface"): one direct-mapped cache
 * per data type (kd nodes, leaf lists, matrices, and shading data: the RGS's camera, light,
 * instance, object, shading record, material, texture entry and texel reads), and one memory port
 * shared by all of them with a fixed latency and a bandwidth.
 *
 * Timing: a request that misses occupies the port for line_bytes / bandwidth (tracked in 1/65536
 * cycle, so 1 GB/s at 90 MHz is 0.09 cycles per byte exactly enough) after the port is free and
 * from the cycle after the request on (the port's request queue, rtl/mem_port.sv), and
 * its data arrives `latency` cycles after the transfer ends. A line being filled is tagged at once
 * and valid from its arrival: a second miss on it waits for the same fill (no second transfer).
 * Only the thread that missed waits (the scheduler parks it); nothing else stalls.
 * Deterministic: all state changes happen in the scheduler's commit phase, in thread order.
 */
#ifndef SAARCOR_MEM_IFACE_H
#define SAARCOR_MEM_IFACE_H

#include <stdint.h>

#include "trace.h"

#define MI_CACHED_KINDS MEM_KINDS /* every kind has its cache (size 0: uncached) */

typedef struct {
    uint32_t size_bytes, line_bytes; /* size 0: uncached */
} cache_config;

typedef struct {
    cache_config cache[MI_CACHED_KINDS];
    uint32_t latency;     /* cycles from the end of a transfer to the data at the unit */
    double mbps;          /* port bandwidth in MB/s (10^6 bytes) */
    double clock_mhz;     /* core clock, to turn bandwidth into bytes per cycle */
} mem_config;

typedef struct {
    uint32_t lines, line_bytes;
    uint64_t *tag;      /* line address + 1 per index; 0: empty */
    uint64_t *valid_at; /* cycle the line's data arrives */
} dm_cache;

typedef struct {
    uint64_t lookups[MEM_KINDS], hits[MEM_KINDS]; /* line lookups (cached kinds) */
    uint64_t bytes[MEM_KINDS];                    /* bytes transferred over the port */
    uint64_t requests[MEM_KINDS];                 /* transfers (line fills, uncached reads) */
} mem_stats;

/* What a read did per line (the waveform's probe, cycle_trace.h): a cache hit, a miss that fills
 * the line, or an uncached transfer; arrive is the cycle the transfer's data is at the unit. */
enum { MI_HIT, MI_MISS, MI_UNCACHED };
typedef void (*mem_probe_fn)(void *arg, uint32_t kind, int what, uint64_t now, uint64_t arrive);

typedef struct {
    mem_config cfg;
    dm_cache cache[MI_CACHED_KINDS];
    uint64_t port_free;     /* cycle the port is free, x 65536 */
    uint64_t answer_at[MI_CACHED_KINDS]; /* the cycle of each cache's last answer: answers leave in request order */
    uint64_t fx_per_byte;   /* port occupancy per byte, x 65536 cycles */
    mem_stats stats;
    mem_probe_fn probe; /* NULL: none */
    void *probe_arg;
} mem_iface;

/* 0 on success, -1 out of memory (cfg checked by the caller). */
int mem_iface_init(mem_iface *m, const mem_config *cfg);
void mem_iface_free(mem_iface *m);

/* Empties the caches (a new memory image) and resets the port to cycle 0 (a new frame). */
void mem_iface_flush(mem_iface *m);
void mem_iface_new_frame(mem_iface *m);

/* The cycle at which the data of read r, requested at cycle now, is at the unit (now for a hit). */
uint64_t mem_iface_read(mem_iface *m, uint32_t kind, uint32_t word_addr, uint32_t words, uint64_t now);

#endif
