/*
 * Tests of the ray generation and shading unit (hls/units/rgs): primary rays through the
 * transformation unit match the camera convention of docs/memory-image.md computed in double
 * (direction W + (x + 1/2) U + (y + 1/2) V, origin O), pixels outside the image are inactive,
 * misses get the background, shading traces shadow rays towards the scene's light and is
 * deterministic; the secondary-ray geometry of docs/shading.md (T_R): reflection angle and unit
 * length, Snell's law, total internal reflection; ray trees: depth limit, shadows switch, a
 * mirror shows what it faces, a glass pane shows what is behind it.
 */
#define _POSIX_C_SOURCE 200809L
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
#include "rgs_ops.h"
#include "scenes.h"

static double D(f24_t x) { return f24_fast_decode(x); }

/* Generated scene name's memory image for a w x h view; with flat, its odd meshes without vertex
 * normals (no generated scene lacks them). */
static mi_builder *build_scene(const char *name, scene *s, uint32_t w, uint32_t h, int flat)
{
    char err[256];
    const scene_gen_params gp = { 1, 0 };
    assert_int_equal(scene_generator_find(name)->build(s, &gp, err, sizeof err), 0);
    for (uint32_t k = 1; flat && k < s->n_meshes; k += 2) {
        free(s->meshes[k].normals);
        s->meshes[k].normals = NULL;
    }
    assert_int_equal(scene_evaluate(s, 0, 0), 0);
    mi_params p;
    mi_params_default(&p);
    p.width = w;
    p.height = h;
    mi_builder *b = mi_build(s, &p, err, sizeof err);
    assert_non_null(b);
    return b;
}

static mi_builder *build_cornell(scene *s, uint32_t w, uint32_t h) { return build_scene("cornell", s, w, h, 0); }

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

static const rgs_config full = { 3, 1, TRAV_STACK };

static void render_block(const uint32_t *mem, const rgs_config *cfg, uint32_t x, uint32_t y, uint32_t rgb[],
                         hit_record h[], rgs_counters *c)
{
    memset(c, 0, sizeof *c);
    rgs_render_block(mem, cfg, x, y, rgb, h, c);
}

static void shading(void **state)
{
    (void)state;
    scene s;
    mi_builder *b = build_cornell(&s, 8, 8);
    uint32_t n;
    const uint32_t *mem = mi_words(b, &n);
    hit_record h[TRACE_PACKET];
    uint32_t rgb[TRACE_PACKET], again[TRACE_PACKET], flat[TRACE_PACKET];
    rgs_counters c, c2;
    render_block(mem, &full, 2, 2, rgb, h, &c);
    assert_true(c.rays[RAY_SHADOW] > 0); /* shadow rays towards the scene's light were traced */
    assert_int_equal(c.rays[RAY_PRIMARY], 4);
    render_block(mem, &full, 2, 2, again, h, &c2);
    const rgs_config no_shadows = { 0, 0, TRAV_STACK };
    rgs_counters c3;
    render_block(mem, &no_shadows, 2, 2, flat, h, &c3);
    assert_int_equal(c3.rays[RAY_SHADOW] + c3.rays[RAY_REFLECTION] + c3.rays[RAY_TRANSMISSION], 0);
    for (int i = 0; i < TRACE_PACKET; i++) {
        assert_true(h[i].instance != TRACE_NO_HIT); /* the back wall fills the centre of the image */
        assert_int_equal(rgb[i], again[i]);
    }
    /* a miss: the corner block of a 8x8 view outside the box sees the background */
    mi_free(b);
    scene_free(&s);
}

static f24_vec3 v3(double x, double y, double z)
{
    return (f24_vec3){ f24_fast_encode(x), f24_fast_encode(y), f24_fast_encode(z) };
}

static void dvec(f24_vec3 v, double out[3])
{
    out[0] = D(v.x);
    out[1] = D(v.y);
    out[2] = D(v.z);
}

