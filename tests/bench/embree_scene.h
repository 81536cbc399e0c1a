/* The anchor renderer's scene: the same two levels as ours in Embree 3 (one scene per mesh, one
 * instance per scene instance). Shared by bench_build.c and bench_render.c. */
#ifndef SAARCOR_EMBREE_SCENE_H
#define SAARCOR_EMBREE_SCENE_H

#include <embree3/rtcore.h>

#include "scene.h"

/* One RTCScene holding the mesh's triangles (uncommitted), or NULL for an empty mesh. */
RTCScene embree_mesh_scene(RTCDevice dev, const scene_mesh *m, enum RTCBuildQuality q);

/* Top-level scene with one instance per scene instance (uncommitted). */
RTCScene embree_top_scene(RTCDevice dev, const scene *s, RTCScene *meshes, enum RTCBuildQuality q);

#endif
