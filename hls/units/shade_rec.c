/* Compact shading record decoding: see shade_rec.h. */
#include "shade_rec.h"

int32_t shade_rec_oct(const uint32_t *normals, uint32_t k, uint32_t c)
{
    const uint32_t v = shade_rec_bits(normals, 2u * SHADE_OCT_BITS * k + SHADE_OCT_BITS * c, SHADE_OCT_BITS);
    return (int32_t)(v ^ 1u << (SHADE_OCT_BITS - 1)) - (1 << (SHADE_OCT_BITS - 1)); /* sign extension */
}

f24_vec3 shade_rec_normal(const uint32_t *normals, uint32_t k)
{
    const int32_t x = shade_rec_oct(normals, k, 0), y = shade_rec_oct(normals, k, 1);
    if (x < -SHADE_OCT_ONE)
        return (f24_vec3){ 0, 0, 0 }; /* missing */
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
