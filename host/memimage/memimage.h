/*
 * The device memory image: one flat array of 32-bit words that is the hardware's entire view of
 * the world (the prototype's SRAM banks). Layout, word by word: docs/memory-image.md. All device
 * numbers are fp24 bit patterns (hls/fp24); addresses are word indices into the image.
 *
 * The host builds it in two parts. Static regions (materials, textures, object table, geometry
 * of rigid objects) are written once. Per-frame regions (camera, lights, instance table,
 * top-level tree, geometry of deforming objects, morphed or skinned, when it changes) are rewritten by
 * mi_update, which also reports how many bytes a frame uploads.
 */
#ifndef SAARCOR_MEMIMAGE_H
#define SAARCOR_MEMIMAGE_H

#include <stddef.h>
#include <stdint.h>

#include "f24_record.h"
#include "kdtree.h"
#include "scene.h"

#define MI_MAGIC 0x524F4353u /* "SCOR" in little-endian bytes */
#define MI_VERSION 6u
#define MI_NONE 0xFFFFFFFFu
#define MI_DEFAULT_BYTES (24u << 20) /* the prototype's six 4 MB banks */

/* Header words. */
enum {
    MI_H_MAGIC = 0, MI_H_VERSION, MI_H_FORMAT, MI_H_MEMORY_WORDS, MI_H_USED_WORDS, MI_H_FRAME,
    MI_H_OBJECTS, MI_H_INSTANCES, MI_H_MATERIALS, MI_H_TEXTURES, MI_H_LIGHTS, MI_H_TOP_NODES,
    MI_H_SCENE_BOUNDS,                 /* 6 fp24 words: lo xyz, hi xyz (root box of the top level) */
    MI_H_REGION_TABLE = MI_H_SCENE_BOUNDS + 6, /* MI_REGION_COUNT x {offset, length} */
};

/* Regions, in address order. Static regions come first; the geometry of deforming objects and
 * everything rewritten every frame follow, so a frame never moves a static region. */
typedef enum {
    MI_R_HEADER, MI_R_MATERIALS, MI_R_TEXTURES, MI_R_STATIC_GEOMETRY, MI_R_DYNAMIC_GEOMETRY,
    MI_R_OBJECTS, MI_R_CAMERA, MI_R_LIGHTS, MI_R_INSTANCES, MI_R_TOP_NODES, MI_R_TOP_LISTS,
    MI_R_TOP_GRID, /* the grid over the instances (accelerator MI_ACCEL_TOP_GRID; else empty) */
    MI_REGION_COUNT
} mi_region;

#define MI_HEADER_WORDS (MI_H_REGION_TABLE + 2 * MI_REGION_COUNT)

/* Record sizes in words. */
enum {
    MI_NODE_WORDS = 2,      /* kd node: {child<<2 | axis, split} or {count<<2 | 3, first} */
    /* 3x4, rows (m0 m1 m2 c): M^-1 (object -> unit triangle, columns 0..2) and the triangle's vertex
     * C (column 3), a packed record (f24_record.h) that starts at a multiple of its size (one cache
     * line) */
    MI_TRIANGLE_WORDS = F24_TRIANGLE_RECORD_WORDS,
    MI_OBJECT_WORDS = 16,   /* see mi_object word offsets */
    MI_INSTANCE_WORDS = F24_INSTANCE_RECORD_WORDS, /* world-to-object 3x4 (12), object (1), flags (1),
                                                      the translation's low words (3), zeros to whole
                                                      triangle records (f24_record.h) */
    MI_MATERIAL_WORDS = 16,
    MI_TEXTURE_WORDS = 4,   /* width, height, texel address, reserved; texels follow the table */
    MI_CAMERA_WORDS = 16,
    MI_LIGHT_WORDS = 16,
};

/* Instance words after the matrix: the object index, flags, and the low words of the translation
 * (column 3 + low words = -A^-1 c in two words, with A^-1 the stored, rounded 3x3: the transformation
 * unit's wide mode, docs/numerics.md). MI_INST_IDENTITY: the matrix is exactly the identity (1 and
 * +0), so the device passes the rays through without a transformation (hls/units/trace.c); set for
 * the objects mi_merge.h bakes into world space. */
enum { MI_I_OBJECT = 12, MI_I_FLAGS = 13, MI_I_T_LO = 14 };
#define MI_INST_IDENTITY 1u

/* Camera word 3: the scene profile's skip bits (PROFILE_* in hls/units/trace.h, mi_profile.h). */
#define MI_CAM_PROFILE 3

/* Object descriptor words. */
enum {
    MI_O_NODES = 0, MI_O_LISTS, MI_O_TRIANGLES, MI_O_SHADING, MI_O_N_NODES, MI_O_N_LIST,
    MI_O_N_TRIANGLES, MI_O_FLAGS, MI_O_BOUNDS /* 6 fp24 words */, MI_O_GRID = 14 /* grid or MI_NONE */
};

