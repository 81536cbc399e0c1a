/*
 * Shared helpers of the scene generators: a scene under construction (materials, meshes, nodes,
 * cameras, lights, animations appended with growing arrays), a mesh builder with primitive
 * shapes placed by an affine transformation (box, frustum/cylinder, lathe, disk, icosphere,
 * height-field grid), quaternions and a seeded random number generator.
 *
 * Out-of-memory handling is sticky: a failed allocation sets the `oom` flag, later calls become
 * no-ops returning harmless indices, and geom_scene_end reports the failure once. Generators can
 * therefore be written as straight-line code.
 */
#ifndef SAARCOR_SCENES_GEOM_H
#define SAARCOR_SCENES_GEOM_H

#include <stddef.h>
#include <stdint.h>

#include "scene.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- random numbers (splitmix64) -------------------------------------------------------- */

typedef struct {
    uint64_t state;
} geom_rng;

/* Seeds a generator from the user's seed and a per-use stream constant. */
void geom_rng_seed(geom_rng *r, uint64_t seed, uint64_t stream);
uint64_t geom_rng_u64(geom_rng *r);
double geom_rand(geom_rng *r);                       /* [0, 1) */
double geom_range(geom_rng *r, double lo, double hi); /* [lo, hi) */

/* ---- transformations -------------------------------------------------------------------- */

/* Unit quaternion (x y z w) of a rotation by angle (radians) about axis (need not be unit). */
void geom_quat_axis(double ax, double ay, double az, double angle, double q[4]);
void geom_quat_mul(const double a[4], const double b[4], double out[4]); /* a * b */
/* Rotation that makes the node's -Z axis point along dir, with +Y as close to up as possible. */
void geom_quat_look(const double dir[3], const double up[3], double q[4]);

/* Translation, rotation about +Y (radians) and per-axis scale as an affine transformation. */
affine geom_place(double tx, double ty, double tz, double yaw, double sx, double sy, double sz);
/* Translation, rotation by angle (radians) about the axis (ax, ay, az), per-axis scale. */
affine geom_trs(double tx, double ty, double tz, double ax, double ay, double az, double angle, double sx, double sy,
                double sz);

/* ---- mesh builder ----------------------------------------------------------------------- */

typedef struct {
    float *pos, *nrm, *uv;
    uint32_t *idx, *mat;
    uint32_t nv, nt, cap_v, cap_t;
    int oom;
} geom_mesh;

void geom_mesh_init(geom_mesh *m);
void geom_mesh_free(geom_mesh *m);

/* Appends a vertex (normal need not be unit; NULL = +Y) and returns its index. */
uint32_t geom_vertex(geom_mesh *m, const double p[3], const double n[3], double u, double v);
void geom_tri(geom_mesh *m, uint32_t a, uint32_t b, uint32_t c, uint32_t material);

/* Shapes, transformed by xf (NULL = identity); normals use the inverse transpose. Triangles are
 * counter-clockwise seen from outside. */
/* Unit cube [-0.5, 0.5]^3: 24 vertices, 12 triangles. */
void geom_box(geom_mesh *m, const affine *xf, uint32_t material);
/* Surface of revolution about +Y of a profile of (radius, y) points, bottom to top:
 * segments * (n - 1) * 2 triangles. */
void geom_lathe(geom_mesh *m, const affine *xf, const double (*profile)[2], uint32_t n, uint32_t segments,
                uint32_t material);
/* Frustum of radii r0 (y = 0) and r1 (y = 1), optional caps; r0 = r1: cylinder. */
void geom_frustum(geom_mesh *m, const affine *xf, double r0, double r1, uint32_t segments, int caps,
                  uint32_t material);
/* Disk of radius 1 at y = 0 facing +Y (down = 1: facing -Y): `segments` triangles. */
void geom_disk(geom_mesh *m, const affine *xf, uint32_t segments, int down, uint32_t material);
/* Square pyramid, open base [-0.5, 0.5]^2 at y = 0, apex (0, 1, 0): 5 vertices, 4 triangles. */
void geom_pyramid(geom_mesh *m, const affine *xf, uint32_t material);
/* Parametric patch p = surface(u, v) over [0, 1]^2 with nu * nv cells, normals along
 * dp/du x dp/dv (the front side): 2 * nu * nv triangles. */
