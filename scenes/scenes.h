/*
 * Scene generators: procedural test scenes built directly into the host scene model (scene.h),
 * written to glTF by `saarcor gen NAME -o FILE` and usable by name wherever a scene is read.
 * Every generator is deterministic for a given seed; `detail` is a generator-specific size knob
 * (0 = the default size; see each generator's summary).
 */
#ifndef SAARCOR_SCENES_H
#define SAARCOR_SCENES_H

#include <stddef.h>
#include <stdint.h>

#include "scene.h"

typedef struct {
    uint64_t seed;
    uint32_t detail; /* 0 = default size */
} scene_gen_params;

typedef struct {
    const char *name;
    const char *summary;
    /* Builds the scene into *out (which is overwritten) and evaluates it at time 0. Returns 0, or
     * -1 with a one-line message in err (out is left empty). */
    int (*build)(scene *out, const scene_gen_params *p, char *err, size_t errlen);
} scene_generator;

extern const scene_generator scene_generators[];
extern const unsigned scene_generator_count;

/* The generator called name, or NULL. */
const scene_generator *scene_generator_find(const char *name);

/* The generators (one file each). */
int scene_gen_cornell(scene *out, const scene_gen_params *p, char *err, size_t errlen);
int scene_gen_room(scene *out, const scene_gen_params *p, char *err, size_t errlen);
int scene_gen_plants(scene *out, const scene_gen_params *p, char *err, size_t errlen);
int scene_gen_terrain(scene *out, const scene_gen_params *p, char *err, size_t errlen);
int scene_gen_animated(scene *out, const scene_gen_params *p, char *err, size_t errlen);
/* scenes/shading.c: one scene per optional shading feature */
int scene_gen_emissive(scene *out, const scene_gen_params *p, char *err, size_t errlen);
int scene_gen_vertex_colours(scene *out, const scene_gen_params *p, char *err, size_t errlen);
int scene_gen_uv_transform(scene *out, const scene_gen_params *p, char *err, size_t errlen);
int scene_gen_unlit(scene *out, const scene_gen_params *p, char *err, size_t errlen);

#endif
