/* A light's weights at a packet's surfaces and its shadow packet, its colour and the accumulation
 * of its light: see rgs_ops.h and docs/shading.md. Outside rgs.c so that the unit capture can wrap
 * rgs_light_packet, rgs_light_colour and rgs_add_light. */
#include "rgs_ops.h"

#define Q12_DIFFUSE 3482u /* 0.85 */

void rgs_light_packet(const uint32_t *l, const surface sf[], f24_t eps, ray_packet *sh, uint32_t diff[], uint32_t spec[],
                      const uint32_t k_of[])
{
    const f24_vec3 lpos = { l[4], l[5], l[6] }, ldir = { l[7], l[8], l[9] };
    const int directional = l[0] == 0;
    sh->active = 0;
shadow_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        diff[i] = spec[i] = 0;
        sh->o[i] = sh->d[i] = (f24_vec3){ 0, 0, 0 };
        sh->tmin[i] = sh->tmax[i] = 0;
        if (!sf[i].valid || sf[i].unlit)
            continue; /* an unlit surface takes no light */
        sh->o[i] = sf[i].p;
        sh->d[i] = directional ? neg3(ldir) : sub3(lpos, sf[i].p);
        const f24_t dist = rgs_length3(sh->d[i]);
        sh->tmin[i] = directional ? eps : f24_div(eps, dist);
        sh->tmax[i] = directional ? F24_POS_INF : F24_ONE;
        f24_t w = f24_div(rgs_dot3(sf[i].n, sh->d[i]), dist);
        if (!f24_lt(0, w))
            continue; /* the light is behind the surface */
        if (SAARCOR_CFG_SPOT_LIGHTS && l[0] == 2) { /* spot: smooth step from the outer to the inner cone */
            const f24_t c = f24_neg(cos_to(ldir, sh->d[i]));
            const f24_t f = f24_div(f24_sub(c, l[12]), f24_sub(l[11], l[12]));
            w = f24_mul(w, f24_max(0, f24_min(f, F24_ONE)));
        }
        diff[i] = q_mul(rgs_q_of(w), Q12_DIFFUSE);
        uint32_t s = rgs_q_of(f24_max(0, cos_to(rgs_reflect(sf[i].d, sf[i].n), sh->d[i])));
    phong_power:
        for (uint32_t j = 0; j < 8; j++)
            if (j < k_of[i])
                s = q_mul(s, s); /* cos^(2^k): k squarings */
        spec[i] = s;
        if (diff[i] | spec[i])
            sh->active |= 1u << i;
    }
}

void rgs_light_colour(const uint32_t *l, uint32_t out[3])
{
    const f24_t m = f24_max(f24_max(l[1], l[2]), l[3]);
normalize_colour:
    for (int c = 0; c < 3; c++)
        out[c] = f24_lt(0, m) ? rgs_q_of(f24_div(l[1 + c], m)) : 0u;
}

void rgs_add_light(uint32_t diffuse[3], uint32_t highlight[3], uint32_t diff, uint32_t spec, const uint32_t colour[3])
{
add_light_channels:
    for (int k = 0; k < 3; k++) {
        diffuse[k] = q_add(diffuse[k], q_mul(diff, colour[k]));
        highlight[k] = q_add(highlight[k], q_mul(spec, colour[k]));
    }
}
