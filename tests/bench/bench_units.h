/*
 * Our side of bench-render and bench-peers, timed by the harness's bench_time (embree_scene.h)
 * like Embree, so a ratio compares like with like. Two measures:
 *   trace only:   trace_packet over the RGS's primary packets generated before timing (the
 *                 same rays Embree gets), no ray generation, no shading;
 *   frame:        render_region, the functional frame of `saarcor render` (tb/cli/render_region.c):
 *                 per 2x2 block the RGS's ray generation, trace and shading (and with the
 *                 config's shadow and secondary rays), the pixels written as the command does.
 * Neither is linked with the command's capture wrappers (--wrap, for --capture-unit-io).
 */
#ifndef SAARCOR_BENCH_UNITS_H
#define SAARCOR_BENCH_UNITS_H

#include <stdint.h>

#include "rgs.h"
#include "trace.h"

/* Seconds to trace packets [0, n_packets) with trace_packet on `threads` host threads; t[i] is
 * the hit distance of ray i (4 per packet), INFINITY for a miss, of the last run. */
double units_trace_time(const uint32_t *mem, const ray_packet *packets, uint32_t n_packets, uint32_t threads, float *t);

/* Seconds to render the whole frame of the image's camera with cfg through render_region, its
 * block rows split over `threads` host threads (1: exactly `saarcor render --threads 1`); pixels
 * (0xRRGGBB, width x height of the camera) and sum (counters) of the last run. */
double units_frame_time(const uint32_t *mem, const rgs_config *cfg, uint32_t threads, uint32_t *pixels,
                        rgs_counters *sum);

#endif