static double ddot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Random unit direction d and unit normal n facing it (n.d < 0), both rounded to fp24. */
static void random_pair(unsigned *seed, double d[3], double n[3])
{
    for (;;) {
        double l = 0, ln = 0;
        for (int k = 0; k < 3; k++) {
            d[k] = 2.0 * rand_r(seed) / RAND_MAX - 1;
            n[k] = 2.0 * rand_r(seed) / RAND_MAX - 1;
            l += d[k] * d[k];
            ln += n[k] * n[k];
        }
        if (l < 0.01 || ln < 0.01 || l > 1 || ln > 1)
            continue;
        for (int k = 0; k < 3; k++) {
            d[k] = f24_fast_decode(f24_fast_encode(d[k] / sqrt(l)));
            n[k] = f24_fast_decode(f24_fast_encode(n[k] / sqrt(ln)));
        }
        if (ddot(n, d) < -0.02)
            return;
    }
}

/* Reflection through T_R: unit length, angle of reflection = angle of incidence, in the plane of
 * d and n. */
static void reflection_geometry(void **state)
{
    (void)state;
    unsigned seed = 7;
    for (int t = 0; t < 10000; t++) {
        double d[3], n[3], r[3];
        random_pair(&seed, d, n);
        dvec(rgs_reflect(v3(d[0], d[1], d[2]), v3(n[0], n[1], n[2])), r);
        assert_true(fabs(ddot(r, r) - 1) < 1e-4);                /* energy of the direction */
        assert_true(fabs(ddot(r, n) + ddot(d, n)) < 1e-4);       /* angle out = angle in */
        const double c[3] = { d[1] * n[2] - d[2] * n[1], d[2] * n[0] - d[0] * n[2], d[0] * n[1] - d[1] * n[0] };
        assert_true(fabs(ddot(r, c)) < 1e-4);                    /* coplanar with d and n */
    }
}

/* Refraction through T_R: Snell's law sin_t = eta sin_i, unit length, transmitted to the far
 * side of the surface, coplanar; total internal reflection exactly where eta sin_i > 1. */
static void refraction_snell(void **state)
{
    (void)state;
    unsigned seed = 11;
    const double etas[] = { 1.0 / 1.5, 1.5, 1.0 / 2.4, 1.33 };
    int tir = 0, refracted = 0;
    for (int t = 0; t < 20000; t++) {
        double d[3], n[3], r[3];
        random_pair(&seed, d, n);
        const double eta = f24_fast_decode(f24_fast_encode(etas[t % 4]));
        f24_vec3 out;
        const int ok = rgs_refract(v3(d[0], d[1], d[2]), v3(n[0], n[1], n[2]), f24_fast_encode(eta), &out);
        const double ci = -ddot(d, n), si = sqrt(fmax(0, 1 - ci * ci));
        if (fabs(eta * si - 1) < 1e-3)
            continue; /* too close to the critical angle to call */
        assert_int_equal(ok, eta * si < 1);
        if (!ok) {
            tir++;
            continue;
        }
        refracted++;
        dvec(out, r);
        assert_true(fabs(ddot(r, r) - 1) < 2e-4);
        const double ct = -ddot(r, n), st = sqrt(fmax(0, 1 - ct * ct));
        assert_true(ct > 0);                                     /* into the surface */
        assert_true(fabs(st - eta * si) < 2e-3);                 /* Snell */
        const double c[3] = { d[1] * n[2] - d[2] * n[1], d[2] * n[0] - d[0] * n[2], d[0] * n[1] - d[1] * n[0] };
        assert_true(fabs(ddot(r, c)) < 2e-4);
    }
    assert_true(tir > 100 && refracted > 10000);
    /* head-on: straight through for any eta */
    f24_vec3 out;
    assert_true(rgs_refract(v3(0, 0, -1), v3(0, 0, 1), f24_fast_encode(1 / 1.5), &out));
    assert_true(D(out.z) == -1.0 && D(out.x) == 0 && D(out.y) == 0);
}

