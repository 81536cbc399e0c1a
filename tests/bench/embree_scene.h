/* The anchor renderer's scene: the same two levels as ours in Embree 3 (one scene per mesh, one
 * instance per scene instance), and the benchmarks' scene list. Shared by bench_build.c,
 * bench_render.c and bench_peers.c. */
#ifndef SAARCOR_EMBREE_SCENE_H
#define SAARCOR_EMBREE_SCENE_H

#include <stddef.h>

#include <embree3/rtcore.h>

#include "scene.h"

/* One RTCScene holding the mesh's triangles (uncommitted), or NULL for an empty mesh. */
RTCScene embree_mesh_scene(RTCDevice dev, const scene_mesh *m, enum RTCBuildQuality q);

/* Top-level scene with one instance per scene instance (uncommitted). */
RTCScene embree_top_scene(RTCDevice dev, const scene *s, RTCScene *meshes, enum RTCBuildQuality q);

/* The scenes bench-render and bench-peers trace: the generated ones and the shared ones. */
#define BENCH_SCENES 8
extern const char *const bench_scene_names[BENCH_SCENES];

/* Loads a generator name (seed 1) or a file of ../shared/scenes/; 0, or -1 with err. */
int bench_scene_load(const char *name, scene *s, char *err, size_t n);

#endif
