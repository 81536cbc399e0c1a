/*
 * Tests of the scene profile (host/memimage/mi_profile) and of the skips it enables in hls/:
 * for generated scenes and single-object variants (identity, scaled), rendering with the
 * profile's skips gives the same pixels and primary hits bit for bit as the general pipeline
 * (mi_params.skip = 0) and never more work; the profile bits are the expected ones; any-hit
 * shadow rays save intersections where shadows are cast; and the validator rejects an image
 * whose profile claims a skip the scene does not allow.
 */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "memimage.h"
#include "mi_profile.h"
#include "rgs.h"
#include "scenes.h"

enum { W = 48, H = 36 };

/* A generated scene; variant 1 keeps only the first instance with the identity transformation,
 * variant 2 keeps it scaled by 1/2 and moved. */
static void scene_make(scene *s, const char *name, int variant)
{
    char err[256];
    const scene_gen_params gp = { 1, 0 };
    assert_int_equal(scene_generator_find(name)->build(s, &gp, err, sizeof err), 0);
    assert_int_equal(scene_evaluate(s, 0.5, 0), 0);
    if (variant) {
        s->n_instances = 1;
        affine *m = &s->instances[0].world;
        memset(m, 0, sizeof *m);
        for (int k = 0; k < 3; k++)
            m->m[k][k] = variant == 1 ? 1.0 : 0.5;
        if (variant == 2)
            m->m[0][3] = 0.25;
    }
}

typedef struct {
    uint32_t rgb[W * H];
    hit_record hits[W * H];
    rgs_counters c;
    uint32_t profile;
} frame;

static int merge_static; /* mi_params.merge of render(): off, so that scenes keep their instances */

static void render(const scene *s, uint32_t skip, const rgs_config *rc, frame *f)
{
    char err[256];
    mi_params p;
    mi_params_default(&p);
    p.merge = merge_static;
    p.width = W;
    p.height = H;
    p.skip = skip;
    mi_builder *b = mi_build(s, &p, err, sizeof err);
    assert_non_null(b);
    uint32_t n;
    const uint32_t *mem = mi_words(b, &n);
    assert_int_equal(mi_validate(mem, n, err, sizeof err), 0);
    memset(f, 0, sizeof *f);
    f->profile = trace_profile(mem);
    for (uint32_t y = 0; y < H; y += 2)
        for (uint32_t x = 0; x < W; x += 2) {
            uint32_t rgb[4];
            hit_record h[4];
            rgs_render_block(mem, rc, x, y, rgb, h, &f->c);
            for (int i = 0; i < 4; i++) {
                f->rgb[(y + (uint32_t)(i >> 1)) * W + x + (uint32_t)(i & 1)] = rgb[i];
                f->hits[(y + (uint32_t)(i >> 1)) * W + x + (uint32_t)(i & 1)] = h[i];
            }
        }
    mi_free(b);
}

/* Renders general and specialized; same bits, no more work; returns the specialized profile. */
static uint32_t check_same(const char *name, int variant, const rgs_config *rc, frame *gen, frame *spec)
{
    scene s;
    scene_make(&s, name, variant);
    render(&s, 0, rc, gen);
    render(&s, PROFILE_ALL, rc, spec);
    scene_free(&s);
    assert_int_equal(gen->profile, 0);
    assert_memory_equal(gen->rgb, spec->rgb, sizeof gen->rgb);
    for (size_t i = 0; i < W * H; i++) {
        assert_int_equal(gen->hits[i].instance, spec->hits[i].instance);
        assert_int_equal(gen->hits[i].triangle, spec->hits[i].triangle);
        assert_int_equal(gen->hits[i].t, spec->hits[i].t);
        assert_int_equal(gen->hits[i].u, spec->hits[i].u);
    }
    for (int k = 0; k < RAY_KINDS; k++)
        assert_int_equal(gen->c.rays[k], spec->c.rays[k]);
    assert_true(spec->c.trace.intersections <= gen->c.trace.intersections);
    assert_true(spec->c.trace.transformations <= gen->c.trace.transformations);
    assert_true(spec->c.trace.leaves <= gen->c.trace.leaves);
    print_message("%s/%d: profile 0x%x, intersections %llu -> %llu, transformations %llu -> %llu, leaves %llu -> %llu\n",
                  name, variant, spec->profile, (unsigned long long)gen->c.trace.intersections,
                  (unsigned long long)spec->c.trace.intersections, (unsigned long long)gen->c.trace.transformations,
                  (unsigned long long)spec->c.trace.transformations, (unsigned long long)gen->c.trace.leaves,
                  (unsigned long long)spec->c.trace.leaves);
    return spec->profile;
}

static frame gen_f, spec_f;
static const rgs_config full = { 3, 1, TRAV_STACK };

static void generated_scenes_same_image(void **state)
{
    (void)state;
    static const char *names[] = { "cornell", "room", "terrain", "animated" };
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        const uint32_t p = check_same(names[i], 0, &full, &gen_f, &spec_f);
        assert_int_equal(p & (PROFILE_SINGLE_OBJECT | PROFILE_IDENTITY), 0); /* several instances */
        assert_true(p & PROFILE_ANY_HIT);
    }
}

