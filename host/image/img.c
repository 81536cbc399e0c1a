/*
 * img.h's API over OpenImageIO (img_oiio.cpp), which a program either links in (the tests and
 * benchmarks) or loads on first use from libsaarcor_img.so next to it (the saarcor program).
 * Why: OpenImageIO brings about 260 shared libraries, and binding them costs every command about
 * 0.2 s of start-up even when it reads or writes no image (`saarcor info`, `version`, every
 * `--json` query of a test script); loaded on demand, only the commands that write or compare
 * images pay, once.
 */
#define _GNU_SOURCE
#include "img_api.h"
#include "img_exr.h"
#include "img_png.h"

#include <dlfcn.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* weak: NULL unless img_oiio.cpp is linked into the program */
extern const img_api *img_oiio_api(void) __attribute__((weak));

static const img_api *loaded;
static char load_error[512];

/* The library next to the program, or up to four folders up (build/hw/saarcor,
 * build/w/FMT/saarcor, build/hw/w/FMT/saarcor and its capture build build/hw/w/FMT/capture/saarcor
 * use build/'s); SAARCOR_IMG_LIB names it. */
static void *open_library(void)
{
    const char *env = getenv("SAARCOR_IMG_LIB");
    if (env && *env)
        return dlopen(env, RTLD_NOW | RTLD_LOCAL);
    char self[1024], path[1200];
    const ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len <= 0)
        return NULL;
    self[len] = 0;
    *strrchr(self, '/') = 0;
    static const char *const up[] = { "", "/..", "/../..", "/../../..", "/../../../.." };
    for (size_t i = 0; i < sizeof up / sizeof up[0]; i++) {
        snprintf(path, sizeof path, "%s%s/libsaarcor_img.so", self, up[i]);
        if (access(path, F_OK) == 0)
            return dlopen(path, RTLD_NOW | RTLD_LOCAL);
    }
    snprintf(load_error, sizeof load_error, "not found next to the program");
    return NULL;
}

/* The functions, or NULL with load_error set (the program then reports it per call). */
static const img_api *api(void)
{
    if (loaded || load_error[0])
        return loaded;
    if (img_oiio_api)
        return loaded = img_oiio_api();
    void *lib = open_library();
    const img_api *(*get)(void) = lib ? (const img_api *(*)(void))(uintptr_t)dlsym(lib, "img_oiio_api") : NULL;
    if (get)
        return loaded = get();
    if (!load_error[0])
        snprintf(load_error, sizeof load_error, "%s", lib ? "it has no img_oiio_api" : dlerror());
    return NULL;
}

static int unavailable(char *err, size_t errlen)
{
    if (err && errlen)
        snprintf(err, errlen, "cannot load libsaarcor_img.so (image input/output; build it with make): %s",
                 load_error);
    return -1;
}

int img_read(const char *path, img_t *out, char *err, size_t errlen)
{
    if (img_png_read(path, out) == 0)
        return 0;
    return api() ? loaded->read(path, out, err, errlen) : unavailable(err, errlen);
}

/* Through the library, as path.tmp renamed when complete (img_api.h). */
static int library_write(const char *path, const img_t *img, const char *const *names, char *err, size_t errlen)
{
    char tmp[IMG_TMP_PATH_MAX];
    if (!api())
        return unavailable(err, errlen);
    if (img_tmp_path(path, tmp, sizeof tmp, err, errlen) != 0)
        return -1;
    return img_tmp_commit(tmp, path, loaded->write(path, tmp, img, names, err, errlen) == 0, err, errlen);
}

int img_write(const char *path, const img_t *img, char *err, size_t errlen)
{
    if (img_png_writes(path, img->channels))
        return img_png_write(path, img, err, errlen);
    if (img_exr_writes(path, img->channels, 0))
        return img_exr_write(path, img, NULL, err, errlen);
    return library_write(path, img, NULL, err, errlen);
}

