/*
 * The whole dynamic ray tracing core for one screen tile (paper sections 2 and 3, Figure 2): the
 * RGS generates each 2x2 block's primary packet and shades its ray tree; traversal, list,
 * transformation and intersection units trace the packets; everything is read from the memory
 * image on an AXI master, pixels are written to the frame buffer on a second one. This is the
 * functional order (one block's ray tree after the other); the multithreaded schedule of the
 * prototype (many blocks in flight, per-type caches) is the cycle model in tb/cycle, which runs
 * the same rgs_step operations. See hls_top.h and docs/hls.md.
 */
#include "hls_top.h"

void dynrtc_top(const uint32_t mem[HLS_MEM_WORDS], uint32_t fb[HLS_FB_WORDS], uint32_t x0, uint32_t y0,
                uint32_t max_depth, uint32_t shadows)
{
#pragma HLS INTERFACE mode=m_axi port=mem offset=slave bundle=scene depth=16777216 max_read_burst_length=16
#pragma HLS INTERFACE mode=m_axi port=fb offset=slave bundle=frame depth=16777216
#pragma HLS INTERFACE mode=s_axilite port=x0
#pragma HLS INTERFACE mode=s_axilite port=y0
#pragma HLS INTERFACE mode=s_axilite port=max_depth
#pragma HLS INTERFACE mode=s_axilite port=shadows
#pragma HLS INTERFACE mode=s_axilite port=return
    uint32_t w, h;
    rgs_image_size(mem, &w, &h);
    const rgs_config cfg = { max_depth, shadows, TRAV_STACK };
    rgs_counters c = { 0 };
tile_rows:
    for (uint32_t by = 0; by < HLS_TILE; by += 2)
    tile_blocks:
        for (uint32_t bx = 0; bx < HLS_TILE; bx += 2) {
            uint32_t rgb[TRACE_PACKET];
#pragma HLS ARRAY_PARTITION variable=rgb complete
            rgs_render_block(mem, &cfg, x0 + bx, y0 + by, rgb, 0, &c);
        block_pixels:
            for (uint32_t i = 0; i < TRACE_PACKET; i++) {
                const uint32_t x = x0 + bx + (i & 1u), y = y0 + by + (i >> 1);
                if (x < w && y < h && (uint64_t)y * w + x < HLS_FB_WORDS)
                    fb[y * w + x] = rgb[i];
            }
        }
}
