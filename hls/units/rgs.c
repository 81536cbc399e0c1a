/* Ray generation and shading unit: see rgs.h. */
#include "rgs.h"

#include "xform_unit.h"

enum {
    H_REGIONS = 18, R_MATERIALS = 1, R_OBJECTS = 5, R_CAMERA = 6, R_INSTANCES = 8,
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

uint32_t rgs_shade(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h)
{
    if (h->instance == TRACE_NO_HIT)
        return BACKGROUND;
    const uint32_t ia = region_start(mem, R_INSTANCES) + INST_WORDS * h->instance;
    const uint32_t obj = region_start(mem, R_OBJECTS) + OBJ_WORDS * mem[ia + 12];
    const uint32_t shade = mem[obj + O_SHADING] + SHADE_WORDS * h->triangle;
    const uint32_t mat = region_start(mem, R_MATERIALS) + MAT_WORDS * mem[shade + 15];
    const f24_vec3 n = hit_normal(mem, h, obj, h->instance), d = rp->d[i];
    /* |cos| between normal and view direction: light at the eye, both faces lit */
    const f24_t nd = dot3(n, d);
    const f24_t cosang = f24_div(f24_abs(nd), f24_sqrt(f24_mul(dot3(n, n), dot3(d, d))));
    const f24_t light = f24_add(ratio(1, 5), f24_mul(ratio(4, 5), f24_min(cosang, F24_ONE)));
    uint32_t rgb = 0;
channels:
    for (int c = 0; c < 3; c++) {
        const f24_t v = f24_add(f24_mul(mem[mat + (uint32_t)c], light), mem[mat + 4 + (uint32_t)c]);
        rgb |= quantize8(f24_min(v, F24_ONE)) << (16 - 8 * c);
    }
    return rgb;
}
