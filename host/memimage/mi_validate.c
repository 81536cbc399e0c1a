/*
 * Memory-image validator: everything the device model relies on is checked before it reads the
 * image, so that a corrupted or hostile image gives an error instead of an out-of-bounds read.
 * Every address range is checked in 64-bit arithmetic; trees must have children after parents
 * (no cycles, bounded traversal); device numbers must be finite fp24 of this build's format.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "f24.h"
#include "memimage.h"
#include "mi_profile.h"
#include "trace.h"
#include "xform_unit.h"
#include "shade_rec.h"

typedef struct {
    const uint32_t *w;
    uint32_t n, accel; /* MI_ACCEL_* bits of the header */
    uint32_t off[MI_REGION_COUNT], len[MI_REGION_COUNT];
    char *err;
    size_t errlen;
} checker;

static int bad(checker *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int bad(checker *c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    const int k = snprintf(c->err, c->errlen, "memory image: ");
    if (k >= 0 && (size_t)k < c->errlen)
        vsnprintf(c->err + k, c->errlen - (size_t)k, fmt, ap);
    va_end(ap);
    return -1;
}

static int finite_f24(uint32_t v) { return (v & ~F24_MASK) == 0 && f24_exp(v) != F24_EXP_MAX; }

/* [addr, addr + count * size) inside region r. */
static int in_region(const checker *c, mi_region r, uint64_t addr, uint64_t count, uint64_t size)
{
    return addr >= c->off[r] && addr + count * size <= (uint64_t)c->off[r] + c->len[r];
}

static int finite_words(const checker *c, uint32_t at, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++)
        if (!finite_f24(c->w[at + i]))
            return 0;
    return 1;
}

/* A packed record of n values (f24_record.h): every value finite, the bits after the last zero. */
/* n finite values, then fields up to bit `bits` of the record, then zero padding bits. */
static int finite_record(const checker *c, uint32_t at, uint32_t n, uint32_t bits)
{
    for (uint32_t i = 0; i < n; i++)
        if (!finite_f24(f24_record_get(c->w, at, i)))
            return 0;
    const uint32_t used = bits % 32;
    return used == 0 || c->w[at + (bits + 31) / 32 - 1] >> used == 0;
}