/* A unit quad in z = 0 with uv = xy, a 2x2 texture (red, green, blue, white), no lights (the
 * host's default light near the eye), seen head-on from (0.5, 0.5, 2): the centre pixel samples
 * the texture centre, the bilinear average of the four texels (grey); a pixel at the centre of
 * texel (0, 0) gets red. */
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
    s.materials[0].emissive_texture = SCENE_NONE;
    s.materials[0].roughness = 1.0f; /* the glTF default: diffuse only, no highlight or reflection */
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
    hit_record h[TRACE_PACKET];
    uint32_t rgb[TRACE_PACKET];
    rgs_counters c;
    const rgs_config primary_only = { 0, 1, TRAV_STACK };
    render_block(mem, &primary_only, 31, 31, rgb, h, &c); /* pixels 31..32: around the texture centre */
    for (int i = 0; i < TRACE_PACKET; i++) {
        assert_true(h[i].instance != TRACE_NO_HIT);
        const int r = (int)(rgb[i] >> 16 & 255), g = (int)(rgb[i] >> 8 & 255), bl = (int)(rgb[i] & 255);
        const int mean = (r + g + bl) / 3; /* (R+G+B+W)/4 x the light: grey, up to the half-texel offset */
        assert_true(abs(r - mean) <= 8 && abs(g - mean) <= 8 && abs(bl - mean) <= 8 && mean > 90 && mean < 140);
    }
    /* pixel (20, 42) sees (u, v) = (0.238, 0.261): the centre of texel (0, 0), red */
    render_block(mem, &primary_only, 20, 42, rgb, h, &c);
    assert_true(h[0].instance != TRACE_NO_HIT);
    assert_true((rgb[0] >> 16 & 255) > 200 && (rgb[0] >> 8 & 255) < 60 && (rgb[0] & 255) < 60);
    mi_free(b);
    scene_free(&s);
}

/* A scene of axis-aligned squares (one node and material each) for the ray-tree tests: square
 * k spans [-r, r]^2 around centre c[k] in the plane z = c[k].z, facing +z or -z. */
typedef struct {
    double z, r;
    scene_material m;
} square;

static void square_scene(scene *s, const square *q, uint32_t n)
{
    memset(s, 0, sizeof *s);
    s->meshes = calloc(n, sizeof *s->meshes);
    s->materials = calloc(n, sizeof *s->materials);
    s->nodes = calloc(n, sizeof *s->nodes);
    s->roots = calloc(n, sizeof *s->roots);
    for (uint32_t k = 0; k < n; k++) {
        scene_mesh *m = &s->meshes[k];
        const float r = (float)q[k].r, z = (float)q[k].z;
        const float pos[] = { -r, -r, z, r, -r, z, r, r, z, -r, r, z };
        static const uint32_t idx[] = { 0, 1, 2, 0, 2, 3 };
        m->n_vertices = 4;
        m->n_triangles = 2;
        m->positions = malloc(sizeof pos);
        memcpy(m->positions, pos, sizeof pos);
        m->indices = malloc(sizeof idx);
        memcpy(m->indices, idx, sizeof idx);
        m->material = malloc(2 * sizeof *m->material);
        m->material[0] = m->material[1] = k;
        s->materials[k] = q[k].m;
        s->materials[k].base_color_texture = s->materials[k].emissive_texture = SCENE_NONE;
        s->nodes[k] = (scene_node){ .parent = -1, .mesh = k, .camera = SCENE_NONE, .light = SCENE_NONE,
                                    .rotation = { 0, 0, 0, 1 }, .scale = { 1, 1, 1 } };
        s->roots[k] = k;
    }
    s->n_meshes = s->n_materials = s->n_nodes = s->n_roots = n;
    /* one directional light shining along -y: grazing every square, so nothing is lit directly */
    s->lights = calloc(1, sizeof *s->lights);
    s->lights[0] = (scene_light){ .kind = LIGHT_DIRECTIONAL, .color = { 1, 1, 1 }, .intensity = 1, .node = SCENE_NONE,
                                  .direction = { 0, -1, 0 } };
    s->n_lights = 1;
    assert_int_equal(scene_evaluate(s, 0, 0), 0);
}

