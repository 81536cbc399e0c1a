/* Compact shading record decoding: see shade_rec.h. */
#include "shade_rec.h"

int32_t shade_rec_oct(const uint32_t *normals, uint32_t k, uint32_t c)
{
    const uint32_t v = shade_rec_bits(normals, 2u * SHADE_OCT_BITS * k + SHADE_OCT_BITS * c, SHADE_OCT_BITS);
    return (int32_t)(v ^ 1u << (SHADE_OCT_BITS - 1)) - (1 << (SHADE_OCT_BITS - 1)); /* sign extension */
}

/* The three normals side by side, one lane each (lane 3 unused, as a missing normal). */
F24Q_FN void shade_rec_normals(const uint32_t *normals, f24_t out[3][F24Q_LANES])
{
    int32_t c[3][F24Q_LANES] = { { 0 } };
    uint32_t missing = 1u << 3;
normal_lanes:
    for (uint32_t k = 0; k < 3; k++) {
        const int32_t x = shade_rec_oct(normals, k, 0), y = shade_rec_oct(normals, k, 1);
        const int32_t ax = x < 0 ? -x : x, ay = y < 0 ? -y : y, z = SHADE_OCT_ONE - ax - ay;
        int32_t fx = x, fy = y;
        if (z < 0) { /* lower hemisphere: folded over the diagonals */
            fx = x < 0 ? ay - SHADE_OCT_ONE : SHADE_OCT_ONE - ay;
            fy = y < 0 ? ax - SHADE_OCT_ONE : SHADE_OCT_ONE - ax;
        }
        c[0][k] = fx;
        c[1][k] = fy;
        c[2][k] = z;
        if (x < -SHADE_OCT_ONE)
            missing |= 1u << k;
    }
    const f24q nx = f24q_from_i32(c[0]), ny = f24q_from_i32(c[1]), nz = f24q_from_i32(c[2]);
    const f24q len2 = f24q_add(f24q_add(f24q_mul(nx, nx), f24q_mul(ny, ny)), f24q_mul(nz, nz));
    const f24q inv = f24q_div(f24q_splat(F24_ONE), f24q_sqrt(len2)), zero = f24q_splat(0);
    f24q_bits(f24q_select(missing, zero, f24q_mul(nx, inv)), out[0]);
    f24q_bits(f24q_select(missing, zero, f24q_mul(ny, inv)), out[1]);
    f24q_bits(f24q_select(missing, zero, f24q_mul(nz, inv)), out[2]);
}

f24_vec3 shade_rec_normal(const uint32_t *normals, uint32_t k)
{
    f24_t n[3][F24Q_LANES];
    shade_rec_normals(normals, n);
    return (f24_vec3){ n[0][k], n[1][k], n[2][k] };
}
