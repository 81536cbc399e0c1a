/* Compact shading record decoding: see shade_rec.h. */
#include "shade_rec.h"

f24_t shade_rec_texcoord(const uint32_t *tail, uint32_t i)
{
    const uint32_t at = SHADE_MATERIAL_BITS + F24_WIDTH * i, w = at / 32u, shift = at % 32u;
    uint64_t bits = tail[w] >> shift;
    if (shift + F24_WIDTH > 32u) /* the field continues in the next word */
        bits |= (uint64_t)tail[w + 1] << (32u - shift);
    return (f24_t)bits & F24_MASK;
}

static int32_t oct_component(uint32_t half) { return (int32_t)(int16_t)(uint16_t)half; }

f24_vec3 shade_rec_normal(uint32_t word)
{
    if ((word & 0xFFFFu) == SHADE_NO_NORMAL)
        return (f24_vec3){ 0, 0, 0 };
    const int32_t x = oct_component(word & 0xFFFFu), y = oct_component(word >> 16);
    const int32_t ax = x < 0 ? -x : x, ay = y < 0 ? -y : y, z = SHADE_OCT_ONE - ax - ay;
    int32_t fx = x, fy = y;
    if (z < 0) { /* lower hemisphere: folded over the diagonals */
        fx = x < 0 ? ay - SHADE_OCT_ONE : SHADE_OCT_ONE - ay;
        fy = y < 0 ? ax - SHADE_OCT_ONE : SHADE_OCT_ONE - ax;
    }
    const f24_vec3 n = { f24_from_i32(fx), f24_from_i32(fy), f24_from_i32(z) };
    const f24_t len2 = f24_add(f24_add(f24_mul(n.x, n.x), f24_mul(n.y, n.y)), f24_mul(n.z, n.z));
    const f24_t inv = f24_div(F24_ONE, f24_sqrt(len2));
    return (f24_vec3){ f24_mul(n.x, inv), f24_mul(n.y, inv), f24_mul(n.z, inv) };
}