void geom_patch(geom_mesh *m, const affine *xf, uint32_t nu, uint32_t nv,
                void (*surface)(double u, double v, const void *ctx, double p[3]), const void *ctx, uint32_t material);
/* Icosphere of radius 1: 20 * 4^subdiv triangles, smooth normals. */
void geom_sphere(geom_mesh *m, const affine *xf, uint32_t subdiv, uint32_t material);
/* Grid of nx * nz cells on [-0.5, 0.5]^2 in the XZ plane facing +Y, height y = heights[j*(nx+1)+i]
 * (NULL: flat), normals from central differences; material_of(cell centre height, slope,
 * ctx) picks each cell's material (NULL: `material`). 2 * nx * nz triangles. */
void geom_grid(geom_mesh *m, const affine *xf, uint32_t nx, uint32_t nz, const float *heights,
               uint32_t material, uint32_t (*material_of)(double height, double slope, const void *ctx),
               const void *ctx);

/* ---- scene under construction ----------------------------------------------------------- */

typedef struct {
    scene *s;
    uint32_t cap_meshes, cap_nodes, cap_materials, cap_textures, cap_cameras, cap_lights, cap_animations;
    int oom;     /* an allocation failed */
    int invalid; /* a channel did not fit its node (a generator bug) */
} geom_scene;

/* Clears *out and starts a scene with the default material 0 (the loader's default). */
void geom_scene_begin(geom_scene *g, scene *out);
/* Roots = all parentless nodes, evaluation at time 0. Returns 0, or -1 with "out of memory" (or
 * an internal error) in err after freeing the scene. */
int geom_scene_end(geom_scene *g, char *err, size_t errlen);

/* A material value with the loader's defaults and the given base colour, metallic, roughness. */
scene_material geom_material(float r, float g, float b, float metallic, float roughness);
uint32_t geom_add_material(geom_scene *g, const scene_material *m);
/* Copies width*height*4 RGBA8 bytes. */
uint32_t geom_add_texture(geom_scene *g, int width, int height, const uint8_t *rgba);
/* Moves the builder's arrays into a new scene mesh (the builder is left empty); texture
 * coordinates are kept only if one of the mesh's materials has a texture (base colour or
 * emissive). */
uint32_t geom_add_mesh(geom_scene *g, geom_mesh *m, const char *name);
/* Morph targets: deltas (n_targets * 3 * n_vertices floats) are copied; weights start at 0. */
void geom_set_morph(geom_scene *g, uint32_t mesh, uint32_t n_targets, const float *deltas);

/* Node with TRS (NULL: identity parts), parent -1 for a root, mesh SCENE_NONE for none. Nodes
 * instancing a morphed mesh get that mesh's weights. */
uint32_t geom_add_node(geom_scene *g, const char *name, int parent, uint32_t mesh, const double t[3],
                       const double q[4], const double sc[3]);
/* Perspective camera node at eye looking at target (+Y up); yfov in radians. */
uint32_t geom_add_camera(geom_scene *g, const double eye[3], const double target[3], double yfov, double aspect,
                         double znear, double zfar);
/* KHR_lights_punctual lights: a point light at pos, a directional light shining along dir. */
uint32_t geom_add_point_light(geom_scene *g, const char *name, const double pos[3], float r, float gr, float b,
                              float intensity);
uint32_t geom_add_dir_light(geom_scene *g, const char *name, const double dir[3], float r, float gr, float b,
                            float intensity);

uint32_t geom_add_animation(geom_scene *g, const char *name);
/* Adds a channel to animation anim; values has n_keys * components (* 3 for CUBICSPLINE:
 * in-tangent, value, out-tangent) floats, components = 3/4 or the node's weight count. */
void geom_add_channel(geom_scene *g, uint32_t anim, uint32_t node, anim_path path, anim_interp interp,
                      uint32_t n_keys, const float *times, const float *values);

#endif
