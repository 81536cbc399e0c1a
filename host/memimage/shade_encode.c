/* Compact shading record encoding: see shade_encode.h. */
#include "shade_encode.h"

#include <math.h>
#include <string.h>

#include "f24_double.h"

/* Sets the width (1..32) bits of w from bit at on (the counterpart of shade_rec_bits). */
static void put_bits(uint32_t *w, uint32_t at, uint32_t width, uint32_t value)
{
    const uint64_t field = (1ull << width) - 1u, mask = field << (at % 32u), bits = (value & field) << (at % 32u);
    w[at / 32u] = (w[at / 32u] & ~(uint32_t)mask) | (uint32_t)bits;
    if (at % 32u + width > 32u)
        w[at / 32u + 1] = (w[at / 32u + 1] & ~(uint32_t)(mask >> 32)) | (uint32_t)(bits >> 32);
}

void shade_encode_set_normal(uint32_t *normals, uint32_t k, uint64_t code)
{
    const uint32_t field = (1u << SHADE_OCT_BITS) - 1u;
    put_bits(normals, 2u * SHADE_OCT_BITS * k, SHADE_OCT_BITS, (uint32_t)code & field);
    put_bits(normals, 2u * SHADE_OCT_BITS * k + SHADE_OCT_BITS, SHADE_OCT_BITS, (uint32_t)(code >> SHADE_OCT_BITS) & field);
}

void shade_encode_texcoord(uint32_t *tail, uint32_t flags, uint32_t uv, uint32_t i, uint32_t value)
{
    put_bits(tail, shade_rec_uv_at(flags, uv) + F24_WIDTH * i, F24_WIDTH, value);
}

/* A colour channel in [0, 1] as a byte (the device widens it as a texel). */
static uint32_t colour_byte(float c) { return (uint32_t)lround(255.0 * (c > 0 ? (c < 1 ? c : 1) : 0)); }

/* Cosine between n (length len) and what the device decodes from code (a unit vector). */
static double decoded_cos(const double n[3], double len, uint64_t code)
{
    uint32_t block[SHADE_NORMAL_WORDS] = { 0 };
    shade_encode_set_normal(block, 0, code);
    const f24_vec3 d = shade_rec_normal(block, 0);
    return (n[0] * f24_fast_decode(d.x) + n[1] * f24_fast_decode(d.y) + n[2] * f24_fast_decode(d.z)) / len;
}

static uint32_t oct_field(double q)
{
    const int32_t i = q < -SHADE_OCT_ONE ? -SHADE_OCT_ONE : q > SHADE_OCT_ONE ? SHADE_OCT_ONE : (int32_t)q;
    return (uint32_t)i & ((1u << SHADE_OCT_BITS) - 1u);
}

/* Of the four grid points around n's octahedral projection, the one decoded closest to n (the
 * decoder is the device's, so its rounding counts too). */
uint64_t shade_encode_normal(const double n[3])
{
    const double l1 = fabs(n[0]) + fabs(n[1]) + fabs(n[2]), len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(l1 > 0) || !isfinite(l1) || !(len > 0) || !isfinite(len))
        return SHADE_NO_NORMAL;
    double px = n[0] / l1, py = n[1] / l1;
    if (n[2] < 0) { /* lower hemisphere: fold over the diagonals (sign of 0 is +, as the decoder's) */
        const double fx = (1 - fabs(py)) * (px < 0 ? -1 : 1);
        py = (1 - fabs(px)) * (py < 0 ? -1 : 1);
        px = fx;
    }
    const double gx = floor(px * SHADE_OCT_ONE), gy = floor(py * SHADE_OCT_ONE);
    uint64_t best = 0;
    double best_cos = -2;
    for (int c = 0; c < 4; c++) {
        const uint64_t code = oct_field(gx + (c & 1)) | (uint64_t)oct_field(gy + (c >> 1)) << SHADE_OCT_BITS;
        const double cs = decoded_cos(n, len, code);
        if (cs > best_cos) {
            best_cos = cs;
            best = code;
        }
    }
    return best;
}

void shade_encode_record(uint32_t *w, uint32_t flags, const shade_triangle *t)
{
    memset(w, 0, shade_rec_words(flags) * sizeof *w);
    for (uint32_t k = 0; (flags & SHADE_HAS_NORMALS) && k < 3; k++)
        shade_encode_set_normal(w, k, t->normal[k]);
    uint32_t *tail = w + shade_rec_tail(flags);
    if (!(flags & SHADE_ONE_MATERIAL))
        tail[0] = t->material;
    const uint32_t sets = (flags & SHADE_HAS_TEXCOORDS) ? ((flags & SHADE_HAS_EMISSIVE_UV) ? 2u : 1u) : 0u;
    for (uint32_t uv = 0; uv < sets; uv++)
        for (uint32_t i = 0; i < 6; i++)
            shade_encode_texcoord(tail, flags, uv, i, f24_fast_encode(t->uv[uv][i / 2][i % 2]));
    for (uint32_t v = 0; (flags & SHADE_HAS_COLOURS) && v < 3; v++)
        for (uint32_t k = 0; k < 3; k++)
            put_bits(tail, shade_rec_colour_bit(flags, v, k), 8u, colour_byte(t->colour[v][k]));
}
