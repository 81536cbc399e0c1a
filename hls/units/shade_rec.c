/* Compact shading record decoding: see shade_rec.h. */
#include "shade_rec.h"

int32_t shade_rec_oct(const uint32_t *normals, uint32_t k, uint32_t c)
{
    const uint32_t v = shade_rec_bits(normals, 2u * SHADE_OCT_BITS * k + SHADE_OCT_BITS * c, SHADE_OCT_BITS);
    return (int32_t)(v ^ 1u << (SHADE_OCT_BITS - 1)) - (1 << (SHADE_OCT_BITS - 1)); /* sign extension */
}

f24w_vec3 shade_rec_normal_w(const uint32_t *normals, uint32_t k)
{
    const int32_t x = shade_rec_oct(normals, k, 0), y = shade_rec_oct(normals, k, 1);
    if (x < -SHADE_OCT_ONE)
        return f24w_vec3_of((f24_vec3){ 0, 0, 0 }); /* missing */
    const int32_t ax = x < 0 ? -x : x, ay = y < 0 ? -y : y, z = SHADE_OCT_ONE - ax - ay;
    int32_t fx = x, fy = y;
    if (z < 0) { /* lower hemisphere: folded over the diagonals */
        fx = x < 0 ? ay - SHADE_OCT_ONE : SHADE_OCT_ONE - ay;
        fy = y < 0 ? ax - SHADE_OCT_ONE : SHADE_OCT_ONE - ax;
    }
    const f24w_vec3 n = { f24w_from_i32(fx), f24w_from_i32(fy), f24w_from_i32(z) };
    return f24w_scale3(n, f24w_div(f24w_of(F24_ONE), f24w_sqrt(f24w_dot3(n, n))));
}

f24_vec3 shade_rec_normal(const uint32_t *normals, uint32_t k) { return f24w_vec3_bits(shade_rec_normal_w(normals, k)); }
