/*
 * The host's scene model: what the glTF loader produces, what the scene generators build, what
 * the kd-tree builders and the memory-image writer consume. Plain C structs, all arrays owned by
 * the scene (scene_free releases everything). Host code: double precision where it matters.
 *
 * Mapping from glTF: each glTF mesh (all its TRIANGLES primitives) is one OBJECT with its own
 * bottom-level tree; each node that references a mesh is one INSTANCE of that object with the
 * node's world transformation. Nodes, animations and morph weights are kept so that the scene
 * can be evaluated at any time (scene_evaluate). A skinned mesh (glTF skins) is deformed on the
 * host by linear blend skinning: its positions and normals become world-space ones, and its
 * instance's transformation the identity, as the glTF specification ignores the node's own.
 */
#ifndef SAARCOR_SCENE_H
#define SAARCOR_SCENE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SCENE_NONE UINT32_MAX

/* Affine transformation x' = m * x + t, stored row-major as 3 rows of (m00 m01 m02 t0). */
typedef struct { double m[3][4]; } affine;

typedef enum { ALPHA_OPAQUE = 0, ALPHA_MASK = 1, ALPHA_BLEND = 2 } alpha_mode;

/* KHR_texture_transform of a texture reference, as the file gives it (scene_texcoord applies
 * it); only if set, so that a zero-initialized material has none. */
typedef struct {
    int set;
    double offset[2], rotation, scale[2];
} scene_uv_map;

typedef struct {
    float base_color[4];        /* linear RGBA factor */
    uint32_t base_color_texture; /* index into scene.textures or SCENE_NONE */
    uint32_t texcoord_set;       /* TEXCOORD_n used by the texture (0 or 1) */
    scene_uv_map base_uv;        /* its KHR_texture_transform */
    alpha_mode alpha;
    float alpha_cutoff;
    float metallic, roughness;
    float emissive[3];           /* emissiveFactor x KHR_materials_emissive_strength */
    uint32_t emissive_texture;   /* index into scene.textures or SCENE_NONE (texels used as stored) */
    uint32_t emissive_texcoord;  /* TEXCOORD_n of the emissive texture (0 or 1) */
    scene_uv_map emissive_uv;
    int unlit;                   /* KHR_materials_unlit: the base colour alone */
    float transmission;          /* KHR_materials_transmission factor, 0 if absent */
    float ior;                   /* KHR_materials_ior, 1.5 if absent */
    int double_sided;
} scene_material;

typedef struct {
    int width, height;
    uint8_t *rgba; /* width*height*4 bytes, row-major, top row first, sRGB-encoded as stored */
} scene_texture;

/* One object: the triangles of all TRIANGLES primitives of one glTF mesh. */
typedef struct {
    char name[64];
    uint32_t n_vertices, n_triangles;
    float *positions;   /* 3 * n_vertices (current geometry: base + weighted morph targets) */
    float *normals;     /* 3 * n_vertices, or NULL */
    float *texcoords;   /* 2 * n_vertices (TEXCOORD_0), or NULL */
    float *texcoords1;  /* 2 * n_vertices (TEXCOORD_1), or NULL */
    float *colours;     /* 3 * n_vertices (COLOR_0, RGB in [0, 1]; alpha is not used), or NULL */
    uint32_t *indices;  /* 3 * n_triangles, every index < n_vertices */
    uint32_t *material; /* n_triangles: index into scene.materials (a default material exists) */
    /* morph targets (position deltas only are applied to the geometry) */
    uint32_t n_targets;
    float *base_positions;  /* 3 * n_vertices, the positions without morphing and skinning (n_targets > 0
                               or joints) */
    float *target_deltas;   /* n_targets * 3 * n_vertices */
    float *weights;         /* n_targets current weights */
    /* skinning (JOINTS_0 / WEIGHTS_0): up to 4 influences per vertex, the joint an index into the
     * joints of scene.skins[skin]; the rest pose (base_positions, morphed) and bind_normals are
     * deformed into positions and normals by scene_evaluate */
    uint16_t *joints;       /* 4 * n_vertices, or NULL: the mesh is not skinned */
    float *joint_weights;   /* 4 * n_vertices */
    float *bind_normals;    /* 3 * n_vertices, the normals before skinning (if normals) */
    uint32_t skin;
    /* bumped whenever scene_evaluate changes positions (morphing, skinning): mi_update rebuilds
     * the object's tree and uploads its geometry when this differs from what it built */
    uint32_t revision;
} scene_mesh;

