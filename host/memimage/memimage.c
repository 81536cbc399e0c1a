/*
 * Memory-image builder (layout: docs/memory-image.md). Prepares every object once (triangle
 * transformations, bottom-level kd-tree over the non-degenerate triangles), then writes the
 * regions; mi_update rewrites only the per-frame regions and the geometry of deforming objects
 * (morph targets, skins) whose geometry changed. All device numbers are rounded from double to fp24 here, bounds
 * outward so that they stay conservative.
 */
#define _GNU_SOURCE /* clock_gettime, M_PI */
#include "memimage.h"
#include "mi_merge.h"
#include "mi_profile.h"
#include "trace.h"
#include "shade_encode.h"
#include "shading_model.h"
#include "ugrid.h"
#include "huge_pages.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "f24.h"
#include "f24_double.h"

typedef struct {
    uint32_t mesh;      /* scene mesh, or with merged set the merged mesh (mi_merge) */
    int merged;
    int dynamic;
    kd_tree tree;       /* leaf entries index valid[] = the object's triangles in the image */
    uint32_t *valid;    /* mesh triangle of each image triangle */
    uint32_t *records;  /* triangle records of the image triangles, MI_TRIANGLE_WORDS each, without
                           their shared-edge flags: the transformations packed when they are made
                           (40 bytes a triangle at e7m16, where the binary64 matrices took 96, all
                           fresh pages the kernel zeroes: the gallery's 48 -> 20 MB) */
    uint8_t *shared;    /* their shared-edge flags (mi_shared_edges) */
    uint32_t n_valid;
    uint32_t revision_seen; /* the mesh's revision the geometry was built from (dynamic objects) */
    kd_rope *ropes;     /* per node (leaves only), with MI_ACCEL_ROPES */
    uint32_t *slot, n_slots; /* image slot of each tree node (tree_slots), nodes stored */
    uint32_t shade_flags;    /* the descriptor's flags word but MI_OBJECT_DYNAMIC (object_shading_flags) */
    ugrid grid;         /* with MI_ACCEL_GRID */
    uint32_t base, words; /* geometry block in the image */
    double centre[3];   /* the object's space is the mesh's moved by -centre (choose_centres) */
    uint64_t *normal_codes; /* its mesh's normal_codes, made beside the trees (edges_run) and freed by
                               object_write; NULL: object_write makes them */
} mi_object;

struct mi_builder {
    mi_params p;
    uint32_t *words, n_words;
    uint32_t n_objects;
    mi_object *obj;
    uint32_t n_textures;       /* textures stored (scene textures used as base colour or emission) */
    uint32_t *texture_map;     /* scene texture -> image texture or MI_NONE */
    uint32_t *inst_scene;      /* per image instance: scene instance index (MI_NONE: a merged object) */
    uint32_t *inst_obj;        /* per image instance: image object */
    uint32_t n_inst;
    mi_merge merge;            /* static geometry baked into world space */
    uint32_t *mesh_obj;        /* per scene mesh: its image object, MI_NONE if not stored */
    uint32_t frame;
    kd_tree top;
    kd_rope *top_ropes;        /* with MI_ACCEL_ROPES */
    uint32_t *top_slot, n_top_slots; /* image slots of the top-level nodes (tree_slots) */
    ugrid top_grid;            /* with MI_ACCEL_TOP_GRID */
    mi_stats st;
};

static const char *region_names[MI_REGION_COUNT] = {
    "HEADER", "MATERIALS", "TEXTURES", "STATIC_GEOMETRY", "DYNAMIC_GEOMETRY", "OBJECTS",
    "CAMERA", "LIGHTS", "INSTANCES", "TOP_NODES", "TOP_LISTS", "TOP_GRID",
};

const char *mi_region_name(mi_region r) { return r < MI_REGION_COUNT ? region_names[r] : "?"; }

/* x rounded to the nearest fp24 value, as a binary64 value: f24_fast_decode(f24_fast_encode(x))
 * without the trip through the bits (the kd-tree builder snaps every candidate plane with it) */
static double quantize(double x) { return f24_fast_round(x); }

/* ---- loops over triangles and vertices on all CPUs ------------------------------------------ */

/* A range of a loop for one thread of for_parts. */
typedef struct {
    void (*fn)(void *ctx, uint32_t from, uint32_t to);
    void *ctx;
    uint32_t from, to;
} loop_part;

static void *run_part(void *arg)
{
    const loop_part *p = arg;
    p->fn(p->ctx, p->from, p->to);
    return NULL;
}

/* fn(ctx, from, to) over [0, n) in consecutive ranges of at least PART_MIN items, one per CPU of
 * the tree builder's budget (kd_thread_count); a range whose thread cannot start runs on this one.
 * fn writes only what belongs to its range, so the result does not depend on the split. */
enum { PART_MIN = 4096, PART_MAX = 8 };
static void for_parts(uint32_t n, void (*fn)(void *ctx, uint32_t from, uint32_t to), void *ctx)
{
    uint32_t k = kd_thread_count();
    k = k < PART_MAX ? k : PART_MAX;
    k = k < n / PART_MIN ? k : n / PART_MIN;
    k = k ? k : 1;
    loop_part p[PART_MAX];
    pthread_t tid[PART_MAX];
    int started[PART_MAX] = { 0 };
    for (uint32_t i = 0; i < k; i++)
        p[i] = (loop_part){ fn, ctx, (uint32_t)((uint64_t)n * i / k), (uint32_t)((uint64_t)n * (i + 1) / k) };
    for (uint32_t i = 1; i < k; i++)
        started[i] = pthread_create(&tid[i], NULL, run_part, &p[i]) == 0;
    run_part(&p[0]);
    for (uint32_t i = 1; i < k; i++) {
        if (started[i])
            pthread_join(tid[i], NULL);
        else
            run_part(&p[i]);
    }
}

void mi_params_default(mi_params *p)
{
    memset(p, 0, sizeof *p);
    p->memory_bytes = MI_DEFAULT_BYTES;
    p->width = 512;
    p->height = 384;
    p->camera = 0;
    kd_params_default(&p->bottom);
    kd_params_default(&p->top);
    p->top.bins = 32;
    /* the top level's "intersection" is an instance entry: the packet's transformation (up to 8
     * slots), a clip and a list entry, against one traversal step per node: C_i 3 measured best
     * (cycles per primary ray at the paper's set-up, render --top-ci 1.5 / 3 / 6: room 10.6 /
     * 10.4 / 10.6, terrain 27.1 / 24.9 / 24.1, plants 51.5 / 49.8 / 49.3; DynRTC bytes per ray
     * on terrain 194 / 168 / 160; before the instance records were put on cache lines) */
    p->top.cost_intersection = 3.0;
    p->bottom.quantize = quantize;
    /* large meshes (from shallow_from triangles, the bunny and the gallery's statues) binned: the
     * nodes over exact_max triangles into a bin per 16 of them, 32 to 256 per axis, the exact event
     * sweep with perfect splits and flat face cells below, one level deeper (kd_params.max_depth).
     * Against the exact sweep throughout: the gallery's trees about 18% faster to build, fewer
     * nodes (bunny.glb 170k -> 156k), fewer cycles per frame (bunny -2.8%, gallery -1.1%, terrain
     * -5.3%, with 128 bins everywhere) at a lower SAH cost; against 128 bins in every node, 9%
     * fewer instructions for the bunny's tree at 1.2% more SAH cost (docs/memory-image.md).
     * Smaller meshes keep the exact sweep throughout: their builds take milliseconds, and binning
     * their upper nodes loses the face cells of walls and floors (the room: +4.9% cycles with 128
     * bins over 48). --kd-bins N bins every object's tree, with at most N bins per axis. */
    p->bottom.bins = 256;
    p->bottom.bin_size = 16;
    p->bottom.bins_from = 1u << 15;
    p->bottom.exact_max = 48;
    /* large meshes at most log2(N) + 5 deep (+ 6 binned): below that the SAH's levels hold most of the nodes
     * but save neither cycles nor traffic in this hardware (the bunny: 29 levels, 146 bytes per
     * triangle, 6.2 cycles per ray; 22 levels, 87 bytes, 5.9 cycles); smaller meshes keep
     * pbrt's depth (the plants' foliage meshes are faster with it; docs/memory-image.md) */
    p->bottom.shallow_from = 1u << 15;
    p->top.quantize = quantize;
    p->max_condition = 16777216.0; /* 2^24 */
    p->skip = PROFILE_ALL;
    p->merge = 0; /* measured: per-object trees with flat face cells beat the merged tree (mi_merge.h) */
}

uint32_t mi_accel_for(uint32_t traversal)
{
    return traversal == TRAV_ROPES ? MI_ACCEL_ROPES
         : traversal == TRAV_GRID  ? MI_ACCEL_GRID
         : traversal == TRAV_GRID2 ? MI_ACCEL_GRID | MI_ACCEL_TOP_GRID
                                   : 0u;
}

int mi_compact_trees(uint32_t traversal)
{
    return traversal == TRAV_STACK || traversal == TRAV_GRID || traversal == TRAV_GRID2;
}

/* The image's trees are compact: for the walkers that can walk them, and without ropes (whose
 * records name every leaf). */
static int trees_compact(const mi_params *p) { return mi_compact_trees(p->traversal) && !(p->accel & MI_ACCEL_ROPES); }

/* Image slots of a tree's nodes: in a compact tree empty leaves (but the root) are not stored
 * (MI_NONE), the others keep their order, so children still follow their parents. Returns the
 * number stored, with *slot allocated; 0 if memory ran out. */
static uint32_t tree_slots(const kd_tree *t, int compact, uint32_t **slot)
{
    *slot = malloc(((size_t)t->n_nodes + 1) * sizeof **slot);
    if (!*slot)
        return 0;
    uint32_t n = 0;
    for (uint32_t i = 0; i < t->n_nodes; i++) {
        const int empty_leaf = t->nodes[i].axis == KD_LEAF && t->nodes[i].count == 0;
        (*slot)[i] = compact && i && empty_leaf ? MI_NONE : n++;
    }
    return n;
}

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- fp24 words --------------------------------------------------------------------------- */

static uint32_t fp24_word(double x) { return f24_fast_encode(x); }

