/*
 * Runs the device model over a memory image that mi_validate accepted: a grid of 2x2 pixel blocks
 * spread over the camera's image, each block's whole ray tree through the RGS unit (primary,
 * shadow, reflection and transmission rays; trace_packet's traversal, list, transformation and
 * intersection units underneath) with every traversal algorithm. Shared by the corrupted-image
 * test (tests/test_corrupt_image.c) and the memory-image fuzzer (tests/fuzz/fuzz_memimage.c):
 * given an image in a buffer of exactly its size, any read outside it is an ASan report.
 * Header only: both programs include it once.
 */
#ifndef SAARCOR_IMAGE_PROBE_H
#define SAARCOR_IMAGE_PROBE_H

#include <stdint.h>

#include "rgs.h"
#include "trace.h"

/* grid x grid blocks; returns an order-independent checksum of the pixels (so the work is used). */
static inline uint32_t image_probe(const uint32_t *mem, uint32_t grid)
{
    uint32_t w, h, sum = 0;
    rgs_image_size(mem, &w, &h);
    for (uint32_t algo = 0; algo < TRAV_KINDS; algo++) {
        const rgs_config cfg = { 2, 1, algo };
        for (uint32_t j = 0; j < grid; j++)
            for (uint32_t i = 0; i < grid; i++) {
                const uint32_t x = (uint32_t)((uint64_t)w * (2 * i + 1) / (2 * grid)) & ~1u;
                const uint32_t y = (uint32_t)((uint64_t)h * (2 * j + 1) / (2 * grid)) & ~1u;
                uint32_t rgb[TRACE_PACKET];
                hit_record hits[TRACE_PACKET];
                rgs_counters c = { { 0 }, { 0 }, 0 };
                rgs_render_block(mem, &cfg, x, y, rgb, hits, &c);
                for (int k = 0; k < TRACE_PACKET; k++)
                    sum += rgb[k] ^ hits[k].triangle;
            }
    }
    return sum;
}

#endif
