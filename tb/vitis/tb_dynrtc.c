/*
 * HOST-ONLY TESTBENCH, not part of the design: it uses libc (stdio, malloc) to read vectors and
 * is never synthesized; make hls-check covers hls/fp24, hls/units and hls/top only.
 *
 * Testbench of dynrtc_top (C simulation with GCC in `make test`, csim and cosim in Vitis HLS,
 * tb/vitis/run.tcl): renders every tile of a memory image through the top function and diffs
 * the frame buffer against the simulator's image of the same scene (a binary PPM written by
 * `saarcor render`). Returns 0 if every pixel matches, 1 otherwise (printing the first
 * mismatches), 2 on bad input.
 *   tb_dynrtc IMAGE.bin EXPECTED.ppm MAX_DEPTH SHADOWS
 */
#include <stdio.h>
#include <stdlib.h>

#include "hls_top.h"

static uint32_t *read_image(const char *path, uint32_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    uint32_t *w = calloc(HLS_MEM_WORDS, sizeof *w);
    *n = w ? (uint32_t)fread(w, 4, HLS_MEM_WORDS, f) : 0;
    fclose(f);
    return w;
}

static unsigned char *read_ppm(const char *path, uint32_t *w, uint32_t *h)
{
    FILE *f = fopen(path, "rb");
    unsigned max = 0;
    if (!f || fscanf(f, "P6 %u %u %u", w, h, &max) != 3 || max != 255 || fgetc(f) == EOF) {
        if (f)
            fclose(f);
        return NULL;
    }
    unsigned char *px = malloc((size_t)*w * *h * 3);
    if (px && fread(px, 3, (size_t)*w * *h, f) != (size_t)*w * *h) {
        free(px);
        px = NULL;
    }
    fclose(f);
    return px;
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: tb_dynrtc IMAGE.bin EXPECTED.ppm MAX_DEPTH SHADOWS\n");
        return 2;
    }
    uint32_t n = 0, w = 0, h = 0, iw, ih;
    uint32_t *mem = read_image(argv[1], &n);
    unsigned char *want = read_ppm(argv[2], &w, &h);
    uint32_t *fb = calloc(HLS_FB_WORDS, sizeof *fb);
    if (!mem || n < 64 || !want || !fb) {
        fprintf(stderr, "tb_dynrtc: cannot read %s or %s\n", argv[1], argv[2]);
        return 2;
    }
    rgs_image_size(mem, &iw, &ih);
    if (iw != w || ih != h || (uint64_t)w * h > HLS_FB_WORDS) {
        fprintf(stderr, "tb_dynrtc: image %ux%u, expected %ux%u\n", iw, ih, w, h);
        return 2;
    }
    const uint32_t depth = (uint32_t)atoi(argv[3]), shadows = (uint32_t)atoi(argv[4]);
    for (uint32_t y = 0; y < h; y += HLS_TILE)
        for (uint32_t x = 0; x < w; x += HLS_TILE)
            dynrtc_top(mem, fb, x, y, depth, shadows);
    uint64_t bad = 0;
    for (uint32_t i = 0; i < w * h; i++) {
        const uint32_t e = (uint32_t)want[3 * i] << 16 | (uint32_t)want[3 * i + 1] << 8 | want[3 * i + 2];
        if (fb[i] != e && bad++ < 5)
            fprintf(stderr, "tb_dynrtc: pixel (%u, %u): top function 0x%06x, simulator 0x%06x\n", i % w, i / w,
                    fb[i], e);
    }
    printf("tb_dynrtc: %ux%u pixels, %llu mismatches%s\n", w, h, (unsigned long long)bad,
#ifdef SAARCOR_CFG_NAME
           " (configuration " SAARCOR_CFG_NAME ")"
#else
           " (general configuration)"
#endif
    );
    free(mem);
    free(want);
    free(fb);
    return bad ? 1 : 0;
}