static void any_hit_shadows_save_work(void **state)
{
    (void)state;
    const rgs_config shadows_only = { 0, 1, TRAV_STACK };
    check_same("room", 0, &shadows_only, &gen_f, &spec_f);
    assert_true(spec_f.c.rays[RAY_SHADOW] > 0);
    assert_true(spec_f.c.trace.intersections < gen_f.c.trace.intersections);
}

static void single_object_identity_and_scaled(void **state)
{
    (void)state;
    uint32_t p = check_same("room", 1, &full, &gen_f, &spec_f);
    assert_int_equal(p & (PROFILE_SINGLE_OBJECT | PROFILE_IDENTITY), PROFILE_SINGLE_OBJECT | PROFILE_IDENTITY);
    assert_true(spec_f.c.trace.transformations <= gen_f.c.trace.transformations); /* identity: no slots anyway */
    assert_true(spec_f.c.trace.leaves < gen_f.c.trace.leaves);                   /* no top-level leaf */
    p = check_same("room", 2, &full, &gen_f, &spec_f);
    assert_int_equal(p & (PROFILE_SINGLE_OBJECT | PROFILE_IDENTITY), PROFILE_SINGLE_OBJECT);
    assert_true(spec_f.c.trace.leaves < gen_f.c.trace.leaves);
    p = check_same("cornell", 1, &full, &gen_f, &spec_f);
    assert_true(p & PROFILE_IDENTITY);
}

/* The room's memory image with default parameters but mi_params.merge. */
static mi_builder *room_image(scene *s, int merge)
{
    char err[256];
    scene_make(s, "room", 0);
    mi_params p;
    mi_params_default(&p);
    p.merge = merge;
    mi_builder *b = mi_build(s, &p, err, sizeof err);
    assert_non_null(b);
    return b;
}

/* mi_params.merge: the static, axis-aligned instances of the room baked into one world-space
 * object under an identity instance (mi_merge.h); the turned chairs keep theirs. The general
 * pipeline and the specialized one give the same bits on it, and the identity instance is
 * flagged, so that the device passes it without transformation slots. */
static void merged_static_scene(void **state)
{
    (void)state;
    merge_static = 1;
    check_same("room", 0, &full, &gen_f, &spec_f);
    scene s;
    mi_builder *b = room_image(&s, 1);
    const mi_stats *st = mi_get_stats(b);
    assert_true(st->merged_objects >= 1 && st->merged_instances > 0 && st->kept_turned > 0);
    assert_int_equal(st->instances, s.n_instances - st->merged_instances + st->merged_objects);
    uint32_t n, identity = 0;
    const uint32_t *mem = mi_words(b, &n);
    for (uint32_t i = 0; i < st->instances; i++)
        identity += mem[mem[MI_H_REGION_TABLE + 2 * MI_R_INSTANCES] + MI_INSTANCE_WORDS * i + MI_I_FLAGS] & MI_INST_IDENTITY;
    assert_int_equal(identity, st->merged_objects);
    mi_free(b);
    scene_free(&s);
    merge_static = 0;
}

static void profile_contents(void **state)
{
    (void)state;
    scene s;
    char err[256];
    mi_builder *b = room_image(&s, 0);
    uint32_t n;
    const uint32_t *mem = mi_words(b, &n);
    mi_profile prof;
    mi_profile_derive(mem, &prof);
    assert_int_equal(prof.instances, s.n_instances);
    assert_false(prof.single_object);
    assert_true(prof.lights >= 1);
    assert_int_equal(prof.lights, prof.point_lights + prof.spot_lights + prof.directional_lights);
    assert_true(prof.reflective > 0);
    assert_int_equal(prof.skip & PROFILE_NO_SECONDARY, 0);
    /* a profile that claims a skip the scene does not allow is refused */
    uint32_t *copy = malloc(n * sizeof *copy);
    assert_non_null(copy);
    memcpy(copy, mem, n * sizeof *copy);
    copy[copy[MI_H_REGION_TABLE + 2 * MI_R_CAMERA] + MI_CAM_PROFILE] |= PROFILE_SINGLE_OBJECT;
    assert_int_not_equal(mi_validate(copy, n, err, sizeof err), 0);
    assert_non_null(strstr(err, "profile"));
    copy[copy[MI_H_REGION_TABLE + 2 * MI_R_CAMERA] + MI_CAM_PROFILE] = 1u << 7; /* unknown bit */
    assert_int_not_equal(mi_validate(copy, n, err, sizeof err), 0);
    free(copy);
    mi_free(b);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(generated_scenes_same_image), cmocka_unit_test(any_hit_shadows_save_work),
        cmocka_unit_test(single_object_identity_and_scaled), cmocka_unit_test(merged_static_scene),
        cmocka_unit_test(profile_contents),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