/* Colour of the centre block of a 16x16 view from (0, 0, 2) down -z. */
static uint32_t centre_colour(const scene *s, uint32_t max_depth, rgs_counters *c)
{
    mi_params p;
    mi_params_default(&p);
    p.width = p.height = 16;
    p.explicit_view = 1;
    const double eye[3] = { 0, 0, 2 }, at[3] = { 0, 0, 0 }, up[3] = { 0, 1, 0 };
    memcpy(p.eye, eye, sizeof eye);
    memcpy(p.at, at, sizeof at);
    memcpy(p.up, up, sizeof up);
    p.fov_degrees = 20;
    char err[256];
    mi_builder *b = mi_build(s, &p, err, sizeof err);
    assert_non_null(b);
    uint32_t n, rgb[TRACE_PACKET];
    hit_record h[TRACE_PACKET];
    const rgs_config cfg = { max_depth, 1, TRAV_STACK };
    render_block(mi_words(b, &n), &cfg, 7, 7, rgb, h, c);
    for (int i = 1; i < TRACE_PACKET; i++)
        assert_int_equal(rgb[i], rgb[0]);
    mi_free(b);
    return rgb[0];
}

static scene_material material(float r, float g, float b, float metallic, float roughness)
{
    scene_material m = { .base_color = { r, g, b, 1 }, .metallic = metallic, .roughness = roughness, .ior = 1.5f };
    return m;
}

/* A mirror (metallic 1, roughness 0: kr = 1, kd = 0) at z = 0 facing the camera shows the red
 * emitter behind the camera at z = 3; without secondary rays it is black (plus nothing). */
static void mirror_reflects(void **state)
{
    (void)state;
    square q[2] = { { 0, 1, material(1, 1, 1, 1, 0) }, { 3, 5, material(0, 0, 0, 0, 1) } };
    q[1].m.emissive[0] = 1;
    scene s;
    square_scene(&s, q, 2);
    rgs_counters c;
    assert_int_equal(centre_colour(&s, 1, &c), 0xFF0000u);
    assert_int_equal(c.rays[RAY_REFLECTION], 4);
    assert_int_equal(centre_colour(&s, 0, &c), 0x000000u);
    assert_int_equal(c.rays[RAY_REFLECTION], 0);
    scene_free(&s);
}

/* Clear glass (transmission 1, roughness 1: kt = 1) in front of a green emitter: seen through
 * it with eta = 1 (straight) and with eta = 1.5 (refracted, head-on: undeviated); tinted glass
 * multiplies the base colour in; a second pane needs a second level. */
static void glass_transmits(void **state)
{
    (void)state;
    square q[3] = { { 0.5, 1, material(1, 1, 1, 0, 1) }, { 0.25, 1, material(1, 1, 1, 0, 1) }, { -1, 5, material(0, 0, 0, 0, 1) } };
    q[0].m.transmission = q[1].m.transmission = 1;
    q[2].m.emissive[1] = 1;
    scene s;
    square_scene(&s, q, 3);
    rgs_counters c;
    assert_int_equal(centre_colour(&s, 2, &c), 0x00FF00u);
    assert_int_equal(c.rays[RAY_TRANSMISSION], 8);
    assert_int_equal(centre_colour(&s, 1, &c), 0x000000u); /* the second pane is dark at depth 1 */
    s.materials[0].ior = s.materials[1].ior = 1.0f;
    s.materials[0].base_color[1] = 0.5f;
    assert_int_equal(centre_colour(&s, 2, &c), 0x008000u);
    scene_free(&s);
}

/* A random fp24 word: mostly a value of about unit size (either sign), sometimes any 24 bits
 * (zeros, subnormal encodings, Inf, NaN of both signs, huge and tiny values). */