static int check_header(checker *c)
{
    const uint32_t *w = c->w;
    if (c->n < MI_HEADER_WORDS)
        return bad(c, "%u words is smaller than the header (%u words)", c->n, (unsigned)MI_HEADER_WORDS);
    if (w[MI_H_MAGIC] != MI_MAGIC)
        return bad(c, "bad magic 0x%08X", w[MI_H_MAGIC]);
    if (w[MI_H_VERSION] != MI_VERSION)
        return bad(c, "version %u, this build reads version %u", w[MI_H_VERSION], MI_VERSION);
    if ((w[MI_H_FORMAT] & 0xFFFFu) != (uint32_t)(F24_EXP_BITS << 8 | F24_MAN_BITS))
        return bad(c, "number format e%um%u, this build is e%dm%d", w[MI_H_FORMAT] >> 8 & 0xFF, w[MI_H_FORMAT] & 0xFF,
                   F24_EXP_BITS, F24_MAN_BITS);
    c->accel = w[MI_H_FORMAT] >> MI_ACCEL_SHIFT;
    if ((c->accel & ~(uint32_t)(MI_ACCEL_ALL | MI_TREES_COMPACT)) ||
        ((c->accel & MI_TREES_COMPACT) && (c->accel & MI_ACCEL_ROPES)))
        return bad(c, "unknown accelerator bits 0x%x, or compact trees with ropes", c->accel);
    if (w[MI_H_USED_WORDS] != c->n || w[MI_H_MEMORY_WORDS] < c->n)
        return bad(c, "size fields (used %u, memory %u) disagree with the %u words present", w[MI_H_USED_WORDS],
                   w[MI_H_MEMORY_WORDS], c->n);
    uint64_t end = 0;
    for (int r = 0; r < MI_REGION_COUNT; r++) {
        c->off[r] = w[MI_H_REGION_TABLE + 2 * r];
        c->len[r] = w[MI_H_REGION_TABLE + 2 * r + 1];
        if (c->off[r] != end || (uint64_t)c->off[r] + c->len[r] > c->n)
            return bad(c, "region %s [%u, +%u) is not contiguous or exceeds the image", mi_region_name((mi_region)r),
                       c->off[r], c->len[r]);
        end = (uint64_t)c->off[r] + c->len[r];
    }
    if (end != c->n || c->len[MI_R_HEADER] != MI_HEADER_WORDS)
        return bad(c, "regions do not cover the image exactly");
    const struct { mi_region r; uint32_t count; uint32_t words; } sized[] = {
        { MI_R_OBJECTS, w[MI_H_OBJECTS], MI_OBJECT_WORDS }, { MI_R_INSTANCES, w[MI_H_INSTANCES], MI_INSTANCE_WORDS },
        { MI_R_MATERIALS, w[MI_H_MATERIALS], MI_MATERIAL_WORDS },
        { MI_R_TOP_NODES, w[MI_H_TOP_NODES], MI_NODE_WORDS }, { MI_R_CAMERA, 1, MI_CAMERA_WORDS },
    };
    for (size_t i = 0; i < sizeof sized / sizeof sized[0]; i++)
        if ((uint64_t)sized[i].count * sized[i].words != c->len[sized[i].r])
            return bad(c, "region %s has %u words for %u records", mi_region_name(sized[i].r), c->len[sized[i].r],
                       sized[i].count);
    /* the lights, then zeros up to a multiple of the triangle record size (the instance table
     * starts on a matrices cache line) */
    const uint64_t lights = (uint64_t)w[MI_H_LIGHTS] * MI_LIGHT_WORDS;
    if (c->len[MI_R_LIGHTS] < lights || c->len[MI_R_LIGHTS] - lights >= MI_TRIANGLE_WORDS)
        return bad(c, "region %s has %u words for %u records", mi_region_name(MI_R_LIGHTS), c->len[MI_R_LIGHTS],
                   w[MI_H_LIGHTS]);
    for (uint64_t k = lights; k < c->len[MI_R_LIGHTS]; k++)
        if (w[c->off[MI_R_LIGHTS] + k] != 0)
            return bad(c, "region %s: padding word %llu is not zero", mi_region_name(MI_R_LIGHTS), (unsigned long long)k);
    if ((uint64_t)w[MI_H_TEXTURES] * MI_TEXTURE_WORDS > c->len[MI_R_TEXTURES])
        return bad(c, "texture table larger than its region");
    if (w[MI_H_MATERIALS] == 0 || w[MI_H_TOP_NODES] == 0)
        return bad(c, "no default material or no top-level root node");
    if (!finite_words(c, MI_H_SCENE_BOUNDS, 6))
        return bad(c, "scene bounds are not finite");
    return 0;
}

/* List entries [first, first + count) of a list of n_list words name existing items. */
static int check_entries(checker *c, const char *what, uint32_t lists, uint32_t n_list, uint32_t first,
                         uint32_t count, uint32_t n_items)
{
    if ((uint64_t)first + count > n_list)
        return bad(c, "%s: list [%u, +%u) exceeds the %u list words", what, first, count, n_list);
    for (uint32_t i = first; i < first + count; i++)
        if (c->w[lists + i] >= n_items)
            return bad(c, "%s: list entry %u names item %u of %u", what, i, c->w[lists + i], n_items);
    return 0;
}

/* A leaf's rope record (before its entries): finite box, ropes naming nodes or MI_NONE. */
static int check_ropes(checker *c, const char *what, uint32_t lists, uint32_t first, uint32_t n_nodes)
{
    if (first < MI_ROPE_WORDS || !finite_words(c, lists + first - MI_ROPE_WORDS, 6))
        return bad(c, "%s: leaf list at %u has no rope record or a non-finite leaf box", what, first);
    for (uint32_t f = 0; f < 6; f++) {
        const uint32_t r = c->w[lists + first - MI_ROPE_WORDS + 6 + f];
        if (r != MI_NONE && r >= n_nodes)
            return bad(c, "%s: rope to node %u of %u", what, r, n_nodes);
    }
    return 0;
}

