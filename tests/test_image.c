/*
 * Tests of the image plumbing (host/image): write/read round trips (PNG 8-bit through libpng,
 * EXR half through the OpenEXR core library), PNG and EXR files of ours and of OpenImageIO
 * decoding to the same pixels around every rounding tie, the comparison metrics against
 * hand-computed values, and against OIIO's own `idiff` tool on the same files.
 */
#define _GNU_SOURCE /* popen, mkdtemp */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "test_tmpdir.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "img.h"
#include "img_api.h"
#include "img_exr.h"
#include "img_png.h"

enum { W = 16, H = 8, C = 3 };


static const char *tmp(const char *name)
{
    static char path[4][128];
    static int k;
    k = (k + 1) % 4;
    snprintf(path[k], sizeof path[k], "%s/%s", test_dir, name);
    return path[k];
}

/* A gradient on an 8-bit grid, so PNG round trips are exact. */
static void make_image(img_t *img)
{
    img->width = W;
    img->height = H;
    img->channels = C;
    img->pixels = calloc(W * H * C, sizeof(float));
    for (int i = 0; i < W * H * C; i++)
        img->pixels[i] = (float)((i * 7) % 256) / 255.0f;
}

static void write_or_fail(const char *path, const img_t *img)
{
    char err[256];
    if (img_write(path, img, err, sizeof err) != 0)
        fail_msg("%s", err);
}

static void round_trip(void **state)
{
    (void)state;
    img_t a, b;
    char err[256];
    make_image(&a);
    const char *formats[] = { "rt.png", "rt.exr" };
    const double tol[] = { 0.5 / 255.0, 1e-3 }; /* 8-bit, half float */
    for (int f = 0; f < 2; f++) {
        write_or_fail(tmp(formats[f]), &a);
        assert_int_equal(img_read(tmp(formats[f]), &b, err, sizeof err), 0);
        assert_int_equal(b.width, W);
        assert_int_equal(b.height, H);
        assert_int_equal(b.channels, C);
        for (int i = 0; i < W * H * C; i++)
            assert_true(fabs(b.pixels[i] - a.pixels[i]) <= tol[f]);
        img_free(&b);
    }
    img_free(&a);
}

/* Moves an 8-bit grid value by k/255 (up or down, staying in [0,1]). */
static void shift_value(float *v, int k)
{
    *v = *v < 0.5f ? *v + (float)k / 255.0f : *v - (float)k / 255.0f;
}

static void compare_hand_computed(void **state)
{
    (void)state;
    img_t a, b;
    make_image(&a);
    make_image(&b);
    /* pixel (3,2): one channel off by 128/255; pixel (5,1): two channels off by 10/255 */
    const int p1 = (2 * W + 3) * C, p2 = (1 * W + 5) * C;
    const double d1 = 128.0 / 255.0, e2 = 10.0 / 255.0;
    shift_value(&b.pixels[p1 + 1], 128);
    shift_value(&b.pixels[p2], 10);
    shift_value(&b.pixels[p2 + 2], 10);
    write_or_fail(tmp("a.png"), &a);
    write_or_fail(tmp("b.png"), &b);

    img_compare_result r;
    char err[256];
    assert_int_equal(img_compare(tmp("a.png"), tmp("a.png"), 0.0, NULL, &r, err, sizeof err), 0);
    assert_true(isinf(r.psnr) && r.max_error == 0.0 && r.differing_pixels == 0);

    assert_int_equal(img_compare(tmp("a.png"), tmp("b.png"), 0.0, tmp("diff.exr"), &r, err, sizeof err), 0);
    const double mse = (d1 * d1 + 2 * e2 * e2) / (W * H * C);
    assert_float_equal(r.psnr, 20.0 * log10(1.0 / sqrt(mse)), 0.05);
    assert_float_equal(r.max_error, d1, 1e-6);
    assert_int_equal(r.max_x, 3);
    assert_int_equal(r.max_y, 2);
    assert_int_equal(r.max_channel, 1);
    assert_int_equal(r.pixels, W * H);
    assert_int_equal(r.differing_pixels, 2);          /* counted per pixel, not per channel */
    assert_true(img_compare(tmp("a.png"), tmp("b.png"), 0.1, NULL, &r, err, sizeof err) == 0 &&
                r.differing_pixels == 1);           /* only the large difference is over 0.1 */

    img_t d;
    assert_int_equal(img_read(tmp("diff.exr"), &d, err, sizeof err), 0);
    assert_float_equal(d.pixels[p1 + 1], d1, 1e-3);
    assert_float_equal(d.pixels[0], 0.0, 0.0);
    img_free(&d);
    img_free(&a);
    img_free(&b);
}

