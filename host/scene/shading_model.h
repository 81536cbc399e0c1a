/*
 * The fixed-function shading model, host side (docs/shading.md): how a glTF material maps onto
 * the shader's parameters, and the model's constants. One truth for the two places that shade:
 * the memory-image builder quantizes these parameters for the RGS unit (hls/units/rgs.c, integer
 * Q12 colour arithmetic), and the double-precision reference renderer uses them unquantized.
 */
#ifndef SAARCOR_SHADING_MODEL_H
#define SAARCOR_SHADING_MODEL_H

#include <stdint.h>

#include "scene.h"

#define SHADE_AMBIENT 0.15           /* ambient term of the diffuse light */
#define SHADE_DIFFUSE 0.85           /* weight of each light's cosine term */
#define SHADE_BACKGROUND 0x1A1A24u   /* 0xRRGGBB of rays that leave the scene */
#define SHADE_MIN_WEIGHT (16.0 / 4096.0) /* secondary rays whose weight is below this are not spawned */
#define SHADE_EPS_SHIFT 10           /* ray offset e = 2^-10 x largest extent of the scene bounds */
#define SHADE_MAX_DEPTH 8            /* deepest secondary-ray level the RGS unit supports */
#define SHADE_DEFAULT_DEPTH 3        /* default --max-depth */

typedef struct {
    double kd;        /* weight of the diffuse (base colour x light) term */
    double kr;        /* weight of the mirror reflection ray (tinted by base colour for metals) */
    double kt;        /* weight of the transmission ray (tinted by base colour) */
    double ks;        /* weight of the Phong highlight (tinted like kr) */
    uint32_t exp_shift; /* Phong exponent n = 2^exp_shift (1..8) */
    double eta;       /* index of refraction of the transmission; 1: straight transparency ray */
    double metallic;  /* tint of reflection and highlight: 1 + metallic (base - 1) */
    int unlit;        /* KHR_materials_unlit: the diffuse term's light is 1, no lights, kr = ks = 0 */
} shading_params;

/* The material mapping of docs/shading.md. */
void shading_params_of(const scene_material *m, shading_params *out);

#endif