/* fp24 value <= x (dir < 0) or >= x (dir > 0): conservative bounds. */
static uint32_t f24_outward(double x, int dir)
{
    uint32_t v = f24_fast_encode(x);
    const double d = f24_fast_decode(v);
    if ((dir < 0 && d > x) || (dir > 0 && d < x)) {
        const int toward_larger_magnitude = (d < 0) == (dir < 0);
        if (f24_is_zero(v))
            v = dir < 0 ? (F24_SIGN_BIT | F24_MIN_NORMAL) : F24_MIN_NORMAL;
        else if (toward_larger_magnitude)
            v += 1u; /* next fp24 away from zero (may reach Inf: still conservative) */
        else
            v = f24_exp(v) == 1 && f24_frac(v) == 0 ? (v & F24_SIGN_BIT) : v - 1u;
    }
    return v;
}

static void put_affine(uint32_t *w, const affine *a)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            w[i * 4 + j] = fp24_word(a->m[i][j]);
}

/* Object bounds margin in ulps of the box's largest coordinate: the unit-triangle test accepts rays
 * a few ulps outside a triangle's edge (its own rounding), so an exact slab test of the object's
 * bounds would reject a ray grazing an edge on the box's face that the triangle test accepts
 * (stress case split-planes, docs/stress.md). The scene bounds stay exact: the RGS derives its
 * epsilon from them, and world-space rays meet the top-level boxes before any rounding. */
#define OBJECT_BOUNDS_MARGIN_ULPS 8

/* Bounds of an empty tree are not meaningful: an empty box at the origin is written instead. */
static void put_bounds(uint32_t *w, const aabb *b, int margin_ulps)
{
    int ok = 1;
    for (int k = 0; k < 3; k++)
        ok = ok && isfinite(b->lo[k]) && isfinite(b->hi[k]) && b->lo[k] <= b->hi[k];
    if (!ok) {
        for (int k = 0; k < 6; k++)
            w[k] = 0;
        return;
    }
    double big = 0;
    for (int k = 0; k < 3; k++)
        big = fmax(big, fmax(fabs(b->lo[k]), fabs(b->hi[k])));
    const double margin = ldexp(big, -F24_MAN_BITS) * margin_ulps;
    for (int k = 0; k < 3; k++) {
        w[k] = f24_outward(b->lo[k] - margin, -1);
        w[3 + k] = f24_outward(b->hi[k] + margin, +1);
    }
}

static int affine_fits_f24(const affine *a)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            if (!isfinite(a->m[i][j]) || f24_is_inf(fp24_word(a->m[i][j])))
                return 0;
    return 1;
}

/* ---- objects ------------------------------------------------------------------------------ */

typedef struct {
    const scene_mesh *m;
    const uint32_t *valid;
    const double *centre;
} tri_source;

/* Vertex k of mesh triangle tri in the space of an object centred at centre. */
static void tri_vertex(const scene_mesh *m, const double centre[3], uint32_t tri, int k, double out[3])
{
    const float *p = &m->positions[3 * (size_t)m->indices[3 * (size_t)tri + (size_t)k]];
    for (int i = 0; i < 3; i++)
        out[i] = p[i] - centre[i];
}

static aabb tri_bounds(const void *user, uint32_t i)
{
    const tri_source *s = user;
    aabb b;
    for (int k = 0; k < 3; k++) {
        double v[3];
        tri_vertex(s->m, s->centre, s->valid[i], k, v);
        for (int a = 0; a < 3; a++) { /* fmin/fmax of finite values, the first on ties (-0, +0), inline */
            b.lo[a] = k && !(v[a] < b.lo[a]) ? b.lo[a] : v[a];
            b.hi[a] = k && !(v[a] > b.hi[a]) ? b.hi[a] : v[a];
        }
    }
    return b;
}

static int tri_clip(const void *user, uint32_t i, const aabb *box, aabb *out)
{
    const tri_source *s = user;
    double a[3], b[3], c[3];
    tri_vertex(s->m, s->centre, s->valid[i], 0, a);
    tri_vertex(s->m, s->centre, s->valid[i], 1, b);
    tri_vertex(s->m, s->centre, s->valid[i], 2, c);
    return kd_clip_triangle(a, b, c, box, out);
}

static int tri_clip_split(const void *user, uint32_t i, const aabb *box, uint32_t axis, double pos, aabb out[2])
{
    const tri_source *s = user;
    double a[3], b[3], c[3];
    tri_vertex(s->m, s->centre, s->valid[i], 0, a);
    tri_vertex(s->m, s->centre, s->valid[i], 1, b);
    tri_vertex(s->m, s->centre, s->valid[i], 2, c);
    return kd_clip_triangle_split(a, b, c, box, axis, pos, out);
}

static void object_release(mi_object *o)
{
    kd_free(&o->tree);
    free(o->ropes);
    free(o->slot);
    o->ropes = NULL;
    o->slot = NULL;
    ugrid_free(&o->grid);
    free(o->valid);
    free(o->records);
    free(o->shared);
    free(o->normal_codes);
    o->valid = NULL;
    o->records = NULL;
    o->shared = NULL;
    o->normal_codes = NULL;
    o->n_valid = 0;
}

/* The geometry of an object: a scene mesh, or a merged world-space mesh. */
static const scene_mesh *obj_mesh(const mi_builder *b, const scene *s, const mi_object *o)
{
    return o->merged ? &b->merge.meshes[o->mesh] : &s->meshes[o->mesh];
}

/* ---- accelerators beside the kd-trees: ropes and uniform grids (docs/traversal.md) -------- */

/* The box the device clips a tree's rays to, as the doubles its fp24 words hold. */
static aabb device_box(const aabb *b, int margin_ulps)
{
    uint32_t w[6];
    put_bounds(w, b, margin_ulps);
    aabb r;
    for (int k = 0; k < 3; k++) {
        r.lo[k] = f24_fast_decode(w[k]);
        r.hi[k] = f24_fast_decode(w[3 + k]);
    }
    return r;
}

/* Cell sizes rounded up to fp24. */
static double quantize_up(double x) { return f24_fast_decode(f24_outward(x, +1)); }

/* Ropes of tree t (NULL if not asked for or out of memory: *fail set). */
static kd_rope *build_ropes(const mi_builder *b, const kd_tree *t, const aabb *root, int *fail)
{
    if (!(b->p.accel & MI_ACCEL_ROPES))
        return NULL;
    kd_rope *r = calloc((size_t)t->n_nodes + 1, sizeof *r);
    if (!r)
        *fail = 1;
    else
        kd_ropes(t, root, r);
    return r;
}

/* A grid over box: cells widened by 8 ulps of the largest coordinate, as the device's rounded
 * cell planes may move by a few ulps. */
static int build_grid(const kd_source *src, const aabb *box, ugrid *g)
{
    const ugrid_params gp = { 2.0, ldexp(1.0, 3 - F24_MAN_BITS), quantize_up };
    return ugrid_build(src, box, &gp, g);
}

static uint32_t grid_words(const ugrid *g) { return g->n[0] ? MI_GRID_WORDS + 2 * ugrid_cells(g) + g->n_prims : 0; }

static void put_grid(uint32_t *w, const ugrid *g, uint32_t addr)
{
    const uint32_t cells = ugrid_cells(g);
    for (int k = 0; k < 3; k++) {
        w[MI_G_LO + k] = fp24_word(g->lo[k]);
        w[MI_G_SIZE + k] = fp24_word(g->size[k]);
        w[MI_G_INV + k] = fp24_word(1.0 / g->size[k]);
        w[MI_G_N + k] = g->n[k];
    }
    w[MI_G_CELLS] = addr + MI_GRID_WORDS;
    w[MI_G_LISTS] = addr + MI_GRID_WORDS + 2 * cells;
    w[MI_G_N_LIST] = g->n_prims;
    for (uint32_t c = 0; c < cells; c++) {
        w[MI_GRID_WORDS + 2 * c] = g->first[c];
        w[MI_GRID_WORDS + 2 * c + 1] = g->count[c];
    }
    memcpy(w + MI_GRID_WORDS + 2 * cells, g->prims, g->n_prims * sizeof *w);
}

static uint32_t leaf_count(const kd_tree *t)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < t->n_nodes; i++)
        n += t->nodes[i].axis == KD_LEAF;
    return n;
}

/* Words of a tree's leaf lists in the image: with ropes, a record before every leaf's entries. */
static uint32_t list_words(const kd_tree *t, const kd_rope *ropes)
{
    return t->n_prims + (ropes ? MI_ROPE_WORDS * leaf_count(t) : 0u);
}

/* Shading record flags of a mesh (the object descriptor's flags 1, 2 and 16). */
static uint32_t shading_flags(const scene_mesh *m)
{
    return (m->normals ? MI_OBJECT_HAS_NORMALS : 0u) |
           (m->texcoords || m->texcoords1 ? MI_OBJECT_HAS_TEXCOORDS : 0u) | (m->colours ? SHADE_HAS_COLOURS : 0u);
}

/* The texture mapping (TEXCOORD_n and KHR_texture_transform) of coordinate set uv of a record
 * of a triangle with material mat: set 0 serves the base colour texture, or the emissive one if
 * the material has no base colour texture; set 1 the emissive texture. */
static void record_mapping(const scene *s, const scene_material *mat, uint32_t uv, uint32_t *set,
                           const scene_uv_map **map)
{
    const int emissive = uv == 1 || mat->base_color_texture >= s->n_textures;
    *set = emissive ? mat->emissive_texcoord : mat->texcoord_set;
    *map = emissive ? &mat->emissive_uv : &mat->base_uv;
}

static int same_uv_map(const scene_uv_map *a, const scene_uv_map *b)
{
    if (!a->set || !b->set)
        return a->set == b->set;
    return a->offset[0] == b->offset[0] && a->offset[1] == b->offset[1] && a->rotation == b->rotation &&
           a->scale[0] == b->scale[0] && a->scale[1] == b->scale[1];
}

