/*
 * Small helpers shared by the units (hls/units: the core's router trace.c, the traversal unit
 * trav_*.c, the list unit, the RGS): ray masks, vector components, and the description of a
 * unit operation (unit_op) with the memory words it reads.
 */
#ifndef SAARCOR_TRACE_OPS_H
#define SAARCOR_TRACE_OPS_H

#include "trace.h"

static inline f24_t axis_of(f24_vec3 v, uint32_t k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }

static inline uint32_t bit(uint32_t mask, int i) { return mask >> i & 1u; }

/* Rays in a packet's mask. */
static inline uint32_t count_rays(uint32_t mask) { return bit(mask, 0) + bit(mask, 1) + bit(mask, 2) + bit(mask, 3); }

static inline void op_set(unit_op *op, uint32_t kind, uint32_t slots)
{
    op->kind = kind;
    op->slots = slots;
    op->n_reads = 0;
    op->hits = 0;
}

static inline void op_read(unit_op *op, trace_counters *c, uint32_t kind, uint32_t addr, uint32_t words)
{
    op->read[op->n_reads].kind = kind;
    op->read[op->n_reads].addr = addr;
    op->read[op->n_reads].words = words;
    op->n_reads++;
    c->words[kind] += words;
}

#endif