static f24_t random_word(unsigned *seed)
{
    const int kind = rand_r(seed) % 8;
    if (kind == 0)
        return (f24_t)rand_r(seed) & F24_MASK;
    if (kind == 1) {
        const f24_t special[4] = { 0, F24_SIGN_BIT, F24_POS_INF, F24_POS_INF | F24_SIGN_BIT }; /* +-0, +-Inf */
        return special[rand_r(seed) % 4];
    }
    return f24_fast_encode(4.0 * rand_r(seed) / RAND_MAX - 2);
}

static f24_vec3 random_vec(unsigned *seed)
{
    const f24_t x = random_word(seed), y = random_word(seed);
    return (f24_vec3){ x, y, random_word(seed) };
}

/* The simulation build's rgs_light_packet computes the rays of a packet side by side
 * (tb/sim/rgs_light_lanes.c): the same shadow packet, weights and bits as the per-ray datapath of
 * hls/units/rgs_light.c, for directional, point and spot lights, surfaces valid, invalid and unlit,
 * on unit-size and arbitrary words. */
static void light_packet_lanes(void **state)
{
    (void)state;
#ifndef F24_SIM_LANES
    skip(); /* one definition only: the per-ray one */
#else
    unsigned seed = 11;
    for (int t = 0; t < 20000; t++) {
        uint32_t l[16] = { 0 };
        l[0] = (uint32_t)(t % 3); /* directional, point, spot */
        for (int k = 1; k < 13; k++)
            l[k] = random_word(&seed);
        surface sf[TRACE_PACKET];
        uint32_t k_of[TRACE_PACKET];
        memset(sf, 0, sizeof sf);
        for (int i = 0; i < TRACE_PACKET; i++) {
            const int kind = rand_r(&seed) % 6;
            sf[i].valid = kind != 0;
            sf[i].unlit = kind == 1;
            sf[i].p = random_vec(&seed);
            sf[i].n = random_vec(&seed);
            sf[i].d = random_vec(&seed);
            k_of[i] = (uint32_t)(rand_r(&seed) % 9);
        }
        const f24_t eps = random_word(&seed);
        ray_packet got, want;
        uint32_t gd[TRACE_PACKET], gs[TRACE_PACKET], wd[TRACE_PACKET], ws[TRACE_PACKET];
        memset(&got, 0x55, sizeof got);
        memset(&want, 0x55, sizeof want);
        rgs_light_packet(l, sf, eps, &got, gd, gs, k_of);
        rgs_light_packet_per_ray(l, sf, eps, &want, wd, ws, k_of);
        assert_int_equal(got.active, want.active);
        assert_memory_equal(got.o, want.o, sizeof got.o);
        assert_memory_equal(got.d, want.d, sizeof got.d);
        assert_memory_equal(got.tmin, want.tmin, sizeof got.tmin);
        assert_memory_equal(got.tmax, want.tmax, sizeof got.tmax);
        assert_memory_equal(gd, wd, sizeof gd);
        assert_memory_equal(gs, ws, sizeof gs);
    }
#endif
}

/* A random Q12 word: 0..65535, often within 0..4096. */
static uint32_t random_q12(unsigned *seed)
{
    return (uint32_t)rand_r(seed) % (rand_r(seed) % 2 ? 4097u : 65536u);
}

/* A random surface for op_accumulate with its material record at word 16 i of mem: T_R from its o,
 * D^, N^ or arbitrary words, any entering, base, emission, tint; the material's index of
 * refraction 1 (straight transparency), a random word (refraction, total internal reflection,
 * special words) and random shader words. */
