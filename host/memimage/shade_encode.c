/* Compact shading record encoding: see shade_encode.h. */
#include "shade_encode.h"

#include <math.h>
#include <string.h>

#include "f24_fast.h"

/* Cosine between n and what the device decodes from word (a unit vector). */
static double decoded_cos(const double n[3], double len, uint32_t word)
{
    const f24_vec3 d = shade_rec_normal(word);
    return (n[0] * f24_fast_decode(d.x) + n[1] * f24_fast_decode(d.y) + n[2] * f24_fast_decode(d.z)) / len;
}

static int32_t clamp_oct(double q) { return q < -SHADE_OCT_ONE ? -SHADE_OCT_ONE : q > SHADE_OCT_ONE ? SHADE_OCT_ONE : (int32_t)q; }

/* Of the four grid points around n's octahedral projection, the one decoded closest to n (the
 * decoder is the device's, so its rounding counts too). */
uint32_t shade_encode_normal(const double n[3])
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
    uint32_t best = 0;
    double best_cos = -2;
    for (int c = 0; c < 4; c++) {
        const int32_t qx = clamp_oct(gx + (c & 1)), qy = clamp_oct(gy + (c >> 1));
        const uint32_t word = ((uint32_t)qx & 0xFFFFu) | ((uint32_t)qy & 0xFFFFu) << 16;
        const double cs = decoded_cos(n, len, word);
        if (cs > best_cos) {
            best_cos = cs;
            best = word;
        }
    }
    return best;
}

void shade_encode_texcoord(uint32_t *tail, uint32_t i, uint32_t value)
{
    const uint32_t at = SHADE_MATERIAL_BITS + F24_WIDTH * i, w = at / 32u;
    const uint64_t mask = (uint64_t)F24_MASK << (at % 32u), bits = (uint64_t)(value & F24_MASK) << (at % 32u);
    tail[w] = (tail[w] & ~(uint32_t)mask) | (uint32_t)bits;
    if (at % 32u + F24_WIDTH > 32u) /* the field continues in the next word */
        tail[w + 1] = (tail[w + 1] & ~(uint32_t)(mask >> 32)) | (uint32_t)(bits >> 32);
}

void shade_encode_record(uint32_t *w, uint32_t flags, const float *const normals[3], const float *const texcoords[3],
                         uint32_t material)
{
    memset(w, 0, shade_rec_words(flags) * sizeof *w);
    for (int k = 0; (flags & SHADE_HAS_NORMALS) && k < 3; k++) {
        const double n[3] = { normals[k][0], normals[k][1], normals[k][2] };
        w[k] = shade_encode_normal(n);
    }
    uint32_t *tail = w + shade_rec_tail(flags);
    tail[0] = material;
    for (uint32_t i = 0; (flags & SHADE_HAS_TEXCOORDS) && i < 6; i++)
        shade_encode_texcoord(tail, i, f24_fast_encode(texcoords[i / 2][i % 2]));
}
