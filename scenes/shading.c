/*
 * Small scenes, one per optional shading feature of docs/shading.md, each a golden case
 * (tests/golden/images/cases.txt) checked against the reference:
 *
 *   emissive        emissive textures: a box with base colour and emissive texture under
 *                   emissiveFactor [1, 1, 1] (the usual export: the emission shows the texture,
 *                   not white), a box whose emissive texture has its own KHR_texture_transform
 *                   (the records' second coordinate set), a sphere with an emissive texture only
 *                   and an emission strength of 3 (KHR_materials_emissive_strength when written).
 *   vertex_colours  COLOR_0: a sphere coloured by its position, a textured box whose colours
 *                   multiply its texture.
 *   uv_transform    KHR_texture_transform: four quads with one texture, moved by an offset,
 *                   turned, scaled (repeated), and read through TEXCOORD_1.
 *   unlit           KHR_materials_unlit: an unlit sphere beside its lit twin, an unlit textured
 *                   quad with vertex colours, and an unlit alpha-blended pane in front.
 *
 * All share a grey floor, a point light and the camera. The seed turns each object by up to 0.1
 * radians; detail is not used.
 */
#include <math.h>
#include <stdlib.h>

#include "geom.h"
#include "scenes.h"

enum { TEX = 8 }; /* texture side, texels */

/* An 8x8 texture of distinct texels (red across, green down): turns and offsets show. */
static uint32_t ramp_texture(geom_scene *g)
{
    uint8_t rgba[TEX * TEX * 4];
    for (int y = 0; y < TEX; y++)
        for (int x = 0; x < TEX; x++) {
            uint8_t *t = &rgba[4 * (y * TEX + x)];
            t[0] = (uint8_t)(32 + 32 * x);
            t[1] = (uint8_t)(32 + 32 * y);
            t[2] = (uint8_t)((x + y) % 2 ? 200 : 40);
            t[3] = 255;
        }
    return geom_add_texture(g, TEX, TEX, rgba);
}

/* Black with a bright diagonal stripe: a label's emissive texture. */
static uint32_t stripe_texture(geom_scene *g)
{
    uint8_t rgba[TEX * TEX * 4];
    for (int y = 0; y < TEX; y++)
        for (int x = 0; x < TEX; x++) {
            uint8_t *t = &rgba[4 * (y * TEX + x)];
            const int lit = (x + y) % 4 < 2;
            t[0] = lit ? 255 : 0;
            t[1] = lit ? 220 : 0;
            t[2] = lit ? 60 : 0;
            t[3] = 255;
        }
    return geom_add_texture(g, TEX, TEX, rgba);
}

/* Floor, light and camera of every scene here; the objects stand on y = 0 around x = 0. */
static void stage(geom_scene *g)
{
    const scene_material floor_m = geom_material(0.5f, 0.5f, 0.52f, 0.0f, 1.0f);
    const uint32_t floor_mat = geom_add_material(g, &floor_m);
    geom_mesh m;
    geom_mesh_init(&m);
    const affine floor_xf = geom_trs(0, 0, 0, 1, 0, 0, 0, 8, 1, 8);
    geom_grid(&m, &floor_xf, 1, 1, NULL, floor_mat, NULL, NULL);
    geom_add_node(g, "floor", -1, geom_add_mesh(g, &m, "floor"), NULL, NULL, NULL);
    const double light_pos[3] = { 2, 4, 3 }, eye[3] = { 0, 1.6, 4.5 }, target[3] = { 0, 0.6, 0 };
    geom_add_point_light(g, "light", light_pos, 1.0f, 1.0f, 1.0f, 10.0f);
    geom_add_camera(g, eye, target, 40 * M_PI / 180, 4.0 / 3.0, 0.1, 100.0);
}

/* A mesh of one shape (box, sphere or upright quad facing +z, turned a little by the seed's
 * generator) with material mat at (x, y, 0), size s, as a node; returns the mesh. */