typedef enum { CAMERA_PERSPECTIVE = 0, CAMERA_ORTHOGRAPHIC = 1 } camera_kind;

typedef struct {
    camera_kind kind;
    double yfov;         /* radians, perspective */
    double aspect;       /* 0 if the file does not say */
    double xmag, ymag;   /* orthographic half extents */
    double znear, zfar;
    uint32_t node;       /* node that carries it (world transform), SCENE_NONE for a default camera */
    affine world;        /* camera-to-world: looks down -Z, +Y up (glTF convention) */
} scene_camera;

typedef enum { LIGHT_DIRECTIONAL = 0, LIGHT_POINT = 1, LIGHT_SPOT = 2 } light_kind;

typedef struct {
    light_kind kind;
    float color[3];
    float intensity;
    float range;             /* 0: infinite */
    float inner_cone, outer_cone;
    uint32_t node;
    double position[3];      /* world space (point, spot) */
    double direction[3];     /* world space, normalized, the way the light shines (-Z of the node) */
} scene_light;

typedef struct {
    char name[64];
    int parent;              /* index or -1 */
    uint32_t mesh;           /* SCENE_NONE if none */
    uint32_t camera, light;  /* SCENE_NONE if none */
    /* local transformation: either TRS (has_matrix = 0) or a matrix */
    int has_matrix;
    affine matrix;
    double translation[3], rotation[4] /* x y z w */, scale[3];
    double *weights;         /* morph weights of the node's mesh instance (NULL: mesh defaults) */
    uint32_t n_weights;
    /* EXT_mesh_gpu_instancing: the node draws its mesh once per row, at node world x row (the
     * rows are in the node's local space); NULL (0 rows): once, at the node's world transform */
    uint32_t n_rows;
    affine *rows;
    affine world;            /* evaluated by scene_evaluate */
} scene_node;

typedef enum { ANIM_TRANSLATION, ANIM_ROTATION, ANIM_SCALE, ANIM_WEIGHTS } anim_path;
typedef enum { INTERP_LINEAR, INTERP_STEP, INTERP_CUBICSPLINE } anim_interp;

typedef struct {
    uint32_t node;
    anim_path path;
    anim_interp interp;
    uint32_t n_keys;
    float *times;            /* n_keys, increasing */
    uint32_t components;     /* per key and element: 3, 4 or n_weights */
    float *values;           /* n_keys * components (x3 for CUBICSPLINE: in-tangent, value, out-tangent) */
} scene_channel;

typedef struct {
    char name[64];
    uint32_t n_channels;
    scene_channel *channels;
    float duration;          /* last key time over all channels */
} scene_animation;

/* A glTF skin: the nodes of its joints and their inverse bind matrices. A vertex influenced by
 * joint j moves with jointMatrix(j) = world(joints[j]) * inverse_bind[j]. */
typedef struct {
    uint32_t n_joints;
    uint32_t *joints;        /* node indices */
    affine *inverse_bind;    /* n_joints (the identity where the file gives none) */
} scene_skin;

typedef struct {
    uint32_t mesh;           /* object */
    uint32_t node;
    affine world;            /* object-to-world */
} scene_instance;

typedef struct {
    uint32_t n_meshes, n_nodes, n_materials, n_textures, n_cameras, n_lights, n_animations, n_skins;
    scene_mesh *meshes;
    scene_node *nodes;
    scene_material *materials;   /* materials[0] is the default material */
    scene_texture *textures;
    scene_camera *cameras;
    scene_light *lights;
    scene_animation *animations;
    scene_skin *skins;
    uint32_t *roots;             /* root nodes of the displayed scene */
    uint32_t n_roots;
    /* evaluated by scene_evaluate */
    uint32_t n_instances;
    scene_instance *instances;
    uint32_t warnings;           /* unsupported features skipped while loading */
    /* the glTF features present in the file that change its appearance and are not implemented
     * (extension names, "normalTexture", "points", ...), each once */
    uint32_t n_ignored;
    char (*ignored)[64];
} scene;

