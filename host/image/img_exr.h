/*
 * OpenEXR writing through the OpenEXR core library (C), without OpenImageIO: private to
 * host/image (img.c). Why: binding OpenImageIO's ~260 shared libraries costs about 0.5 s of CPU
 * per process, more than rendering a small frame, and every `render --aov` and every `reference`
 * writes an EXR file; libOpenEXRCore costs a few milliseconds. The files hold what OpenImageIO's
 * writer put in them (scanlines, ZIP compression, the channels by name, half floats rounded to
 * nearest even, the date in capDate): read back, they give the same pixels (tests/test_image.c
 * checks it around every rounding tie of binary16). OpenImageIO still reads EXR files.
 */
#ifndef SAARCOR_IMG_EXR_H
#define SAARCOR_IMG_EXR_H

#include "img.h"

/* 1 if path names an OpenEXR file (extension .exr, any case). */
int img_exr_path(const char *path);

/* 1 if img_exr_write writes path: an EXR file with channel names (named 1), or unnamed RGB or RGBA. */
int img_exr_writes(const char *path, int channels, int named);

/* Writes img to path: names NULL, as half floats in channels R, G, B (and A); else full floats in
 * the channels names[0 .. channels-1]. 0 on success; on failure err holds a one-line message and
 * -1 is returned. */
int img_exr_write(const char *path, const img_t *img, const char *const *names, char *err, size_t errlen);

#endif