enum { BOX, SPHERE, QUAD };
static uint32_t place(geom_scene *g, geom_rng *rng, int shape, uint32_t mat, double x, double y, double s,
                      const char *name)
{
    geom_mesh m;
    geom_mesh_init(&m);
    const double turn = geom_range(rng, -0.1, 0.1);
    const affine xf = shape == QUAD ? geom_trs(x, y, 0, 1, 0, 0, M_PI / 2 + turn, s, 1, s)
                                    : geom_trs(x, y, 0, 0, 1, 0, 0.6 + turn, s, s, s);
    if (shape == BOX)
        geom_box(&m, &xf, mat);
    else if (shape == SPHERE)
        geom_sphere(&m, &xf, 3, mat);
    else
        geom_grid(&m, &xf, 1, 1, NULL, mat, NULL, NULL);
    const uint32_t mesh = geom_add_mesh(g, &m, name);
    geom_add_node(g, name, -1, mesh, NULL, NULL, NULL);
    return mesh;
}

/* Vertex colours of a mesh from its positions: a smooth rainbow over the scene. */
static void colour_by_position(geom_scene *g, uint32_t mesh)
{
    if (g->oom || mesh >= g->s->n_meshes)
        return;
    scene_mesh *m = &g->s->meshes[mesh];
    m->colours = malloc(3 * (size_t)m->n_vertices * sizeof(float) + 1);
    if (!m->colours) {
        g->oom = 1;
        return;
    }
    for (size_t v = 0; v < m->n_vertices; v++)
        for (int k = 0; k < 3; k++)
            m->colours[3 * v + (size_t)k] = (float)(0.6 + 0.4 * sin(4 * (m->positions[3 * v] + m->positions[3 * v + 1]) + 2.1 * k));
}

/* TEXCOORD_1 of a mesh: TEXCOORD_0 mirrored in s and doubled. */
static void second_texcoords(geom_scene *g, uint32_t mesh)
{
    if (g->oom || mesh >= g->s->n_meshes || !g->s->meshes[mesh].texcoords)
        return;
    scene_mesh *m = &g->s->meshes[mesh];
    m->texcoords1 = malloc(2 * (size_t)m->n_vertices * sizeof(float) + 1);
    if (!m->texcoords1) {
        g->oom = 1;
        return;
    }
    for (size_t v = 0; v < m->n_vertices; v++) {
        m->texcoords1[2 * v] = 2 * (1 - m->texcoords[2 * v]);
        m->texcoords1[2 * v + 1] = 2 * m->texcoords[2 * v + 1];
    }
}

static scene_uv_map uv_map(double ox, double oy, double rotation, double sx, double sy)
{
    return (scene_uv_map){ 1, { ox, oy }, rotation, { sx, sy } };
}

int scene_gen_emissive(scene *out, const scene_gen_params *p, char *err, size_t errlen)
{
    geom_scene g;
    geom_rng rng;
    geom_rng_seed(&rng, p->seed, 0x5AD);
    geom_scene_begin(&g, out);
    stage(&g);
    const uint32_t ramp = ramp_texture(&g), stripes = stripe_texture(&g);
    scene_material label = geom_material(1, 1, 1, 0, 0.6f);
    label.base_color_texture = ramp;
    label.emissive_texture = stripes;
    label.emissive[0] = label.emissive[1] = label.emissive[2] = 1;
    scene_material turned = label;
    turned.emissive_uv = uv_map(0.5, 0, 0.8, 2, 2);
    scene_material glow = geom_material(0.2f, 0.2f, 0.2f, 0, 1);
    glow.emissive_texture = stripes;
    glow.emissive[0] = 3;
    glow.emissive[1] = 1.5f;
    glow.emissive[2] = 0.6f;
    place(&g, &rng, BOX, geom_add_material(&g, &label), -1.3, 0.5, 0.9, "label");
    place(&g, &rng, BOX, geom_add_material(&g, &turned), 0, 0.5, 0.9, "turned_label");
    place(&g, &rng, SPHERE, geom_add_material(&g, &glow), 1.3, 0.5, 0.5, "glow");
    return geom_scene_end(&g, err, errlen);
}

