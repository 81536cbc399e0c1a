/*
 * plants: after the paper's "SunCOR" (thousands of instances of one large sunflower): ONE
 * procedural sunflower of 29,992 triangles (stem, 16 leaves, a head of 7,000 seeds in a
 * Fibonacci spiral, 34 petals) placed by `detail` nodes (default 5,000) with random yaw, a small
 * random tilt, random scale and position on a square soil plane. The field's side grows with
 * the square root of the instance count.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "geom.h"
#include "scenes.h"

enum { DEFAULT_PLANTS = 5000, MAX_PLANTS = 200000, SEEDS = 7000, LEAVES = 16, PETALS = 34 };

typedef struct {
    double length, width, lift, droop, fold, base;
} blade;

/* A leaf or petal along +X from x = base: u along its length, v across it; the front faces +Y. */
static void blade_surface(double u, double v, const void *ctx, double p[3])
{
    const blade *b = ctx;
    const double shape = pow(sin(M_PI * (0.04 + 0.92 * u)), 0.7);
    const double w = (0.5 - v) * b->width * shape;
    p[0] = b->base + u * b->length;
    p[1] = b->lift * u - b->droop * u * u + b->fold * fabs(w);
    p[2] = w;
}

static uint32_t build_sunflower(geom_scene *g)
{
    const scene_material stem_m = geom_material(0.22f, 0.45f, 0.10f, 0.0f, 0.7f);
    scene_material leaf_m = geom_material(0.15f, 0.55f, 0.12f, 0.0f, 0.6f);
    leaf_m.double_sided = 1;
    const scene_material sepal_m = geom_material(0.10f, 0.30f, 0.06f, 0.0f, 0.8f);
    const scene_material disk_m = geom_material(0.45f, 0.30f, 0.08f, 0.0f, 0.9f);
    const scene_material seed_m = geom_material(0.20f, 0.12f, 0.05f, 0.0f, 0.9f);
    scene_material petal_m = geom_material(1.00f, 0.78f, 0.05f, 0.0f, 0.5f);
    petal_m.double_sided = 1;
    const uint32_t stem = geom_add_material(g, &stem_m), leaf = geom_add_material(g, &leaf_m);
    const uint32_t sepal = geom_add_material(g, &sepal_m), disk = geom_add_material(g, &disk_m);
    const uint32_t seed = geom_add_material(g, &seed_m), petal = geom_add_material(g, &petal_m);

    geom_mesh m;
    geom_mesh_init(&m);
    static const double stem_profile[10][2] = { { 0.036, 0.0 }, { 0.034, 0.18 }, { 0.032, 0.36 }, { 0.030, 0.54 },
                                                { 0.028, 0.72 }, { 0.026, 0.9 }, { 0.024, 1.08 }, { 0.022, 1.26 },
                                                { 0.021, 1.44 }, { 0.020, 1.6 } };
    geom_lathe(&m, NULL, stem_profile, 10, 12, stem);

    for (int i = 0; i < LEAVES; i++) {
        const double h = 0.2 + 1.1 * i / (LEAVES - 1), size = 1.0 - 0.45 * i / (LEAVES - 1);
        const blade b = { 0.34, 0.18, 0.25, 0.45, 0.25, 0.02 };
        const affine xf = geom_place(0, h, 0, i * 2.39996, size, size, size);
        geom_patch(&m, &xf, 8, 3, blade_surface, &b, leaf);
    }

    /* the head: local frame with the seed disk in the XZ plane facing +Y, tilted towards +Z */
    const double R = 0.15;
    const affine head = geom_trs(0, 1.62, 0, 1, 0, 0, 60.0 * M_PI / 180, 1, 1, 1);
    static const double back_profile[8][2] = { { 0.0, -0.06 }, { 0.04, -0.058 }, { 0.08, -0.05 }, { 0.11, -0.04 },
                                               { 0.13, -0.028 }, { 0.145, -0.015 }, { 0.152, -0.005 }, { 0.15, 0.0 } };
    geom_lathe(&m, &head, back_profile, 8, 32, sepal);
    const affine disk_local = geom_place(0, 0, 0, 0, R, 1, R), disk_xf = affine_mul(&head, &disk_local);
    geom_disk(&m, &disk_xf, 48, 0, disk);
    for (int k = 0; k < SEEDS; k++) { /* Fibonacci spiral, golden angle */
        const double r = R * 0.97 * sqrt((k + 0.5) / SEEDS), th = k * 2.39996322972865332;
        const affine local = geom_place(r * cos(th), 0, r * sin(th), -th, 0.0034, 0.004, 0.0034);
        const affine xf = affine_mul(&head, &local);
        geom_pyramid(&m, &xf, seed);
    }
    for (int i = 0; i < PETALS; i++) {
        const blade b = { 0.13, 0.04, i & 1 ? 0.03 : 0.0, 0.02, 0.05, R * 0.92 };
        const affine local = geom_place(0, 0, 0, 2 * M_PI * i / PETALS, 1, 1, 1), xf = affine_mul(&head, &local);
        geom_patch(&m, &xf, 4, 2, blade_surface, &b, petal);
    }
    return geom_add_mesh(g, &m, "sunflower");
}

