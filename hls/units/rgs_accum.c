/* A ray's share of op_accumulate and the packet's: see rgs_ops.h and docs/shading.md. Outside
 * rgs.c so that the unit capture can wrap rgs_accumulate_ray (rtl/rgs_accum.sv is checked against
 * it) and rgs_accumulate_rays. */
#include "rgs_ops.h"

#ifdef F24_SIM_LANES
#define rgs_accumulate_rays rgs_accumulate_rays_per_ray /* the simulation build's is side by side (rgs_ops.h) */
#endif

#define BACKGROUND 0x1A1A24u

void rgs_ray_colour(const uint32_t *m, const surface *sf, const uint32_t weight[3], const uint32_t diffuse[3],
                    const uint32_t highlight[3], uint32_t acc[3])
{
ray_colour:
    for (int k = 0; k < 3; k++) {
        uint32_t local = q_byte(BACKGROUND >> (16 - 8 * k) & 0xFFu);
        if (sf->valid)
            local = q_add(q_add(sf->emission[k], q_mul(q_mul(rgs_mat_kd(m), sf->base[k]), diffuse[k])),
                          q_mul(q_mul(rgs_mat_ks(m), sf->tint[k]), highlight[k]));
        acc[k] = q_add(acc[k], q_mul(weight[k], local));
    }
}

int rgs_accumulate_ray(const uint32_t *m, const surface *sf, int i, const uint32_t weight[3], const uint32_t diffuse[3],
                       const uint32_t highlight[3], f24_t eps, uint32_t spawn, uint32_t acc[3], rgs_task *refl,
                       rgs_task *trans)
{
    rgs_ray_colour(m, sf, weight, diffuse, highlight, acc);
#if SAARCOR_CFG_SECONDARY
    if (sf->valid && (spawn & RGS_SPAWN_ON)) {
        const uint32_t spawned = refl->rays.active | trans->rays.active;
        rgs_spawn_children(m, weight, eps, i, sf, refl, trans);
        return rgs_child_steps(spawn, spawned, refl, trans);
    }
#else
    (void)i, (void)eps, (void)spawn, (void)refl, (void)trans;
#endif
    return 0;
}

uint32_t rgs_accumulate_rays(const uint32_t *mem, const surface sf[], uint32_t active, const uint32_t weight[][3],
                             const uint32_t diffuse[][3], const uint32_t highlight[][3], f24_t eps, uint32_t spawn,
                             uint32_t acc[][3], rgs_task *refl, rgs_task *trans)
{
    uint32_t children = 0;
accumulate:
    for (int i = 0; i < TRACE_PACKET; i++)
        if (active >> i & 1u)
            children += (uint32_t)rgs_accumulate_ray(sf[i].valid ? &mem[sf[i].mat] : 0, &sf[i], i, weight[i], diffuse[i],
                                           highlight[i], eps, spawn, acc[i], refl, trans);
    return children;
}
