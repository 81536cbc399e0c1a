/*
 * Ray generation and shading unit (RGS, paper section 2.2 and 3), first stage: primary rays and
 * local shading of the closest hit.
 *
 * Primary rays use the transformation unit: the camera block of the memory image holds O and the
 * columns U, V, W of T_R = [U V W] (the corrected form of the paper's matrix, see
 * docs/memory-image.md), so the direction of pixel (x, y) is T_R (x + 1/2, y + 1/2, 1) and the
 * origin is O (perspective), or the origin O + (x + 1/2) U + (y + 1/2) V and direction W
 * (orthographic). A packet is a 2x2 pixel block, whose rays share their origin.
 * Shading: interpolated vertex normal (or the geometric normal, row 2 of the triangle
 * transformation, when the object has none or it is zero), taken to world space with the
 * transposed world-to-object matrix, normalized and turned towards the viewer; base colour times
 * (ambient 0.15 + 0.85 x sum over the scene's lights of cosine x spot factor x light colour, for
 * lights whose shadow ray reaches the point), plus emission; 8-bit RGB via f24_to_i32. Shadow
 * rays of a packet towards one light form one packet (origin the hit point, direction to the
 * light, t in [1/512, 1]). A scene without lights gets a light at the eye (no shadows).
 * The base colour is the material factor times a bilinear sample of its base-colour texture
 * (texel centres at +1/2, repeat wrapping, texels as stored, i.e. sRGB-encoded values used as
 * they are). Reflection and refraction come with the next stage.
 */
#ifndef SAARCOR_RGS_H
#define SAARCOR_RGS_H

#include "trace.h"

/* Primary rays of the 2x2 block with top-left pixel (x0, y0); pixels outside the image are
 * inactive. */
void rgs_primary(const uint32_t *mem, uint32_t x0, uint32_t y0, ray_packet *rp);

/* 0xRRGGBB colours of the packet's rays given their hits; shadow rays are traced (counted in c). */
void rgs_shade_packet(const uint32_t *mem, const ray_packet *rp, const hit_record h[], uint32_t rgb[], trace_counters *c);

/* Image size of the camera block. */
void rgs_image_size(const uint32_t *mem, uint32_t *width, uint32_t *height);

#endif