/* The material samples its two textures through different coordinates: its records need set 1. */
static int needs_emissive_uv(const scene *s, const scene_material *mat)
{
    uint32_t set[2];
    const scene_uv_map *map[2];
    for (uint32_t uv = 0; uv < 2; uv++)
        record_mapping(s, mat, uv, &set[uv], &map[uv]);
    return mat->base_color_texture < s->n_textures && mat->emissive_texture < s->n_textures &&
           (set[0] != set[1] || !same_uv_map(map[0], map[1]));
}

/* The object's shading flags: those of its mesh, the emissive coordinates if a material needs
 * them, and the one material of all its triangles if they share it (then their records carry
 * none: hls/units/shade_rec.h). */
static uint32_t object_shading_flags(const scene *s, const scene_mesh *m, const mi_object *o)
{
    uint32_t same = o->n_valid > 0, flags = shading_flags(m);
    for (uint32_t i = 1; same && i < o->n_valid; i++)
        same = m->material[o->valid[i]] == m->material[o->valid[0]];
    for (uint32_t i = 0; (flags & MI_OBJECT_HAS_TEXCOORDS) && i < o->n_valid; i++)
        if (needs_emissive_uv(s, &s->materials[m->material[o->valid[i]]]))
            flags |= SHADE_HAS_EMISSIVE_UV;
    return flags | (same ? SHADE_ONE_MATERIAL | m->material[o->valid[0]] << SHADE_OBJ_MATERIAL_SHIFT : 0u);
}

/* The record field of C - hi for a vertex component C with high word hi: the multiple k of
 * 2^-8 ulp(hi) nearest to it (f24_vertex_lo decodes; exact for a binary32 vertex). */
static uint32_t vertex_lo_field(double c, f24_t hi)
{
    if (f24_exp(hi) == 0 || f24_exp(hi) == F24_EXP_MAX)
        return 0;
    const double unit = ldexp(1.0, (int)f24_exp(hi) - F24_BIAS - F24_MAN_BITS - F24_VERTEX_LO_SHIFT);
    const double k = fmin(fmax(nearbyint((c - f24_fast_decode(hi)) / unit), -256), 255);
    return (uint32_t)(int32_t)k;
}

/* The triangle record of a: M^-1 rounded, the vertex C (column 3) in a high word and the low
 * part's field; its shared-edge flags zero (records_part adds them). */
static void put_triangle(uint32_t *w, const affine *a)
{
    f24_t v[F24_TRIANGLE_VALUES];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            v[i * 4 + j] = fp24_word(a->m[i][j]);
    memset(w, 0, MI_TRIANGLE_WORDS * sizeof *w);
    f24_record_put(w, v, F24_TRIANGLE_VALUES);
    for (int i = 0; i < 3; i++)
        f24_record_put_field(w, F24_TRIANGLE_VALUES * F24_WIDTH + (uint32_t)i * F24_VERTEX_LO_BITS, F24_VERTEX_LO_BITS,
                             vertex_lo_field(a->m[i][3], v[i * 4 + 3]));
}

typedef struct {
    const scene_mesh *m;
    mi_object *o;
    double max_condition;
    uint8_t *ok; /* per mesh triangle: its transformation is kept */
} transform_job;

/* The transformations of mesh triangles [from, to), each as its record at its own index of
 * o->records. */
static void transform_part(void *ctx, uint32_t from, uint32_t to)
{
    const transform_job *j = ctx;
    for (uint32_t t = from; t < to; t++) {
        double a[3], bb[3], c[3];
        affine xf;
        tri_vertex(j->m, j->o->centre, t, 0, a);
        tri_vertex(j->m, j->o->centre, t, 1, bb);
        tri_vertex(j->m, j->o->centre, t, 2, c);
        j->ok[t] = mi_triangle_transform(a, bb, c, j->max_condition, &xf) && affine_fits_f24(&xf);
        if (j->ok[t])
            put_triangle(j->o->records + (size_t)MI_TRIANGLE_WORDS * t, &xf);
    }
}

/* Tree parameters q with the node budget left for tree `own` (p.max_nodes less the nodes of
 * every other tree of the image; none of own's): 0, or MI_FAIL_NODE_LIMIT if none is left. */
static int tree_budget(const mi_builder *b, const kd_tree *own, const kd_params *p, kd_params *q)
{
    *q = *p;
    if (!b->p.max_nodes)
        return 0;
    uint64_t used = own == &b->top ? 0 : b->top.n_nodes;
    for (uint32_t i = 0; i < b->n_objects; i++)
        used += &b->obj[i].tree == own ? 0 : b->obj[i].tree.n_nodes;
    q->max_nodes = used < b->p.max_nodes ? b->p.max_nodes - used : 0;
    return q->max_nodes ? 0 : MI_FAIL_NODE_LIMIT;
}

/* kd_build of tree `own` within the image's node budget: 0, or an mi_failure. */
static int build_tree(const mi_builder *b, const kd_source *src, const kd_params *p, kd_tree *own)
{
    kd_params q;
    const int rc = tree_budget(b, own, p, &q);
    if (rc != 0)
        return rc;
    const int kd = kd_build(src, &q, own);
    return kd == 0 ? 0 : kd == KD_TOO_MANY_NODES ? MI_FAIL_NODE_LIMIT : MI_FAIL_OTHER;
}

/* The bottom-level build of a list of objects (mi_build: all of them; mi_update: the deforming
 * ones whose mesh changed) runs in three stages, so that the image is the same bits for any number
 * of threads: (1) one object at a time, the triangle transformations (each object's triangles on
 * all CPUs); (2) the objects' shared edges, kd-trees, ropes and grids, several objects at once,
 * each into its own buffers and touching nothing else; (3) in object order, the node budget and
 * the objects' sizes in the image. The trees do not depend on the order or the threads (kd_build
 * is deterministic, and a node limit only ever stops a build), and stage 3 decides the node limit
 * as the object-by-object build did, so results and errors are those of a serial build. */

/* Stage 1: the triangle transformations of o (its old geometry released): 0, or -1 (memory). */
static int object_transform(mi_builder *b, const scene_mesh *m, mi_object *o)
{
    object_release(o);
    o->valid = malloc(((size_t)m->n_triangles + 1) * sizeof *o->valid);
    o->records = huge_pages_malloc(((size_t)m->n_triangles + 1) * MI_TRIANGLE_WORDS * sizeof *o->records);
    o->shared = malloc((size_t)m->n_triangles + 1);
    uint8_t *ok = malloc((size_t)m->n_triangles + 1);
    if (!o->valid || !o->records || !o->shared || !ok) {
        free(ok);
        return -1;
    }
    transform_job job = { m, o, b->p.max_condition, ok };
    for_parts(m->n_triangles, transform_part, &job);
    for (uint32_t t = 0; t < m->n_triangles; t++) /* the kept ones, in order */
        if (ok[t]) {
            if (o->n_valid != t) /* in place until the first dropped one: mostly all of them */
                memcpy(o->records + (size_t)MI_TRIANGLE_WORDS * o->n_valid, o->records + (size_t)MI_TRIANGLE_WORDS * t,
                       MI_TRIANGLE_WORDS * sizeof *o->records);
            o->valid[o->n_valid++] = t;
        }
    free(ok);
    b->st.degenerate_triangles += m->n_triangles - o->n_valid;
    return 0;
}

typedef struct {
    const scene_mesh *m;
    mi_object *o;
    int rc; /* mi_shared_edges' */
} edges_job;

/* The shared edges of jobs j[0..n). */
typedef struct {
    edges_job *j;
    uint32_t n;
} edges_list;

static uint64_t *normal_codes(const scene_mesh *m, int parallel);

/* The shared edges and normal codes of each job's object: the writing of the image needs the
 * codes, and making them here, beside the trees, takes them off the writing's wall time (the
 * gallery: 0.57 G instructions, as much as the records). Without memory for the codes, they
 * are made at writing. */
static void *edges_run(void *arg)
{
    const edges_list *l = arg;
    mi_edge_table table = { 0 }; /* one for the list (trees_build's: largest first) */
    for (uint32_t k = 0; k < l->n; k++) {
        edges_job *j = &l->j[k];
        j->rc = mi_shared_edges(j->m, j->o->valid, j->o->n_valid, j->o->shared, &table);
        if (j->m->normals && !j->o->normal_codes)
            j->o->normal_codes = normal_codes(j->m, 0);
    }
    mi_edge_table_free(&table);
    return NULL;
}

/* Runs the edges of l on a thread of its own, if one can be started (0), else here (-1). */
static int edges_beside(edges_list *l, pthread_t *tid)
{
    if (pthread_create(tid, NULL, edges_run, l) == 0)
        return 0;
    edges_run(l);
    return -1;
}

/* o's ropes and grid after its tree (source ks): 0, or MI_FAIL_OTHER. */
static int object_finish(const mi_builder *b, const kd_source *ks, mi_object *o)
{
    const aabb root = device_box(&o->tree.bounds, OBJECT_BOUNDS_MARGIN_ULPS);
    int fail = 0;
    o->ropes = build_ropes(b, &o->tree, &root, &fail);
    if (fail || ((b->p.accel & MI_ACCEL_GRID) && build_grid(ks, &root, &o->grid) != 0))
        return MI_FAIL_OTHER;
    return 0;
}

/* The mi_failure of an object from its shared edges' and kd_build's return values. */
static int tree_failure(int edges, int kd)
{
    return edges != 0 ? MI_FAIL_OTHER : kd == 0 ? 0 : kd == KD_TOO_MANY_NODES ? MI_FAIL_NODE_LIMIT : MI_FAIL_OTHER;
}

/* Stage 2 for one object: o's shared edges, tree (parameters q), ropes and grid: 0, or an
 * mi_failure. Reads b, writes only o. With several threads the shared edges run on a thread of
 * their own beside the tree, whose start (the root's events and sort, the first splits) runs on
 * one thread; the flags do not depend on the tree. */
static int object_tree(const mi_builder *b, const scene_mesh *m, mi_object *o, const kd_params *q)
{
    edges_job e = { m, o, 0 };
    edges_list l = { &e, 1 };
    pthread_t tid;
    const int beside = q->threads > 1 ? edges_beside(&l, &tid) == 0 : (edges_run(&l), 0);
    const tri_source src = { m, o->valid, o->centre };
    const kd_source ks = { o->n_valid, &src, tri_bounds, tri_clip, tri_clip_split };
    const int kd = kd_build(&ks, q, &o->tree);
    if (beside)
        pthread_join(tid, NULL);
    const int rc = tree_failure(e.rc, kd);
    return rc != 0 ? rc : object_finish(b, &ks, o);
}

