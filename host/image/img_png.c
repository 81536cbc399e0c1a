/*
 * 8-bit PNG files through libpng's simplified API (img_png.h says why not OpenImageIO). The file
 * is written as path.tmp and renamed when complete, as img_oiio.cpp does, so an interrupted write
 * never leaves a truncated image under the real name.
 */
#include "img_png.h"

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

unsigned char img_png_quantize(float v)
{
    const float s = v * 255.0f; /* a binary32 product, as OpenImageIO's conversion */
    return s >= 255.0f ? 255 : s > 0.0f ? (unsigned char)roundf(s) : 0; /* NaN fails both tests */
}

int img_png_write(const char *path, const img_t *img, char *err, size_t errlen)
{
    const size_t n = (size_t)img->width * (size_t)img->height * (size_t)img->channels;
    unsigned char *bytes = malloc(n ? n : 1);
    char tmp[4200];
    if (!bytes || snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp) {
        free(bytes);
        snprintf(err, errlen, "cannot write '%s': %s", path, bytes ? "path too long" : "out of memory");
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        bytes[i] = img_png_quantize(img->pixels[i]);
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    im.width = (png_uint_32)img->width;
    im.height = (png_uint_32)img->height;
    im.format = img->channels == 3 ? PNG_FORMAT_RGB : PNG_FORMAT_GRAY;
    const int ok = png_image_write_to_file(&im, tmp, 0, bytes, 0, NULL);
    free(bytes);
    if (!ok) {
        snprintf(err, errlen, "cannot write '%s': %s", path, im.message);
        remove(tmp);
        return -1;
    }
    if (rename(tmp, path) != 0) {
        snprintf(err, errlen, "cannot write '%s': rename failed: %s", path, strerror(errno));
        remove(tmp);
        return -1;
    }
    return 0;
}
