/*
 * Hard limits of the commands that load a scene (docs/limits.md): how big a scene, a tree, an
 * image or an animation the simulator accepts before it starts allocating and building, so that
 * a hostile or mistaken input ends with one clear line instead of exhausting memory or running
 * for days. Every limit has a default and a ceiling (what the design or the memory image can
 * represent at all) and is raised with `--limit NAME=N` (a scene option). Exceeding one prints
 *   saarcor CMD: error: limit NAME exceeded: <what> is V, the limit is L (raise it with --limit NAME=N, up to C)
 * and exits with SAARCOR_EXIT_LIMIT.
 */
#ifndef SAARCOR_CLI_LIMITS_H
#define SAARCOR_CLI_LIMITS_H

#include <stdint.h>

#include "memimage.h"
#include "scene.h"

typedef enum {
    LIMIT_TRIANGLES,    /* triangles of all meshes of the scene (before instancing) */
    LIMIT_INSTANCES,    /* mesh instances of the evaluated scene */
    LIMIT_KD_NODES,     /* kd-tree nodes of both levels in the memory image */
    LIMIT_KD_DEPTH,     /* depth of any kd-tree (bottom or top level) */
    LIMIT_TEXTURE_SIZE, /* width or height of any texture, texels */
    LIMIT_RAY_DEPTH,    /* render/reference --max-depth: levels of secondary rays */
    LIMIT_WIDTH,        /* image width, pixels */
    LIMIT_HEIGHT,       /* image height, pixels */
    LIMIT_FRAMES,       /* frames of one render --frames A:B */
    LIMIT_COUNT
} limit_id;

typedef struct {
    uint64_t value[LIMIT_COUNT];
} limits;

void limits_default(limits *l);

/* "NAME=N" (the argument of --limit). Returns 1, or 0 after printing a usage error. */
int limits_parse(limits *l, const char *cmd, const char *arg);

/* Checks value against limit id (what: what is counted, for the message). Returns
 * SAARCOR_EXIT_OK, or prints the one-line error and returns SAARCOR_EXIT_LIMIT. */
int limit_check(const limits *l, const char *cmd, limit_id id, uint64_t value, const char *what);

/* The scene as loaded, before scene_evaluate allocates its instances: triangles, instances (with
 * `extra` more to come, the --ground plane), texture sizes. */
int limits_check_scene(const limits *l, const char *cmd, const scene *s, uint32_t extra);

/* The tree parameters and image size of a build before it starts (explicit --kd-max-depth,
 * --width, --height). */
int limits_check_params(const limits *l, const char *cmd, const mi_params *p);

/* Before the build of the evaluated scene s: the deepest tree the builder may make (kd_depth_bound
 * of the largest object, or of all instanced triangles when merging, and of the top level). */
int limits_check_depth(const limits *l, const char *cmd, const mi_params *p, const scene *s);

/* After the build, as a net for trees built with other parameters: their depth. (The kd nodes of
 * both levels are counted by the builder as the trees grow, mi_params.max_nodes.) */
int limits_check_build(const limits *l, const char *cmd, const mi_stats *st);

#endif
