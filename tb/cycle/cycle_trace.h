/*
 * Waveforms of the cycle model (render --vcd, --usage-plot; docs/cycle-model.md): the signals of
 * every pipe as a value change dump (IEEE 1364 VCD) for a window of cycles, and each unit's busy
 * cycles per controller epoch for the utilisation plot.
 *
 * Per pipe and unit: busy (an issue slot is in use; the traversal unit's: a trav_node slot),
 * issue (an operation issues this cycle), queue_depth and thread_id (of the operation in those
 * slots, x when idle); per cache:
 * lookups and misses in the cycle, fills (lines requested and not arrived); the memory port's
 * outstanding transfers; threads in flight (holding a block).
 *
 * Why it looks like this: the simulator skips cycles in which nothing happens and runs pipes in
 * parallel between epochs, so each pipe records its value changes with their cycle (a signal that
 * returns to rest later, such as busy after its slots, keeps that cycle pending until it is
 * reached), and after each epoch the changes of all pipes are merged in (cycle, pipe, order) and
 * written. The file is therefore the same for any host thread count.
 */
#ifndef SAARCOR_CYCLE_TRACE_H
#define SAARCOR_CYCLE_TRACE_H

#include <stddef.h>
#include <stdint.h>

#include "cycle_sim.h"

typedef struct trace_pipe trace_pipe;

/* A trace of one frame. vcd_path NULL: only the busy cycles per epoch (for the plot). The window
 * is cycles [from, to). NULL if out of memory or the file cannot be created (err says which). */
cycle_trace *cycle_trace_open(const char *vcd_path, uint64_t from, uint64_t to, const cycle_config *cfg, char *err,
                              size_t errlen);

/* Ends the frame at cycle `cycles`: the file is complete and renamed into place; frees tr (read
 * cycle_trace_usage first). 0, or -1 with err. */
int cycle_trace_close(cycle_trace *tr, uint64_t cycles, char *err, size_t errlen);

/* Drops the trace and its unfinished file (a stopped frame). */
void cycle_trace_abort(cycle_trace *tr);

/* The recorder of pipe i. */
trace_pipe *cycle_trace_pipe(cycle_trace *tr, uint32_t i);

/* Called by the simulator after every epoch, with every pipe's changes before `until` final
 * (UINT64_MAX: the frame is done): writes them. */
void cycle_trace_epoch(cycle_trace *tr, uint64_t until);

/* Busy cycles of unit u per epoch, summed over pipes: *n epochs of cfg->epoch cycles (the caller
 * frees the array). NULL if out of memory. */
uint64_t *cycle_trace_usage(const cycle_trace *tr, int u, size_t *n);

/* ---- the simulator's hooks (one pipe, in its own host thread; t is the current cycle) ---------- */

/* Unit u issues an operation. */
void trace_issue(trace_pipe *tp, int u, uint64_t t);
/* Thread tid's operation holds unit u's datapath for `slots` cycles from t (the issue slots; the
 * traversal unit's trav_node slots, which come after its issue). */
void trace_busy(trace_pipe *tp, int u, uint64_t t, uint32_t tid, uint32_t slots);
void trace_queue(trace_pipe *tp, int u, uint64_t t, uint32_t depth);
void trace_threads(trace_pipe *tp, uint64_t t, uint32_t active);

/* The memory interface's probe (mem_iface.h). */
void trace_mem(void *tp, uint32_t kind, int what, uint64_t t, uint64_t arrive);

#endif