/* Accelerators beside the kd-trees (header format word bits 16..; docs/memory-image.md and
 * docs/traversal.md): ropes (a record before each leaf's list entries, both levels), a uniform
 * grid per object (MI_O_GRID), a grid over the instances (region MI_R_TOP_GRID). */
enum { MI_ACCEL_ROPES = 1, MI_ACCEL_GRID = 2, MI_ACCEL_TOP_GRID = 4, MI_ACCEL_ALL = 7 };
/* Header word 2 bit 16 + 3: the kd-trees are compact (mi_compact_trees); the device walks them
 * with the stack whatever it is asked for, but the grids. */
#define MI_TREES_COMPACT 8u
#define MI_ACCEL_SHIFT 16
#define MI_ROPE_WORDS 12 /* leaf box lo xyz hi xyz (fp24), ropes -x +x -y +y -z +z (node or MI_NONE) */
/* Grid header: lo xyz, cell size xyz, 1 / size xyz (fp24), cells per axis xyz, cell table
 * address (2 words per cell, x fastest: first entry, count), list address, list length. */
enum { MI_G_LO = 0, MI_G_SIZE = 3, MI_G_INV = 6, MI_G_N = 9, MI_G_CELLS = 12, MI_G_LISTS = 13, MI_G_N_LIST = 14,
       MI_GRID_WORDS = 15 };
#define MI_OBJECT_HAS_NORMALS 1u
#define MI_OBJECT_HAS_TEXCOORDS 2u
#define MI_OBJECT_DYNAMIC 4u

/* Node word 0: a leaf count << 2 | 3; an inner node child << 4 | empty << 2 | axis, where empty
 * bit 0 (1) says the side below the split is an empty leaf that is not stored, bit 1 (2) the
 * side above it; child is the first stored child (the one above at child + 1 if both are). */
#define MI_NODE_LEAF 3u
#define MI_NODE_CHILD_SHIFT 4
#define MI_NODE_EMPTY_LO 1u
#define MI_NODE_EMPTY_HI 2u
static inline uint32_t mi_node_leaf(uint32_t count) { return count << 2 | MI_NODE_LEAF; }
static inline uint32_t mi_node_inner(uint32_t axis, uint32_t child, uint32_t empty)
{
    return child << MI_NODE_CHILD_SHIFT | empty << 2 | axis;
}

typedef struct {
    uint64_t memory_bytes;     /* size of the device memory (default MI_DEFAULT_BYTES) */
    uint32_t width, height;    /* image size the camera block is set up for (default 512 x 384) */
    uint32_t camera;           /* scene camera to use; SCENE_NONE or out of range: a default view */
    int explicit_view;         /* 1: ignore the scene's cameras, look from eye at `at` */
    double eye[3], at[3], up[3], fov_degrees; /* vertical field of view */
    kd_params bottom, top;     /* tree parameters; top uses binned SAH */
    double max_condition;      /* triangles whose matrix condition number exceeds this are dropped */
    uint32_t skip;             /* PROFILE_* bits the device may use where the scene profile allows
                                  them (default all; 0: the general pipeline, render --general) */
    uint32_t accel;            /* MI_ACCEL_* structures to build beside the kd-trees (default 0) */
    uint32_t traversal;        /* TRAV_* the image is walked with (default TRAV_STACK): mi_compact_trees */
    int merge;                 /* 1: bake static geometry into world-space objects (mi_merge.h;
                                  default 0; --merge: 1) */
    uint64_t max_nodes;        /* kd-tree nodes of both levels together at most (0, the default: no
                                  limit; --limit kd-nodes): counted as the trees grow, before their
                                  nodes are allocated */
} mi_params;

void mi_params_default(mi_params *p);

/* The MI_ACCEL_* structures traversal algorithm TRAV_* (hls/units/trace.h) walks. */
uint32_t mi_accel_for(uint32_t traversal);

/* 1 if traversal algorithm TRAV_* walks compact trees: flat cells on node faces (kdtree.c
 * consider_face) and no stored empty leaves (their parent marks the side empty). The walkers
 * that restart or follow ropes need every cell explicit: they measure a ray's progress by the
 * cells it left, and would skip a flat cell lying exactly where the last one ended. */
int mi_compact_trees(uint32_t traversal);

