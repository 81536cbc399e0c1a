/* The child rays of a surface: see rgs_ops.h and docs/shading.md ("Secondary rays through the
 * transformation unit"). Outside rgs.c so that the unit capture can wrap rgs_spawn_children. */
#include "rgs_ops.h"

#include "xform_unit.h"

#define MIN_WEIGHT 16u /* 1/256: lighter secondary rays are not spawned */

static uint32_t mat_kr(const uint32_t *m) { return m[M_SHADER0] >> 13 & 0x1FFFu; }
static uint32_t mat_kt(const uint32_t *m) { return m[M_SHADER1] & 0x1FFFu; }

static uint32_t q_max3(const uint32_t c[3])
{
    const uint32_t m = c[0] > c[1] ? c[0] : c[1];
    return m > c[2] ? m : c[2];
}

void rgs_child_rays(const uint32_t *m, const uint32_t weight[3], int i, const surface *sf, f24_vec3 back,
                    f24_vec3 mirror, f24_vec3 t_o, f24_vec3 t_d, rgs_task *refl, rgs_task *trans)
{
    const uint32_t w_r = mat_kr(m), w_t = mat_kt(m);
child_weights:
    for (int k = 0; k < 3; k++) {
        refl->weight[i][k] = q_mul(q_mul(weight[k], w_r), sf->tint[k]);
        trans->weight[i][k] = q_mul(q_mul(weight[k], w_t), sf->base[k]);
    }
    refl->rays.o[i] = back;
    refl->rays.d[i] = mirror;
    if (q_max3(refl->weight[i]) >= MIN_WEIGHT)
        refl->rays.active |= 1u << i;
    trans->rays.o[i] = t_o;
    trans->rays.d[i] = t_d;
    if (q_max3(trans->weight[i]) >= MIN_WEIGHT)
        trans->rays.active |= 1u << i;
}

void rgs_spawn_children(const uint32_t *m, const uint32_t weight[3], f24_t eps, int i, const surface *sf,
                        rgs_task *refl, rgs_task *trans)
{
    const f24_t c = rgs_dot3(sf->n, sf->d), e = eps;
    const f24_vec3 back = xform_point(&sf->tr, (f24_vec3){ f24_neg(e), 0, sf->t_hat });
    f24_vec3 t_o = xform_point(&sf->tr, (f24_vec3){ e, 0, sf->t_hat }); /* ahead */
    const f24_vec3 mirror = xform_vector(&sf->tr, (f24_vec3){ F24_ONE, f24_neg(f24_add(c, c)), 0 });
    f24_vec3 t_d = sf->d; /* transparency: (1, 0, 0) through T_R */
#if SAARCOR_CFG_REFRACTION
    const f24_t ior = m[M_ETA], eta_r = sf->entering ? f24_div(F24_ONE, ior) : ior;
    if (!f24_eq(ior, F24_ONE) && !rgs_refract(sf->d, sf->n, eta_r, &t_d)) {
        t_o = back; /* total internal reflection */
        t_d = mirror;
    }
#endif
    rgs_child_rays(m, weight, i, sf, back, mirror, t_o, t_d, refl, trans);
}