/* Reads "key = value" numbers from `idiff -v -a` output. */
static double idiff_value(const char *out, const char *key)
{
    const char *p = strstr(out, key);
    if (!p)
        fail_msg("idiff output lacks '%s': %s", key, out);
    p = strchr(p, '=');
    return p ? strtod(p + 1, NULL) : NAN;
}

static void agrees_with_idiff(void **state)
{
    (void)state;
    img_t a, b;
    make_image(&a);
    make_image(&b);
    for (int i = 0; i < W * H * C; i += 5) /* many small differences */
        b.pixels[i] = fminf(1.0f, b.pixels[i] + (float)(i % 3 + 1) / 255.0f);
    write_or_fail(tmp("ia.png"), &a);
    write_or_fail(tmp("ib.png"), &b);
    char cmd[512], out[4096] = { 0 };
    snprintf(cmd, sizeof cmd, "idiff -v -a -fail 0 '%s' '%s' 2>&1", tmp("ia.png"), tmp("ib.png"));
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    const size_t n = fread(out, 1, sizeof out - 1, p);
    out[n] = '\0';
    pclose(p);

    img_compare_result r, o;
    char err[256];
    assert_int_equal(img_compare(tmp("ia.png"), tmp("ib.png"), 0.0, NULL, &r, err, sizeof err), 0);
    /* the PNG pair is compared without OpenImageIO (host/image/img.c): its own metrics agree */
    for (int t = 0; t < 2; t++) {
        const double threshold = t ? 1.5 / 255.0 : 0.0;
        assert_int_equal(img_compare(tmp("ia.png"), tmp("ib.png"), threshold, NULL, &r, err, sizeof err), 0);
        assert_int_equal(img_oiio_api()->compare(tmp("ia.png"), tmp("ib.png"), threshold, NULL, &o, err, sizeof err), 0);
        assert_float_equal(r.psnr, o.psnr, 1e-9);
        assert_float_equal(r.mean_error, o.mean_error, 1e-12);
        assert_float_equal(r.rms_error, o.rms_error, 1e-12);
        assert_true(r.max_error == o.max_error && r.max_x == o.max_x && r.max_y == o.max_y &&
                    r.max_channel == o.max_channel && r.pixels == o.pixels && r.differing_pixels == o.differing_pixels);
    }
    assert_int_equal(img_compare(tmp("ia.png"), tmp("ib.png"), 0.0, NULL, &r, err, sizeof err), 0);
    assert_float_equal(r.psnr, idiff_value(out, "Peak SNR"), 1e-3);
    assert_float_equal(r.max_error, idiff_value(out, "Max error"), 1e-6);
    assert_float_equal(r.rms_error, idiff_value(out, "RMS error"), 1e-6);
    char key[64];
    snprintf(key, sizeof key, "%llu pixels", (unsigned long long)r.differing_pixels);
    if (!strstr(out, key))
        fail_msg("idiff does not report '%s': %s", key, out);
    img_free(&a);
    img_free(&b);
}

static void errors_are_reported(void **state)
{
    (void)state;
    img_t a, small;
    img_compare_result r;
    char err[256];
    assert_int_equal(img_read(tmp("missing.png"), &a, err, sizeof err), -1);
    assert_non_null(strstr(err, "missing.png"));
    assert_null(strchr(err, '\n'));
    make_image(&a);
    write_or_fail(tmp("c.png"), &a);
    small = a;
    small.width = W / 2;
    write_or_fail(tmp("small.png"), &small);
    assert_int_equal(img_compare(tmp("c.png"), tmp("small.png"), 0.0, NULL, &r, err, sizeof err), -1);
    assert_non_null(strstr(err, "differ in size"));
    FILE *f = fopen(tmp("garbage.png"), "w");
    fputs("not an image", f);
    fclose(f);
    assert_int_equal(img_read(tmp("garbage.png"), &a, err, sizeof err) == -1 ? -1 : 0, -1);
    assert_int_equal(img_write("/nonexistent-dir/x.png", &small, err, sizeof err), -1);
    img_free(&small);
}

/* Every 8-bit value read from a PNG file without OpenImageIO (host/image/img_png.c) is the float
 * OpenImageIO reads. */
