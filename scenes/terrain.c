/*
 * terrain: a 200 x 200 height field of `detail` x `detail` cells (default 256: 131,072
 * triangles) from seeded fractal value noise, coloured grass / rock (steep) / snow (high), with
 * 300 trees: two tree meshes (a conifer and a broadleaf tree) instanced on gentle slopes below
 * the snow line with random yaw and scale.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom.h"
#include "scenes.h"

enum { DEFAULT_CELLS = 256, MAX_CELLS = 2048, TREES = 300 };

static const double SIZE = 200.0, HEIGHT = 32.0, SNOW = 21.0;

/* Lattice value in [-1, 1] from a hash of the cell and the seed. */
static double lattice(uint64_t seed, int64_t x, int64_t y)
{
    geom_rng r = { seed ^ ((uint64_t)x * 0x9E3779B97F4A7C15ull) ^ ((uint64_t)y * 0xC2B2AE3D27D4EB4Full) };
    return 2.0 * geom_rand(&r) - 1.0;
}

static double value_noise(uint64_t seed, double x, double y)
{
    const double fx = floor(x), fy = floor(y), u = x - fx, v = y - fy;
    const int64_t ix = (int64_t)fx, iy = (int64_t)fy;
    const double su = u * u * (3 - 2 * u), sv = v * v * (3 - 2 * v);
    const double a = lattice(seed, ix, iy), b = lattice(seed, ix + 1, iy);
    const double c = lattice(seed, ix, iy + 1), d = lattice(seed, ix + 1, iy + 1);
    return (a + (b - a) * su) * (1 - sv) + (c + (d - c) * su) * sv;
}

/* Height in world units at (x, z) in [-SIZE/2, SIZE/2]^2: 6 octaves, ridges from 1 - |n|. */
static double height_at(uint64_t seed, double x, double z)
{
    double h = 0, amp = 1, freq = 3.0 / SIZE, norm = 0;
    for (int o = 0; o < 6; o++) {
        const double n = value_noise(seed + (uint64_t)o * 7919, x * freq + 17.3, z * freq - 5.1);
        h += amp * (o < 2 ? n : 0.6 * n + 0.4 * (1 - 2 * fabs(n)));
        norm += amp;
        amp *= 0.5;
        freq *= 2.03;
    }
    h /= norm;
    /* a valley along the middle, mountains towards the back */
    const double back = 0.5 - z / SIZE;
    return HEIGHT * (0.55 * h + 0.35 * back * back + 0.08 * (x / SIZE) * (x / SIZE) * 4) + 4.0;
}

typedef struct {
    uint32_t grass, rock, snow;
} terrain_materials;

static uint32_t terrain_material(double height, double up, const void *ctx)
{
    const terrain_materials *t = ctx;
    if (height > SNOW && up > 0.6)
        return t->snow;
    return up < 0.82 ? t->rock : t->grass;
}

/* Height of the triangulated grid at (x, z) (the surface the trees stand on). */
static double surface_at(const float *h, uint32_t n, double x, double z)
{
    const double gx = (x / SIZE + 0.5) * n, gz = (z / SIZE + 0.5) * n;
    uint32_t i = (uint32_t)fmin(fmax(floor(gx), 0), n - 1), j = (uint32_t)fmin(fmax(floor(gz), 0), n - 1);
    const double u = gx - i, v = gz - j;
    const double h00 = h[j * (n + 1) + i], h10 = h[j * (n + 1) + i + 1];
    const double h01 = h[(j + 1) * (n + 1) + i], h11 = h[(j + 1) * (n + 1) + i + 1];
    /* cells are split along (i,j)-(i+1,j+1): triangles (00, 01, 11) and (00, 11, 10) */
    return v >= u ? h00 + (h11 - h01) * u + (h01 - h00) * v : h00 + (h10 - h00) * u + (h11 - h10) * v;
}

static uint32_t conifer(geom_scene *g, uint32_t bark, uint32_t needles)
{
    geom_mesh m;
    geom_mesh_init(&m);
    const affine trunk = geom_place(0, -0.3, 0, 0, 0.25, 2.3, 0.25);
    geom_frustum(&m, &trunk, 1.0, 0.6, 10, 1, bark);
    for (int k = 0; k < 4; k++) {
        const double r = 2.2 - 0.45 * k, y = 1.5 + 1.5 * k;
        const affine cone = geom_place(0, y, 0, 0.4 * k, r, 2.6 - 0.2 * k, r);
        geom_frustum(&m, &cone, 1.0, 0.0, 16, 1, needles);
    }
    return geom_add_mesh(g, &m, "conifer");
}

static uint32_t broadleaf(geom_scene *g, uint32_t bark, uint32_t foliage)
{
    geom_mesh m;
    geom_mesh_init(&m);
    const affine trunk = geom_place(0, -0.3, 0, 0, 0.3, 3.3, 0.3);
    geom_frustum(&m, &trunk, 1.0, 0.7, 10, 1, bark);
    const affine crown = geom_place(0, 4.6, 0, 0, 2.4, 2.0, 2.4);
    geom_sphere(&m, &crown, 2, foliage);
    const affine top = geom_place(0.6, 6.0, -0.3, 0, 1.5, 1.3, 1.5);
    geom_sphere(&m, &top, 2, foliage);
    return geom_add_mesh(g, &m, "broadleaf");
}

