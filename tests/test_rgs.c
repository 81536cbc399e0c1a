/*
 * Tests of the ray generation and shading unit (hls/units/rgs): primary rays through the
 * transformation unit match the camera convention of docs/memory-image.md computed in double
 * (direction W + (x + 1/2) U + (y + 1/2) V, origin O), pixels outside the image are inactive,
 * misses get the background, shading traces shadow rays towards the scene's light and is
 * deterministic.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "f24_fast.h"
#include "memimage.h"
#include "rgs.h"
#include "scenes.h"

static double D(f24_t x) { return f24_fast_decode(x); }

static mi_builder *build_cornell(scene *s, uint32_t w, uint32_t h)
{
    char err[256];
    const scene_gen_params gp = { 1, 0 };
    assert_int_equal(scene_generator_find("cornell")->build(s, &gp, err, sizeof err), 0);
    assert_int_equal(scene_evaluate(s, 0, 0), 0);
    mi_params p;
    mi_params_default(&p);
    p.width = w;
    p.height = h;
    mi_builder *b = mi_build(s, &p, err, sizeof err);
    assert_non_null(b);
    return b;
}

static void primary_rays(void **state)
{
    (void)state;
    scene s;
    mi_builder *b = build_cornell(&s, 37, 21);
    uint32_t n, w, h;
    const uint32_t *mem = mi_words(b, &n);
    rgs_image_size(mem, &w, &h);
    assert_int_equal(w, 37);
    assert_int_equal(h, 21);
    const uint32_t *cam = mem + mem[MI_H_REGION_TABLE + 2 * MI_R_CAMERA];
    for (uint32_t y = 0; y < h + 1; y += 2) {
        for (uint32_t x = 0; x < w + 1; x += 2) {
            ray_packet rp;
            rgs_primary(mem, x, y, &rp);
            for (int i = 0; i < 4; i++) {
                const uint32_t px = x + (uint32_t)(i & 1), py = y + (uint32_t)(i >> 1);
                assert_int_equal(rp.active >> i & 1u, px < w && py < h);
                const f24_t *o = &rp.o[i].x, *d = &rp.d[i].x;
                for (int k = 0; k < 3; k++) {
                    assert_int_equal(o[k], cam[4 + k]);
                    const double want = D(cam[13 + k]) + (px + 0.5) * D(cam[7 + k]) + (py + 0.5) * D(cam[10 + k]);
                    const double mag = fabs(D(cam[13 + k])) + fabs((px + 0.5) * D(cam[7 + k])) + fabs((py + 0.5) * D(cam[10 + k]));
                    assert_true(fabs(D(d[k]) - want) <= 5e-5 * mag + 1e-30);
                }
            }
        }
    }
    mi_free(b);
    scene_free(&s);
}

static void shading(void **state)
{
    (void)state;
    scene s;
    mi_builder *b = build_cornell(&s, 8, 8);
    uint32_t n;
    const uint32_t *mem = mi_words(b, &n);
    ray_packet rp;
    rgs_primary(mem, 2, 2, &rp);
    hit_record h[TRACE_PACKET], miss[TRACE_PACKET];
    uint32_t rgb[TRACE_PACKET], bg[TRACE_PACKET], again[TRACE_PACKET];
    trace_counters c;
    memset(&c, 0, sizeof c);
    for (int i = 0; i < TRACE_PACKET; i++)
        miss[i] = (hit_record){ TRACE_NO_HIT, TRACE_NO_HIT, F24_POS_INF, 0, 0, 0 };
    rgs_shade_packet(mem, &rp, miss, bg, &c);
    assert_int_equal(bg[0], bg[3]); /* background */
    trace_packet(mem, &rp, h, &c);
    const uint64_t before = c.transformations;
    rgs_shade_packet(mem, &rp, h, rgb, &c);
    assert_true(c.transformations > before); /* shadow rays towards the scene's light were traced */
    rgs_shade_packet(mem, &rp, h, again, &c);
    for (int i = 0; i < TRACE_PACKET; i++) {
        assert_true(h[i].instance != TRACE_NO_HIT); /* the back wall fills the centre of the image */
        assert_true(rgb[i] != bg[i]);
        assert_int_equal(rgb[i], again[i]);
    }
    mi_free(b);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = { cmocka_unit_test(primary_rays), cmocka_unit_test(shading) };
    return cmocka_run_group_tests_name("rgs", tests, NULL, NULL);
}