/* Children an inner node stores: one if a side is an empty leaf (compact trees), else two. */
static uint32_t stored_children(uint32_t w0) { return (w0 >> 2 & 3u) ? 1u : 2u; }

/* An inner node: its stored children after it and in range; at most one side an empty leaf that
 * is not stored, and none with ropes (their records name every leaf). */
static int check_inner(checker *c, const char *what, uint32_t i, uint32_t w0, uint32_t n_nodes)
{
    const uint32_t child = w0 >> MI_NODE_CHILD_SHIFT, empty = w0 >> 2 & 3u;
    const uint32_t stored = stored_children(w0);
    if (empty == (MI_NODE_EMPTY_LO | MI_NODE_EMPTY_HI) || (empty && !(c->accel & MI_TREES_COMPACT)))
        return bad(c, "%s: node %u marks both sides or, in trees that are not compact, a side as empty (0x%X)", what,
                   i, w0);
    if (child <= i || (uint64_t)child + stored > n_nodes)
        return bad(c, "%s: node %u child index %u is not after the node or out of range", what, i, child);
    return 0;
}

/* Every node but the root has exactly one parent, and no path is deeper than the traversal
 * stack: the nodes form a tree that a walk visits at most once per packet. Children after their
 * parents already rule out cycles, but a corrupted image could share subtrees (a walk of such a
 * graph can take exponentially long) or chain nodes deeper than the stack holds (the stack walker
 * would drop entries and never finish). Parents come before children, so one pass in index order
 * knows each parent's depth before its children's. */
static int check_tree_shape(checker *c, const char *what, uint32_t nodes, uint32_t n_nodes)
{
    uint8_t *parents = calloc(n_nodes, 1), *depth = calloc(n_nodes, 1);
    int rc = parents && depth ? 0 : bad(c, "%s: out of memory checking %u nodes", what, n_nodes);
    for (uint32_t i = 0; i < n_nodes && rc == 0; i++) {
        const uint32_t w0 = c->w[nodes + 2 * i], child = w0 >> MI_NODE_CHILD_SHIFT;
        if (i > 0 && parents[i] != 1)
            rc = bad(c, "%s: node %u has %u parents (a tree node has one)", what, i, parents[i]);
        else if (depth[i] > TRACE_STACK - 1)
            rc = bad(c, "%s: node %u lies deeper than the traversal stack (%d levels)", what, i, TRACE_STACK);
        for (uint32_t k = 0; rc == 0 && (w0 & 3u) != MI_NODE_LEAF && k < stored_children(w0); k++) {
            parents[child + k] += parents[child + k] < 255;
            depth[child + k] = (uint8_t)(depth[i] + 1);
        }
    }
    free(parents);
    free(depth);
    return rc;
}

/* A kd-tree: inner nodes' children after the node and in range, each node but the root the child
 * of one node, finite split planes, leaves' lists in range naming existing items, and with ropes
 * each leaf's rope record. */
static int check_tree(checker *c, const char *what, uint32_t nodes, uint32_t n_nodes, uint32_t lists,
                      uint32_t n_list, uint32_t n_items)
{
    if (n_nodes == 0)
        return bad(c, "%s: empty tree", what);
    for (uint32_t i = 0; i < n_nodes; i++) {
        const uint32_t w0 = c->w[nodes + 2 * i], w1 = c->w[nodes + 2 * i + 1], hi = w0 >> 2;
        if ((w0 & 3u) == MI_NODE_LEAF) {
            if (check_entries(c, what, lists, n_list, w1, hi, n_items) != 0 ||
                ((c->accel & MI_ACCEL_ROPES) && check_ropes(c, what, lists, w1, n_nodes) != 0))
                return -1;
        } else if (check_inner(c, what, i, w0, n_nodes) != 0) {
            return -1;
        } else if (!finite_f24(w1)) {
            return bad(c, "%s: node %u split plane 0x%X is not a finite fp24 value", what, i, w1);
        }
    }
    return check_tree_shape(c, what, nodes, n_nodes);
}

