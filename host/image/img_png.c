/*
 * 8-bit PNG files through libpng's simplified API (img_png.h says why not OpenImageIO). A file
 * is written as path.tmp and renamed when complete (img_api.h), as every image file of the program.
 */
#include "img_png.h"
#include "img_api.h"

#include <errno.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

int img_png_path(const char *path)
{
    const size_t n = strlen(path);
    return n >= 4 && strcasecmp(path + n - 4, ".png") == 0;
}

int img_png_writes(const char *path, int channels) { return img_png_path(path) && (channels == 1 || channels == 3); }

/* OpenImageIO's float-to-8-bit conversion: v * 255 in binary32, clamped to [0, 255], rounded to
 * nearest with ties away from zero; NaN to 0. */
static unsigned char quantize(float v)
{
    const float s = v * 255.0f; /* a binary32 product, as OpenImageIO's conversion */
    return s >= 255.0f ? 255 : s > 0.0f ? (unsigned char)roundf(s) : 0; /* NaN fails both tests */
}

int img_png_write(const char *path, const img_t *img, char *err, size_t errlen)
{
    const size_t n = (size_t)img->width * (size_t)img->height * (size_t)img->channels;
    char tmp[IMG_TMP_PATH_MAX];
    if (img_tmp_path(path, tmp, sizeof tmp, err, errlen) != 0)
        return -1;
    unsigned char *bytes = malloc(n ? n : 1);
    if (!bytes) {
        snprintf(err, errlen, "cannot write '%s': out of memory", path);
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        bytes[i] = quantize(img->pixels[i]);
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    im.width = (png_uint_32)img->width;
    im.height = (png_uint_32)img->height;
    im.format = img->channels == 3 ? PNG_FORMAT_RGB : PNG_FORMAT_GRAY;
    const int ok = png_image_write_to_file(&im, tmp, 0, bytes, 0, NULL);
    free(bytes);
    if (!ok)
        snprintf(err, errlen, "cannot write '%s': %s", path, im.message);
    return img_tmp_commit(tmp, path, ok, err, errlen);
}

/* The file's pixels when they are 8-bit grey or RGB without alpha, palette or a colour space
 * other than sRGB (what img_png_write writes): then libpng hands them over unconverted. */
int img_png_read(const char *path, img_t *out)
{
    if (!img_png_path(path))
        return 1;
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&im, path))
        return 1;
    const png_uint_32 other = PNG_FORMAT_FLAG_ALPHA | PNG_FORMAT_FLAG_LINEAR | PNG_FORMAT_FLAG_COLORMAP;
    const int channels = im.format == PNG_FORMAT_RGB ? 3 : im.format == PNG_FORMAT_GRAY ? 1 : 0;
    const size_t n = (size_t)im.width * im.height * (size_t)channels;
    unsigned char *bytes = channels && !(im.format & other) && !(im.flags & PNG_IMAGE_FLAG_COLORSPACE_NOT_sRGB)
                               ? malloc(n ? n : 1) : NULL;
    float *px = bytes ? malloc((n ? n : 1) * sizeof *px) : NULL;
    if (!px || !png_image_finish_read(&im, NULL, bytes, 0, NULL)) {
        png_image_free(&im);
        free(bytes);
        free(px);
        return 1;
    }
    for (size_t i = 0; i < n; i++)
        px[i] = (float)bytes[i] * (1.0f / 255.0f); /* OpenImageIO's 8-bit-to-float conversion */
    free(bytes);
    *out = (img_t){ (int)im.width, (int)im.height, channels, px };
    return 0;
}
