/* A light's weights at a packet's surfaces and its shadow packet, its colour and the accumulation
 * of its light: see rgs_ops.h and docs/shading.md. Outside rgs.c so that the unit capture can wrap
 * rgs_light_packet, rgs_light_colour and rgs_add_light. */
#include "rgs_ops.h"

#ifdef F24_SIM_LANES
#define rgs_light_packet rgs_light_packet_per_ray /* the simulation build's is side by side (rgs_ops.h) */
#endif

void rgs_light_packet(const uint32_t *l, const surface sf[], f24_t eps, ray_packet *sh, uint32_t diff[], uint32_t spec[],
                      const uint32_t k_of[])
{
    const f24_vec3 ldir = { l[7], l[8], l[9] };
    const f24w_vec3 lpos_w = f24w_vec3_of((f24_vec3){ l[4], l[5], l[6] }), ldir_w = f24w_vec3_of(ldir);
    const f24w zero = f24w_of(0), eps_w = f24w_of(eps);
    const int directional = l[0] == 0;
    sh->active = 0;
shadow_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!rgs_takes_light(&sf[i], sh, diff, spec, i))
            continue;
        /* the direction to the light (a directional light's is its words' negation, not rounded) */
        const f24w_vec3 to_light = directional ? neg3_w(ldir_w) : sub3_w(lpos_w, f24w_vec3_of(sf[i].p));
        const f24w dist = rgs_length3_w(to_light);
        rgs_shadow_ray(l, &sf[i], eps, f24w_vec3_bits(to_light), f24w_bits(f24w_div(eps_w, dist)), sh, i);
        /* cosines of the light direction with the normal, the cone axis, the mirror direction */
        f24w w = f24w_div(f24w_dot3(f24w_vec3_of(sf[i].n), to_light), dist);
        if (!f24w_lt(zero, w))
            continue; /* the light is behind the surface */
        if (SAARCOR_CFG_SPOT_LIGHTS && l[0] == 2) { /* spot: smooth step from the outer to the inner cone */
            const f24w c = f24w_neg(f24w_div(f24w_dot3(ldir_w, to_light), dist));
            const f24w f = f24w_div(f24w_sub(c, f24w_of(l[12])), f24w_sub(f24w_of(l[11]), f24w_of(l[12])));
            w = f24w_mul(w, f24w_max(zero, f24w_min(f, f24w_of(F24_ONE))));
        }
        const f24w_vec3 mirror = f24w_vec3_of(rgs_reflect(sf[i].d, sf[i].n));
        const f24w h = f24w_max(zero, f24w_div(f24w_dot3(mirror, to_light), dist));
        if (rgs_light_weights(w, h, k_of[i], &diff[i], &spec[i]))
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
