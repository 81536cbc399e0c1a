/*
 * Image input/output and comparison for the host, through OpenImageIO (a thin C++ shim,
 * img_oiio.cpp, with this extern "C" API), except what the program writes and reads most: 8-bit
 * PNG files through libpng (img_png.c) and EXR writing through the OpenEXR core library
 * (img_exr.c), so a render that writes PNG and EXR files never loads OpenImageIO. PNG and other
 * 8-bit formats are written as 8-bit, EXR as half floats; pixels are float RGB(A) in [0,1] for
 * 8-bit formats.
 */
#ifndef SAARCOR_IMG_H
#define SAARCOR_IMG_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int width, height, channels;
    float *pixels; /* width*height*channels, row-major, top row first */
} img_t;

/* Reads any format OpenImageIO knows into float pixels. 0 on success; on failure fills err
 * with a one-line message and returns -1. img_free releases the pixels. */
int img_read(const char *path, img_t *out, char *err, size_t errlen);
int img_write(const char *path, const img_t *img, char *err, size_t errlen);
void img_free(img_t *img);

/* Writes a float image with named channels (e.g. an EXR of AOVs); full float precision. */
int img_write_channels(const char *path, const img_t *img, const char *const *names, char *err, size_t errlen);

typedef struct {
    double mean_error, rms_error, psnr, max_error; /* psnr is +inf for identical images */
    int max_x, max_y, max_channel;
    uint64_t pixels, differing_pixels; /* pixels with some channel differing by > threshold */
} img_compare_result;

/* Compares two images of the same size and channel count; optionally writes |A-B| to
 * diff_path (NULL: none). PSNR = 20 log10(1 / RMS) over all channels (peak value 1). */
int img_compare(const char *path_a, const char *path_b, double threshold, const char *diff_path,
                img_compare_result *res, char *err, size_t errlen);

const char *img_library_version(void);

/* 0 if images can be read and written; else -1 with a one-line err (the saarcor program loads the
 * image library on demand: commands that will write images check it before the long work). */
int img_ready(char *err, size_t errlen);

/* img_ready for a command that will write to path (NULL: none) an unnamed image of that many
 * channels (img_write, named 0) or one with named channels (img_write_channels, named 1, any
 * count): 0 without loading the library when the program writes that itself (PNG:
 * host/image/img_png.c, grey or RGB; EXR: img_exr.c, RGB, RGBA or named channels), by the
 * writers' own rule. */
int img_ready_for(const char *path, int channels, int named, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
