/*
 * render --usage-plot FILE.svg: each unit's utilisation over the frame, per controller epoch (busy
 * issue cycles over the epoch's cycles of all pipes), as an SVG line chart, for those who would
 * rather look than open the waveform. The legend gives each unit's mean, the --stats "usage".
 */
#ifndef SAARCOR_USAGE_PLOT_H
#define SAARCOR_USAGE_PLOT_H

#include <stddef.h>
#include <stdint.h>

#include "cycle_trace.h"

/* Writes the plot of a frame of `cycles` cycles recorded in tr. 0, or -1 with a one-line err. */
int usage_plot_write(const char *path, const cycle_trace *tr, const cycle_config *cfg, uint64_t cycles, char *err,
                     size_t errlen);

#endif