/* A uniform grid at addr inside region r: header, cell table and lists in the region, 1..1023
 * cells per axis, finite numbers, every cell's entries in its list naming existing items. */
static int check_grid(checker *c, const char *what, mi_region r, uint32_t addr, uint32_t n_items)
{
    if (!in_region(c, r, addr, 1, MI_GRID_WORDS) || !finite_words(c, addr, 9))
        return bad(c, "%s: grid header at %u outside region %s or not finite", what, addr, mi_region_name(r));
    const uint32_t *g = c->w + addr;
    uint64_t cells = 1;
    for (int k = 0; k < 3; k++) {
        if (g[MI_G_N + k] == 0 || g[MI_G_N + k] > 1023)
            return bad(c, "%s: grid has %u cells on axis %d (1..1023)", what, g[MI_G_N + k], k);
        cells *= g[MI_G_N + k];
    }
    if (!in_region(c, r, g[MI_G_CELLS], cells, 2) || !in_region(c, r, g[MI_G_LISTS], g[MI_G_N_LIST], 1))
        return bad(c, "%s: grid cells or lists outside region %s", what, mi_region_name(r));
    for (uint64_t i = 0; i < cells; i++) {
        const uint32_t *cell = c->w + g[MI_G_CELLS] + 2 * i;
        if (check_entries(c, what, g[MI_G_LISTS], g[MI_G_N_LIST], cell[0], cell[1], n_items) != 0)
            return -1;
    }
    return 0;
}

/* Octahedral normal k of a normal block: both components in range, or exactly the missing mark. */
static int oct_ok(const uint32_t *normals, uint32_t k)
{
    const int32_t x = shade_rec_oct(normals, k, 0), y = shade_rec_oct(normals, k, 1);
    return (x >= -SHADE_OCT_ONE && y >= -SHADE_OCT_ONE) || (x < -SHADE_OCT_ONE && y == 0);
}

/* A shading record (hls/units/shade_rec.h): normals, material in range, finite texture
 * coordinates, the tail's unused bits zero. */
static int shading_record_ok(const checker *c, uint32_t at, uint32_t flags, uint32_t n_mat)
{
    const uint32_t *tail = c->w + at + shade_rec_tail(flags), tail_words = shade_rec_words(flags) - shade_rec_tail(flags);
    for (uint32_t k = 0; (flags & SHADE_HAS_NORMALS) && k < 3; k++)
        if (!oct_ok(c->w + at, k))
            return 0;
    if ((flags & SHADE_HAS_NORMALS) && c->w[at + SHADE_NORMAL_WORDS - 1] >> (6 * SHADE_OCT_BITS - 96))
        return 0; /* the normal block's last two bits */
    if (shade_rec_material(flags, tail) >= n_mat)
        return 0;
    const uint32_t used = shade_rec_tail_bits(flags);
    if (used % 32u && tail[tail_words - 1] >> (used % 32u))
        return 0;
    const uint32_t sets = (flags & SHADE_HAS_TEXCOORDS) ? ((flags & SHADE_HAS_EMISSIVE_UV) ? 2u : 1u) : 0u;
    for (uint32_t i = 0; i < 6 * sets; i++)
        if (!finite_f24(shade_rec_texcoord(flags, tail, i / 6, i % 6)))
            return 0;
    return 1;
}

