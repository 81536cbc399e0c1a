/*
 * The shading half of `saarcor reference`: the fixed-function shading model of docs/shading.md
 * in binary64 (unquantized material parameters from host/scene/shading_model.c, exact
 * bilinear texture filtering, the same ray tree, ray offsets and lights), over the
 * double-precision BVH of ref_bvh.h. It shares with the hardware path only the scene loader,
 * the shading model and the camera definition (mi_camera_frame), so that its image differs from
 * the units' only by their arithmetic and algorithms.
 */
#ifndef SAARCOR_REF_RENDER_H
#define SAARCOR_REF_RENDER_H

#include "memimage.h"
#include "ref_bvh.h"

typedef struct {
    uint32_t max_depth;
    int shadows;
    mi_camera cam;
    scene_light *lights;  /* the scene's lights, or the memory image's default light */
    uint32_t n_lights;
    double eps;           /* ray offset e */
    int (*stop)(void);    /* polled before each row: non-zero stops the image (Ctrl-C); NULL: never */
} ref_params;

/* Camera, lights and ray offset as the device sees them (b: the scene's memory-image builder,
 * used only for the camera and the default light). lights is allocated; ref_params_free. */
int ref_params_init(ref_params *p, const mi_builder *b, const ref_scene *r, uint32_t max_depth, int shadows);
void ref_params_free(ref_params *p);

/* Primary ray of pixel (x, y): origin and (unnormalized) direction, as the device's T_init. */
void ref_primary(const mi_camera *c, uint32_t x, uint32_t y, double o[3], double d[3]);

/* Colour of pixel (x, y), each channel clamped to [0, 1]; the primary hit in *hit. */
void ref_pixel(const ref_scene *r, const ref_params *p, uint32_t x, uint32_t y, double rgb[3], ref_hit *hit);

/* The whole image with `threads` host threads (interleaved rows; the result does not depend on
 * their number): clamped RGB (3 floats per pixel) and, if hits is not NULL, the primary hits.
 * 0, -1 if out of memory, 1 if p->stop stopped it (the image is incomplete). */
int ref_render_image(const ref_scene *r, const ref_params *p, uint32_t threads, float *rgb, ref_hit *hits);

/* Unit world geometric normal of a hit, A-B-C orientation through the transposed
 * world-to-object matrix (the AOV's N). */
void ref_geometric_normal(const ref_scene *r, const ref_hit *h, double n[3]);

#endif
