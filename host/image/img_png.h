/*
 * 8-bit PNG writing through libpng, without OpenImageIO: private to host/image (img.c).
 * Why: binding OpenImageIO's ~260 shared libraries costs about 0.6 s of CPU per process on the
 * 2-core machine, more than rendering a small frame; a render that writes only PNG files (most of
 * them: every test script's, every animation frame's) never loads it. The pixels are quantized as
 * OpenImageIO quantizes float to 8 bits, so both writers give the same decoded pixels
 * (tests/test_image.c checks it around every rounding tie).
 */
#ifndef SAARCOR_IMG_PNG_H
#define SAARCOR_IMG_PNG_H

#include "img.h"

/* 1 if path names a PNG file (extension .png, any case). */
int img_png_path(const char *path);

/* 1 if img_png_write writes an image of that many channels to path: a PNG file in grey or RGB
 * (with alpha, OpenImageIO divides the colours by alpha before it quantizes: its writer keeps those). */
int img_png_writes(const char *path, int channels);

/* Writes img (grey or RGB, floats in [0,1]) as an 8-bit PNG to path. 0 on success; on failure
 * err holds a one-line message and -1 is returned. */
int img_png_write(const char *path, const img_t *img, char *err, size_t errlen);

/* Reads path into out (img_free releases it) and returns 0 if it is an 8-bit grey or RGB PNG file
 * in sRGB (what img_png_write writes), with OpenImageIO's values; 1 (nothing read) for any other
 * file, which is OpenImageIO's to read or to reject with its message. */
int img_png_read(const char *path, img_t *out);

#endif
