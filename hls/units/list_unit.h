/*
 * Mailboxed list unit (paper section 3, Figure 2: path c; the mailboxes of section 2.3 against
 * visiting an item twice in the cells of a kd-tree).
 *
 * What it does: one entry per operation of the list of the leaf (or grid cell) the traversal unit
 * reported: it reads the entry (an instance at the top level, a triangle below) and checks it
 * against the mailbox of every ray of the leaf that is still traced. A ray whose mailbox holds the
 * entry skips it (at the top level: an instance already visited gave the ray its closest hit in
 * it; below: a triangle already intersected in another cell); otherwise the mailbox remembers the
 * entry, round robin over TRACE_MAILBOX = 8 entries, and the ray needs it. The rays that need the
 * entry go on to the transformation unit (path d for an instance, path e for a triangle). Per ray
 * and level one mailbox; a level's mailboxes start empty with the packet (top level) or with each
 * visit of an instance (bottom level).
 *
 * Latency 3 cycles (rtl/list_unit.sv: mailbox and list entry read, 32 comparators, mailbox
 * update; the cycle model's default, docs/cycle-model.md), throughput one list entry per cycle
 * (1 issue slot). rtl/list_unit.sv is co-simulated against this file (rtl/tb/tb_list.cpp). Operators: no floating point (docs/synth.md);
 * per ray 8 32-bit equality comparators against the mailbox entries (32 for the packet), a
 * 3-bit round-robin pointer, and the list address adder.
 */
#ifndef SAARCOR_LIST_UNIT_H
#define SAARCOR_LIST_UNIT_H

#include "trace.h"

/* Empties the mailboxes of a level (one per ray). */
void list_mailboxes_clear(trace_mailbox box[TRACE_PACKET]);

/* One entry of w's current leaf (w->leaf_first + w->k in the lists at w->lists): reads it into
 * *key, moves w->k on, and returns the rays of the leaf (w->leaf_mask & alive) that need it after
 * their mailbox check in box (counts list_entries and mailbox_skips). */
uint32_t list_unit_entry(const uint32_t *mem, trav_walker *w, trace_mailbox box[TRACE_PACKET], uint32_t alive,
                         uint32_t *key, unit_op *op, trace_counters *c);

#endif