/* The loader decodes no texture larger than this a side (16384^2 RGBA texels are 1 GB); the
 * command line's texture-size limit (docs/limits.md) is at most this. */
#define SCENE_MAX_TEXTURE_SIDE 16384u

/* The loader refuses a file with more instances than this (EXT_mesh_gpu_instancing rows can share
 * one accessor, so a small file could otherwise ask for billions); the command line's instance
 * limit (docs/limits.md) is at most this. */
#define SCENE_MAX_INSTANCES (1u << 26)

/* Loads a .gltf or .glb file and evaluates it at time 0. On failure returns -1 with a one-line
 * message in err (the scene is left empty); a file whose extensionsRequired names an extension
 * the loader does not implement fails with a message naming it, before any data is decoded.
 * Unsupported features are skipped with a one-line warning each on stderr (counted in
 * scene.warnings); those that change the appearance are listed once each in scene.ignored. */
int scene_load_gltf(const char *path, scene *out, char *err, size_t errlen);

/* Writes a scene as glTF 2.0 (.glb or .gltf by extension). Returns 0 or -1 with err. */
int scene_write_gltf(const scene *s, const char *path, char *err, size_t errlen);

/* Applies the animations at time t (seconds; looped by each animation's duration when loop is
 * set), recomputes world transforms, morphed and skinned positions, instances (nodes with a mesh
 * under one of the roots), camera and light placement. Returns 0, or -1 if memory ran out. */
int scene_evaluate(scene *s, double t, int loop);

/* Keeps only the animation named `which` (or with that index; a name wins) and frees the others:
 * scene_evaluate plays every animation at once, and clips of one character (a fox's "Walk" and
 * "Run") drive the same nodes. 0, or -1 if no animation matches (the scene is unchanged). */
int scene_select_animation(scene *s, const char *which);

/* 1 if the mesh's geometry can change from frame to frame (morph targets or a skin). */
int scene_mesh_deforms(const scene_mesh *m);

/* The instances scene_evaluate makes (nodes with a mesh under one of the roots), counted without
 * allocating: the instance limit is checked before (tb/cli/cli_limits.h). */
uint32_t scene_count_instances(const scene *s);

void scene_free(scene *s);

/* The view of a scene without cameras, as model viewers frame one: looking at the centre of the
 * box [lo, hi] from 1.2 diagonals away, from the front (+Z) turned 30 degrees to the right (+X)
 * and raised 25 degrees (+Y up), vertical field of view 45 degrees; so a flat model is never seen
 * edge-on. */
scene_camera scene_default_camera(const double lo[3], const double hi[3]);

/* Adds a ground plane under the evaluated scene (+Y up, as glTF): a polished metal square
 * (base 0.6 grey, metallic 1, roughness 0.2) four times the scene's largest extent wide, just
 * below its lowest point, so that shadows and reflections show. A scene without cameras gets
 * its default view of the scene without the ground. Call scene_evaluate after it.
 * Returns 0 (also for an empty scene, which gets none), -1 if memory ran out. */
int scene_add_ground(scene *s);

/* Texture coordinates (s, t) of vertex v of mesh m for a texture read through TEXCOORD_set with
 * map uv; 0 and (0, 0) if the mesh lacks that set. */
int scene_texcoord(const scene_mesh *m, uint32_t set, const scene_uv_map *uv, uint32_t v, double st[2]);

/* Affine helpers. */
affine affine_identity(void);
affine affine_mul(const affine *a, const affine *b);                 /* a * b */
affine affine_from_trs(const double t[3], const double q[4], const double s[3]);
int affine_invert(const affine *a, affine *inv);                      /* 0 if singular */
void affine_apply_point(const affine *a, const double p[3], double out[3]);
void affine_apply_vector(const affine *a, const double v[3], double out[3]);

#ifdef __cplusplus
}
#endif

#endif
