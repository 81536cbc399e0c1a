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
#include <stdlib.h>
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

/* A unit quad in z = 0 with uv = xy, a 2x2 texture (red, green, blue, white), no lights (the
 * light at the eye), seen head-on from (0.5, 0.5, 2): the centre pixel samples the texture centre,
 * the bilinear average of the four texels; a pixel at the centre of texel (0, 0) gets red. */
static void bilinear_texture(void **state)
{
    (void)state;
    scene s;
    memset(&s, 0, sizeof s);
    static const float pos[] = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 }, uv[] = { 0, 0, 1, 0, 1, 1, 0, 1 };
    static const uint32_t idx[] = { 0, 1, 2, 0, 2, 3 };
    static const uint8_t texels[] = { 255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255 };
    s.n_meshes = 1;
    s.meshes = calloc(1, sizeof *s.meshes);
    scene_mesh *m = &s.meshes[0];
    m->n_vertices = 4;
    m->n_triangles = 2;
    m->positions = malloc(sizeof pos);
    memcpy(m->positions, pos, sizeof pos);
    m->texcoords = malloc(sizeof uv);
    memcpy(m->texcoords, uv, sizeof uv);
    m->indices = malloc(sizeof idx);
    memcpy(m->indices, idx, sizeof idx);
    m->material = calloc(2, sizeof *m->material);
    s.n_materials = 1;
    s.materials = calloc(1, sizeof *s.materials);
    for (int k = 0; k < 4; k++)
        s.materials[0].base_color[k] = 1.0f;
    s.materials[0].base_color_texture = 0;
    s.n_textures = 1;
    s.textures = calloc(1, sizeof *s.textures);
    s.textures[0] = (scene_texture){ 2, 2, malloc(sizeof texels) };
    memcpy(s.textures[0].rgba, texels, sizeof texels);
    s.n_nodes = s.n_roots = 1;
    s.nodes = calloc(1, sizeof *s.nodes);
    s.nodes[0] = (scene_node){ .parent = -1, .mesh = 0, .camera = SCENE_NONE, .light = SCENE_NONE,
                               .rotation = { 0, 0, 0, 1 }, .scale = { 1, 1, 1 } };
    s.roots = calloc(1, sizeof *s.roots);
    assert_int_equal(scene_evaluate(&s, 0, 0), 0);
    mi_params p;
    mi_params_default(&p);
    p.width = p.height = 64;
    p.explicit_view = 1;
    const double eye[3] = { 0.5, 0.5, 2 }, at[3] = { 0.5, 0.5, 0 }, up[3] = { 0, 1, 0 };
    memcpy(p.eye, eye, sizeof eye);
    memcpy(p.at, at, sizeof at);
    memcpy(p.up, up, sizeof up);
    p.fov_degrees = 40; /* the view spans [-0.228, 1.228] in x and y at the quad */
    char err[256];
    mi_builder *b = mi_build(&s, &p, err, sizeof err);
    assert_non_null(b);
    uint32_t n;
    const uint32_t *mem = mi_words(b, &n);
    trace_counters c;
    memset(&c, 0, sizeof c);
    ray_packet rp;
    hit_record h[TRACE_PACKET];
    uint32_t rgb[TRACE_PACKET];
    rgs_primary(mem, 31, 31, &rp); /* pixels 31..32: around the image centre = texture centre */
    trace_packet(mem, &rp, h, &c);
    rgs_shade_packet(mem, &rp, h, rgb, &c);
    for (int i = 0; i < TRACE_PACKET; i++) {
        assert_true(h[i].instance != TRACE_NO_HIT);
        const int r = (int)(rgb[i] >> 16 & 255), g = (int)(rgb[i] >> 8 & 255), bl = (int)(rgb[i] & 255);
        assert_true(abs(r - 127) <= 8 && abs(g - 127) <= 8 && abs(bl - 127) <= 8); /* (R+G+B+W)/4 */
    }
    /* pixel (20, 42) sees (u, v) = (0.238, 0.261): the centre of texel (0, 0), red */
    rgs_primary(mem, 20, 42, &rp);
    trace_packet(mem, &rp, h, &c);
    rgs_shade_packet(mem, &rp, h, rgb, &c);
    assert_true(h[0].instance != TRACE_NO_HIT);
    assert_true((rgb[0] >> 16 & 255) > 200 && (rgb[0] >> 8 & 255) < 60 && (rgb[0] & 255) < 60);
    mi_free(b);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = { cmocka_unit_test(primary_rays), cmocka_unit_test(shading),
                                        cmocka_unit_test(bilinear_texture) };
    return cmocka_run_group_tests_name("rgs", tests, NULL, NULL);
}
