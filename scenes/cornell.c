/*
 * cornell: the classic Cornell box. A 2 x 2 x 2 room open towards the camera (white floor,
 * ceiling and back wall, red left and green right wall), one box mesh instanced as the tall and
 * the short block, a small emissive quad under the ceiling (the area light) and a point light
 * just below it. The seed turns the blocks by a few degrees; detail is not used.
 * 24 triangles in 3 objects (walls, block, area light), 4 instances, 36 triangles in the scene.
 */
#include "geom.h"
#include "scenes.h"

int scene_gen_cornell(scene *out, const scene_gen_params *p, char *err, size_t errlen)
{
    geom_scene g;
    geom_rng rng;
    geom_rng_seed(&rng, p->seed, 0xC0);
    geom_scene_begin(&g, out);

    const scene_material white_m = geom_material(0.73f, 0.73f, 0.73f, 0.0f, 0.9f);
    const scene_material red_m = geom_material(0.65f, 0.05f, 0.05f, 0.0f, 0.9f);
    const scene_material green_m = geom_material(0.12f, 0.45f, 0.15f, 0.0f, 0.9f);
    const scene_material block_m = geom_material(0.80f, 0.76f, 0.66f, 0.0f, 0.8f);
    scene_material light_m = geom_material(0.78f, 0.78f, 0.78f, 0.0f, 1.0f);
    light_m.emissive[0] = 17.0f;
    light_m.emissive[1] = 12.0f;
    light_m.emissive[2] = 4.0f;
    const uint32_t white = geom_add_material(&g, &white_m), red = geom_add_material(&g, &red_m);
    const uint32_t green = geom_add_material(&g, &green_m), block = geom_add_material(&g, &block_m);
    const uint32_t light = geom_add_material(&g, &light_m);

    /* walls: unit quads (XZ plane, facing +Y) turned inwards; x in [-1, 1], y in [0, 2], z in [-1, 1] */
    geom_mesh m;
    geom_mesh_init(&m);
    const affine floor_xf = geom_trs(0, 0, 0, 1, 0, 0, 0, 2, 1, 2);
    const affine ceiling_xf = geom_trs(0, 2, 0, 1, 0, 0, M_PI, 2, 1, 2);
    const affine back_xf = geom_trs(0, 1, -1, 1, 0, 0, M_PI / 2, 2, 1, 2);
    const affine left_xf = geom_trs(-1, 1, 0, 0, 0, 1, -M_PI / 2, 2, 1, 2);
    const affine right_xf = geom_trs(1, 1, 0, 0, 0, 1, M_PI / 2, 2, 1, 2);
    geom_grid(&m, &floor_xf, 1, 1, NULL, white, NULL, NULL);
    geom_grid(&m, &ceiling_xf, 1, 1, NULL, white, NULL, NULL);
    geom_grid(&m, &back_xf, 1, 1, NULL, white, NULL, NULL);
    geom_grid(&m, &left_xf, 1, 1, NULL, red, NULL, NULL);
    geom_grid(&m, &right_xf, 1, 1, NULL, green, NULL, NULL);
    const uint32_t walls = geom_add_mesh(&g, &m, "walls");

    geom_box(&m, NULL, block);
    const uint32_t box = geom_add_mesh(&g, &m, "block");

    const affine lamp_xf = geom_trs(0, 1.995, 0, 1, 0, 0, M_PI, 0.5, 1, 0.4);
    geom_grid(&m, &lamp_xf, 1, 1, NULL, light, NULL, NULL);
    const uint32_t lamp = geom_add_mesh(&g, &m, "area_light");

    geom_add_node(&g, "walls", -1, walls, NULL, NULL, NULL);
    double q[4];
    const double tall_t[3] = { -0.34, 0.6, -0.3 }, tall_s[3] = { 0.58, 1.2, 0.58 };
    geom_quat_axis(0, 1, 0, (17.0 + geom_range(&rng, -5, 5)) * M_PI / 180, q);
    geom_add_node(&g, "tall_block", -1, box, tall_t, q, tall_s);
    const double short_t[3] = { 0.34, 0.3, 0.32 }, short_s[3] = { 0.58, 0.6, 0.58 };
    geom_quat_axis(0, 1, 0, (-17.0 + geom_range(&rng, -5, 5)) * M_PI / 180, q);
    geom_add_node(&g, "short_block", -1, box, short_t, q, short_s);
    geom_add_node(&g, "area_light", -1, lamp, NULL, NULL, NULL);

    const double light_pos[3] = { 0, 1.85, 0 };
    geom_add_point_light(&g, "ceiling_light", light_pos, 1.0f, 0.85f, 0.6f, 4.0f);
    const double eye[3] = { 0, 1, 3.9 }, target[3] = { 0, 1, 0 };
    geom_add_camera(&g, eye, target, 39.3 * M_PI / 180, 1.0, 0.1, 100.0);
    return geom_scene_end(&g, err, errlen);
}
