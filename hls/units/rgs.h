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
 * transposed world-to-object matrix and turned towards the viewer; base colour times
 * (ambient + diffuse) from a light at the eye, plus emission; 8-bit RGB via f24_to_i32.
 * Shadows, reflection, refraction, textures and the scene's lights come with the next stage.
 */
#ifndef SAARCOR_RGS_H
#define SAARCOR_RGS_H

#include "trace.h"

/* Primary rays of the 2x2 block with top-left pixel (x0, y0); pixels outside the image are
 * inactive. */
void rgs_primary(const uint32_t *mem, uint32_t x0, uint32_t y0, ray_packet *rp);

/* 0xRRGGBB colour of ray i of the packet given its hit. */
uint32_t rgs_shade(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h);

/* Image size of the camera block. */
void rgs_image_size(const uint32_t *mem, uint32_t *width, uint32_t *height);

#endif
