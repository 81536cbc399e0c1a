/*
 * Per-pixel cost (render --aov, --heatmap; docs/cli.md, docs/cycle-model.md): the work counters
 * of the units (trace_counters) attributed to the pixels whose rays they served, measured in the
 * simulator around each rgs_step without any state in the hardware units.
 *
 * Lane i of every packet of a 2x2 block (primary, shadow, reflection, transmission) serves pixel
 * i of the block, so an operation serves the pixels of the rays in its mask. The mask of each
 * counted operation is read from the block's trace_state just before the step:
 *   traversal step      the rays of the kd-tree entry (or cursor group) as issued: entry mask & alive
 *   list entry          the rays of the current leaf still alive: leaf mask & alive
 *   transformation      the rays that need the instance or triangle (need): its issue slots
 *   intersection        the rays that need the triangle (need): one test each
 * An operation's count is split evenly over the rays of its mask. Counts are kept in twelfths
 * (PC_UNIT = 12 = lcm(1, 2, 3, 4)), so that a split over 1..4 rays is exact and the per-pixel
 * counts of a frame sum exactly to the --stats totals (x 12).
 * Cycle mode adds the cycles a block's thread held it (from taking the block to its last result:
 * in units, queued and waiting for memory), split evenly over the block's pixels in the image;
 * they sum to thread_cycles in_unit + queued + memory.
 */
#ifndef SAARCOR_PIXEL_COST_H
#define SAARCOR_PIXEL_COST_H

#include <stdint.h>

#include "rgs.h"

#define PC_UNIT 12u

enum { PC_TRAVERSAL_STEPS, PC_LIST_ENTRIES, PC_INTERSECTIONS, PC_TRANSFORMATIONS, PC_CYCLES, PC_KINDS };

/* The channel names (also the --stats keys of the totals, but "cycles") and their units. */
extern const char *const pc_names[PC_KINDS];
extern const char *const pc_units[PC_KINDS];

/* One pixel's cost, in twelfths of a count (twelfths of a cycle). */
typedef struct {
    uint64_t v[PC_KINDS];
} pixel_cost;

/* rgs_step, with the counter increments of the step attributed to cost[lane] (cost may be NULL:
 * a plain rgs_step). */
int pc_step(const uint32_t *mem, const rgs_config *cfg, rgs_block *b, unit_op *op, rgs_counters *c,
            pixel_cost cost[TRACE_PACKET]);

/* rgs_render_block through pc_step: the same bits, and the block's costs per lane (zeroed first). */
void pc_render_block(const uint32_t *mem, const rgs_config *cfg, uint32_t x0, uint32_t y0, uint32_t rgb[],
                     hit_record primary_hits[], rgs_counters *c, pixel_cost cost[TRACE_PACKET]);

/* Adds `amount` (whole units) split evenly over the lanes of block (x0, y0) inside a w x h image. */
void pc_split_block(pixel_cost cost[TRACE_PACKET], int kind, uint64_t amount, uint32_t x0, uint32_t y0, uint32_t w,
                    uint32_t h);

/* Stores a block's lane costs into the per-pixel array of a w x h image (pixels outside skipped). */
void pc_store_block(pixel_cost *costs, const pixel_cost cost[TRACE_PACKET], uint32_t x0, uint32_t y0, uint32_t w,
                    uint32_t h);

#endif
