/*
 * animated: objects moving under affine transformations from glTF animations over 4 seconds,
 * covering every interpolation and path: a spinning cube (rotation, LINEAR), a hopping cube
 * (translation and rotation, STEP), a bouncing ball (translation and non-uniform squash scale,
 * CUBICSPLINE), a pulsing cylinder (non-uniform scale, LINEAR), a swinging arm with a child
 * hierarchy (rotation, CUBICSPLINE) and a blob whose geometry changes: one mesh with two morph
 * targets (stretch, ripple) driven by a weights channel (LINEAR). The seed varies the phases;
 * detail is not used.
 */
#include <math.h>
#include <stdlib.h>

#include "geom.h"
#include "scenes.h"

enum { KEYS = 9 }; /* keys at 0, 0.5, ..., 4 s */

static void set3(float *v, double x, double y, double z)
{
    v[0] = (float)x;
    v[1] = (float)y;
    v[2] = (float)z;
}

static void set_quat(float *v, double ax, double ay, double az, double angle)
{
    double q[4];
    geom_quat_axis(ax, ay, az, angle, q);
    for (int i = 0; i < 4; i++)
        v[i] = (float)q[i];
}

int scene_gen_animated(scene *out, const scene_gen_params *p, char *err, size_t errlen)
{
    geom_scene g;
    geom_rng rng;
    geom_rng_seed(&rng, p->seed, 0xA417);
    geom_scene_begin(&g, out);

    const scene_material floor_m = geom_material(0.55f, 0.55f, 0.58f, 0.0f, 0.9f);
    const scene_material red_m = geom_material(0.80f, 0.15f, 0.12f, 0.0f, 0.5f);
    const scene_material blue_m = geom_material(0.15f, 0.30f, 0.85f, 0.0f, 0.4f);
    const scene_material yellow_m = geom_material(0.90f, 0.75f, 0.10f, 0.0f, 0.3f);
    const scene_material green_m = geom_material(0.20f, 0.70f, 0.30f, 0.0f, 0.6f);
    const scene_material metal_m = geom_material(0.75f, 0.75f, 0.78f, 1.0f, 0.25f);
    const scene_material purple_m = geom_material(0.55f, 0.20f, 0.70f, 0.0f, 0.35f);
    const uint32_t floor_mat = geom_add_material(&g, &floor_m), red = geom_add_material(&g, &red_m);
    const uint32_t blue = geom_add_material(&g, &blue_m), yellow = geom_add_material(&g, &yellow_m);
    const uint32_t green = geom_add_material(&g, &green_m), metal = geom_add_material(&g, &metal_m);
    const uint32_t purple = geom_add_material(&g, &purple_m);

    geom_mesh m;
    geom_mesh_init(&m);
    const affine floor_xf = geom_place(0, 0, 0, 0, 20, 1, 20);
    geom_grid(&m, &floor_xf, 10, 10, NULL, floor_mat, NULL, NULL);
    const uint32_t ground = geom_add_mesh(&g, &m, "ground");
    geom_box(&m, NULL, red);
    const uint32_t cube = geom_add_mesh(&g, &m, "cube");
    geom_box(&m, NULL, blue);
    const uint32_t blue_cube = geom_add_mesh(&g, &m, "blue_cube");
    geom_sphere(&m, NULL, 3, yellow);
    const uint32_t ball = geom_add_mesh(&g, &m, "ball");
    const affine cyl_xf = geom_place(0, 0, 0, 0, 0.5, 1.5, 0.5);
    geom_frustum(&m, &cyl_xf, 1.0, 1.0, 24, 1, green);
    const uint32_t cylinder = geom_add_mesh(&g, &m, "cylinder");
    const affine rod_xf = geom_place(0, -3, 0, 0, 0.08, 3, 0.08);
    geom_frustum(&m, &rod_xf, 1.0, 1.0, 12, 1, metal);
    const uint32_t rod = geom_add_mesh(&g, &m, "rod");
    geom_sphere(&m, NULL, 3, purple);
    const uint32_t blob = geom_add_mesh(&g, &m, "blob");
    if (!g.oom) { /* morph targets: 0 stretches along +Y, 1 ripples along the normal */
        const scene_mesh *bm = &g.s->meshes[blob];
        float *d = calloc(2 * 3 * (size_t)bm->n_vertices, sizeof *d);
        if (!d) {
            g.oom = 1;
        } else {
            for (uint32_t v = 0; v < bm->n_vertices; v++) {
                const float *q = &bm->positions[3 * v];
                const double ripple = 0.25 * sin(6.0 * q[0]) * cos(6.0 * q[2]);
                d[3 * v + 1] = 0.8f * q[1];
                for (int k = 0; k < 3; k++)
                    d[3 * (size_t)bm->n_vertices + 3 * v + k] = (float)(ripple * q[k]);
            }
            geom_set_morph(&g, blob, 2, d);
            free(d);
        }
    }

    geom_add_node(&g, "ground", -1, ground, NULL, NULL, NULL);
    const double spin_t[3] = { -4, 0.75, 0 }, spin_s[3] = { 1.5, 1.5, 1.5 };
    const uint32_t spinner = geom_add_node(&g, "spinner", -1, cube, spin_t, NULL, spin_s);
    const double hop_t[3] = { -1.5, 0.5, 2.5 };
    const uint32_t hopper = geom_add_node(&g, "hopper", -1, blue_cube, hop_t, NULL, NULL);
    const double ball_t[3] = { -3, 0.5, 3.5 }, ball_s[3] = { 0.5, 0.5, 0.5 };
    const uint32_t bouncer = geom_add_node(&g, "ball", -1, ball, ball_t, NULL, ball_s);
    const double cyl_t[3] = { 4, 0, 0 };
    const uint32_t pulser = geom_add_node(&g, "pulser", -1, cylinder, cyl_t, NULL, NULL);
    const double pivot_t[3] = { 0, 4, -3 };
    const uint32_t arm = geom_add_node(&g, "arm_pivot", -1, SCENE_NONE, pivot_t, NULL, NULL);
    const double hand_t[3] = { 0, -3.2, 0 }, hand_s[3] = { 0.4, 0.4, 0.4 };
    geom_add_node(&g, "arm_rod", (int)arm, rod, NULL, NULL, NULL);
    geom_add_node(&g, "arm_weight", (int)arm, ball, hand_t, NULL, hand_s);
    const double blob_t[3] = { 1.5, 1.2, 2 };
    const uint32_t blob_node = geom_add_node(&g, "blob", -1, blob, blob_t, NULL, NULL);

    const uint32_t anim = geom_add_animation(&g, "motion");
    float times[KEYS], v[KEYS * 12];
    for (int k = 0; k < KEYS; k++)
        times[k] = 0.5f * (float)k;
    const double phase = geom_range(&rng, 0, 0.5);

    /* spinner: a full turn about a slanted axis, LINEAR (slerp between 45-degree steps) */
    for (int k = 0; k < KEYS; k++)
        set_quat(&v[4 * k], 0.2, 1, 0.1, 2 * M_PI * k / (KEYS - 1) + phase);
    geom_add_channel(&g, anim, spinner, ANIM_ROTATION, INTERP_LINEAR, KEYS, times, v);

    /* hopper: jumps between four spots and turns by quarter turns, STEP */
    for (int k = 0; k < KEYS; k++)
        set3(&v[3 * k], -1.5 + 1.0 * (k % 4), 0.5 + 0.25 * (k & 1), 2.5 - 0.5 * (k % 3));
    geom_add_channel(&g, anim, hopper, ANIM_TRANSLATION, INTERP_STEP, KEYS, times, v);
    for (int k = 0; k < KEYS; k++)
        set_quat(&v[4 * k], 0, 1, 0, 0.5 * M_PI * k);
    geom_add_channel(&g, anim, hopper, ANIM_ROTATION, INTERP_STEP, KEYS, times, v);

    /* ball: bounces (CUBICSPLINE translation: in-tangent, value, out-tangent per key), squashed on
     * contact by a non-uniform CUBICSPLINE scale */
    for (int k = 0; k < KEYS; k++) {
        const int low = (k & 1) == 0;
        const double x = -3 + 0.75 * k, vy = low ? 10.0 : 0.0;
        set3(&v[9 * k], 0.75 / 0.5, -vy, 0);                    /* in-tangent (units per second) */
        set3(&v[9 * k + 3], x, low ? 0.45 : 2.8, 3.5);           /* value */
        set3(&v[9 * k + 6], 0.75 / 0.5, vy, 0);                  /* out-tangent */
    }
    geom_add_channel(&g, anim, bouncer, ANIM_TRANSLATION, INTERP_CUBICSPLINE, KEYS, times, v);
    for (int k = 0; k < KEYS; k++) {
        const int low = (k & 1) == 0;
        set3(&v[9 * k], 0, 0, 0);
        set3(&v[9 * k + 3], low ? 0.65 : 0.45, low ? 0.35 : 0.58, low ? 0.65 : 0.45);
        set3(&v[9 * k + 6], 0, 0, 0);
    }
    geom_add_channel(&g, anim, bouncer, ANIM_SCALE, INTERP_CUBICSPLINE, KEYS, times, v);

    /* pulser: non-uniform scale, LINEAR */
    for (int k = 0; k < KEYS; k++) {
        const double a = 0.5 + 0.5 * sin(M_PI * k / 2 + 2 * M_PI * phase);
        set3(&v[3 * k], 1 + 0.6 * a, 1.4 - 0.7 * a, 1 + 0.3 * a);
    }
    geom_add_channel(&g, anim, pulser, ANIM_SCALE, INTERP_LINEAR, KEYS, times, v);

    /* arm: swings about Z (CUBICSPLINE, zero tangents: ease in and out) */
    for (int k = 0; k < KEYS; k++) {
        for (int i = 0; i < 4; i++)
            v[12 * k + i] = v[12 * k + 8 + i] = 0.0f;
        set_quat(&v[12 * k + 4], 0, 0, 1, (k & 1 ? (k & 2 ? -1 : 1) : 0) * 50.0 * M_PI / 180);
    }
    geom_add_channel(&g, anim, arm, ANIM_ROTATION, INTERP_CUBICSPLINE, KEYS, times, v);

    /* blob: morph weights, LINEAR */
    for (int k = 0; k < KEYS; k++) {
        v[2 * k] = (float)(0.5 - 0.5 * cos(M_PI * k / 2));
        v[2 * k + 1] = (float)(k % 4 == 3 ? 1.0 : k % 2 ? 0.4 : 0.0);
    }
    geom_add_channel(&g, anim, blob_node, ANIM_WEIGHTS, INTERP_LINEAR, KEYS, times, v);

    const double key_pos[3] = { 3, 6, 5 }, sun[3] = { 0.3, -1, -0.4 };
    geom_add_point_light(&g, "key_light", key_pos, 1.0f, 0.95f, 0.9f, 60.0f);
    geom_add_dir_light(&g, "sun", sun, 0.9f, 0.95f, 1.0f, 2.0f);
    const double eye[3] = { 0, 6, 13 }, target[3] = { 0, 1.5, 0 };
    geom_add_camera(&g, eye, target, 45.0 * M_PI / 180, 16.0 / 9.0, 0.1, 200.0);
    return geom_scene_end(&g, err, errlen);
}