/* Stage 3: o's node slots, shading flags and size in the image: 0, or -1 (memory). */
static int object_size(mi_builder *b, const scene *s, const scene_mesh *m, mi_object *o)
{
    o->revision_seen = m->revision;
    o->n_slots = tree_slots(&o->tree, trees_compact(&b->p), &o->slot);
    if (!o->n_slots)
        return -1;
    o->shade_flags = object_shading_flags(s, m, o);
    o->words = MI_NODE_WORDS * o->n_slots + list_words(&o->tree, o->ropes) + MI_TRIANGLE_WORDS - 1 +
               (MI_TRIANGLE_WORDS + shade_rec_words(o->shade_flags)) * o->n_valid + grid_words(&o->grid);
    return 0;
}

/* Stage 2 over the objects list[0..n) with `threads` threads: their trees in one kd_build_many
 * (largest first: a thread done with one object's tree helps with the others' subtrees, so that
 * none waits idle for the last object; the gallery's seven objects are 100k to 23k triangles,
 * and its smallest costs the most per triangle), their shared edges on a thread beside it, then
 * their ropes and grids. rc[list[k]]: an mi_failure or 0. */
static void trees_build(const mi_builder *b, const scene *s, uint32_t *list, uint32_t n, const kd_params *q,
                        uint32_t threads, int *rc)
{
    for (uint32_t k = 0; k < n; k++) { /* insertion sort: a few objects; ties in object order */
        const uint32_t i = list[k];
        uint32_t at = k;
        for (; at > 0 && b->obj[list[at - 1]].n_valid < b->obj[i].n_valid; at--)
            list[at] = list[at - 1];
        list[at] = i;
    }
    tri_source *src = malloc(((size_t)n + 1) * sizeof *src);
    kd_source *ks = malloc(((size_t)n + 1) * sizeof *ks);
    kd_params *ps = malloc(((size_t)n + 1) * sizeof *ps);
    kd_tree *trees = malloc(((size_t)n + 1) * sizeof *trees);
    edges_job *e = malloc(((size_t)n + 1) * sizeof *e);
    int *kd = malloc(((size_t)n + 1) * sizeof *kd);
    if (!src || !ks || !ps || !trees || !e || !kd) {
        for (uint32_t k = 0; k < n; k++)
            rc[list[k]] = MI_FAIL_OTHER;
        goto done;
    }
    for (uint32_t k = 0; k < n; k++) {
        mi_object *o = &b->obj[list[k]];
        const scene_mesh *m = obj_mesh(b, s, o);
        src[k] = (tri_source){ m, o->valid, o->centre };
        ks[k] = (kd_source){ o->n_valid, &src[k], tri_bounds, tri_clip, tri_clip_split };
        ps[k] = *q;
        e[k] = (edges_job){ m, o, 0 };
    }
    edges_list l = { e, n };
    pthread_t tid;
    const int beside = threads > 1 ? edges_beside(&l, &tid) == 0 : (edges_run(&l), 0);
    if (kd_build_many(ks, ps, n, threads, trees, kd) != 0)
        for (uint32_t k = 0; k < n; k++)
            kd[k] = -1;
    if (beside)
        pthread_join(tid, NULL);
    for (uint32_t k = 0; k < n; k++) {
        mi_object *o = &b->obj[list[k]];
        if (kd[k] == 0)
            o->tree = trees[k];
        rc[list[k]] = tree_failure(e[k].rc, kd[k]);
        if (rc[list[k]] == 0)
            rc[list[k]] = object_finish(b, &ks[k], o);
    }
done:
    free(src);
    free(ks);
    free(ps);
    free(trees);
    free(e);
    free(kd);
}

/* Builds the objects list[0..n) of b (their geometry and trees) in the three stages: 0, or an
 * mi_failure with *failed the object it names (the first in object order that failed). */
static int objects_prepare(mi_builder *b, const scene *s, uint32_t *list, uint32_t n, uint32_t *failed)
{
    int ret = -1;
    int *rc = calloc((size_t)b->n_objects + 1, sizeof *rc);
    uint64_t *old_nodes = calloc((size_t)b->n_objects + 1, sizeof *old_nodes);
    uint32_t *order = malloc(((size_t)n + 1) * sizeof *order);
    *failed = n ? list[0] : 0;
    if (!rc || !old_nodes || !order)
        goto done;
    const double t0 = seconds();
    for (uint32_t k = 0; k < n; k++) {
        mi_object *o = &b->obj[list[k]];
        old_nodes[list[k]] = o->tree.n_nodes;
        rc[list[k]] = object_transform(b, obj_mesh(b, s, o), o) != 0 ? MI_FAIL_OTHER : 0;
    }
    const double t1 = seconds();
    b->st.transform_seconds += t1 - t0;

    /* The concurrent trees share the node budget the others leave (the top level and the objects
     * not in the list): together they allocate no more nodes than the limit allows. */
    uint64_t others = b->top.n_nodes, shared = 0;
    for (uint32_t i = 0; i < b->n_objects; i++)
        others += b->obj[i].tree.n_nodes; /* the listed objects' trees are released */
    kd_params q = b->p.bottom;
    q.shared_nodes = &shared;
    if (b->p.max_nodes)
        q.max_nodes = others < b->p.max_nodes ? b->p.max_nodes - others : 0;
    const uint32_t threads = b->p.bottom.threads ? b->p.bottom.threads : kd_thread_count();
    uint32_t m = 0;
    for (uint32_t k = 0; k < n; k++)
        if (rc[list[k]] == 0 && (!b->p.max_nodes || q.max_nodes))
            order[m++] = list[k];
        else if (rc[list[k]] == 0)
            rc[list[k]] = MI_FAIL_NODE_LIMIT;
    trees_build(b, s, order, m, &q, threads, rc);

    /* Then the budget as a build one object after the other in object order charges it: object
     * list[k] after the new trees before it, beside the old ones (mi_update) of the listed
     * objects after it. A tree the shared budget stopped (which one depends on the timing) is
     * built again with exactly that budget, so the first object over the limit fails, always. */
    uint64_t later_old = 0;
    for (uint32_t k = 0; k < n; k++)
        later_old += old_nodes[list[k]];
    uint64_t used = others;
    for (uint32_t k = 0; k < n; k++) {
        mi_object *o = &b->obj[list[k]];
        *failed = list[k];
        later_old -= old_nodes[list[k]];
        if (rc[list[k]] == MI_FAIL_NODE_LIMIT && b->p.max_nodes && used + later_old < b->p.max_nodes) {
            kd_params alone = b->p.bottom;
            alone.threads = threads;
            alone.max_nodes = b->p.max_nodes - used - later_old;
            rc[list[k]] = object_tree(b, obj_mesh(b, s, o), o, &alone);
        }
        used += o->tree.n_nodes;
        if (rc[list[k]] == 0 && b->p.max_nodes && used + later_old > b->p.max_nodes)
            rc[list[k]] = MI_FAIL_NODE_LIMIT;
        if (rc[list[k]] == 0 && object_size(b, s, obj_mesh(b, s, o), o) != 0)
            rc[list[k]] = MI_FAIL_OTHER;
        if (rc[list[k]] != 0) {
            ret = rc[list[k]];
            goto done;
        }
    }
    b->st.bottom_build_seconds += seconds() - t1;
    ret = 0;
done:
    free(rc);
    free(old_nodes);
    free(order);
    return ret;
}

static void put_node(uint32_t *w, const kd_node *n, uint32_t first, const uint32_t *slot)
{
    if (n->axis == KD_LEAF) {
        w[0] = mi_node_leaf(n->count);
        w[1] = first;
    } else {
        const uint32_t lo = slot[n->child], hi = slot[n->child + 1];
        const uint32_t empty = (lo == MI_NONE ? MI_NODE_EMPTY_LO : 0u) | (hi == MI_NONE ? MI_NODE_EMPTY_HI : 0u);
        w[0] = mi_node_inner(n->axis, lo == MI_NONE ? hi : lo, empty);
        w[1] = fp24_word(n->split); /* already an fp24 value (quantized split) */
    }
}

static void put_rope_record(uint32_t *w, const kd_rope *r)
{
    for (int k = 0; k < 3; k++) {
        w[k] = fp24_word(r->box.lo[k]); /* split planes and the device box: fp24 values already */
        w[3 + k] = fp24_word(r->box.hi[k]);
    }
    for (int f = 0; f < 6; f++)
        w[6 + f] = r->rope[f] == KD_NO_ROPE ? MI_NONE : r->rope[f];
}

/* A tree's nodes at their slots and its leaf lists; with ropes (every node stored), each leaf's
 * entries follow its rope record. */
static void put_tree(uint32_t *nodes, uint32_t *lists, const kd_tree *t, const kd_rope *ropes, const uint32_t *slot)
{
    if (!ropes) {
        for (uint32_t i = 0; i < t->n_nodes; i++)
            if (slot[i] != MI_NONE)
                put_node(nodes + MI_NODE_WORDS * slot[i], &t->nodes[i], t->nodes[i].first, slot);
        memcpy(lists, t->prims, t->n_prims * sizeof *lists);
        return;
    }
    uint32_t at = 0;
    for (uint32_t i = 0; i < t->n_nodes; i++) {
        const kd_node *n = &t->nodes[i];
        if (n->axis == KD_LEAF) {
            put_rope_record(lists + at, &ropes[i]);
            at += MI_ROPE_WORDS;
            memcpy(lists + at, t->prims + n->first, n->count * sizeof *lists);
        }
        put_node(nodes + MI_NODE_WORDS * i, n, at, slot);
        at += n->axis == KD_LEAF ? n->count : 0;
    }
}

/* The octahedral codes of the mesh's vertex normals, each vertex encoded once (a vertex is shared
 * by about six triangles, and an encoding decodes four candidates); NULL if memory ran out. */
typedef struct {
    const scene_mesh *m;
    uint64_t *codes;
} normals_job;