static surface random_surface(unsigned *seed, uint32_t *mem, int i)
{
    surface sf;
    memset(&sf, 0, sizeof sf);
    sf.valid = rand_r(seed) % 6 != 0;
    sf.n = random_vec(seed);
    sf.d = random_vec(seed);
    sf.tr = t_r(random_vec(seed), sf.d, sf.n);
    if (rand_r(seed) % 4 == 0)
        for (int r = 0; r < 3; r++)
            for (int k = 0; k < 4; k++)
                sf.tr.m[r][k] = random_word(seed);
    sf.t_hat = random_word(seed);
    sf.entering = rand_r(seed) % 2;
    for (int k = 0; k < 3; k++)
        sf.base[k] = random_q12(seed), sf.emission[k] = random_q12(seed), sf.tint[k] = random_q12(seed);
    sf.mat = 16u * (uint32_t)i;
    uint32_t *m = &mem[sf.mat];
    m[M_ETA] = rand_r(seed) % 3 == 0 ? F24_ONE : random_word(seed);
    m[M_SHADER0] = (uint32_t)rand_r(seed) ^ (uint32_t)rand_r(seed) << 16;
    m[M_SHADER1] = (uint32_t)rand_r(seed) ^ (uint32_t)rand_r(seed) << 16;
    return sf;
}

/* The simulation build's rgs_accumulate_rays computes the child rays' geometry of a packet side by
 * side (tb/sim/rgs_accum_lanes.c): the same colours, child rays, weights, active bits and T_R step
 * count as the per-ray loop of hls/units/rgs_accum.c, for any active rays and spawn bits. */
static void accumulate_rays_lanes(void **state)
{
    (void)state;
#ifndef F24_SIM_LANES
    skip(); /* one definition only: the per-ray one */
#else
    unsigned seed = 19;
    for (int t = 0; t < 20000; t++) {
        uint32_t mem[16 * TRACE_PACKET] = { 0 }, weight[TRACE_PACKET][3], diffuse[TRACE_PACKET][3];
        uint32_t highlight[TRACE_PACKET][3], got_acc[TRACE_PACKET][3], want_acc[TRACE_PACKET][3];
        surface sf[TRACE_PACKET];
        for (int i = 0; i < TRACE_PACKET; i++) {
            sf[i] = random_surface(&seed, mem, i);
            for (int k = 0; k < 3; k++) {
                weight[i][k] = random_q12(&seed), diffuse[i][k] = random_q12(&seed);
                highlight[i][k] = random_q12(&seed), got_acc[i][k] = want_acc[i][k] = random_q12(&seed);
            }
        }
        const uint32_t active = (uint32_t)rand_r(&seed) % 16u, spawn = (uint32_t)rand_r(&seed) % 4u;
        const f24_t eps = random_word(&seed);
        rgs_task got[2], want[2];
        memset(got, 0x55, sizeof got);
        got[0].rays.active = (uint32_t)rand_r(&seed) % 16u;
        got[1].rays.active = (uint32_t)rand_r(&seed) % 16u;
        memcpy(want, got, sizeof got);
        const uint32_t n = rgs_accumulate_rays(mem, sf, active, weight, diffuse, highlight, eps, spawn, got_acc, &got[0],
                                               &got[1]);
        assert_int_equal(n, rgs_accumulate_rays_per_ray(mem, sf, active, weight, diffuse, highlight, eps, spawn,
                                                        want_acc, &want[0], &want[1]));
        assert_memory_equal(got_acc, want_acc, sizeof got_acc);
        assert_memory_equal(got, want, sizeof got);
    }
#endif
}

/* The simulation build's rgs_surfaces computes the frames of a packet's hits side by side
 * (tb/sim/rgs_surface_lanes.c): rgs_surface_frames gives rgs_surface_frame's fields for the rays
 * in valid, on arbitrary words (rays, distances, normals, instance matrices), and leaves the others
 * as they were. */
