/*
 * Options shared by the commands that load a scene and build its memory image (info, and later
 * render and bench): the scene argument (a .gltf/.glb path or the name of a generator) and the
 * kd-tree and memory parameters.
 */
#ifndef SAARCOR_SCENE_OPTS_H
#define SAARCOR_SCENE_OPTS_H

#include <getopt.h>

#include "cli_limits.h"
#include "memimage.h"
#include "scene.h"

/* getopt_long entries for the shared options (values from SCENE_OPT_BASE up) and their help. */
#define SCENE_OPT_BASE 1000
#define SCENE_LONG_OPTIONS                                                                              \
    { "mem-mb", required_argument, NULL, SCENE_OPT_BASE + 0 }, { "ct", required_argument, NULL, SCENE_OPT_BASE + 1 }, \
    { "ci", required_argument, NULL, SCENE_OPT_BASE + 2 }, { "empty-bonus", required_argument, NULL, SCENE_OPT_BASE + 3 }, \
    { "kd-max-depth", required_argument, NULL, SCENE_OPT_BASE + 4 }, { "leaf-size", required_argument, NULL, SCENE_OPT_BASE + 5 }, \
    { "top-bins", required_argument, NULL, SCENE_OPT_BASE + 6 }, { "width", required_argument, NULL, SCENE_OPT_BASE + 7 }, \
    { "height", required_argument, NULL, SCENE_OPT_BASE + 8 }, { "time", required_argument, NULL, SCENE_OPT_BASE + 9 }, \
    { "max-condition", required_argument, NULL, SCENE_OPT_BASE + 10 }, { "camera", required_argument, NULL, SCENE_OPT_BASE + 11 }, \
    { "eye", required_argument, NULL, SCENE_OPT_BASE + 12 }, { "at", required_argument, NULL, SCENE_OPT_BASE + 13 }, \
    { "up", required_argument, NULL, SCENE_OPT_BASE + 14 }, { "fov", required_argument, NULL, SCENE_OPT_BASE + 15 }, \
    { "ground", no_argument, NULL, SCENE_OPT_BASE + 16 }, { "general", no_argument, NULL, SCENE_OPT_BASE + 17 }, \
    { "limit", required_argument, NULL, SCENE_OPT_BASE + 18 }, { "merge", no_argument, NULL, SCENE_OPT_BASE + 19 }, \
    { "top-ci", required_argument, NULL, SCENE_OPT_BASE + 20 }, { "animation", required_argument, NULL, SCENE_OPT_BASE + 21 }, \
    { "kd-bins", required_argument, NULL, SCENE_OPT_BASE + 22 }

/* `info` also accepts the kd-tree depth as --max-depth (render and reference use that name for
 * the ray depth). */
#define SCENE_KD_DEPTH_ALIAS { "max-depth", required_argument, NULL, SCENE_OPT_BASE + 4 }