int scene_gen_vertex_colours(scene *out, const scene_gen_params *p, char *err, size_t errlen)
{
    geom_scene g;
    geom_rng rng;
    geom_rng_seed(&rng, p->seed, 0x5AD);
    geom_scene_begin(&g, out);
    stage(&g);
    const scene_material white = geom_material(1, 1, 1, 0, 0.5f);
    scene_material textured = white;
    textured.base_color_texture = ramp_texture(&g);
    colour_by_position(&g, place(&g, &rng, SPHERE, geom_add_material(&g, &white), -0.8, 0.6, 0.6, "rainbow"));
    colour_by_position(&g, place(&g, &rng, BOX, geom_add_material(&g, &textured), 0.8, 0.5, 1.0, "tinted_box"));
    return geom_scene_end(&g, err, errlen);
}

int scene_gen_uv_transform(scene *out, const scene_gen_params *p, char *err, size_t errlen)
{
    geom_scene g;
    geom_rng rng;
    geom_rng_seed(&rng, p->seed, 0x5AD);
    geom_scene_begin(&g, out);
    stage(&g);
    scene_material m = geom_material(1, 1, 1, 0, 1);
    m.base_color_texture = ramp_texture(&g);
    const scene_uv_map maps[4] = { uv_map(0.25, 0.5, 0, 1, 1), uv_map(0, 0, 0.7, 1, 1), uv_map(0, 0, 0, 3, 2),
                                   uv_map(0.125, 0, 0, 1, 1) };
    for (int i = 0; i < 4; i++) {
        m.base_uv = maps[i];
        m.texcoord_set = i == 3; /* the last quad reads TEXCOORD_1 */
        const uint32_t mesh = place(&g, &rng, QUAD, geom_add_material(&g, &m), -1.65 + 1.1 * i, 0.6, 1.0, "quad");
        if (i == 3)
            second_texcoords(&g, mesh);
    }
    return geom_scene_end(&g, err, errlen);
}

int scene_gen_unlit(scene *out, const scene_gen_params *p, char *err, size_t errlen)
{
    geom_scene g;
    geom_rng rng;
    geom_rng_seed(&rng, p->seed, 0x5AD);
    geom_scene_begin(&g, out);
    stage(&g);
    scene_material lit = geom_material(0.9f, 0.3f, 0.2f, 0, 0.4f), unlit = lit;
    unlit.unlit = 1;
    scene_material poster = geom_material(1, 1, 1, 0, 1);
    poster.base_color_texture = ramp_texture(&g);
    poster.unlit = 1;
    scene_material pane = geom_material(0.3f, 0.6f, 1.0f, 0, 1);
    pane.base_color[3] = 0.5f;
    pane.alpha = ALPHA_BLEND;
    pane.unlit = 1;
    place(&g, &rng, SPHERE, geom_add_material(&g, &lit), -1.2, 0.5, 0.5, "lit");
    place(&g, &rng, SPHERE, geom_add_material(&g, &unlit), 0, 0.5, 0.5, "unlit");
    colour_by_position(&g, place(&g, &rng, QUAD, geom_add_material(&g, &poster), 1.3, 0.6, 1.0, "poster"));
    geom_mesh mesh;
    geom_mesh_init(&mesh);
    const affine pane_xf = geom_trs(-0.6, 0.5, 1.2, 1, 0, 0, M_PI / 2, 1.0, 1, 0.8);
    geom_grid(&mesh, &pane_xf, 1, 1, NULL, geom_add_material(&g, &pane), NULL, NULL);
    geom_add_node(&g, "pane", -1, geom_add_mesh(&g, &mesh, "pane"), NULL, NULL, NULL);
    return geom_scene_end(&g, err, errlen);
}