static void normals_part(void *ctx, uint32_t from, uint32_t to)
{
    const normals_job *j = ctx;
    for (uint32_t v = from; v < to; v++) {
        const float *n = &j->m->normals[3 * (size_t)v];
        j->codes[v] = shade_encode_normal((const double[3]){ n[0], n[1], n[2] });
    }
}

/* On all CPUs (for_parts) if parallel, else on this thread. */
static uint64_t *normal_codes(const scene_mesh *m, int parallel)
{
    normals_job job = { m, malloc(((size_t)m->n_vertices + 1) * sizeof *job.codes) };
    if (job.codes && parallel)
        for_parts(m->n_vertices, normals_part, &job);
    else if (job.codes)
        normals_part(&job, 0, m->n_vertices);
    return job.codes;
}

/* codes: normal_codes(m), or NULL if the mesh has no normals. */
static void write_shading(uint32_t *w, const scene *s, const scene_mesh *m, const uint64_t *codes, uint32_t flags,
                          uint32_t tri)
{
    shade_triangle t = { .material = m->material[tri] };
    for (uint32_t k = 0; k < 3; k++) {
        const uint32_t v = m->indices[3 * (size_t)tri + k];
        t.normal[k] = codes ? codes[v] : 0;
        t.colour[k] = m->colours ? &m->colours[3 * (size_t)v] : NULL;
        for (uint32_t uv = 0; uv < 2; uv++) {
            uint32_t set;
            const scene_uv_map *map;
            record_mapping(s, &s->materials[t.material], uv, &set, &map);
            scene_texcoord(m, set, map, v, t.uv[uv][k]);
        }
    }
    shade_encode_record(w, flags, &t);
}

/* Address of the triangle transformations: after the lists, padded to a multiple of the record
 * size, so that with cache lines of one record every record is one line. */
static uint32_t triangles_at(const mi_object *o)
{
    const uint32_t end = o->base + MI_NODE_WORDS * o->n_slots + list_words(&o->tree, o->ropes);
    return (end + MI_TRIANGLE_WORDS - 1) / MI_TRIANGLE_WORDS * MI_TRIANGLE_WORDS;
}

typedef struct {
    const scene_mesh *m;
    const mi_object *o;
    const scene *s;
    const uint64_t *codes;      /* normal_codes(m), or NULL */
    uint32_t *triangles, *shading; /* the object's records in the image */
} records_job;

/* The triangle transformations and shading records of image triangles [from, to). */
static void records_part(void *ctx, uint32_t from, uint32_t to)
{
    const records_job *j = ctx;
    const uint32_t stride = shade_rec_words(j->o->shade_flags);
    for (uint32_t i = from; i < to; i++) {
        uint32_t *w = j->triangles + (size_t)MI_TRIANGLE_WORDS * i;
        memcpy(w, j->o->records + (size_t)MI_TRIANGLE_WORDS * i, MI_TRIANGLE_WORDS * sizeof *w);
        f24_record_put_field(w, F24_EDGE_FLAG_BIT, F24_EDGE_FLAG_BITS, j->o->shared[i]);
        write_shading(j->shading + (size_t)stride * i, j->s, j->m, j->codes, j->o->shade_flags, j->o->valid[i]);
    }
}

/* Geometry block: nodes, leaf lists, padding, triangle transformations, shading records. 0, or
 * -1 if memory ran out. */
static int object_write(mi_builder *b, const scene *s, mi_object *o)
{
    const scene_mesh *m = obj_mesh(b, s, o);
    /* the object has normals if its mesh has */
    uint64_t *codes = o->normal_codes ? o->normal_codes : m->normals ? normal_codes(m, 1) : NULL;
    o->normal_codes = NULL;
    if (m->normals && !codes)
        return -1;
    /* Zeroed here, so that the padding is deterministic: the tree's words up to the records, and
     * the grid's after them. The records (2/3 of the gallery's block) are written whole
     * (records_part, shade_encode_record) on the for_parts threads: their first touch of the
     * image's fresh pages is then not on one thread (a memset of the whole block was). */
    uint32_t *w = b->words + o->base, *end = b->words + o->base + o->words;
    memset(w, 0, (triangles_at(o) - o->base) * sizeof *w);
    put_tree(w, w + MI_NODE_WORDS * o->n_slots, &o->tree, o->ropes, o->slot);
    w = b->words + triangles_at(o);
    records_job job = { m, o, s, codes, w, w + (size_t)MI_TRIANGLE_WORDS * o->n_valid };
    for_parts(o->n_valid, records_part, &job);
    free(codes);
    w = job.shading + (size_t)shade_rec_words(o->shade_flags) * o->n_valid;
    memset(w, 0, (size_t)(end - w) * sizeof *w);
    if (o->grid.n[0])
        put_grid(w, &o->grid, (uint32_t)(w - b->words));
    return 0;
}

static void object_describe(uint32_t *w, const mi_object *o)
{
    memset(w, 0, MI_OBJECT_WORDS * sizeof *w);
    w[MI_O_NODES] = o->base;
    w[MI_O_LISTS] = o->base + MI_NODE_WORDS * o->n_slots;
    w[MI_O_TRIANGLES] = triangles_at(o);
    w[MI_O_SHADING] = w[MI_O_TRIANGLES] + MI_TRIANGLE_WORDS * o->n_valid;
    w[MI_O_N_NODES] = o->n_slots;
    w[MI_O_N_LIST] = list_words(&o->tree, o->ropes);
    w[MI_O_N_TRIANGLES] = o->n_valid;
    w[MI_O_FLAGS] = o->shade_flags | (o->dynamic ? MI_OBJECT_DYNAMIC : 0u);
    put_bounds(&w[MI_O_BOUNDS], &o->tree.bounds, OBJECT_BOUNDS_MARGIN_ULPS);
    w[MI_O_GRID] = o->grid.n[0] ? w[MI_O_SHADING] + shade_rec_words(o->shade_flags) * o->n_valid : MI_NONE;
}

/* ---- per-frame content: instances, top level, camera, lights ------------------------------ */

typedef struct {
    const scene *s;
    const mi_builder *b;
} inst_source;

/* The object-to-world map of image instance i: its scene instance's, or the identity of a
 * merged object. */
static affine instance_world(const mi_builder *b, const scene *s, uint32_t i)
{
    if (b->inst_scene[i] == MI_NONE)
        return affine_identity();
    affine w = s->instances[b->inst_scene[i]].world; /* composed with the move to the object's centre */
    const double *c = b->obj[b->inst_obj[i]].centre;
    for (int r = 0; r < 3; r++)
        w.m[r][3] += w.m[r][0] * c[0] + w.m[r][1] * c[1] + w.m[r][2] * c[2];
    return w;
}

static aabb instance_bounds(const void *user, uint32_t i)
{
    const inst_source *is = user;
    const affine world = instance_world(is->b, is->s, i);
    const aabb *ob = &is->b->obj[is->b->inst_obj[i]].tree.bounds;
    aabb r;
    for (int c = 0; c < 8; c++) {
        const double p[3] = { c & 1 ? ob->hi[0] : ob->lo[0], c & 2 ? ob->hi[1] : ob->lo[1], c & 4 ? ob->hi[2] : ob->lo[2] };
        double q[3];
        affine_apply_point(&world, p, q);
        for (int k = 0; k < 3; k++) {
            r.lo[k] = c ? fmin(r.lo[k], q[k]) : q[k];
            r.hi[k] = c ? fmax(r.hi[k], q[k]) : q[k];
        }
    }
    return r;
}

static void add_instance(mi_builder *b, uint32_t scene_inst, uint32_t obj)
{
    b->inst_scene[b->n_inst] = scene_inst;
    b->inst_obj[b->n_inst++] = obj;
}

/* Instances whose object has triangles and whose transformation is invertible in fp24, then one
 * identity instance per merged object (the scene instances baked into it are not instances). */
static int select_instances(mi_builder *b, const scene *s)
{
    free(b->inst_scene);
    free(b->inst_obj);
    b->inst_scene = malloc(((size_t)s->n_instances + b->n_objects + 1) * sizeof *b->inst_scene);
    b->inst_obj = malloc(((size_t)s->n_instances + b->n_objects + 1) * sizeof *b->inst_obj);
    if (!b->inst_scene || !b->inst_obj)
        return -1;
    b->n_inst = 0;
    for (uint32_t i = 0; i < s->n_instances; i++) {
        const uint32_t obj = b->mesh_obj[s->instances[i].mesh];
        affine inv;
        if (b->merge.baked_node[s->instances[i].node] || obj == MI_NONE || b->obj[obj].n_valid == 0 ||
            !affine_invert(&s->instances[i].world, &inv) || !affine_fits_f24(&inv))
            continue;
        add_instance(b, i, obj);
    }
    for (uint32_t o = 0; o < b->n_objects; o++)
        if (b->obj[o].merged && b->obj[o].n_valid)
            add_instance(b, MI_NONE, o);
    return 0;
}

/* 1 if every entry of a is exactly that of the identity: the device may skip it. */
static int affine_is_identity(const affine *a)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            if (a->m[i][j] != (i == j ? 1.0 : 0.0))
                return 0;
    return 1;
}

/* The world-to-object map of an instance as the device holds it: the inverse's 3x3 rounded to fp24
 * (inv), and the translation -A^-1 c of that rounded 3x3, so that the object lands where the scene
 * puts it to double-word precision (the rounding of A^-1 then only scales and turns the object about
 * its own origin), split into fp24 high words (inv's column 3) and low words (t_lo). */
static void device_inverse(const affine *world, affine *inv, uint32_t t_lo[3])
{
    affine_invert(world, inv);
    for (int i = 0; i < 3; i++) {
        double t = 0;
        for (int j = 0; j < 3; j++) {
            inv->m[i][j] = f24_fast_decode(fp24_word(inv->m[i][j]));
            t -= inv->m[i][j] * world->m[j][3];
        }
        const uint32_t hi = fp24_word(t);
        inv->m[i][3] = t;
        t_lo[i] = f24_is_inf(hi) ? 0u : fp24_word(t - f24_fast_decode(hi));
    }
}