static int check_objects(checker *c)
{
    const uint32_t n_mat = c->w[MI_H_MATERIALS];
    for (uint32_t o = 0; o < c->w[MI_H_OBJECTS]; o++) {
        const uint32_t *d = c->w + c->off[MI_R_OBJECTS] + MI_OBJECT_WORDS * o;
        const mi_region r = (d[MI_O_FLAGS] & MI_OBJECT_DYNAMIC) ? MI_R_DYNAMIC_GEOMETRY : MI_R_STATIC_GEOMETRY;
        const uint32_t nt = d[MI_O_N_TRIANGLES];
        char what[48];
        snprintf(what, sizeof what, "object %u", o);
        if (!in_region(c, r, d[MI_O_NODES], d[MI_O_N_NODES], MI_NODE_WORDS) ||
            !in_region(c, r, d[MI_O_LISTS], d[MI_O_N_LIST], 1) ||
            !in_region(c, r, d[MI_O_TRIANGLES], nt, MI_TRIANGLE_WORDS) ||
            !in_region(c, r, d[MI_O_SHADING], nt, shade_rec_words(d[MI_O_FLAGS])))
            return bad(c, "%s: geometry outside region %s", what, mi_region_name(r));
        if (!finite_words(c, c->off[MI_R_OBJECTS] + MI_OBJECT_WORDS * o + MI_O_BOUNDS, 6))
            return bad(c, "%s: bounds are not finite", what);
        const uint32_t known = SHADE_HAS_NORMALS | SHADE_HAS_TEXCOORDS | MI_OBJECT_DYNAMIC | SHADE_ONE_MATERIAL |
                               SHADE_HAS_COLOURS | SHADE_HAS_EMISSIVE_UV;
        if ((d[MI_O_FLAGS] & 0xFFFFu & ~known) ||
            ((d[MI_O_FLAGS] & SHADE_HAS_EMISSIVE_UV) && !(d[MI_O_FLAGS] & SHADE_HAS_TEXCOORDS)) ||
            ((d[MI_O_FLAGS] & SHADE_ONE_MATERIAL) ? shade_rec_material(d[MI_O_FLAGS], NULL) >= n_mat
                                                  : d[MI_O_FLAGS] >> SHADE_OBJ_MATERIAL_SHIFT != 0))
            return bad(c, "%s: bad flags word 0x%X (unknown flags, emissive coordinates without texture coordinates, "
                          "or material not below %u)", what, d[MI_O_FLAGS], n_mat);
        if (check_tree(c, what, d[MI_O_NODES], d[MI_O_N_NODES], d[MI_O_LISTS], d[MI_O_N_LIST], nt) != 0 ||
            ((c->accel & MI_ACCEL_GRID) && check_grid(c, what, r, d[MI_O_GRID], nt) != 0))
            return -1;
        for (uint32_t t = 0; t < nt; t++)
            if (!finite_record(c, d[MI_O_TRIANGLES] + MI_TRIANGLE_WORDS * t, F24_TRIANGLE_VALUES, F24_TRIANGLE_BITS))
                return bad(c, "%s: triangle transformation %u is not finite or has nonzero padding bits", what, t);
        for (uint32_t t = 0; t < nt; t++)
            if (!shading_record_ok(c, d[MI_O_SHADING] + shade_rec_words(d[MI_O_FLAGS]) * t, d[MI_O_FLAGS], n_mat))
                return bad(c, "%s: shading record %u is malformed (normal out of range, material not below %u, "
                              "non-finite texture coordinate or non-zero padding)", what, t, n_mat);
    }
    return 0;
}

/* The instance matrix at w is the identity up to the signs of its zeros: the device may pass the
 * rays through (xform_identity gives the bits the transformation would). */
static int identity_matrix(const uint32_t *w)
{
    const f24_affine m = f24_affine_load(w, 0);
    return xform_is_identity(&m);
}

