/* A ray's share of op_accumulate: see rgs_ops.h and docs/shading.md. Outside rgs.c so that the
 * unit capture can wrap rgs_accumulate_ray (rtl/rgs_accum.sv is checked against it). */
#include "rgs_ops.h"

#define BACKGROUND 0x1A1A24u

int rgs_accumulate_ray(const uint32_t *m, const surface *sf, int i, const uint32_t weight[3], const uint32_t diffuse[3],
                       const uint32_t highlight[3], f24_t eps, uint32_t spawn, uint32_t acc[3], rgs_task *refl,
                       rgs_task *trans)
{
ray_colour:
    for (int k = 0; k < 3; k++) {
        uint32_t local = q_byte(BACKGROUND >> (16 - 8 * k) & 0xFFu);
        if (sf->valid)
            local = q_add(q_add(sf->emission[k], q_mul(q_mul(rgs_mat_kd(m), sf->base[k]), diffuse[k])),
                          q_mul(q_mul(rgs_mat_ks(m), sf->tint[k]), highlight[k]));
        acc[k] = q_add(acc[k], q_mul(weight[k], local));
    }
#if SAARCOR_CFG_SECONDARY
    if (sf->valid && (spawn & RGS_SPAWN_ON)) {
        const uint32_t spawned = refl->rays.active | trans->rays.active;
        rgs_spawn_children(m, weight, eps, i, sf, refl, trans);
        /* its T_R steps (the general pipeline runs them for every surface) */
        return !(spawn & RGS_SPAWN_LIVE) || ((refl->rays.active | trans->rays.active) != spawned);
    }
#else
    (void)i, (void)eps, (void)spawn, (void)refl, (void)trans;
#endif
    return 0;
}