static void write_instances(mi_builder *b, const scene *s, uint32_t *w)
{
    for (uint32_t i = 0; i < b->n_inst; i++, w += MI_INSTANCE_WORDS) {
        const affine world = instance_world(b, s, i);
        affine inv;
        memset(w, 0, MI_INSTANCE_WORDS * sizeof *w);
        device_inverse(&world, &inv, &w[MI_I_T_LO]);
        put_affine(w, &inv);
        w[MI_I_OBJECT] = b->inst_obj[i];
        w[MI_I_FLAGS] = affine_is_identity(&inv) ? MI_INST_IDENTITY : 0u;
    }
}

static void normalize3(double v[3])
{
    const double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3 && l > 0; k++)
        v[k] /= l;
}

/* A perspective camera at eye looking at `at` (glTF convention: looks down -Z, +Y up). */
static scene_camera view_camera(const mi_params *p)
{
    scene_camera c = { 0 };
    c.kind = CAMERA_PERSPECTIVE;
    c.yfov = p->fov_degrees * M_PI / 180.0;
    double f[3] = { p->at[0] - p->eye[0], p->at[1] - p->eye[1], p->at[2] - p->eye[2] }, r[3], u[3];
    normalize3(f);
    r[0] = f[1] * p->up[2] - f[2] * p->up[1];
    r[1] = f[2] * p->up[0] - f[0] * p->up[2];
    r[2] = f[0] * p->up[1] - f[1] * p->up[0];
    normalize3(r);
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    for (int k = 0; k < 3; k++) {
        c.world.m[k][0] = r[k];
        c.world.m[k][1] = u[k];
        c.world.m[k][2] = -f[k];
        c.world.m[k][3] = p->eye[k];
    }
    return c;
}

/* The camera in double: origin O, pixel steps U and V, direction W to the corner of pixel
 * (0,0); the primary ray of pixel (x, y) has direction W + (x+1/2) U + (y+1/2) V (perspective)
 * or origin O + (x+1/2) U + (y+1/2) V and direction W (orthographic). */
void mi_camera_frame(const mi_builder *b, const scene *s, mi_camera *out)
{
    const scene_camera c = b->p.explicit_view            ? view_camera(&b->p)
                           : b->p.camera < s->n_cameras ? s->cameras[b->p.camera]
                                                        : scene_default_camera(b->top.bounds.lo, b->top.bounds.hi);
    const double wpx = b->p.width, hpx = b->p.height, aspect = wpx / hpx;
    const double zero[3] = { 0, 0, 0 };
    out->orthographic = c.kind == CAMERA_ORTHOGRAPHIC;
    out->width = b->p.width;
    out->height = b->p.height;
    if (out->orthographic) {
        const double ul[3] = { -c.xmag, c.ymag, 0 }, su[3] = { 2 * c.xmag / wpx, 0, 0 }, sv[3] = { 0, -2 * c.ymag / hpx, 0 },
                     dir[3] = { 0, 0, -1 };
        affine_apply_point(&c.world, ul, out->o);
        affine_apply_vector(&c.world, su, out->u);
        affine_apply_vector(&c.world, sv, out->v);
        affine_apply_vector(&c.world, dir, out->w);
    } else {
        const double th = tan(0.5 * c.yfov);
        const double su[3] = { 2 * th * aspect / wpx, 0, 0 }, sv[3] = { 0, -2 * th / hpx, 0 }, corner[3] = { -th * aspect, th, -1 };
        affine_apply_point(&c.world, zero, out->o);
        affine_apply_vector(&c.world, su, out->u);
        affine_apply_vector(&c.world, sv, out->v);
        affine_apply_vector(&c.world, corner, out->w);
    }
}

/* Camera block: mi_camera_frame rounded to fp24. */
static void write_camera(const mi_builder *b, const scene *s, uint32_t *w)
{
    mi_camera c;
    mi_camera_frame(b, s, &c);
    const double *o = c.o, *u = c.u, *v = c.v, *d = c.w;
    memset(w, 0, MI_CAMERA_WORDS * sizeof *w);
    w[0] = (uint32_t)c.orthographic;
    w[1] = b->p.width;
    w[2] = b->p.height;
    for (int k = 0; k < 3; k++) {
        w[4 + k] = fp24_word(o[k]);
        w[7 + k] = fp24_word(u[k]);
        w[10 + k] = fp24_word(v[k]);
        w[13 + k] = fp24_word(d[k]);
    }
}

/* The light of a scene that has none (docs/shading.md): a white point light above and to the
 * right of the eye, 0.3 x the largest extent of the scene bounds away along the camera's up and
 * right, so that shadows fall visibly behind and below what the camera sees. */
void mi_default_light(const mi_builder *b, const scene *s, scene_light *out)
{
    mi_camera c;
    mi_camera_frame(b, s, &c);
    double extent = 0, eye[3], right[3], up[3];
    for (int k = 0; k < 3; k++) {
        extent = fmax(extent, b->top.bounds.hi[k] - b->top.bounds.lo[k]);
        eye[k] = c.orthographic ? c.o[k] + 0.5 * (c.width * c.u[k] + c.height * c.v[k]) : c.o[k];
        right[k] = c.u[k];
        up[k] = -c.v[k];
    }
    normalize3(right);
    normalize3(up);
    memset(out, 0, sizeof *out);
    out->kind = LIGHT_POINT;
    out->color[0] = out->color[1] = out->color[2] = 1.0f;
    out->intensity = 1.0f;
    out->node = SCENE_NONE;
    for (int k = 0; k < 3; k++)
        out->position[k] = eye[k] + 0.3 * extent * (up[k] + right[k]);
    out->direction[2] = -1;
}

static uint32_t light_count(const scene *s) { return s->n_lights ? s->n_lights : 1; }

static void write_light(const scene_light *l, uint32_t *w)
{
    memset(w, 0, MI_LIGHT_WORDS * sizeof *w);
    w[0] = l->kind;
    for (int k = 0; k < 3; k++) {
        w[1 + k] = fp24_word((double)l->color[k] * l->intensity);
        w[4 + k] = fp24_word(l->position[k]);
        w[7 + k] = fp24_word(l->direction[k]);
    }
    w[10] = fp24_word(l->range);
    w[11] = fp24_word(cos(l->inner_cone));
    w[12] = fp24_word(cos(l->outer_cone));
}

static void write_lights(const mi_builder *b, const scene *s, uint32_t *w)
{
    if (s->n_lights == 0) {
        scene_light l;
        mi_default_light(b, s, &l);
        write_light(&l, w);
    }
    for (uint32_t i = 0; i < s->n_lights; i++, w += MI_LIGHT_WORDS)
        write_light(&s->lights[i], w);
}

/* A shader weight in [0, 1] as Q12 (docs/shading.md). */
static uint32_t q12(double x) { return (uint32_t)lround(4096.0 * (x > 0 ? (x < 1 ? x : 1) : 0)); }

/* The image's index of scene texture t, or MI_NONE. */
static uint32_t image_texture(const mi_builder *b, const scene *s, uint32_t t)
{
    return t < s->n_textures ? b->texture_map[t] : MI_NONE;
}

static void write_materials(const mi_builder *b, const scene *s, uint32_t *w)
{
    for (uint32_t i = 0; i < s->n_materials; i++, w += MI_MATERIAL_WORDS) {
        const scene_material *m = &s->materials[i];
        memset(w, 0, MI_MATERIAL_WORDS * sizeof *w);
        for (int k = 0; k < 4; k++)
            w[k] = fp24_word(m->base_color[k]);
        for (int k = 0; k < 3; k++)
            w[4 + k] = fp24_word(m->emissive[k]);
        shading_params sp;
        shading_params_of(m, &sp);
        w[7] = image_texture(b, s, m->base_color_texture);
        w[SHADE_M_FLAGS] = (uint32_t)m->alpha | (m->double_sided ? 4u : 0u) | (sp.unlit ? SHADE_MAT_UNLIT : 0u);
        w[9] = fp24_word(m->alpha_cutoff);
        w[10] = fp24_word(m->metallic);
        w[11] = fp24_word(m->roughness);
        w[SHADE_M_EMISSIVE_TEXTURE] = image_texture(b, s, m->emissive_texture);
        w[13] = fp24_word(sp.eta);
        w[14] = q12(sp.kd) | q12(sp.kr) << 13 | sp.exp_shift << 26;
        w[15] = q12(sp.kt) | q12(sp.ks) << 13;
    }
}

/* Only textures that some material uses as base colour or emission are stored. */
static uint32_t texture_words(mi_builder *b, const scene *s)
{
    uint32_t words = 0;
    b->n_textures = 0;
    for (uint32_t t = 0; t < s->n_textures; t++) {
        b->texture_map[t] = MI_NONE;
        for (uint32_t m = 0; m < s->n_materials; m++)
            if (s->materials[m].base_color_texture == t || s->materials[m].emissive_texture == t) {
                b->texture_map[t] = b->n_textures++;
                words += (uint32_t)s->textures[t].width * (uint32_t)s->textures[t].height;
                break;
            }
    }
    return words + MI_TEXTURE_WORDS * b->n_textures;
}

static void write_textures(const mi_builder *b, const scene *s, uint32_t *w, uint32_t base)
{
    uint32_t texel = base + MI_TEXTURE_WORDS * b->n_textures;
    for (uint32_t t = 0; t < s->n_textures; t++) {
        if (b->texture_map[t] == MI_NONE)
            continue;
        const scene_texture *tx = &s->textures[t];
        const uint32_t n = (uint32_t)tx->width * (uint32_t)tx->height;
        uint32_t *e = w + MI_TEXTURE_WORDS * b->texture_map[t];
        e[0] = (uint32_t)tx->width;
        e[1] = (uint32_t)tx->height;
        e[2] = texel;
        e[3] = 0;
        uint32_t *dst = w + (texel - base);
        for (uint32_t i = 0; i < n; i++)
            dst[i] = (uint32_t)tx->rgba[4 * (size_t)i] | (uint32_t)tx->rgba[4 * (size_t)i + 1] << 8 |
                     (uint32_t)tx->rgba[4 * (size_t)i + 2] << 16 | (uint32_t)tx->rgba[4 * (size_t)i + 3] << 24;
        texel += n;
    }
}

/* ---- layout and frames -------------------------------------------------------------------- */