static void png_read_as_oiio(void **state)
{
    (void)state;
    static float v[256 * 3];
    for (int i = 0; i < 256 * 3; i++)
        v[i] = (float)(i % 256) / 255.0f;
    img_t img = { 256, 1, 3, v }, ours, theirs;
    write_or_fail(tmp("all.png"), &img);
    char err[256];
    assert_int_equal(img_png_read(tmp("all.png"), &ours), 0);
    assert_int_equal(img_oiio_api()->read(tmp("all.png"), &theirs, err, sizeof err), 0);
    assert_true(ours.width == 256 && ours.height == 1 && ours.channels == 3);
    assert_memory_equal(ours.pixels, theirs.pixels, sizeof v);
    img_free(&ours);
    img_free(&theirs);
}

/* The values next to every 8-bit rounding tie (n + 1/2) / 255, a few ulps each way, and the
 * clamped ones: libpng's file (img_write, host/image/img_png.c) and OpenImageIO's PNG writer
 * decode to the same bytes, in grey and RGB (images with alpha are OpenImageIO's: it divides
 * the colours by alpha before it quantizes). */
static void png_quantized_as_oiio(void **state)
{
    (void)state;
    enum { ULPS = 6, N = 256 * (2 * ULPS + 1) + 6 };
    static float v[N];
    int n = 0;
    for (int t = 0; t < 256; t++)
        for (int k = -ULPS; k <= ULPS; k++) {
            float x = ((float)t + 0.5f) / 255.0f;
            for (int j = 0; j < (k < 0 ? -k : k); j++)
                x = nextafterf(x, k < 0 ? -1.0f : 2.0f);
            v[n++] = x;
        }
    const float edges[] = { -1.0f, -0.0f, 1.0f, 1.5f, INFINITY, -INFINITY };
    for (int i = 0; i < 6; i++)
        v[n++] = edges[i];
    char err[256];
    for (int c = 1; c <= 3; c += 2) {
        img_t img = { N / c, 1, c, v }, ours, theirs;
        char ours_name[32], theirs_name[32]; /* a name per file: OpenImageIO caches what it read */
        snprintf(ours_name, sizeof ours_name, "ours%d.png", c);
        snprintf(theirs_name, sizeof theirs_name, "theirs%d.png", c);
        write_or_fail(tmp(ours_name), &img);
        const char *theirs_path = tmp(theirs_name);
        if (img_oiio_api()->write(theirs_path, theirs_path, &img, NULL, err, sizeof err) != 0)
            fail_msg("%s", err);
        assert_int_equal(img_read(tmp(ours_name), &ours, err, sizeof err), 0);
        assert_int_equal(img_read(tmp(theirs_name), &theirs, err, sizeof err), 0);
        assert_int_equal(ours.channels, c);
        assert_int_equal(theirs.channels, c);
        for (int i = 0; i < (N / c) * c; i++)
            if (ours.pixels[i] != theirs.pixels[i])
                fail_msg("%d channels: %.9g written as %.0f by libpng, %.0f by OpenImageIO", c, (double)v[i],
                         255.0 * ours.pixels[i], 255.0 * theirs.pixels[i]);
        img_free(&ours);
        img_free(&theirs);
    }
}

/* img_write, or OpenImageIO's writer (theirs), to path; then read back by OpenImageIO. */
static void write_read(const char *path, const img_t *img, const char *const *names, int theirs, img_t *back)
{
    char err[256];
    const int rc = theirs ? img_oiio_api()->write(path, path, img, names, err, sizeof err)
                          : names ? img_write_channels(path, img, names, err, sizeof err) : img_write(path, img, err, sizeof err);
    if (rc != 0)
        fail_msg("%s", err);
    assert_int_equal(img_read(path, back, err, sizeof err), 0);
    assert_true(back->width == img->width && back->height == img->height && back->channels == img->channels);
}

/* Our EXR file (host/image/img_exr.c) and OpenImageIO's read back to the same float bits. */
static void exr_as_oiio(const char *name, const img_t *img, const char *const *names)
{
    char ours_name[64], theirs_name[64]; /* a name per file: OpenImageIO caches what it read */
    snprintf(ours_name, sizeof ours_name, "ours_%s.exr", name);
    snprintf(theirs_name, sizeof theirs_name, "theirs_%s.exr", name);
    img_t ours, theirs;
    write_read(tmp(ours_name), img, names, 0, &ours);
    write_read(tmp(theirs_name), img, names, 1, &theirs);
    const size_t n = (size_t)img->width * img->height * img->channels;
    for (size_t i = 0; i < n; i++)
        if (memcmp(&ours.pixels[i], &theirs.pixels[i], sizeof(float)) != 0)
            fail_msg("%s: value %zu, %.9g, read back as %.9g from ours, %.9g from OpenImageIO's", name, i,
                     (double)img->pixels[i], (double)ours.pixels[i], (double)theirs.pixels[i]);
    img_free(&ours);
    img_free(&theirs);
}