#define SCENE_OPTIONS_HELP                                                                              \
    "scene options:\n"                                                                                  \
    "  SCENE                 a .gltf/.glb file, or a generator name (saarcor gen --list)\n"            \
    "  --time T              evaluate animations at T seconds (default 0)\n"                           \
    "  --animation A         play only the animation named A (or numbered A, from 0; default: all)\n" \
    "  --camera N            use the scene's camera N (default 0; a default view if there is none)\n" \
    "  --eye X,Y,Z --at X,Y,Z [--up X,Y,Z] [--fov DEG]  explicit perspective view instead (up 0,1,0,\n" \
    "                        vertical field of view 45 degrees; pixel centres at +1/2)\n"             \
    "  --ground              add a polished metal ground plane under the scene (+Y up), so that\n"    \
    "                        shadows and reflections show\n"                                         \
    "  --width W --height H  image size for the camera set-up (default 512 x 384)\n"                   \
    "  --mem-mb N            device memory size in MB (default 24, as the prototype)\n"                \
    "  --ct X --ci Y         SAH traversal and intersection costs of both levels (default 1, 1.5;\n"  \
    "                        the top level's C_i 3, an instance entry)\n"                           \
    "  --top-ci Y            the top level's C_i alone (after --ci)\n"                                \
    "  --empty-bonus B       SAH bonus for cutting off empty space, 0..1 (default 0.2)\n"              \
    "  --kd-max-depth D      kd-tree depth limit (default 0: 8 + 1.3 log2 N)\n"                        \
    "  --leaf-size L         never split nodes with at most L primitives (default 1)\n"               \
    "  --top-bins N          bins of the top-level SAH (default 32)\n"                                 \
    "  --kd-bins N           bin every object's tree nodes over 48 triangles into up to N bins per\n" \
    "                        axis, one per 16 triangles, at least min(N, 32) (0: the exact sweep\n"  \
    "                        throughout; default: meshes of 32768 triangles or more, up to 256)\n" \
    "  --max-condition K     drop triangles whose shape condition number exceeds K (default 2^24)\n" \
    "  --limit NAME=N        raise (or lower) a hard limit: triangles, instances, kd-nodes, kd-depth,\n" \
    "                        texture-size, ray-depth, width, height, frames (docs/limits.md)\n"     \
    "  --general             the general pipeline: ignore the scene profile (no any-hit shadow rays,\n" \
    "                        no single-object shortcut, ...; same image, more work; saarcor profile)\n" \
    "  --merge               merge static, axis-aligned instances into one world-space object\n"     \
    "                        (default: every mesh instance keeps its own object; docs/memory-image.md)\n"

typedef struct {
    const char *scene;   /* path or generator name */
    double time;
    const char *animation; /* --animation: the one animation to play, NULL: all */
    int ground;          /* --ground: add scene_add_ground's plane */
    mi_params mi;
    limits lim;          /* --limit */
} scene_opts;

void scene_opts_default(scene_opts *o);

/* Handles one getopt result c >= SCENE_OPT_BASE. Returns 1 if handled, 0 if not a shared
 * option, -1 after printing a usage error (the command then exits with SAARCOR_EXIT_USAGE). */
int scene_opts_parse(scene_opts *o, const char *cmd, int c, const char *arg);

/* Loads (or generates) the scene and evaluates it at o->time, checking the hard limits of the
 * options (image size, kd depth) before and of the scene (triangles, instances, textures) after.
 * Returns a SAARCOR_EXIT_* code; errors are printed as one line. */
int scene_opts_load(const scene_opts *o, const char *cmd, scene *s);

/* The largest device memory, --mem-mb 2047: where a scene that does not fit is built to learn its
 * size, and what the binary64 reference (not bound by the device) builds in. */
#define SCENE_MAX_MEM_BYTES ((uint64_t)2047 << 20)

/* The --mem-mb value that holds an image of n_words 32-bit words. */
uint32_t scene_mem_mb_for(uint64_t n_words);

/* mi_build with o->mi, then the limits of the result (kd nodes, depth). A scene that does not fit
 * the device memory is built again in SCENE_MAX_MEM_BYTES to learn how much it needs: with fits
 * NULL the error names the --mem-mb to pass; with fits, that image is returned and *fits = 0
 * (info reports on it). NULL after printing the error, with the exit code in *rc. */
mi_builder *scene_opts_build(const scene_opts *o, const char *cmd, const scene *s, int *fits, int *rc);

/* --traversal NAME (render, info): the traversal unit's algorithm (a TRAV_* value) and the
 * structures it needs in the memory image set in o->mi. -1 after printing a usage error. */
int scene_opts_traversal(scene_opts *o, const char *cmd, const char *arg);

/* One warning line on stderr if the scene's meshes have triangles the device cannot hold (fp24
 * range or the condition limit; they are dropped from the image), with the counts by reason. */
void scene_opts_warn_dropped(const scene_opts *o, const char *cmd, const scene *s);

#endif
