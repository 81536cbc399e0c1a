/* Ray generation and shading unit: see rgs.h. */
#include "rgs.h"

#include "xform_unit.h"

enum {
    H_LIGHTS = 10, H_TEXTURES = 9, H_REGIONS = 18, R_MATERIALS = 1, R_TEXTURES = 2, R_OBJECTS = 5,
    TEX_WORDS = 4, HAS_TEXCOORDS = 2, R_CAMERA = 6, R_LIGHTS = 7, R_INSTANCES = 8,
    LIGHT_WORDS = 16, MAX_LIGHTS = 64,
    OBJ_WORDS = 16, O_TRIANGLES = 2, O_SHADING = 3, O_FLAGS = 7, HAS_NORMALS = 1,
    INST_WORDS = 16, TRI_WORDS = 12, SHADE_WORDS = 16, MAT_WORDS = 16,
};

#define BACKGROUND 0x1A1A24u

static uint32_t region_start(const uint32_t *mem, uint32_t r) { return mem[H_REGIONS + 2 * r]; }

static f24_t ratio(int32_t num, int32_t den) { return f24_div(f24_from_i32(num), f24_from_i32(den)); }

void rgs_image_size(const uint32_t *mem, uint32_t *width, uint32_t *height)
{
    const uint32_t cam = region_start(mem, R_CAMERA);
    *width = mem[cam + 1];
    *height = mem[cam + 2];
}

void rgs_primary(const uint32_t *mem, uint32_t x0, uint32_t y0, ray_packet *rp)
{
    const uint32_t cam = region_start(mem, R_CAMERA), kind = mem[cam], w = mem[cam + 1], h = mem[cam + 2];
    f24_affine t; /* columns U V W, translation O */
camera_matrix:
    for (int r = 0; r < 3; r++) {
        t.m[r][0] = mem[cam + 7 + (uint32_t)r];
        t.m[r][1] = mem[cam + 10 + (uint32_t)r];
        t.m[r][2] = mem[cam + 13 + (uint32_t)r];
        t.m[r][3] = mem[cam + 4 + (uint32_t)r];
    }
    const f24_vec3 origin = { mem[cam + 4], mem[cam + 5], mem[cam + 6] };
    const f24_t half = ratio(1, 2);
    rp->active = 0;
block_pixels:
    for (int i = 0; i < TRACE_PACKET; i++) {
        const uint32_t x = x0 + (uint32_t)(i & 1), y = y0 + (uint32_t)(i >> 1);
        const f24_vec3 p = { f24_mul(f24_from_i32((int32_t)(2 * x + 1)), half),
                             f24_mul(f24_from_i32((int32_t)(2 * y + 1)), half), F24_ONE };
        if (kind == 1) { /* orthographic: O + x U + y V, direction W */
            const f24_vec3 p2 = { p.x, p.y, 0 };
            rp->o[i] = xform_point(&t, p2);
            rp->d[i] = (f24_vec3){ t.m[0][2], t.m[1][2], t.m[2][2] };
        } else {
            rp->o[i] = origin;
            rp->d[i] = xform_vector(&t, p);
        }
        rp->tmin[i] = 0;
        rp->tmax[i] = F24_POS_INF;
        if (x < w && y < h)
            rp->active |= 1u << i;
    }
}

static f24_t dot3(f24_vec3 a, f24_vec3 b)
{
    return f24_add(f24_add(f24_mul(a.x, b.x), f24_mul(a.y, b.y)), f24_mul(a.z, b.z));
}

static f24_vec3 lerp3(const uint32_t *w, f24_t u, f24_t v)
{
    const f24_t c = f24_sub(f24_sub(F24_ONE, u), v); /* weight of vertex C */
    f24_vec3 n;
    f24_t *out = &n.x;
interpolate:
    for (int k = 0; k < 3; k++)
        out[k] = f24_add(f24_add(f24_mul(u, w[k]), f24_mul(v, w[3 + k])), f24_mul(c, w[6 + k]));
    return n;
}

/* World-space normal at the hit (not normalized). */
static f24_vec3 hit_normal(const uint32_t *mem, const hit_record *h, uint32_t obj, uint32_t inst)
{
    const uint32_t shade = mem[obj + O_SHADING] + SHADE_WORDS * h->triangle;
    f24_vec3 n = { 0, 0, 0 };
    if (mem[obj + O_FLAGS] & HAS_NORMALS)
        n = lerp3(&mem[shade], h->u, h->v);
    if (f24_is_zero(dot3(n, n))) { /* geometric normal: row 2 of the triangle transformation */
        const uint32_t tri = mem[obj + O_TRIANGLES] + TRI_WORDS * h->triangle;
        n = (f24_vec3){ mem[tri + 8], mem[tri + 9], mem[tri + 10] };
    }
    const f24_affine w2o = f24_affine_load(mem, region_start(mem, R_INSTANCES) + INST_WORDS * inst);
    f24_affine tr; /* transposed 3x3: object-space normals to world space */
transpose:
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++)
            tr.m[r][c] = w2o.m[c][r];
        tr.m[r][3] = 0;
    }
    return xform_vector(&tr, n);
}