static uint32_t *region_entry(mi_builder *b, mi_region r) { return &b->words[MI_H_REGION_TABLE + 2 * r]; }

static void format_mb(char *buf, size_t n, uint64_t words)
{
    snprintf(buf, n, "%.2f MB", (double)words * 4.0 / (1024.0 * 1024.0));
}

/* The --mem-mb value that holds an image of this many words. */
static uint32_t mem_mb_for(uint64_t words) { return (uint32_t)((words * 4 + (1u << 20) - 1) >> 20); }

/* Places the regions with the given lengths; fails if the image exceeds the memory size. */
static int place_regions(mi_builder *b, const uint64_t len[MI_REGION_COUNT], uint32_t off[MI_REGION_COUNT],
                         char *err, size_t errlen)
{
    uint64_t at = 0;
    for (int r = 0; r < MI_REGION_COUNT; r++) {
        off[r] = (uint32_t)at;
        at += len[r];
    }
    const uint64_t cap = b->p.memory_bytes / 4;
    if (at > cap || at > UINT32_MAX / 2) {
        int big = 0;
        for (int r = 1; r < MI_REGION_COUNT; r++)
            if (len[r] > len[big])
                big = r;
        char need[32], have[32], region[32];
        format_mb(need, sizeof need, at);
        format_mb(have, sizeof have, cap);
        format_mb(region, sizeof region, len[big]);
        snprintf(err, errlen, "scene does not fit the %s device memory: the image needs %s, largest region %s "
                 "is %s (pass --mem-mb %u)", have, need, region_names[big], region, mem_mb_for(at));
        return -1;
    }
    return 0;
}

/* The message of a build that would pass p.max_nodes while building `what`. */
static int node_limit_error(const mi_builder *b, const char *what, char *err, size_t errlen)
{
    snprintf(err, errlen, "limit kd-nodes exceeded: the kd-tree node count of the memory image, where the build "
             "stopped (%s), is %llu, the limit is %llu (raise it with --limit kd-nodes=N)", what,
             (unsigned long long)b->p.max_nodes + 1, (unsigned long long)b->p.max_nodes);
    return MI_FAIL_NODE_LIMIT;
}

/* object_prepare's failure rc on mesh m as err: the node limit, or memory. */
static int object_error(const mi_builder *b, int rc, const scene_mesh *m, const char *verb, char *err, size_t errlen)
{
    char what[300];
    snprintf(what, sizeof what, "the tree of mesh '%s'", m->name);
    if (rc == MI_FAIL_NODE_LIMIT)
        return node_limit_error(b, what, err, errlen);
    snprintf(err, errlen, "out of memory while %s %s", verb, what);
    return MI_FAIL_OTHER;
}

/* 0, or an mi_failure with err. */
static int write_frame(mi_builder *b, const scene *s, int full, int dynamic_changed, char *err, size_t errlen)
{
    const double t0 = seconds();
    if (select_instances(b, s) != 0)
        goto oom;
    inst_source is = { s, b };
    kd_free(&b->top);
    const kd_source ks = { b->n_inst, &is, instance_bounds, NULL, NULL };
    const int rc = build_tree(b, &ks, &b->p.top, &b->top);
    if (rc == MI_FAIL_NODE_LIMIT)
        return node_limit_error(b, "the top-level tree", err, errlen);
    if (rc != 0)
        goto oom;
    const aabb scene_box = device_box(&b->top.bounds, 0);
    int fail = 0;
    free(b->top_ropes);
    b->top_ropes = build_ropes(b, &b->top, &scene_box, &fail);
    ugrid_free(&b->top_grid);
    if (fail || ((b->p.accel & MI_ACCEL_TOP_GRID) && b->n_inst && build_grid(&ks, &scene_box, &b->top_grid) != 0))
        goto oom;
    b->st.top_build_seconds = seconds() - t0;

    uint64_t len[MI_REGION_COUNT] = { 0 };
    len[MI_R_HEADER] = MI_HEADER_WORDS;
    len[MI_R_MATERIALS] = (uint64_t)MI_MATERIAL_WORDS * s->n_materials;
    len[MI_R_TEXTURES] = texture_words(b, s);
    for (uint32_t i = 0; i < b->n_objects; i++)
        len[b->obj[i].dynamic ? MI_R_DYNAMIC_GEOMETRY : MI_R_STATIC_GEOMETRY] += b->obj[i].words;
    len[MI_R_OBJECTS] = (uint64_t)MI_OBJECT_WORDS * b->n_objects;
    len[MI_R_CAMERA] = MI_CAMERA_WORDS;
    len[MI_R_LIGHTS] = (uint64_t)MI_LIGHT_WORDS * light_count(s);
    uint64_t before_instances = 0; /* the lights end with zeros to a multiple of the triangle record */
    for (int r = 0; r < MI_R_INSTANCES; r++) /* size: the instance table starts on a matrices line */
        before_instances += len[r];
    len[MI_R_LIGHTS] += (MI_TRIANGLE_WORDS - before_instances % MI_TRIANGLE_WORDS) % MI_TRIANGLE_WORDS;
    len[MI_R_INSTANCES] = (uint64_t)MI_INSTANCE_WORDS * b->n_inst;
    free(b->top_slot);
    b->n_top_slots = tree_slots(&b->top, trees_compact(&b->p), &b->top_slot);
    if (!b->n_top_slots)
        goto oom;
    len[MI_R_TOP_NODES] = (uint64_t)MI_NODE_WORDS * b->n_top_slots;
    len[MI_R_TOP_LISTS] = list_words(&b->top, b->top_ropes);
    len[MI_R_TOP_GRID] = grid_words(&b->top_grid);
    uint32_t off[MI_REGION_COUNT];
    if (place_regions(b, len, off, err, errlen) != 0)
        return -1;
    const uint32_t total = off[MI_REGION_COUNT - 1] + (uint32_t)len[MI_REGION_COUNT - 1];
    uint32_t *w = huge_pages_realloc(b->words, ((size_t)total + 1) * sizeof *w);
    if (!w)
        goto oom;
    b->words = w;
    b->n_words = total;

    /* geometry blocks get their addresses, in object order within each region */
    uint32_t at[2] = { off[MI_R_STATIC_GEOMETRY], off[MI_R_DYNAMIC_GEOMETRY] };
    for (uint32_t i = 0; i < b->n_objects; i++) {
        mi_object *o = &b->obj[i];
        o->base = at[o->dynamic];
        at[o->dynamic] += o->words;
        if ((full || (o->dynamic && dynamic_changed)) && object_write(b, s, o) != 0)
            goto oom;
    }
    int written[MI_REGION_COUNT] = { 0 };
    if (full) {
        write_materials(b, s, w + off[MI_R_MATERIALS]);
        write_textures(b, s, w + off[MI_R_TEXTURES], off[MI_R_TEXTURES]);
        written[MI_R_MATERIALS] = written[MI_R_TEXTURES] = written[MI_R_STATIC_GEOMETRY] = 1;
    }
    if (full || dynamic_changed) {
        for (uint32_t i = 0; i < b->n_objects; i++)
            object_describe(w + off[MI_R_OBJECTS] + MI_OBJECT_WORDS * i, &b->obj[i]);
        written[MI_R_DYNAMIC_GEOMETRY] = written[MI_R_OBJECTS] = 1;
    }
    write_camera(b, s, w + off[MI_R_CAMERA]);
    memset(w + off[MI_R_LIGHTS], 0, len[MI_R_LIGHTS] * sizeof *w); /* with the padding */
    write_lights(b, s, w + off[MI_R_LIGHTS]);
    write_instances(b, s, w + off[MI_R_INSTANCES]);
    put_tree(w + off[MI_R_TOP_NODES], w + off[MI_R_TOP_LISTS], &b->top, b->top_ropes, b->top_slot);
    if (b->top_grid.n[0])
        put_grid(w + off[MI_R_TOP_GRID], &b->top_grid, off[MI_R_TOP_GRID]);
    written[MI_R_HEADER] = written[MI_R_CAMERA] = written[MI_R_LIGHTS] = written[MI_R_INSTANCES] = 1;
    written[MI_R_TOP_NODES] = written[MI_R_TOP_LISTS] = written[MI_R_TOP_GRID] = 1;

    /* header */
    const uint32_t accel = (b->p.accel & MI_ACCEL_ALL & ~(b->top_grid.n[0] ? 0u : (uint32_t)MI_ACCEL_TOP_GRID)) |
                           (trees_compact(&b->p) ? MI_TREES_COMPACT : 0u);
    const uint32_t head[MI_H_SCENE_BOUNDS] = { MI_MAGIC, MI_VERSION,
                                                (uint32_t)(accel << MI_ACCEL_SHIFT | F24_EXP_BITS << 8 | F24_MAN_BITS),
                                                (uint32_t)(b->p.memory_bytes / 4), total, b->frame,
                                                b->n_objects, b->n_inst, s->n_materials, b->n_textures, light_count(s),
                                                b->n_top_slots };
    memcpy(w, head, sizeof head);
    put_bounds(w + MI_H_SCENE_BOUNDS, &b->top.bounds, 0);
    uint64_t upload = 0;
    for (int r = 0; r < MI_REGION_COUNT; r++) {
        region_entry(b, (mi_region)r)[0] = off[r];
        region_entry(b, (mi_region)r)[1] = (uint32_t)len[r];
        b->st.region_words[r] = (uint32_t)len[r];
        upload += written[r] ? len[r] * 4 : 0;
    }
    mi_profile prof;
    mi_profile_derive(w, &prof);
    w[off[MI_R_CAMERA] + MI_CAM_PROFILE] = prof.skip & b->p.skip;
    b->st.frame_upload_bytes = upload;
    b->st.frame_geometry_bytes = written[MI_R_DYNAMIC_GEOMETRY] ? 4 * (len[MI_R_DYNAMIC_GEOMETRY] + len[MI_R_OBJECTS]) : 0;
    return 0;
oom:
    snprintf(err, errlen, "out of memory while building the memory image");
    return MI_FAIL_OTHER;
}