int scene_gen_plants(scene *out, const scene_gen_params *p, char *err, size_t errlen)
{
    const uint32_t n = p->detail ? p->detail : DEFAULT_PLANTS;
    memset(out, 0, sizeof *out);
    if (n > MAX_PLANTS) {
        snprintf(err, errlen, "detail %u is too large (at most %u instances)", n, (unsigned)MAX_PLANTS);
        return -1;
    }
    geom_scene g;
    geom_rng rng;
    geom_rng_seed(&rng, p->seed, 0x5C0);
    geom_scene_begin(&g, out);

    const uint32_t plant = build_sunflower(&g);
    const double side = 0.9 * sqrt((double)n) + 2.0;
    const scene_material soil_m = geom_material(0.33f, 0.24f, 0.14f, 0.0f, 1.0f);
    const uint32_t soil = geom_add_material(&g, &soil_m);
    geom_mesh m;
    geom_mesh_init(&m);
    const affine ground_xf = geom_place(0, 0, 0, 0, side + 4, 1, side + 4);
    geom_grid(&m, &ground_xf, 4, 4, NULL, soil, NULL, NULL);
    const uint32_t ground = geom_add_mesh(&g, &m, "ground");
    geom_add_node(&g, "ground", -1, ground, NULL, NULL, NULL);

    for (uint32_t i = 0; i < n; i++) {
        const double t[3] = { geom_range(&rng, -0.5, 0.5) * side, 0, geom_range(&rng, -0.5, 0.5) * side };
        const double s = geom_range(&rng, 0.75, 1.25), h = geom_range(&rng, 0.9, 1.15);
        const double sc[3] = { s, s * h, s };
        const double tilt_dir = geom_range(&rng, 0, 2 * M_PI);
        double yaw[4], tilt[4], q[4];
        geom_quat_axis(0, 1, 0, geom_range(&rng, 0, 2 * M_PI), yaw);
        geom_quat_axis(cos(tilt_dir), 0, sin(tilt_dir), geom_range(&rng, 0, 0.12), tilt);
        geom_quat_mul(tilt, yaw, q);
        char name[24];
        snprintf(name, sizeof name, "plant%u", i);
        geom_add_node(&g, name, -1, plant, t, q, sc);
    }

    const double sun[3] = { -0.4, -1.0, -0.5 };
    geom_add_dir_light(&g, "sun", sun, 1.0f, 0.95f, 0.85f, 3.0f);
    const double eye[3] = { 0, 0.15 * side + 1.5, 0.62 * side + 2 }, target[3] = { 0, 0.8, -0.05 * side };
    geom_add_camera(&g, eye, target, 50.0 * M_PI / 180, 4.0 / 3.0, 0.1, 10.0 * side + 100);
    return geom_scene_end(&g, err, errlen);
}