static uint32_t quantize8(f24_t c)
{
    const int32_t v = f24_to_i32(f24_add(f24_mul(c, f24_from_i32(255)), ratio(1, 2)));
    return v < 0 ? 0u : v > 255 ? 255u : (uint32_t)v;
}

static f24_vec3 sub3(f24_vec3 a, f24_vec3 b) { return (f24_vec3){ f24_sub(a.x, b.x), f24_sub(a.y, b.y), f24_sub(a.z, b.z) }; }
static f24_vec3 scale3(f24_vec3 a, f24_t s) { return (f24_vec3){ f24_mul(a.x, s), f24_mul(a.y, s), f24_mul(a.z, s) }; }
static f24_vec3 neg3(f24_vec3 a) { return (f24_vec3){ f24_neg(a.x), f24_neg(a.y), f24_neg(a.z) }; }

/* What shading needs to know about a hit: point, unit normal facing the viewer, material. */
typedef struct {
    int valid;
    f24_vec3 p, n;
    uint32_t mat;   /* address of the material record */
    f24_t base[3];  /* base colour: factor x bilinear texture sample */
} surface;

/* Texel channel k (0..3) of texture entry tex at integer coordinates, wrapped (repeat). */
static f24_t texel(const uint32_t *mem, const uint32_t *tex, int32_t x, int32_t y, int k)
{
    const int32_t w = (int32_t)tex[0], h = (int32_t)tex[1];
    const int32_t xw = ((x % w) + w) % w, yw = ((y % h) + h) % h;
    const uint32_t t = mem[tex[2] + (uint32_t)(yw * w + xw)];
    return f24_div(f24_from_i32((int32_t)(t >> (8 * k) & 0xFFu)), f24_from_i32(255));
}

/* Floor of x as an integer and the fraction x - floor(x). */
static int32_t floor_frac(f24_t x, f24_t *frac)
{
    int32_t i = f24_to_i32(x);
    if (f24_lt(x, f24_from_i32(i)))
        i -= 1; /* to_i32 rounds toward zero */
    *frac = f24_sub(x, f24_from_i32(i));
    return i;
}

static f24_t lerp(f24_t a, f24_t b, f24_t t) { return f24_add(a, f24_mul(t, f24_sub(b, a))); }

/* Bilinear sample (texel centres at +1/2, repeat wrapping) of texture entry tex at (s, t). */
static void sample_bilinear(const uint32_t *mem, const uint32_t *tex, f24_t s, f24_t t, f24_t out[3])
{
    const f24_t half = ratio(1, 2);
    f24_t fx, fy;
    const int32_t x = floor_frac(f24_sub(f24_mul(s, f24_from_i32((int32_t)tex[0])), half), &fx);
    const int32_t y = floor_frac(f24_sub(f24_mul(t, f24_from_i32((int32_t)tex[1])), half), &fy);
bilinear:
    for (int k = 0; k < 3; k++)
        out[k] = lerp(lerp(texel(mem, tex, x, y, k), texel(mem, tex, x + 1, y, k), fx),
                      lerp(texel(mem, tex, x, y + 1, k), texel(mem, tex, x + 1, y + 1, k), fx), fy);
}

/* Base colour at the hit: the material factor, times the texture if the material has one and
 * the object has texture coordinates. */
static void base_colour(const uint32_t *mem, uint32_t mat, uint32_t obj, const uint32_t *shade, const hit_record *h,
                        f24_t out[3])
{
    const uint32_t t = mem[mat + 7];
base_factor:
    for (int k = 0; k < 3; k++)
        out[k] = mem[mat + (uint32_t)k];
    if (t >= mem[H_TEXTURES] || !(mem[obj + O_FLAGS] & HAS_TEXCOORDS))
        return;
    const f24_t c = f24_sub(f24_sub(F24_ONE, h->u), h->v);
    const f24_t s = f24_add(f24_add(f24_mul(h->u, shade[9]), f24_mul(h->v, shade[11])), f24_mul(c, shade[13]));
    const f24_t tt = f24_add(f24_add(f24_mul(h->u, shade[10]), f24_mul(h->v, shade[12])), f24_mul(c, shade[14]));
    f24_t tex[3];
    sample_bilinear(mem, &mem[region_start(mem, R_TEXTURES) + TEX_WORDS * t], s, tt, tex);
    for (int k = 0; k < 3; k++)
        out[k] = f24_mul(out[k], tex[k]);
}

