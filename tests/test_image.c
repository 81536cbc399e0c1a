/*
 * Tests of the image plumbing (host/image): write/read round trips (PNG 8-bit through libpng,
 * EXR half through OpenImageIO), PNG files of libpng and of OpenImageIO decoding to the same
 * pixels around every rounding tie, the comparison metrics against hand-computed values, and
 * against OIIO's own `idiff` tool on the same files.
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
        if (img_oiio_api()->write(tmp(theirs_name), &img, NULL, err, sizeof err) != 0)
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(round_trip),
        cmocka_unit_test(compare_hand_computed),
        cmocka_unit_test(agrees_with_idiff),
        cmocka_unit_test(errors_are_reported),
        cmocka_unit_test(png_quantized_as_oiio),
        cmocka_unit_test(png_read_as_oiio),
    };
    return cmocka_run_group_tests_name("image", tests, test_tmpdir_setup, test_tmpdir_teardown);
}
