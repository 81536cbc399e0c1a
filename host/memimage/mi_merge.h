/*
 * Static geometry merged into world space (issue: the hardware at least as efficient as the
 * prototype). An instance costs every ray that enters it a world-to-object transformation (a
 * packet's origin and directions: up to 8 transformation slots) and a clip, and overlapping
 * instances make rays visit several objects where one tree would do. Geometry that neither moves
 * nor morphs does not need an instance of its own: the host bakes it into one world-space object
 * (one bottom-level tree) under an identity instance, which the device passes without a
 * transformation. Separate objects remain where they are needed:
 *   - a node that an animation moves (it or an ancestor has a translation, rotation or scale
 *     channel) keeps its instance, rebuilt per frame in the top level;
 *   - a deforming mesh (morph targets, skin) keeps its object (its geometry is rebuilt when it changes);
 *   - a mirrored instance (negative determinant) keeps its instance: baking it would flip the
 *     side its triangles face, which the shading's entering/leaving decision reads;
 *   - a turned instance (its linear part does not map the axes onto the axes) keeps its
 *     instance: the mesh's own tree is built in the space where its faces are axis-aligned, and
 *     a world-space tree over slanted faces needs several times the ray-triangle tests;
 *   - an instanced mesh (several static instances) is baked copy by copy only while the copies
 *     fit the memory budget: merging always saves the instance entries the SAH charges (two
 *     transformation slots per ray entering a copy), but costs the copies' triangles in memory.
 *     The budget is the scene's own unique triangles: copies of the smallest meshes are baked
 *     first, until the baked copies would add more triangles than the scene has.
 * Meshes without texture coordinates but with a textured material go to a second merged object
 * (the object descriptor says whether its triangles have texture coordinates).
 */
#ifndef SAARCOR_MI_MERGE_H
#define SAARCOR_MI_MERGE_H

#include <stdint.h>

#include "scene.h"

#define MI_MERGE_CLASSES 2 /* all, and meshes with a textured material but no texture coordinates */

typedef struct {
    uint32_t n_meshes;        /* merged objects (non-empty classes) */
    scene_mesh *meshes;       /* world-space geometry, owned */
    uint32_t **src_instance;  /* per merged mesh and triangle: the scene instance it came from */
    uint32_t **src_triangle;  /* ... and its triangle in that instance's mesh */
    uint8_t *baked_node;      /* per scene node: 1 if its instance is baked */
    /* what `saarcor info` reports */
    uint32_t baked_instances, animated_instances, morphing_instances, mirrored_instances, turned_instances,
        instanced_kept;
    uint64_t baked_copy_triangles; /* triangles added by baking copies of instanced meshes */
} mi_merge;

/* Plans and builds the merge for the scene as evaluated now (instances and node transforms).
 * enabled = 0 bakes nothing. Returns 0, or -1 if memory ran out. */
int mi_merge_build(const scene *s, int enabled, mi_merge *out);

void mi_merge_free(mi_merge *m);

#endif
