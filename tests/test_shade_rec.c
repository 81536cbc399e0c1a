/*
 * Tests of the compact shading record (hls/units/shade_rec.h, host/memimage/shade_encode.c):
 * octahedral normals round-trip through the device's decoder within SHADE_OCT_MAX_ERR_URAD of
 * angle (random directions, the axes, the fold's edges) and decode to unit length; neighbouring
 * fields of a block do not disturb each other; missing
 * normals (zero, non-finite) decode to zero; texture coordinates and the material index come back
 * bit for bit; the record's stride follows the object's flags.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "f24_fast.h"
#include "shade_encode.h"

static uint64_t rng = 0x243F6A8885A308D3ull;
static double urand(void) /* [-1, 1) */
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng >> 11) / 4503599627370496.0 - 1.0;
}

/* Angle in microradians between n and the decoded normal of its encoding; the decoded length's
 * distance from 1 in len_err. */
static double round_trip_urad(const double n[3], double *len_err)
{
    uint32_t block[SHADE_NORMAL_WORDS] = { 0 };
    shade_encode_set_normal(block, 1, shade_encode_normal(n)); /* normal B: straddles words 1 and 2 */
    const f24_vec3 d = shade_rec_normal(block, 1);
    const double v[3] = { f24_fast_decode(d.x), f24_fast_decode(d.y), f24_fast_decode(d.z) };
    const double lv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double cr[3] = { n[1] * v[2] - n[2] * v[1], n[2] * v[0] - n[0] * v[2], n[0] * v[1] - n[1] * v[0] };
    const double dt = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
    *len_err = fabs(lv - 1);
    return 1e6 * atan2(sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]), dt);
}

static void normals_within_bound(void **state)
{
    (void)state;
    double worst = 0, worst_len = 0, len_err;
    for (int i = 0; i < 200000; i++) {
        double n[3] = { urand(), urand(), urand() };
        if (i % 7 == 0)
            n[i % 3] = 0; /* on the octahedron's edges and the fold */
        if (n[0] == 0 && n[1] == 0 && n[2] == 0)
            continue;
        const double s = i % 5 == 0 ? 1e-3 : 1; /* any length: a direction */
        const double m[3] = { s * n[0], s * n[1], s * n[2] };
        worst = fmax(worst, round_trip_urad(m, &len_err));
        worst_len = fmax(worst_len, len_err);
    }
    for (int a = 0; a < 6; a++) {
        double n[3] = { 0, 0, 0 };
        n[a / 2] = a % 2 ? -1 : 1;
        assert_true(round_trip_urad(n, &len_err) < 1.0); /* the axes are exact */
    }
    print_message("octahedral normals: worst angle %.1f urad (bound %d), worst |length - 1| %.2e\n", worst,
                  SHADE_OCT_MAX_ERR_URAD, worst_len);
    assert_true(worst <= SHADE_OCT_MAX_ERR_URAD);
    assert_true(worst_len <= 4.0 / (1 << F24_MAN_BITS)); /* a few fp24 roundings */
}

static void missing_normals(void **state)
{
    (void)state;
    const double zero[3] = { 0, 0, 0 }, inf[3] = { INFINITY, 0, 0 }, nan3[3] = { NAN, 1, 0 };
    assert_int_equal(shade_encode_normal(zero), SHADE_NO_NORMAL);
    assert_int_equal(shade_encode_normal(inf), SHADE_NO_NORMAL);
    assert_int_equal(shade_encode_normal(nan3), SHADE_NO_NORMAL);
    uint32_t block[SHADE_NORMAL_WORDS] = { 0 };
    for (uint32_t k = 0; k < 3; k++) {
        shade_encode_set_normal(block, k, SHADE_NO_NORMAL);
        const f24_vec3 d = shade_rec_normal(block, k);
        assert_true(f24_is_zero(d.x) && f24_is_zero(d.y) && f24_is_zero(d.z));
    }
}

/* A record with every part: normals, texture coordinates of both sets (fp24 bits exact,
 * including huge and negative values), vertex colours (bytes), material (in the record, or the
 * object's: SHADE_ONE_MATERIAL); and the strides of the flag combinations. */