typedef struct {
    uint32_t objects, instances, triangles, degenerate_triangles;
    uint32_t bottom_nodes, bottom_leaves, bottom_empty_leaves, bottom_depth;
    uint64_t bottom_references;
    double bottom_sah;         /* sum over objects of SAH cost x triangles (a size-weighted figure) */
    uint32_t top_nodes, top_leaves, top_empty_leaves, top_depth;
    uint64_t top_references;
    double top_sah;
    double bottom_build_seconds, top_build_seconds, transform_seconds; /* of the last build/update */
    uint32_t region_words[MI_REGION_COUNT];
    uint64_t frame_upload_bytes;  /* bytes rewritten by the last mi_build/mi_update */
    uint32_t rebuilt_objects;     /* deforming objects (morphed, skinned) rebuilt by the last update */
    uint64_t frame_geometry_bytes; /* of which DYNAMIC_GEOMETRY and the object table (0: no object changed) */
    /* static geometry baked into world space (mi_merge.h): merged objects, the scene instances
     * baked into them, the triangles baked copies of instanced meshes add, and the instances
     * kept, by reason */
    uint32_t merged_objects, merged_instances, kept_animated, kept_morphing, kept_mirrored, kept_turned, kept_instanced;
    uint64_t merged_copy_triangles;
} mi_stats;

/* Host-side state kept across frames: bottom-level trees, dropped triangles, the image. */
typedef struct mi_builder mi_builder;

/* Builds the complete image for the scene as evaluated now. Returns NULL with a one-line
 * message in err (e.g. the scene does not fit, naming the region and the sizes). */
mi_builder *mi_build(const scene *s, const mi_params *p, char *err, size_t errlen);

/* Why a build or an update failed: mi_build_why's *why, mi_update's return value. */
typedef enum { MI_FAIL_OTHER = -1, MI_FAIL_NODE_LIMIT = -2 } mi_failure;

/* mi_build, and on failure *why. */
mi_builder *mi_build_why(const scene *s, const mi_params *p, mi_failure *why, char *err, size_t errlen);

/* After scene_evaluate for a new time: rebuilds the per-frame regions (and the geometry of
 * deforming objects whose mesh revision changed). 0, or an mi_failure with err. */
int mi_update(mi_builder *b, const scene *s, char *err, size_t errlen);

const uint32_t *mi_words(const mi_builder *b, uint32_t *n_words);
const mi_stats *mi_get_stats(const mi_builder *b);

/* Host-side provenance of a device hit (for AOVs and hit comparisons): the scene instance and
 * the triangle of its mesh (primitives concatenated in file order) that image triangle
 * image_triangle of image instance image_instance came from (degenerate triangles are not in the
 * image; a merged object's triangles come from several scene instances). Both MI_NONE if out of
 * range. */
void mi_hit_source(const mi_builder *b, uint32_t image_instance, uint32_t image_triangle, uint32_t *scene_inst,
                   uint32_t *mesh_triangle);
void mi_free(mi_builder *b);

/* The camera of the image in double precision, before rounding to fp24 (the camera block). */
typedef struct {
    int orthographic;
    uint32_t width, height;
    double o[3], u[3], v[3], w[3];
} mi_camera;
void mi_camera_frame(const mi_builder *b, const scene *s, mi_camera *out);

/* The light the image holds for a scene without lights (docs/shading.md). */
void mi_default_light(const mi_builder *b, const scene *s, scene_light *out);

const char *mi_region_name(mi_region r);

/* Checks an image before the device model uses it: header, region bounds, every index and
 * count, tree shape (children after parents, so no cycles), finite fp24 where required.
 * Returns 0 if valid, else -1 with a one-line description of the first problem. */
int mi_validate(const uint32_t *words, uint32_t n_words, char *err, size_t errlen);

/* Triangle transformation of paper section 2.1: the affine map taking a, b, c to (1,0,0),
 * (0,1,0), (0,0,0) and the unit normal to (0,0,1). Returns 0 (and leaves t untouched) when the
 * triangle is degenerate: zero or non-finite area, or condition number of [a-c, b-c, n] above
 * max_condition. */
int mi_triangle_transform(const double a[3], const double b[3], const double c[3], double max_condition,
                          affine *t);

/* The hash table of mi_shared_edges, kept between calls (zero-initialized; mi_edge_table_free). */
typedef struct {
    uint64_t *slot;
    size_t size;
} mi_edge_table;

void mi_edge_table_free(mi_edge_table *t);

/* The shared-edge flags (TRI_SHARED_* of hls/units/vec3.h) of the n triangles tri[] of mesh m:
 * edge k of a triangle is flagged when another of them joins the same two vertex positions and
 * is not its coincident copy. Its hash table is t's (grown if too small: a caller with several
 * meshes gives the largest first), or with t NULL one of its own. Returns 0, or -1 out of memory. */
int mi_shared_edges(const scene_mesh *m, const uint32_t *tri, uint32_t n, uint8_t *flags, mi_edge_table *t);

#endif