int img_write_channels(const char *path, const img_t *img, const char *const *names, char *err, size_t errlen)
{
    if (img_exr_writes(path, img->channels, 1))
        return img_exr_write(path, img, names, err, errlen);
    return library_write(path, img, names, err, errlen);
}

int img_tmp_path(const char *path, char *tmp, size_t len, char *err, size_t errlen)
{
    if (snprintf(tmp, len, "%s.tmp", path) < (int)len)
        return 0;
    snprintf(err, errlen, "cannot write '%s': path too long", path);
    return -1;
}

int img_tmp_commit(const char *tmp, const char *path, int written, char *err, size_t errlen)
{
    if (written && rename(tmp, path) == 0)
        return 0;
    if (written)
        snprintf(err, errlen, "cannot write '%s': rename failed: %s", path, strerror(errno));
    remove(tmp);
    return -1;
}

/* The pixels of img_read (std::malloc in the shim) and of the callers' own images (malloc):
 * freed without loading the library for them. */
void img_free(img_t *img)
{
    free(img->pixels);
    img->pixels = NULL;
}

/* OpenImageIO's metrics (ImageBufAlgo::compare, img_oiio.cpp) over two images of equal size: the
 * absolute difference of each channel value (a binary32 difference), its sum and sum of squares
 * in binary64, the first largest with its place, the pixels with a channel over the threshold. */
static void compare_pixels(const img_t *a, const img_t *b, double threshold, img_compare_result *res)
{
    const size_t pixels = (size_t)a->width * (size_t)a->height, c = (size_t)a->channels;
    double sum = 0, sum_sq = 0;
    *res = (img_compare_result){ .pixels = pixels };
    for (size_t p = 0; p < pixels; p++) {
        int over = 0;
        for (size_t k = 0; k < c; k++) {
            const double f = fabsf(a->pixels[p * c + k] - b->pixels[p * c + k]);
            sum += f;
            sum_sq += f * f;
            if (f > res->max_error) {
                res->max_error = f;
                res->max_x = (int)(p % (size_t)a->width);
                res->max_y = (int)(p / (size_t)a->width);
                res->max_channel = (int)k;
            }
            over |= f > (float)threshold; /* OpenImageIO takes it as binary32 */
        }
        res->differing_pixels += (uint64_t)over;
    }
    const double values = (double)(pixels * c);
    res->mean_error = values > 0 ? sum / values : 0;
    res->rms_error = values > 0 ? sqrt(sum_sq / values) : 0;
    res->psnr = res->rms_error > 0 ? 20.0 * log10(1.0 / res->rms_error) : INFINITY;
}

/* Two 8-bit PNG files (every render's) are compared here without loading the library; any other
 * pair, or one with a difference image to write, by OpenImageIO. */
int img_compare(const char *path_a, const char *path_b, double threshold, const char *diff_path,
                img_compare_result *res, char *err, size_t errlen)
{
    img_t a = { 0 }, b = { 0 };
    const int native = !diff_path && img_png_read(path_a, &a) == 0 && img_png_read(path_b, &b) == 0;
    const int same = native && a.width == b.width && a.height == b.height && a.channels == b.channels;
    if (same)
        compare_pixels(&a, &b, threshold, res);
    img_free(&a);
    img_free(&b);
    if (same)
        return 0;
    return api() ? loaded->compare(path_a, path_b, threshold, diff_path, res, err, errlen) : unavailable(err, errlen);
}

int img_ready(char *err, size_t errlen) { return api() ? 0 : unavailable(err, errlen); }

int img_ready_for(const char *path, int channels, int named, char *err, size_t errlen)
{
    /* the writers' own tests: img_write tries PNG then EXR, img_write_channels EXR */
    const int native = !path || img_exr_writes(path, channels, named) || (!named && img_png_writes(path, channels));
    return native ? 0 : img_ready(err, errlen);
}

const char *img_library_version(void) { return api() ? loaded->version() : "(libsaarcor_img.so not loaded)"; }
