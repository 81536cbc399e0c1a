/*
 * room: a small furnished room after the paper's "Scene6": a 6 x 3 x 5 room (checker-textured
 * floor, walls, ceiling), a table, four chairs that are ONE chair mesh placed by four nodes, a
 * hanging lamp and a few objects on the table (a glass vase, a bowl with three fruits that are
 * one instanced sphere mesh, two instanced cups, a book). The seed jitters the chairs' placement;
 * detail is not used. 2,936 triangles in 9 objects, 15 instances, 4,584 triangles in the scene.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "geom.h"
#include "scenes.h"

enum { TEX = 64 };

/* 8 x 8 checker of two wood tones with a little seeded grain. */
static uint32_t floor_texture(geom_scene *g, geom_rng *rng)
{
    uint8_t *px = malloc(TEX * TEX * 4);
    if (!px) {
        g->oom = 1;
        return SCENE_NONE;
    }
    for (int y = 0; y < TEX; y++) {
        for (int x = 0; x < TEX; x++) {
            const int dark = ((x / 8) + (y / 8)) & 1;
            const double grain = geom_range(rng, -12, 12);
            uint8_t *p = &px[(y * TEX + x) * 4];
            p[0] = (uint8_t)((dark ? 120 : 200) + grain);
            p[1] = (uint8_t)((dark ? 80 : 150) + grain);
            p[2] = (uint8_t)((dark ? 45 : 95) + grain);
            p[3] = 255;
        }
    }
    const uint32_t t = geom_add_texture(g, TEX, TEX, px);
    free(px);
    return t;
}