int scene_gen_terrain(scene *out, const scene_gen_params *p, char *err, size_t errlen)
{
    const uint32_t n = p->detail ? p->detail : DEFAULT_CELLS;
    memset(out, 0, sizeof *out);
    if (n < 2 || n > MAX_CELLS) {
        snprintf(err, errlen, "detail %u is out of range (2..%u cells per side)", n, (unsigned)MAX_CELLS);
        return -1;
    }
    geom_scene g;
    geom_rng rng;
    geom_rng_seed(&rng, p->seed, 0x7E4);
    const uint64_t noise_seed = geom_rng_u64(&rng);
    geom_scene_begin(&g, out);

    const scene_material grass_m = geom_material(0.24f, 0.45f, 0.13f, 0.0f, 0.9f);
    const scene_material rock_m = geom_material(0.42f, 0.39f, 0.36f, 0.0f, 0.8f);
    const scene_material snow_m = geom_material(0.93f, 0.94f, 0.97f, 0.0f, 0.6f);
    const scene_material bark_m = geom_material(0.30f, 0.20f, 0.12f, 0.0f, 0.9f);
    const scene_material needle_m = geom_material(0.07f, 0.28f, 0.12f, 0.0f, 0.8f);
    const scene_material foliage_m = geom_material(0.30f, 0.55f, 0.10f, 0.0f, 0.7f);
    const terrain_materials tm = { geom_add_material(&g, &grass_m), geom_add_material(&g, &rock_m),
                                   geom_add_material(&g, &snow_m) };
    const uint32_t bark = geom_add_material(&g, &bark_m), needles = geom_add_material(&g, &needle_m);
    const uint32_t foliage = geom_add_material(&g, &foliage_m);

    float *h = malloc((size_t)(n + 1) * (n + 1) * sizeof *h);
    if (!h) {
        g.oom = 1;
        return geom_scene_end(&g, err, errlen);
    }
    for (uint32_t j = 0; j <= n; j++)
        for (uint32_t i = 0; i <= n; i++)
            h[(size_t)j * (n + 1) + i] = (float)height_at(noise_seed, SIZE * ((double)i / n - 0.5), SIZE * ((double)j / n - 0.5));
    geom_mesh m;
    geom_mesh_init(&m);
    const affine ground_xf = geom_place(0, 0, 0, 0, SIZE, 1, SIZE);
    geom_grid(&m, &ground_xf, n, n, h, tm.grass, terrain_material, &tm);
    const uint32_t land = geom_add_mesh(&g, &m, "terrain");
    geom_add_node(&g, "terrain", -1, land, NULL, NULL, NULL);

    const uint32_t tree[2] = { conifer(&g, bark, needles), broadleaf(&g, bark, foliage) };
    uint32_t placed = 0;
    for (uint32_t attempt = 0; placed < TREES && attempt < 100 * TREES; attempt++) {
        const double x = geom_range(&rng, -0.45, 0.45) * SIZE, z = geom_range(&rng, -0.45, 0.45) * SIZE;
        const double y = surface_at(h, n, x, z), e = 1.0;
        const double gx = surface_at(h, n, x + e, z) - surface_at(h, n, x - e, z);
        const double gz = surface_at(h, n, x, z + e) - surface_at(h, n, x, z - e);
        if (y > SNOW - 2 || sqrt(gx * gx + gz * gz) / (2 * e) > 0.5)
            continue;
        const int kind = y > 12.0 + geom_range(&rng, -3, 3) ? 0 : 1; /* conifers higher up */
        const double s = geom_range(&rng, 0.7, 1.4), t[3] = { x, y, z }, sc[3] = { s, s * geom_range(&rng, 0.85, 1.2), s };
        double q[4];
        geom_quat_axis(0, 1, 0, geom_range(&rng, 0, 2 * M_PI), q);
        char name[24];
        snprintf(name, sizeof name, "tree%u", placed++);
        geom_add_node(&g, name, -1, tree[kind], t, q, sc);
    }
    free(h);

    const double sun[3] = { -0.5, -0.8, -0.35 }, eye[3] = { -60, 45, 110 }, target[3] = { 10, 8, -10 };
    geom_add_dir_light(&g, "sun", sun, 1.0f, 0.93f, 0.8f, 3.5f);
    const double lamp[3] = { 0, 40, 0 };
    geom_add_point_light(&g, "sky_fill", lamp, 0.6f, 0.7f, 1.0f, 500.0f);
    geom_add_camera(&g, eye, target, 50.0 * M_PI / 180, 16.0 / 9.0, 0.5, 2000.0);
    return geom_scene_end(&g, err, errlen);
}