static void collect_stats(mi_builder *b, const scene *s)
{
    mi_stats *st = &b->st;
    st->objects = b->n_objects;
    st->instances = b->n_inst;
    st->triangles = 0;
    for (uint32_t i = 0; i < s->n_meshes; i++) /* unique triangles as authored, merged or not */
        st->triangles += s->meshes[i].n_triangles;
    st->merged_objects = b->merge.n_meshes;
    st->merged_instances = b->merge.baked_instances;
    st->merged_copy_triangles = b->merge.baked_copy_triangles;
    st->kept_animated = b->merge.animated_instances;
    st->kept_morphing = b->merge.morphing_instances;
    st->kept_mirrored = b->merge.mirrored_instances;
    st->kept_turned = b->merge.turned_instances;
    st->kept_instanced = b->merge.instanced_kept;
    st->bottom_nodes = st->bottom_leaves = st->bottom_empty_leaves = st->bottom_depth = 0;
    st->bottom_references = 0;
    st->bottom_sah = 0;
    for (uint32_t i = 0; i < b->n_objects; i++) {
        const kd_tree *t = &b->obj[i].tree;
        st->bottom_nodes += t->n_nodes;
        st->bottom_leaves += t->stats.n_leaves;
        st->bottom_empty_leaves += t->stats.n_empty_leaves;
        st->bottom_depth = t->stats.depth > st->bottom_depth ? t->stats.depth : st->bottom_depth;
        st->bottom_references += t->stats.references;
        st->bottom_sah += t->stats.sah_cost * b->obj[i].n_valid;
    }
    st->top_nodes = b->top.n_nodes;
    st->top_leaves = b->top.stats.n_leaves;
    st->top_empty_leaves = b->top.stats.n_empty_leaves;
    st->top_depth = b->top.stats.depth;
    st->top_references = b->top.stats.references;
    st->top_sah = b->top.stats.sah_cost;
}

/* The image's objects: every scene mesh that some instance not baked into world space uses, in
 * mesh order, then the merged world-space objects. */
/* 1 if some scene instance shows mesh m untransformed. */
static int mesh_has_identity_instance(const scene *s, uint32_t m)
{
    for (uint32_t i = 0; i < s->n_instances; i++)
        if (s->instances[i].mesh == m && affine_is_identity(&s->instances[i].world))
            return 1;
    return 0;
}

/* Objects whose instances all transform them get their space centred on their bounds: the device
 * then holds vertices and rays as offsets no larger than the object, and the rounding of an
 * instance's matrix (a relative error of the fp24 format) moves the object's points by that much
 * less (docs/numerics.md). Objects shown untransformed somewhere keep the mesh's space, so that
 * their instances stay identities the device skips. */
static void choose_centres(mi_builder *b, const scene *s)
{
    for (uint32_t i = 0; i < b->n_objects; i++) {
        mi_object *o = &b->obj[i];
        const scene_mesh *m = obj_mesh(b, s, o);
        o->centre[0] = o->centre[1] = o->centre[2] = 0;
        if (o->merged || m->n_vertices == 0 || mesh_has_identity_instance(s, o->mesh))
            continue;
        for (int k = 0; k < 3; k++) {
            double lo = m->positions[k], hi = lo;
            for (uint32_t v = 1; v < m->n_vertices; v++) {
                lo = fmin(lo, m->positions[3 * (size_t)v + (size_t)k]);
                hi = fmax(hi, m->positions[3 * (size_t)v + (size_t)k]);
            }
            o->centre[k] = f24_fast_decode(fp24_word(0.5 * (lo + hi)));
        }
    }
}

static void choose_objects(mi_builder *b, const scene *s)
{
    for (uint32_t k = 0; k < s->n_meshes; k++)
        b->mesh_obj[k] = MI_NONE;
    for (uint32_t i = 0; i < s->n_instances; i++)
        if (!b->merge.baked_node[s->instances[i].node])
            b->mesh_obj[s->instances[i].mesh] = 0;
    b->n_objects = 0;
    for (uint32_t k = 0; k < s->n_meshes; k++)
        if (b->mesh_obj[k] != MI_NONE) {
            b->obj[b->n_objects] = (mi_object){ .mesh = k, .dynamic = scene_mesh_deforms(&s->meshes[k]) };
            b->mesh_obj[k] = b->n_objects++;
        }
    for (uint32_t k = 0; k < b->merge.n_meshes; k++)
        b->obj[b->n_objects++] = (mi_object){ .mesh = k, .merged = 1 };
}

mi_builder *mi_build(const scene *s, const mi_params *p, char *err, size_t errlen)
{
    mi_failure why;
    return mi_build_why(s, p, &why, err, errlen);
}

mi_builder *mi_build_why(const scene *s, const mi_params *p, mi_failure *why, char *err, size_t errlen)
{
    *why = MI_FAIL_OTHER;
    mi_builder *b = calloc(1, sizeof *b);
    if (!b) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    b->p = *p;
    if (!trees_compact(p))
        b->p.bottom.face_splits = 0;
    b->obj = calloc((size_t)s->n_meshes + MI_MERGE_CLASSES + 1, sizeof *b->obj);
    b->mesh_obj = malloc(((size_t)s->n_meshes + 1) * sizeof *b->mesh_obj);
    b->texture_map = calloc((size_t)s->n_textures + 1, sizeof *b->texture_map);
    if (!b->obj || !b->mesh_obj || !b->texture_map || mi_merge_build(s, p->merge, &b->merge) != 0) {
        snprintf(err, errlen, "out of memory");
        mi_free(b);
        return NULL;
    }
    if (s->n_materials > 1u << SHADE_MATERIAL_BITS) {
        snprintf(err, errlen, "scene has %u materials; a shading record names at most %u", s->n_materials,
                 1u << SHADE_MATERIAL_BITS);
        mi_free(b);
        return NULL;
    }
    choose_objects(b, s);
    choose_centres(b, s);
    uint64_t floor_words = 0; /* what the triangles need before any tree: fail early on hopeless scenes */
    for (uint32_t i = 0; i < b->n_objects; i++) {
        const scene_mesh *m = obj_mesh(b, s, &b->obj[i]);
        floor_words += (uint64_t)(MI_TRIANGLE_WORDS + shade_rec_words(shading_flags(m))) * m->n_triangles;
    }
    if (floor_words > p->memory_bytes / 4) {
        char need[32], have[32];
        format_mb(need, sizeof need, floor_words);
        format_mb(have, sizeof have, p->memory_bytes / 4);
        snprintf(err, errlen, "scene does not fit the %s device memory: the triangle transformations and shading "
                 "records of region STATIC_GEOMETRY alone need %s (pass --mem-mb %u or more)", have, need,
                 mem_mb_for(floor_words));
        mi_free(b);
        return NULL;
    }
    uint32_t *list = malloc(((size_t)b->n_objects + 1) * sizeof *list), failed;
    if (!list) {
        snprintf(err, errlen, "out of memory");
        mi_free(b);
        return NULL;
    }
    for (uint32_t i = 0; i < b->n_objects; i++)
        list[i] = i;
    const int built = objects_prepare(b, s, list, b->n_objects, &failed);
    free(list);
    if (built != 0) {
        *why = (mi_failure)object_error(b, built, obj_mesh(b, s, &b->obj[failed]), "building", err, errlen);
        mi_free(b);
        return NULL;
    }
    const int rc = write_frame(b, s, 1, 1, err, errlen);
    if (rc != 0) {
        *why = (mi_failure)rc;
        mi_free(b);
        return NULL;
    }
    collect_stats(b, s);
    return b;
}

int mi_update(mi_builder *b, const scene *s, char *err, size_t errlen)
{
    int changed = 0;
    b->frame++;
    b->st.rebuilt_objects = 0;
    b->st.bottom_build_seconds = b->st.transform_seconds = 0; /* figures of this update only */
    uint32_t *list = malloc(((size_t)b->n_objects + 1) * sizeof *list), n = 0, failed;
    if (!list) {
        snprintf(err, errlen, "out of memory");
        return MI_FAIL_OTHER;
    }
    for (uint32_t i = 0; i < b->n_objects; i++) {
        const mi_object *o = &b->obj[i];
        const scene_mesh *m = obj_mesh(b, s, o);
        if (!o->dynamic || o->revision_seen == m->revision)
            continue;
        b->st.degenerate_triangles -= m->n_triangles - o->n_valid;
        list[n++] = i;
    }
    const int built = objects_prepare(b, s, list, n, &failed);
    free(list);
    if (built != 0)
        return object_error(b, built, obj_mesh(b, s, &b->obj[failed]), "rebuilding", err, errlen);
    b->st.rebuilt_objects = n;
    changed = n > 0;
    const int rc = write_frame(b, s, 0, changed, err, errlen);
    if (rc != 0)
        return rc;
    collect_stats(b, s);
    return 0;
}

const uint32_t *mi_words(const mi_builder *b, uint32_t *n_words)
{
    *n_words = b->n_words;
    return b->words;
}

const mi_stats *mi_get_stats(const mi_builder *b) { return &b->st; }

void mi_hit_source(const mi_builder *b, uint32_t image_instance, uint32_t image_triangle, uint32_t *scene_inst,
                   uint32_t *mesh_triangle)
{
    *scene_inst = *mesh_triangle = MI_NONE;
    if (image_instance >= b->n_inst)
        return;
    const mi_object *o = &b->obj[b->inst_obj[image_instance]];
    if (image_triangle >= o->n_valid)
        return;
    const uint32_t t = o->valid[image_triangle]; /* the triangle of the object's mesh */
    *scene_inst = o->merged ? b->merge.src_instance[o->mesh][t] : b->inst_scene[image_instance];
    *mesh_triangle = o->merged ? b->merge.src_triangle[o->mesh][t] : t;
}

void mi_free(mi_builder *b)
{
    if (!b)
        return;
    for (uint32_t i = 0; i < b->n_objects && b->obj; i++)
        object_release(&b->obj[i]);
    kd_free(&b->top);
    free(b->top_ropes);
    free(b->top_slot);
    ugrid_free(&b->top_grid);
    free(b->obj);
    free(b->texture_map);
    free(b->inst_scene);
    free(b->inst_obj);
    free(b->mesh_obj);
    mi_merge_free(&b->merge);
    free(b->words);
    free(b);
}