static surface surface_at(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h)
{
    surface sf = { 0, { 0, 0, 0 }, { 0, 0, 0 }, 0, { 0, 0, 0 } };
    if (h->instance == TRACE_NO_HIT || !(rp->active >> i & 1u))
        return sf;
    const uint32_t ia = region_start(mem, R_INSTANCES) + INST_WORDS * h->instance;
    const uint32_t obj = region_start(mem, R_OBJECTS) + OBJ_WORDS * mem[ia + 12];
    const uint32_t shade = mem[obj + O_SHADING] + SHADE_WORDS * h->triangle;
    f24_vec3 n = hit_normal(mem, h, obj, h->instance);
    if (!f24_sign(dot3(n, rp->d[i])))
        n = neg3(n); /* towards the viewer: both faces are front faces */
    sf.valid = 1;
    sf.n = scale3(n, f24_div(F24_ONE, f24_sqrt(dot3(n, n))));
    sf.p = (f24_vec3){ f24_add(rp->o[i].x, f24_mul(h->t, rp->d[i].x)), f24_add(rp->o[i].y, f24_mul(h->t, rp->d[i].y)),
                       f24_add(rp->o[i].z, f24_mul(h->t, rp->d[i].z)) };
    sf.mat = region_start(mem, R_MATERIALS) + MAT_WORDS * mem[shade + 15];
    base_colour(mem, sf.mat, obj, &mem[shade], h, sf.base);
    return sf;
}

/* Cosine between unit vector n and direction d (any length). */
static f24_t cos_to(f24_vec3 n, f24_vec3 d) { return f24_div(dot3(n, d), f24_sqrt(dot3(d, d))); }

/* Light colour scaled to a maximum component of one: the fixed-function shader uses the
 * light's colour and direction, not its photometric intensity. */
static void light_colour(const uint32_t *l, f24_t out[3])
{
    const f24_t m = f24_max(f24_max(l[1], l[2]), l[3]);
normalize_colour:
    for (int c = 0; c < 3; c++)
        out[c] = f24_lt(0, m) ? f24_div(l[1 + c], m) : 0;
}

/* Shadow rays of light l for the packet's surfaces; weight[i] = cosine x spot factor, 0 if the
 * light does not reach the point. */
static void light_packet(const uint32_t *l, const surface sf[], ray_packet *sh, f24_t weight[])
{
    const f24_vec3 lpos = { l[4], l[5], l[6] }, ldir = { l[7], l[8], l[9] };
    sh->active = 0;
shadow_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        weight[i] = 0;
        if (!sf[i].valid)
            continue;
        const int directional = l[0] == 0;
        sh->o[i] = sf[i].p;
        sh->d[i] = directional ? neg3(ldir) : sub3(lpos, sf[i].p);
        sh->tmin[i] = ratio(1, 512); /* of the distance to the light: keeps the ray off its own surface */
        sh->tmax[i] = directional ? F24_POS_INF : F24_ONE;
        f24_t w = cos_to(sf[i].n, sh->d[i]);
        if (l[0] == 2) { /* spot: smooth step from the outer to the inner cone */
            const f24_t c = f24_neg(cos_to(ldir, sh->d[i]));
            const f24_t f = f24_div(f24_sub(c, l[12]), f24_sub(l[11], l[12]));
            w = f24_mul(w, f24_max(0, f24_min(f, F24_ONE)));
        }
        if (f24_lt(0, w)) {
            weight[i] = w;
            sh->active |= 1u << i;
        }
    }
}

void rgs_shade_packet(const uint32_t *mem, const ray_packet *rp, const hit_record h[], uint32_t rgb[], trace_counters *c)
{
    surface sf[TRACE_PACKET];
    f24_t light[TRACE_PACKET][3];
    const f24_t ambient = ratio(3, 20), diffuse = ratio(17, 20);
    const uint32_t n_lights = mem[H_LIGHTS] < MAX_LIGHTS ? mem[H_LIGHTS] : MAX_LIGHTS;
surfaces:
    for (int i = 0; i < TRACE_PACKET; i++) {
        sf[i] = surface_at(mem, rp, i, &h[i]);
        /* no lights in the scene: a light at the eye, which needs no shadow ray */
        const f24_t head = n_lights ? 0 : f24_mul(diffuse, f24_abs(cos_to(sf[i].n, rp->d[i])));
        for (int k = 0; k < 3; k++)
            light[i][k] = f24_add(ambient, head);
    }
lights:
    for (uint32_t li = 0; li < n_lights; li++) {
        const uint32_t *l = &mem[region_start(mem, R_LIGHTS) + LIGHT_WORDS * li];
        ray_packet sh;
        f24_t weight[TRACE_PACKET], colour[3];
        hit_record blocked[TRACE_PACKET];
        light_packet(l, sf, &sh, weight);
        light_colour(l, colour);
        trace_packet(mem, &sh, blocked, c);
        for (int i = 0; i < TRACE_PACKET; i++)
            if ((sh.active >> i & 1u) && blocked[i].instance == TRACE_NO_HIT)
                for (int k = 0; k < 3; k++)
                    light[i][k] = f24_add(light[i][k], f24_mul(f24_mul(diffuse, weight[i]), colour[k]));
    }
pixels:
    for (int i = 0; i < TRACE_PACKET; i++) {
        rgb[i] = BACKGROUND;
        if (!sf[i].valid)
            continue;
        rgb[i] = 0;
        for (int k = 0; k < 3; k++) {
            const f24_t v = f24_add(f24_mul(sf[i].base[k], light[i][k]), mem[sf[i].mat + 4 + (uint32_t)k]);
            rgb[i] |= quantize8(f24_min(v, F24_ONE)) << (16 - 8 * k);
        }
    }
}
