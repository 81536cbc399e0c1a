/*
 * Top-level functions for high-level synthesis (Vitis HLS, Bambu): one per datapath unit, and the
 * whole DynRTC (ray generation and shading, traversal, list, transformation and intersection
 * units reading the memory image) for a screen tile. They wrap the hls/units functions that the
 * simulator runs, unchanged, behind synthesis interfaces (docs/hls.md):
 *
 *   xform_top, isect_top, trav_top   a stream of transactions in, a stream of results out
 *                                    (axis), II = 1: the units the RTL in rtl/ implements, with
 *                                    the transaction format of `render --capture-unit-io`;
 *   dynrtc_top                       the memory image and the frame buffer on AXI masters
 *                                    (m_axi), the tile and the render options on AXI-Lite.
 *
 * Batches are bounded (HLS_BATCH transactions per call) so that every loop has a static trip
 * count. GCC ignores the pragmas (-Wno-unknown-pragmas); `make hls-check` compiles this folder
 * with hls/units and hls/fp24 alone and proves the subset (no libc, no recursion, no floats, no
 * VLAs, static loop bounds). Configuration: hls/config.h.
 */
#ifndef SAARCOR_HLS_TOP_H
#define SAARCOR_HLS_TOP_H

#include "rgs.h"
#include "isect_unit.h"
#include "trav_node.h"
#include "xform_unit.h"

#define HLS_BATCH 1024u               /* transactions per call of a unit top function */
#define HLS_TILE 16u                  /* tile edge of dynrtc_top in pixels (even) */
#define HLS_MEM_WORDS (1u << 24)      /* largest memory image: 64 MB of board memory */
#define HLS_FB_WORDS (4096u * 4096u)  /* largest frame buffer */

/* Transformation unit: matrix rows, a point (translation applied) or a vector. */
typedef struct {
    f24_affine m;
    f24_vec3 v;
    uint32_t point;
} xform_txn;

/* Intersection unit: the ray in unit-triangle space, the distance its origin was moved by (the
 * rebase unit's te), its interval and the triangle's shared-edge flags. */
typedef struct {
    f24_vec3 o, d;
    f24_t te, tmin, tmax;
    uint32_t shared;
} isect_txn;

/* Traversal unit, one inner node for a 4-ray packet: the entry (mask, intervals), the node's
 * axis and split, the rays. */
typedef struct {
    trav_entry e;
    uint32_t axis;
    f24_t split;
    f24_vec3 o[TRACE_PACKET], d[TRACE_PACKET];
} trav_txn;

typedef struct {
    trav_entry l, r;
    uint32_t near_left;
} trav_result;

void xform_top(const xform_txn in[HLS_BATCH], f24_vec3 out[HLS_BATCH], uint32_t n);
void isect_top(const isect_txn in[HLS_BATCH], isect_result out[HLS_BATCH], uint32_t n);
void trav_top(const trav_txn in[HLS_BATCH], trav_result out[HLS_BATCH], uint32_t n);

/* Renders the tile whose top-left pixel is (x0, y0) (multiples of HLS_TILE) of the image the
 * memory image's camera describes into fb (width x height words 0xRRGGBB, row-major). */
void dynrtc_top(const uint32_t mem[HLS_MEM_WORDS], uint32_t fb[HLS_FB_WORDS], uint32_t x0, uint32_t y0,
                uint32_t max_depth, uint32_t shadows);

#endif
