/*
 * saarcor render --capture-unit-io DIR: the inputs and outputs of the datapath units while a
 * frame renders, as hex vectors for the RTL co-simulation (rtl/tb/tb_units.cpp): DIR/xform.hex
 * (12 matrix words, 3 vector words, point flag, 3 result words), DIR/isect.hex (O', D', the
 * rebase distance te, tmin, tmax; hit, t, u, v, cos), DIR/trav.hex (axis, split, mask, 4 x O, 4 x D, 4 x tn, 4 x tf; child
 * masks, near-left bits, 4 x left tn, tf, right tn, tf). The hls/ units are not touched: the
 * program is linked with --wrap for xform_point, xform_vector, isect_unit_rebased and
 * trav_node_split, and the wrappers record the calls while capturing is on (at most `limit`
 * transactions per unit; recorded in call order, which with several host threads interleaves).
 */
#ifndef SAARCOR_CAPTURE_H
#define SAARCOR_CAPTURE_H

#include <stdint.h>

/* 0, or -1 with a message in err if DIR cannot be made or its files written. */
int capture_start(const char *dir, uint64_t limit, char *err, unsigned errlen);

/* Transactions recorded per unit: xform, isect, trav. */
void capture_counts(uint64_t out[3]);

/* Closes the files; 0, or -1 if writing failed. */
int capture_stop(void);

#endif