static void surface_frames_lanes(void **state)
{
    (void)state;
#ifndef F24_SIM_LANES
    skip(); /* one definition only: the per-ray one */
#else
    unsigned seed = 23;
    for (int t = 0; t < 20000; t++) {
        ray_packet rp;
        hit_record h[TRACE_PACKET];
        f24_vec3 n[TRACE_PACKET];
        f24_affine w2o[TRACE_PACKET];
        surface got[TRACE_PACKET], want[TRACE_PACKET];
        memset(h, 0, sizeof h);
        memset(got, 0x55, sizeof got);
        memcpy(want, got, sizeof got);
        const uint32_t valid = (uint32_t)rand_r(&seed) % 16u;
        for (int i = 0; i < TRACE_PACKET; i++) {
            rp.o[i] = random_vec(&seed);
            rp.d[i] = random_vec(&seed);
            h[i].t = random_word(&seed);
            h[i].cos_n = random_word(&seed);
            n[i] = random_vec(&seed);
            for (int r = 0; r < 3; r++)
                for (int k = 0; k < 4; k++)
                    w2o[i].m[r][k] = random_word(&seed);
            if (valid >> i & 1u)
                rgs_surface_frame(rp.o[i], rp.d[i], h[i].t, h[i].cos_n, n[i], &w2o[i], &want[i]);
        }
        rgs_surface_frames(&rp, h, n, w2o, valid, got);
        assert_memory_equal(got, want, sizeof got);
    }
#endif
}

/* rgs_surfaces side by side against the per-ray loop on the traced primary hits of the Cornell box
 * and the room (textured), each also with half its meshes without vertex normals, their distances,
 * barycentrics and cosines also replaced by arbitrary words: the same surfaces, reads and counters. */
#ifdef F24_SIM_LANES
static void surfaces_lanes_of(const char *name, int flat)
{
    scene s;
    mi_builder *b = build_scene(name, &s, 16, 16, flat);
    uint32_t words;
    const uint32_t *mem = mi_words(b, &words);
    unsigned seed = 29;
    for (uint32_t y = 0; y < 16; y += 2)
        for (uint32_t x = 0; x < 16; x += 2)
            for (int v = 0; v < 8; v++) {
                ray_packet rp;
                hit_record h[TRACE_PACKET];
                trace_counters tc = { 0 }, gc = { 0 }, wc = { 0 };
                rgs_primary(mem, x, y, &rp);
                trace_packet(mem, &rp, h, &tc);
                rp.active &= (uint32_t)rand_r(&seed) % 16u | (v == 0 ? 0xFu : 0u);
                for (int i = 0; i < TRACE_PACKET && v > 1; i++) {
                    h[i].t = random_word(&seed);
                    h[i].u = random_word(&seed);
                    h[i].v = random_word(&seed);
                    h[i].cos_n = random_word(&seed);
                }
                unit_op got_op, want_op;
                surface got[TRACE_PACKET], want[TRACE_PACKET];
                memset(&got_op, 0, sizeof got_op);
                memset(&want_op, 0, sizeof want_op);
                rgs_surfaces(mem, &rp, h, got, &got_op, &gc);
                rgs_surfaces_per_ray(mem, &rp, h, want, &want_op, &wc);
                assert_memory_equal(got, want, sizeof got);
                assert_memory_equal(&got_op, &want_op, sizeof got_op);
                assert_memory_equal(&gc, &wc, sizeof gc);
            }
    mi_free(b);
    scene_free(&s);
}
#endif

static void surfaces_lanes(void **state)
{
    (void)state;
#ifndef F24_SIM_LANES
    skip(); /* one definition only: the per-ray one */
#else
    for (int flat = 0; flat < 2; flat++) {
        surfaces_lanes_of("cornell", flat);
        surfaces_lanes_of("room", flat);
    }
#endif
}

int main(void)
{
    const struct CMUnitTest tests[] = { cmocka_unit_test(primary_rays), cmocka_unit_test(shading),
                                        cmocka_unit_test(reflection_geometry), cmocka_unit_test(refraction_snell),
                                        cmocka_unit_test(bilinear_texture), cmocka_unit_test(mirror_reflects),
                                        cmocka_unit_test(glass_transmits), cmocka_unit_test(light_packet_lanes),
                                        cmocka_unit_test(accumulate_rays_lanes), cmocka_unit_test(surface_frames_lanes),
                                        cmocka_unit_test(surfaces_lanes) };
    return cmocka_run_group_tests_name("rgs", tests, NULL, NULL);
}