int scene_gen_room(scene *out, const scene_gen_params *p, char *err, size_t errlen)
{
    geom_scene g;
    geom_rng rng;
    geom_rng_seed(&rng, p->seed, 0x6006);
    geom_scene_begin(&g, out);

    scene_material floor_m = geom_material(1.0f, 1.0f, 1.0f, 0.0f, 0.6f);
    floor_m.base_color_texture = floor_texture(&g, &rng);
    const scene_material wall_m = geom_material(0.85f, 0.80f, 0.68f, 0.0f, 0.95f);
    const scene_material ceiling_m = geom_material(0.95f, 0.95f, 0.95f, 0.0f, 1.0f);
    const scene_material table_m = geom_material(0.45f, 0.27f, 0.12f, 0.0f, 0.5f);
    const scene_material chair_m = geom_material(0.55f, 0.12f, 0.10f, 0.0f, 0.6f);
    const scene_material metal_m = geom_material(0.20f, 0.20f, 0.22f, 1.0f, 0.35f);
    scene_material glass_m = geom_material(0.70f, 0.85f, 0.95f, 0.0f, 0.05f);
    glass_m.transmission = 0.9f;
    glass_m.ior = 1.5f;
    glass_m.double_sided = 1;
    scene_material bowl_m = geom_material(0.15f, 0.30f, 0.65f, 0.0f, 0.3f);
    bowl_m.double_sided = 1; /* open shells: seen from inside too */
    const scene_material fruit_m = geom_material(0.85f, 0.45f, 0.05f, 0.0f, 0.4f);
    const scene_material cup_m = geom_material(0.92f, 0.92f, 0.88f, 0.0f, 0.2f);
    const scene_material book_m = geom_material(0.10f, 0.40f, 0.25f, 0.0f, 0.8f);
    scene_material shade_m = geom_material(0.95f, 0.85f, 0.55f, 0.0f, 0.7f);
    shade_m.double_sided = 1;
    scene_material bulb_m = geom_material(1.0f, 0.95f, 0.8f, 0.0f, 1.0f);
    bulb_m.emissive[0] = 8.0f;
    bulb_m.emissive[1] = 7.0f;
    bulb_m.emissive[2] = 5.0f;
    const uint32_t floor_mat = geom_add_material(&g, &floor_m), wall = geom_add_material(&g, &wall_m);
    const uint32_t ceiling = geom_add_material(&g, &ceiling_m), wood = geom_add_material(&g, &table_m);
    const uint32_t fabric = geom_add_material(&g, &chair_m), metal = geom_add_material(&g, &metal_m);
    const uint32_t glass = geom_add_material(&g, &glass_m), ceramic = geom_add_material(&g, &bowl_m);
    const uint32_t fruit_mat = geom_add_material(&g, &fruit_m), porcelain = geom_add_material(&g, &cup_m);
    const uint32_t cover = geom_add_material(&g, &book_m), shade = geom_add_material(&g, &shade_m);
    const uint32_t bulb = geom_add_material(&g, &bulb_m);

    geom_mesh m;
    geom_mesh_init(&m);

    /* the room: x in [-3, 3], y in [0, 3], z in [-2.5, 2.5], all faces pointing inwards */
    const affine floor_xf = geom_place(0, 0, 0, 0, 6, 1, 5);
    const affine ceil_xf = geom_trs(0, 3, 0, 1, 0, 0, M_PI, 6, 1, 5);
    const affine back_xf = geom_trs(0, 1.5, -2.5, 1, 0, 0, M_PI / 2, 6, 1, 3);
    const affine front_xf = geom_trs(0, 1.5, 2.5, 1, 0, 0, -M_PI / 2, 6, 1, 3);
    const affine left_xf = geom_trs(-3, 1.5, 0, 0, 0, 1, -M_PI / 2, 3, 1, 5);
    const affine right_xf = geom_trs(3, 1.5, 0, 0, 0, 1, M_PI / 2, 3, 1, 5);
    geom_grid(&m, &floor_xf, 12, 10, NULL, floor_mat, NULL, NULL);
    geom_grid(&m, &back_xf, 6, 3, NULL, wall, NULL, NULL);
    geom_grid(&m, &front_xf, 6, 3, NULL, wall, NULL, NULL);
    geom_grid(&m, &left_xf, 3, 5, NULL, wall, NULL, NULL);
    geom_grid(&m, &right_xf, 3, 5, NULL, wall, NULL, NULL);
    geom_grid(&m, &ceil_xf, 6, 5, NULL, ceiling, NULL, NULL);
    const uint32_t room = geom_add_mesh(&g, &m, "room");

    /* table: 1.6 x 0.9 top at 0.75, four round legs */
    const affine top_xf = geom_place(0, 0.73, 0, 0, 1.6, 0.05, 0.9);
    geom_box(&m, &top_xf, wood);
    for (int k = 0; k < 4; k++) {
        const affine leg = geom_place(k & 1 ? 0.7 : -0.7, 0, k & 2 ? 0.35 : -0.35, 0, 0.035, 0.705, 0.035);
        geom_frustum(&m, &leg, 1.0, 0.8, 16, 1, wood);
    }
    const uint32_t table = geom_add_mesh(&g, &m, "table");

    /* chair, facing +Z: seat at 0.45, four legs, a backrest of two posts and three slats */
    const affine seat_xf = geom_place(0, 0.45, 0, 0, 0.45, 0.05, 0.45);
    geom_box(&m, &seat_xf, fabric);
    for (int k = 0; k < 4; k++) {
        const affine leg = geom_place(k & 1 ? 0.19 : -0.19, 0, k & 2 ? 0.19 : -0.19, 0, 0.02, 0.425, 0.02);
        geom_frustum(&m, &leg, 1.0, 1.0, 12, 1, metal);
    }
    for (int k = 0; k < 2; k++) {
        const affine post = geom_place(k ? 0.19 : -0.19, 0.7, -0.2, 0, 0.04, 0.5, 0.04);
        geom_box(&m, &post, metal);
    }
    for (int k = 0; k < 3; k++) {
        const affine slat = geom_place(0, 0.62 + 0.13 * k, -0.2, 0, 0.36, 0.06, 0.025);
        geom_box(&m, &slat, metal);
    }
    const uint32_t chair = geom_add_mesh(&g, &m, "chair");

    /* vase: a glass surface of revolution */
    static const double vase_profile[][2] = { { 0.0, 0.0 }, { 0.05, 0.0 }, { 0.07, 0.03 }, { 0.085, 0.08 },
                                              { 0.08, 0.14 }, { 0.06, 0.2 }, { 0.035, 0.25 }, { 0.03, 0.29 },
                                              { 0.04, 0.32 }, { 0.045, 0.33 } };
    geom_lathe(&m, NULL, vase_profile, sizeof vase_profile / sizeof vase_profile[0], 32, glass);
    const uint32_t vase = geom_add_mesh(&g, &m, "vase");

    static const double bowl_profile[][2] = { { 0.0, 0.0 }, { 0.06, 0.0 }, { 0.1, 0.02 }, { 0.13, 0.05 },
                                              { 0.15, 0.09 }, { 0.155, 0.1 } };
    geom_lathe(&m, NULL, bowl_profile, sizeof bowl_profile / sizeof bowl_profile[0], 32, ceramic);
    const uint32_t bowl = geom_add_mesh(&g, &m, "bowl");

    const affine fruit_xf = geom_place(0, 0.04, 0, 0, 0.04, 0.04, 0.04);
    geom_sphere(&m, &fruit_xf, 2, fruit_mat);
    const uint32_t fruit = geom_add_mesh(&g, &m, "fruit");

    static const double cup_profile[][2] = { { 0.0, 0.0 }, { 0.03, 0.0 }, { 0.035, 0.01 }, { 0.04, 0.09 },
                                             { 0.042, 0.1 } };
    geom_lathe(&m, NULL, cup_profile, sizeof cup_profile / sizeof cup_profile[0], 24, porcelain);
    const affine handle_xf = geom_trs(0.045, 0.05, 0, 1, 0, 0, M_PI / 2, 0.02, 0.006, 0.025);
    geom_frustum(&m, &handle_xf, 1.0, 1.0, 12, 1, porcelain);
    const uint32_t cup = geom_add_mesh(&g, &m, "cup");

    const affine book_xf = geom_place(0, 0.02, 0, 0, 0.22, 0.04, 0.3);
    geom_box(&m, &book_xf, cover);
    const uint32_t book = geom_add_mesh(&g, &m, "book");

    /* lamp hanging from the ceiling: cord, shade, bulb */
    const affine cord_xf = geom_place(0, 2.45, 0, 0, 0.006, 0.55, 0.006);
    geom_frustum(&m, &cord_xf, 1.0, 1.0, 8, 0, metal);
    static const double shade_profile[][2] = { { 0.3, 2.2 }, { 0.25, 2.28 }, { 0.15, 2.38 }, { 0.06, 2.44 },
                                               { 0.02, 2.45 } };
    geom_lathe(&m, NULL, shade_profile, sizeof shade_profile / sizeof shade_profile[0], 32, shade);
    const affine bulb_xf = geom_place(0, 2.33, 0, 0, 0.06, 0.08, 0.06);
    geom_sphere(&m, &bulb_xf, 2, bulb);
    const uint32_t lamp = geom_add_mesh(&g, &m, "lamp");

    geom_add_node(&g, "room", -1, room, NULL, NULL, NULL);
    const uint32_t table_node = geom_add_node(&g, "table", -1, table, NULL, NULL, NULL);
    for (int k = 0; k < 4; k++) { /* two chairs on each long side, facing the table */
        const double side = k < 2 ? -1 : 1;
        const double t[3] = { (k & 1 ? 0.4 : -0.4) + geom_range(&rng, -0.05, 0.05), 0,
                              side * (0.72 + geom_range(&rng, 0, 0.12)) };
        double q[4];
        geom_quat_axis(0, 1, 0, (side > 0 ? M_PI : 0) + geom_range(&rng, -0.15, 0.15), q);
        char name[24]; /* room for any int: -O1 checks the format's worst case */
        snprintf(name, sizeof name, "chair%d", k);
        geom_add_node(&g, name, -1, chair, t, q, NULL);
    }
    /* objects on the table top (y = 0.755), children of the table node */
    const double vase_t[3] = { -0.45, 0.755, -0.1 }, bowl_t[3] = { 0.15, 0.755, 0.05 }, book_t[3] = { 0.55, 0.755, -0.15 };
    geom_add_node(&g, "vase", (int)table_node, vase, vase_t, NULL, NULL);
    const uint32_t bowl_node = geom_add_node(&g, "bowl", (int)table_node, bowl, bowl_t, NULL, NULL);
    for (int k = 0; k < 3; k++) {
        const double t[3] = { 0.05 * cos(2.1 * k), 0.012 + 0.01 * k, 0.05 * sin(2.1 * k) };
        char name[24];
        snprintf(name, sizeof name, "fruit%d", k);
        geom_add_node(&g, name, (int)bowl_node, fruit, t, NULL, NULL);
    }
    for (int k = 0; k < 2; k++) {
        const double t[3] = { k ? 0.5 : -0.2, 0.755, k ? 0.25 : 0.28 };
        double q[4];
        geom_quat_axis(0, 1, 0, k ? 2.0 : 0.7, q);
        geom_add_node(&g, k ? "cup1" : "cup0", (int)table_node, cup, t, q, NULL);
    }
    double q[4];
    geom_quat_axis(0, 1, 0, 0.3, q);
    geom_add_node(&g, "book", (int)table_node, book, book_t, q, NULL);
    geom_add_node(&g, "lamp", -1, lamp, NULL, NULL, NULL);

    const double lamp_light[3] = { 0, 2.15, 0 }, corner_light[3] = { -2.4, 2.6, 2.0 };
    geom_add_point_light(&g, "lamp_light", lamp_light, 1.0f, 0.9f, 0.7f, 6.0f);
    geom_add_point_light(&g, "fill_light", corner_light, 0.7f, 0.8f, 1.0f, 2.0f);
    const double eye[3] = { 2.6, 1.7, 2.2 }, target[3] = { 0, 0.7, 0 };
    geom_add_camera(&g, eye, target, 55.0 * M_PI / 180, 4.0 / 3.0, 0.05, 50.0);
    return geom_scene_end(&g, err, errlen);
}
