/* The RGS's vector helpers, the barycentric interpolation and the frame of a hit: see rgs_ops.h
 * and docs/shading.md. Outside rgs.c so that the unit capture can wrap rgs_lerp and
 * rgs_surface_frame. */
#include "rgs_ops.h"

#include "xform_unit.h"

f24_t rgs_dot3(f24_vec3 a, f24_vec3 b) { return f24w_bits(f24w_dot3(f24w_vec3_of(a), f24w_vec3_of(b))); }

f24w rgs_length3_w(f24w_vec3 a) { return f24w_sqrt(f24w_dot3(a, a)); }
f24_t rgs_length3(f24_vec3 a) { return f24w_bits(rgs_length3_w(f24w_vec3_of(a))); }

uint32_t rgs_q_of_w(f24w x)
{
    const int32_t i = f24w_to_i32(f24w_add(f24w_mul(x, f24w_from_i32(4096)), rgs_ratio_w(1, 2)));
    return i < 0 ? 0u : q_sat((uint32_t)i);
}
uint32_t rgs_q_of(f24_t x) { return rgs_q_of_w(f24w_of(x)); }

f24_t rgs_lerp(f24_t a, f24_t b, f24_t c, f24_t u, f24_t v)
{
    const f24w uw = f24w_of(u), vw = f24w_of(v), w = f24w_sub(f24w_sub(f24w_of(F24_ONE), uw), vw);
    return f24w_bits(f24w_add(f24w_add(f24w_mul(uw, f24w_of(a)), f24w_mul(vw, f24w_of(b))), f24w_mul(w, f24w_of(c))));
}

F24Q_FN f24_vec3 rgs_lerp_normal(const f24_t n[3][F24Q_LANES], f24_t u, f24_t v)
{
    const f24_t w = f24w_bits(f24w_sub(f24w_sub(f24w_of(F24_ONE), f24w_of(u)), f24w_of(v)));
    const f24_t weights[F24Q_LANES] = { u, v, w, 0 };
    const f24q k = f24q_of(weights);
    f24_t r[3];
normal_components:
    for (int c = 0; c < 3; c++) {
        const f24q p = f24q_mul(f24q_of(n[c]), k);
        r[c] = f24w_bits(f24w_add(f24w_add(f24q_lane(p, 0), f24q_lane(p, 1)), f24q_lane(p, 2)));
    }
    return (f24_vec3){ r[0], r[1], r[2] };
}

void rgs_surface_frame(f24_vec3 o, f24_vec3 d, f24_t t, f24_t cos_n, f24_vec3 n, const f24_affine *w2o, surface *sf)
{
    const f24w one = f24w_of(F24_ONE), dlen = rgs_length3_w(f24w_vec3_of(d));
    const f24w_vec3 dw = f24w_scale3(f24w_vec3_of(d), f24w_div(one, dlen));
    sf->d = f24w_vec3_bits(dw);
    f24_affine tr;
transpose:
    for (int r = 0; r < 3; r++) {
        for (int k = 0; k < 3; k++)
            tr.m[r][k] = w2o->m[k][r];
        tr.m[r][3] = 0;
    }
    f24w_vec3 nw = f24w_vec3_of(xform_vector(&tr, n));
    if (!f24w_sign(f24w_dot3(nw, dw)))
        nw = neg3_w(nw); /* towards the ray: both faces are front faces */
    sf->n = f24w_vec3_bits(f24w_scale3(nw, f24w_div(one, rgs_length3_w(nw))));
    sf->entering = f24_sign(cos_n) != 0; /* the sign of n.d survives the instance transformation */
    sf->t_hat = f24w_bits(f24w_mul(f24w_of(t), dlen));
    sf->tr = t_r(o, sf->d, sf->n);
    sf->p = xform_point(&sf->tr, (f24_vec3){ 0, 0, sf->t_hat });
}