static void record_round_trip(void **state)
{
    (void)state;
    const float na[3] = { 0, 0, 1 }, nb[3] = { 0.6f, -0.8f, 0 }, nc[3] = { -1, -1, -1 };
    const float ca[3] = { 0, 0.5f, 1 }, cb[3] = { 1, 1, 1 }, cc[3] = { 0.2f, -1, 7 };
    const float *const normals[3] = { na, nb, nc };
    shade_triangle t = { .normal = { 0 }, .colour = { ca, cb, cc }, .material = 4321,
                         .uv = { { { 0.25, -3.5 }, { 1e6, 0.999 }, { -7e-5, 8191.5 / 8192 } },
                                 { { 3, 1.5 }, { -0.5, 0 }, { 1, 2 } } } };
    for (int k = 0; k < 3; k++)
        t.normal[k] = shade_encode_normal((const double[3]){ normals[k][0], normals[k][1], normals[k][2] });
    const uint8_t bytes[3][3] = { { 0, 128, 255 }, { 255, 255, 255 }, { 51, 0, 255 } };
    for (uint32_t combo = 0; combo < 32; combo++) {
        const uint32_t flags = (combo & 3u) | (combo & 4u ? SHADE_ONE_MATERIAL | 4321u << SHADE_OBJ_MATERIAL_SHIFT : 0u) |
                               (combo & 8u ? SHADE_HAS_COLOURS : 0u) | ((combo & 16u) && (combo & 2u) ? SHADE_HAS_EMISSIVE_UV : 0u);
        uint32_t w[SHADE_MAX_WORDS + 1];
        w[shade_rec_words(flags)] = 0xDEADBEEFu; /* guard: the record stays within its stride */
        shade_encode_record(w, flags, &t);
        assert_int_equal(w[shade_rec_words(flags)], 0xDEADBEEFu);
        const uint32_t *tail = w + shade_rec_tail(flags);
        assert_int_equal(shade_rec_material(flags, tail), 4321);
        const uint32_t sets = (flags & SHADE_HAS_EMISSIVE_UV) ? 2u : (flags & SHADE_HAS_TEXCOORDS) ? 1u : 0u;
        for (uint32_t i = 0; i < 6 * sets; i++)
            assert_int_equal(shade_rec_texcoord(flags, tail, i / 6, i % 6), f24_fast_encode(t.uv[i / 6][i % 6 / 2][i % 2]));
        for (uint32_t v = 0; (flags & SHADE_HAS_COLOURS) && v < 3; v++)
            for (uint32_t k = 0; k < 3; k++)
                assert_int_equal(shade_rec_colour(flags, tail, v, k), bytes[v][k]);
        for (uint32_t k = 0; (flags & SHADE_HAS_NORMALS) && k < 3; k++) {
            uint32_t one[SHADE_NORMAL_WORDS] = { 0 };
            shade_encode_set_normal(one, 0, t.normal[k]);
            for (uint32_t c = 0; c < 2; c++)
                assert_int_equal(shade_rec_oct(w, k, c), shade_rec_oct(one, 0, c));
        }
    }
    if (F24_WIDTH == 24) { /* 5, 9, 1, 5 words: 20, 36, 4, 20 bytes per triangle */
        assert_int_equal(shade_rec_words(SHADE_HAS_NORMALS), 5);
        assert_int_equal(shade_rec_words(SHADE_HAS_NORMALS | SHADE_HAS_TEXCOORDS), 9);
        assert_int_equal(shade_rec_words(0), 1);
        assert_int_equal(shade_rec_words(SHADE_HAS_TEXCOORDS), 5);
        /* one material per object: 4, 9, 0, 5 words */
        assert_int_equal(shade_rec_words(SHADE_ONE_MATERIAL | SHADE_HAS_NORMALS), 4);
        assert_int_equal(shade_rec_words(SHADE_ONE_MATERIAL | SHADE_HAS_NORMALS | SHADE_HAS_TEXCOORDS), 9);
        assert_int_equal(shade_rec_words(SHADE_ONE_MATERIAL), 0);
        assert_int_equal(shade_rec_words(SHADE_ONE_MATERIAL | SHADE_HAS_TEXCOORDS), 5);
        /* vertex colours: 72 bits more; emissive coordinates: 144 bits more */
        assert_int_equal(shade_rec_words(SHADE_HAS_COLOURS), 3);
        assert_int_equal(shade_rec_words(SHADE_ONE_MATERIAL | SHADE_HAS_COLOURS), 3);
        assert_int_equal(shade_rec_words(SHADE_HAS_TEXCOORDS | SHADE_HAS_EMISSIVE_UV), 10);
        assert_int_equal(shade_rec_words(SHADE_HAS_NORMALS | SHADE_HAS_TEXCOORDS | SHADE_HAS_EMISSIVE_UV | SHADE_HAS_COLOURS),
                         4 + 12);
    }
    assert_true(shade_rec_words(SHADE_HAS_NORMALS | SHADE_HAS_TEXCOORDS | SHADE_HAS_EMISSIVE_UV | SHADE_HAS_COLOURS) <=
                SHADE_MAX_WORDS);
}

/* Setting one field leaves its neighbours alone: texture coordinates beside the material, the
 * components of three normals (negative ones included: sign extension). */
static void fields_independent(void **state)
{
    (void)state;
    uint32_t tail[SHADE_MAX_WORDS];
    memset(tail, 0xFF, sizeof tail);
    tail[0] = 0xFFFF0007u;
    for (uint32_t i = 0; i < 6; i++)
        shade_encode_texcoord(tail, SHADE_HAS_TEXCOORDS, 0, i, i + 1);
    for (uint32_t i = 0; i < 6; i++)
        assert_int_equal(shade_rec_texcoord(SHADE_HAS_TEXCOORDS, tail, 0, i), i + 1);
    assert_int_equal(shade_rec_material(SHADE_HAS_TEXCOORDS, tail), 7);
    uint32_t normals[SHADE_NORMAL_WORDS];
    memset(normals, 0xFF, sizeof normals);
    const int32_t v[3][2] = { { -SHADE_OCT_ONE, 5 }, { 123456, -654321 }, { SHADE_OCT_ONE, -1 } };
    const uint32_t field = (1u << SHADE_OCT_BITS) - 1u;
    for (uint32_t k = 0; k < 3; k++)
        shade_encode_set_normal(normals, k, ((uint32_t)v[k][0] & field) | (uint64_t)((uint32_t)v[k][1] & field) << SHADE_OCT_BITS);
    for (uint32_t k = 0; k < 3; k++)
        for (uint32_t c = 0; c < 2; c++)
            assert_int_equal(shade_rec_oct(normals, k, c), v[k][c]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(normals_within_bound),
        cmocka_unit_test(missing_normals),
        cmocka_unit_test(record_round_trip),
        cmocka_unit_test(fields_independent),
    };
    return cmocka_run_group_tests_name("shading record (hls/units/shade_rec.h, host/memimage/shade_encode.c)", tests,
                                       NULL, NULL);
}
