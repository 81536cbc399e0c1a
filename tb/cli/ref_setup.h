/* Shared set-up of the commands that use the double-precision reference (reference,
 * compare-hits): load the scene, build its memory image (camera, default light, and the
 * device's view for compare-hits) and the reference BVH. */
#ifndef SAARCOR_REF_SETUP_H
#define SAARCOR_REF_SETUP_H

#include "ref_bvh.h"
#include "scene_opts.h"

/* Returns a SAARCOR_EXIT_* code; on success the caller frees r, *b and s. */
int ref_setup(const char *cmd, const scene_opts *o, scene *s, mi_builder **b, ref_scene *r);

#endif