static int check_records(checker *c)
{
    const uint32_t *w = c->w;
    for (uint32_t i = 0; i < w[MI_H_INSTANCES]; i++) {
        const uint32_t at = c->off[MI_R_INSTANCES] + MI_INSTANCE_WORDS * i;
        if (!finite_words(c, at, 12) || w[at + MI_I_OBJECT] >= w[MI_H_OBJECTS])
            return bad(c, "instance %u: non-finite transformation or object %u of %u", i, w[at + MI_I_OBJECT],
                       w[MI_H_OBJECTS]);
        if ((w[at + MI_I_FLAGS] & ~MI_INST_IDENTITY) ||
            ((w[at + MI_I_FLAGS] & MI_INST_IDENTITY) && !identity_matrix(w + at)))
            return bad(c, "instance %u: bad flags 0x%x (identity flag on a matrix that is not the identity)", i,
                       w[at + MI_I_FLAGS]);
    }
    for (uint32_t i = 0; i < w[MI_H_MATERIALS]; i++) {
        const uint32_t at = c->off[MI_R_MATERIALS] + MI_MATERIAL_WORDS * i;
        const uint32_t flags = w[at + SHADE_M_FLAGS], emissive = w[at + SHADE_M_EMISSIVE_TEXTURE];
        if (!finite_words(c, at, 7) || !finite_words(c, at + 9, 3) || !finite_words(c, at + 13, 1) ||
            (flags & 3u) > ALPHA_BLEND || (flags & ~(7u | SHADE_MAT_UNLIT)) ||
            (w[at + 7] != MI_NONE && w[at + 7] >= w[MI_H_TEXTURES]) ||
            (emissive != MI_NONE && emissive >= w[MI_H_TEXTURES]))
            return bad(c, "material %u: bad value, flags or texture index", i);
    }
    for (uint32_t i = 0; i < w[MI_H_TEXTURES]; i++) {
        const uint32_t *t = w + c->off[MI_R_TEXTURES] + MI_TEXTURE_WORDS * i;
        const uint64_t table_end = (uint64_t)c->off[MI_R_TEXTURES] + MI_TEXTURE_WORDS * w[MI_H_TEXTURES];
        if (t[0] == 0 || t[1] == 0 || t[2] < table_end || !in_region(c, MI_R_TEXTURES, t[2], (uint64_t)t[0] * t[1], 1))
            return bad(c, "texture %u: %ux%u texels at %u outside the texture region", i, t[0], t[1], t[2]);
    }
    const uint32_t cam = c->off[MI_R_CAMERA];
    if (w[cam] > CAMERA_ORTHOGRAPHIC || w[cam + 1] == 0 || w[cam + 2] == 0 || w[cam + 1] > 65536 ||
        w[cam + 2] > 65536 || !finite_words(c, cam + 4, 12))
        return bad(c, "camera: bad kind, size or non-finite vectors");
    if (check_tree(c, "top level", c->off[MI_R_TOP_NODES], w[MI_H_TOP_NODES], c->off[MI_R_TOP_LISTS],
                   c->len[MI_R_TOP_LISTS], w[MI_H_INSTANCES]) != 0 ||
        ((c->accel & MI_ACCEL_TOP_GRID) &&
         check_grid(c, "top level", MI_R_TOP_GRID, c->off[MI_R_TOP_GRID], w[MI_H_INSTANCES]) != 0))
        return -1;
    mi_profile prof;
    mi_profile_derive(w, &prof);
    if (w[cam + MI_CAM_PROFILE] & ~prof.skip)
        return bad(c, "camera: profile bits 0x%x claim what the scene needs (it allows 0x%x)", w[cam + MI_CAM_PROFILE],
                   prof.skip);
    for (uint32_t i = 0; i < w[MI_H_LIGHTS]; i++) {
        const uint32_t at = c->off[MI_R_LIGHTS] + MI_LIGHT_WORDS * i;
        if (w[at] > LIGHT_SPOT || !finite_words(c, at + 1, 12))
            return bad(c, "light %u: bad kind or non-finite values", i);
    }
    return 0;
}

int mi_validate(const uint32_t *words, uint32_t n_words, char *err, size_t errlen)
{
    checker c = { .w = words, .n = n_words, .err = err, .errlen = errlen };
    if (!words)
        return bad(&c, "no image");
    if (check_header(&c) != 0 || check_objects(&c) != 0 || check_records(&c) != 0)
        return -1;
    return 0;
}