/* binary16 bits to binary32 (the test's own decoding: 1 sign, 5 exponent, 10 fraction bits) */
static float half_value(unsigned h)
{
    const float mag = (h >> 10 & 31) ? ldexpf(1.0f + (float)(h & 1023) / 1024.0f, (int)(h >> 10 & 31) - 15)
                                     : ldexpf((float)(h & 1023), -24);
    return h & 0x8000 ? -mag : mag;
}

/* Half floats (RGB EXR, img_write): every rounding tie between two neighbouring binary16 values,
 * of both signs, subnormals included, with the floats next to it, and the edges (overflow to
 * infinity, below the smallest subnormal, infinities, NaN). */
static void exr_half_as_oiio(void **state)
{
    (void)state;
    enum { PAIRS = 2 * 31743, N = 3 * PAIRS + 9 };
    float *v = malloc(N * sizeof *v);
    int n = 0;
    for (unsigned sign = 0; sign <= 0x8000; sign += 0x8000)
        for (unsigned h = 0; h < 0x7BFF; h++) { /* 0 .. below the largest finite half, 0x7BFF */
            const float tie = (half_value(sign | h) + half_value(sign | (h + 1))) / 2.0f; /* exact */
            v[n++] = nextafterf(tie, -INFINITY);
            v[n++] = tie;
            v[n++] = nextafterf(tie, INFINITY);
        }
    const float edges[] = { 65504.0f, 65519.996f, 65520.0f, 1e-9f, -1e-9f, INFINITY, -INFINITY, NAN, -0.0f };
    for (int i = 0; i < 9; i++)
        v[n++] = edges[i];
    assert_int_equal(n, N);
    const img_t img = { N / 3, 1, 3, v };
    exr_as_oiio("half", &img, NULL);
    const img_t rgba = { N / 4, 1, 4, v };
    exr_as_oiio("half_rgba", &rgba, NULL);
    free(v);
}

/* Full floats with channel names (render --aov, reference -o): every bit pattern class, the
 * channels named out of EXR's sorted order, so each must land in its own channel. */
static void exr_channels_as_oiio(void **state)
{
    (void)state;
    enum { PX = 64 * 16, CH = 5 };
    static float v[PX * CH];
    uint32_t x = 12345;
    for (int i = 0; i < PX * CH; i++) {
        x = x * 1664525u + 1013904223u;
        memcpy(&v[i], &x, sizeof x);
    }
    v[0] = NAN;
    v[1] = -INFINITY;
    const char *const names[CH] = { "t", "N.X", "triangle", "N.Z", "A" };
    const img_t img = { 64, 16, CH, v };
    exr_as_oiio("channels", &img, names);
}

/* With SOURCE_DATE_EPOCH, two EXR files of the same pixels have the same bytes; without it, the
 * date is now. */
static void exr_dated_by_source_date_epoch(void **state)
{
    (void)state;
    img_t img;
    make_image(&img);
    setenv("SOURCE_DATE_EPOCH", "0", 1);
    write_or_fail(tmp("d1.exr"), &img);
    setenv("SOURCE_DATE_EPOCH", "86400", 1);
    write_or_fail(tmp("d2.exr"), &img);
    setenv("SOURCE_DATE_EPOCH", "0", 1);
    write_or_fail(tmp("d3.exr"), &img);
    unsetenv("SOURCE_DATE_EPOCH");
    char cmd[512];
    snprintf(cmd, sizeof cmd, "cmp -s '%s' '%s'", tmp("d1.exr"), tmp("d3.exr"));
    assert_int_equal(system(cmd), 0);
    snprintf(cmd, sizeof cmd, "cmp -s '%s' '%s'", tmp("d1.exr"), tmp("d2.exr"));
    assert_int_not_equal(system(cmd), 0);
    snprintf(cmd, sizeof cmd, "iinfo -v '%s' | grep -q 'DateTime: \"1970:01:02 00:00:00\"'", tmp("d2.exr"));
    assert_int_equal(system(cmd), 0);
    free(img.pixels);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(round_trip),
        cmocka_unit_test(compare_hand_computed),
        cmocka_unit_test(agrees_with_idiff),
        cmocka_unit_test(errors_are_reported),
        cmocka_unit_test(png_quantized_as_oiio),
        cmocka_unit_test(png_read_as_oiio),
        cmocka_unit_test(exr_half_as_oiio),
        cmocka_unit_test(exr_channels_as_oiio),
        cmocka_unit_test(exr_dated_by_source_date_epoch),
    };
    return cmocka_run_group_tests_name("image", tests, test_tmpdir_setup, test_tmpdir_teardown);
}
