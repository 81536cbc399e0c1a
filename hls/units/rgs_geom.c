/* The RGS's vector helpers, the barycentric interpolation and the frame of a hit: see rgs_ops.h
 * and docs/shading.md. Outside rgs.c so that the unit capture can wrap rgs_lerp and
 * rgs_surface_frame. */
#include "rgs_ops.h"

#include "xform_unit.h"

F24Q_FN f24_t rgs_dot3(f24_vec3 a, f24_vec3 b)
{
    const f24_t al[4] = { a.x, a.y, a.z, 0 }, bl[4] = { b.x, b.y, b.z, 0 };
    const f24q p = f24q_mul(f24q_of(al), f24q_of(bl));
    return f24w_bits(f24w_add(f24w_add(f24q_lane(p, 0), f24q_lane(p, 1)), f24q_lane(p, 2)));
}

f24_t rgs_length3(f24_vec3 a) { return f24_sqrt(rgs_dot3(a, a)); }

uint32_t rgs_q_of(f24_t x)
{
    const int32_t i = f24_to_i32(f24_add(f24_mul(x, f24_from_i32(4096)), f24_div(F24_ONE, f24_from_i32(2))));
    return i < 0 ? 0u : q_sat((uint32_t)i);
}

f24_t rgs_lerp(f24_t a, f24_t b, f24_t c, f24_t u, f24_t v)
{
    return f24_add(f24_add(f24_mul(u, a), f24_mul(v, b)), f24_mul(f24_sub(f24_sub(F24_ONE, u), v), c));
}

void rgs_surface_frame(f24_vec3 o, f24_vec3 d, f24_t t, f24_t cos_n, f24_vec3 n, const f24_affine *w2o, surface *sf)
{
    const f24_t dlen = rgs_length3(d);
    sf->d = scale3(d, f24_div(F24_ONE, dlen));
    f24_affine tr;
transpose:
    for (int r = 0; r < 3; r++) {
        for (int k = 0; k < 3; k++)
            tr.m[r][k] = w2o->m[k][r];
        tr.m[r][3] = 0;
    }
    f24_vec3 nw = xform_vector(&tr, n);
    if (!f24_sign(rgs_dot3(nw, sf->d)))
        nw = neg3(nw); /* towards the ray: both faces are front faces */
    sf->n = scale3(nw, f24_div(F24_ONE, rgs_length3(nw)));
    sf->entering = f24_sign(cos_n) != 0; /* the sign of n.d survives the instance transformation */
    sf->t_hat = f24_mul(t, dlen);
    sf->tr = t_r(o, sf->d, sf->n);
    sf->p = xform_point(&sf->tr, (f24_vec3){ 0, 0, sf->t_hat });
}
