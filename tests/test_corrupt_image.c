/*
 * Corrupted memory images against the device model (issue 9): valid images of generated scenes
 * (cornell, room, animated) are corrupted with fixed seeds -- bit flips, random words, words of
 * the header and the record tables overwritten, truncation with the size field adjusted -- and
 * each variant must either be refused by mi_validate with a one-line error or render a few 2x2
 * blocks through the units (tests/image_probe.h) without a fault. Every variant is copied into a
 * buffer of exactly its size, so that under build/asan (make test) any read outside the image
 * is an AddressSanitizer report and fails the test. Also the fuzzers' findings on valid images:
 * texture coordinates of +-2^40 (finite, so valid) made the texel floor overflow int32
 * (UndefinedBehaviorSanitizer; tests/fuzz/regress/memimage/texcoord-floor-overflow.bin).
 */
#define _GNU_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "f24.h"
#include "image_probe.h"
#include "memimage.h"
#include "scenes.h"
#include "shade_encode.h"

enum { VARIANTS = 1500 };

static uint64_t rng;
static uint32_t next32(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (uint32_t)(rng >> 32);
}
static uint32_t below(uint32_t n) { return (uint32_t)(((uint64_t)next32() * n) >> 32); }

/* One corruption of w[0..n) in place; returns the new length. */
static uint32_t corrupt(uint32_t *w, uint32_t n)
{
    const uint32_t kind = below(5), count = 1 + below(4);
    for (uint32_t k = 0; k < count && kind < 4; k++) {
        /* kinds 2 and 3 aim at the header and the small record tables after the geometry */
        const uint32_t objects = w[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
        const uint32_t at = kind == 2 ? below(MI_HEADER_WORDS) : kind == 3 && objects < n ? objects + below(n - objects)
                                                                                         : below(n);
        if (kind == 0 || kind == 3)
            w[at] ^= 1u << below(32);
        else
            w[at] = below(4) == 0 ? below(n + 8) : next32(); /* plausible indices or anything */
    }
    if (kind == 4) { /* truncation, with the size field telling the new length (or not) */
        n = below(n);
        if (n > MI_H_USED_WORDS && below(2))
            w[MI_H_USED_WORDS] = n;
    }
    return n;
}

/* The memory image of a generated scene with a 64x48 camera. */
static mi_builder *build_scene(const char *name, scene *s)
{
    char err[512];
    const scene_gen_params gp = { 1, 0 };
    if (scene_generator_find(name)->build(s, &gp, err, sizeof err) != 0)
        fail_msg("%s: %s", name, err);
    mi_params p;
    mi_params_default(&p);
    p.width = 64;
    p.height = 48;
    mi_builder *b = mi_build(s, &p, err, sizeof err);
    if (!b)
        fail_msg("%s: %s", name, err);
    return b;
}

static void run_scene(const char *name, uint64_t seed)
{
    scene s;
    char err[512];
    mi_builder *b = build_scene(name, &s);
    uint32_t n;
    const uint32_t *good = mi_words(b, &n);
    assert_int_equal(mi_validate(good, n, err, sizeof err), 0);
    uint32_t *w = malloc((size_t)n * sizeof *w);
    uint32_t refused = 0, rendered = 0;
    rng = seed;
    for (int v = 0; v < VARIANTS; v++) {
        memcpy(w, good, (size_t)n * sizeof *w);
        const uint32_t len = corrupt(w, n);
        uint32_t *exact = malloc(((size_t)len + 1) * sizeof *exact); /* +1: malloc(0) may be NULL */
        memcpy(exact, w, (size_t)len * sizeof *exact);
        err[0] = 0;
        if (mi_validate(exact, len, err, sizeof err) != 0) {
            refused++;
            if (err[0] == 0 || strchr(err, '\n'))
                fail_msg("%s variant %d: refused without a one-line error", name, v);
        } else {
            image_probe(exact, 2);
            rendered++;
        }
        free(exact);
    }
    print_message("%s: %u words, %d corrupted variants (seed %llu): %u refused, %u rendered without a fault\n", name,
                  n, VARIANTS, (unsigned long long)seed, refused, rendered);
    assert_true(refused > 0 && rendered > 0);
    free(w);
    mi_free(b);
    scene_free(&s);
}

static void corrupt_cornell(void **state) { (void)state; run_scene("cornell", 0x5EED0001ull); }
static void corrupt_room(void **state) { (void)state; run_scene("room", 0x5EED0002ull); }
static void corrupt_animated(void **state) { (void)state; run_scene("animated", 0x5EED0003ull); }

/* Every texture coordinate of the room's textured objects at -2^40 or +2^40: valid, renders. */
static void huge_texcoords(void **state)
{
    (void)state;
    scene s;
    mi_builder *b = build_scene("room", &s);
    uint32_t n, patched = 0;
    const uint32_t *good = mi_words(b, &n);
    uint32_t *w = malloc((size_t)n * sizeof *w);
    for (uint32_t sign = 0; sign < 2; sign++) {
        memcpy(w, good, (size_t)n * sizeof *w);
        const uint32_t huge = (sign ? F24_SIGN_BIT : 0u) | (uint32_t)(F24_BIAS + 40) << F24_MAN_BITS;
        for (uint32_t o = 0; o < w[MI_H_OBJECTS]; o++) {
            const uint32_t *d = w + w[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS] + MI_OBJECT_WORDS * o;
            for (uint32_t t = 0; (d[MI_O_FLAGS] & MI_OBJECT_HAS_TEXCOORDS) && t < d[MI_O_N_TRIANGLES]; t++, patched++)
                for (uint32_t k = 0; k < 6; k++)
                    shade_encode_texcoord(&w[d[MI_O_SHADING] + shade_rec_words(d[MI_O_FLAGS]) * t +
                                             shade_rec_tail(d[MI_O_FLAGS])], d[MI_O_FLAGS], 0, k, huge);
        }
        char err[256];
        assert_int_equal(mi_validate(w, n, err, sizeof err), 0);
        image_probe(w, 4);
    }
    assert_true(patched > 0);
    free(w);
    mi_free(b);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(corrupt_cornell), cmocka_unit_test(corrupt_room), cmocka_unit_test(corrupt_animated),
        cmocka_unit_test(huge_texcoords),
    };
    return cmocka_run_group_tests_name("corrupt_image", tests, NULL, NULL);
}
