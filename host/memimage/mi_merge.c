/* Static geometry merged into world-space objects: see mi_merge.h. */
#define _GNU_SOURCE /* qsort_r */
#include "mi_merge.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Nodes an animation moves: targeted by a translation, rotation or scale channel, or below one. */
static uint8_t *animated_nodes(const scene *s)
{
    uint8_t *moved = calloc((size_t)s->n_nodes + 1, 1), *out = calloc((size_t)s->n_nodes + 1, 1);
    if (!moved || !out) {
        free(moved);
        free(out);
        return NULL;
    }
    for (uint32_t a = 0; a < s->n_animations; a++)
        for (uint32_t c = 0; c < s->animations[a].n_channels; c++) {
            const scene_channel *ch = &s->animations[a].channels[c];
            if (ch->path != ANIM_WEIGHTS && ch->node < s->n_nodes)
                moved[ch->node] = 1;
        }
    for (uint32_t i = 0; i < s->n_nodes; i++) {
        uint32_t steps = 0; /* parents bounded by the node count: no cycle can loop */
        for (int p = (int)i; p >= 0 && steps <= s->n_nodes && !out[i]; p = s->nodes[p].parent, steps++)
            out[i] = moved[p];
    }
    free(moved);
    return out;
}

static double det3(const affine *a)
{
    const double(*m)[4] = a->m;
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* The linear part maps the axes onto the axes (scales, mirror-free 90-degree turns): the mesh's
 * axis-aligned planes stay axis-aligned in world space, so a world-space tree separates its
 * triangles as well as its own tree does. A turned instance keeps its object-space tree: baking
 * it would cut slanted faces with axis-aligned planes (the cornell boxes: 10 triangles per leaf
 * in world space, 2 in their own space). */
static int axis_aligned(const affine *a)
{
    for (int r = 0; r < 3; r++) {
        int nonzero = 0;
        double big = 0;
        for (int c = 0; c < 3; c++)
            big = fmax(big, fabs(a->m[r][c]));
        for (int c = 0; c < 3; c++)
            nonzero += fabs(a->m[r][c]) > 1e-12 * big;
        if (nonzero != 1)
            return 0;
    }
    return 1;
}

typedef struct {
    uint32_t mesh, copies; /* an instanced mesh and its static copies */
} copy_candidate;

static int by_size(const void *a, const void *b, void *s)
{
    const scene *sc = s;
    const uint32_t na = sc->meshes[((const copy_candidate *)a)->mesh].n_triangles;
    const uint32_t nb = sc->meshes[((const copy_candidate *)b)->mesh].n_triangles;
    return (na > nb) - (na < nb);
}

/* Which instances are baked (bake[i] for scene instance i), with the counts info reports. */
static int plan(const scene *s, uint8_t *bake, mi_merge *m)
{
    uint8_t *animated = animated_nodes(s);
    uint32_t *eligible = calloc((size_t)s->n_meshes + 1, sizeof *eligible);
    uint32_t *uses = calloc((size_t)s->n_meshes + 1, sizeof *uses);
    copy_candidate *cand = calloc((size_t)s->n_meshes + 1, sizeof *cand);
    int rc = animated && eligible && uses && cand ? 0 : -1;
    for (uint32_t i = 0; rc == 0 && i < s->n_instances; i++) {
        const scene_instance *in = &s->instances[i];
        const scene_mesh *me = &s->meshes[in->mesh];
        uses[in->mesh]++;
        m->animated_instances += animated[in->node] != 0;
        m->morphing_instances += !animated[in->node] && scene_mesh_deforms(me);
        const int static_ok = !animated[in->node] && !scene_mesh_deforms(me) && me->n_triangles > 0;
        m->mirrored_instances += static_ok && !(det3(&in->world) > 0);
        m->turned_instances += static_ok && det3(&in->world) > 0 && !axis_aligned(&in->world);
        bake[i] = static_ok && det3(&in->world) > 0 && axis_aligned(&in->world);
        eligible[in->mesh] += bake[i];
    }
    /* instanced meshes: copies of the smallest first, within the budget of the unique triangles */
    uint64_t unique = 0, added = 0;
    uint32_t n_cand = 0;
    for (uint32_t k = 0; rc == 0 && k < s->n_meshes; k++) {
        unique += s->meshes[k].n_triangles;
        if (uses[k] > 1 && eligible[k] > 0)
            cand[n_cand++] = (copy_candidate){ k, eligible[k] };
    }
    if (rc == 0)
        qsort_r(cand, n_cand, sizeof *cand, by_size, (void *)s);
    for (uint32_t c = 0; rc == 0 && c < n_cand; c++) {
        const uint64_t n = s->meshes[cand[c].mesh].n_triangles;
        /* the copies replace the object only if every instance of the mesh is baked */
        const uint64_t cost = n * cand[c].copies - (cand[c].copies == uses[cand[c].mesh] ? n : 0);
        const int keep = added + cost > unique;
        if (!keep)
            added += cost;
        m->baked_copy_triangles = added;
        for (uint32_t i = 0; keep && i < s->n_instances; i++)
            if (s->instances[i].mesh == cand[c].mesh && bake[i]) {
                bake[i] = 0;
                m->instanced_kept++;
            }
    }
    free(animated);
    free(eligible);
    free(uses);
    free(cand);
    return rc;
}

/* Normals go through the inverse transpose of the linear part (cofactor matrix / det: only the
 * direction matters, and det > 0 for every baked instance). */
static void normal_matrix(const affine *w, double n[3][3])
{
    const double(*a)[4] = w->m;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            n[r][c] = a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1];
        }
}

static void bake_normal(const double nm[3][3], const float *in, float *out)
{
    double v[3], len = 0;
    for (int r = 0; r < 3; r++) {
        v[r] = nm[r][0] * in[0] + nm[r][1] * in[1] + nm[r][2] * in[2];
        len += v[r] * v[r];
    }
    len = len > 0 && isfinite(len) ? 1.0 / sqrt(len) : 0.0; /* a zero normal stays zero: "none" */
    for (int r = 0; r < 3; r++)
        out[r] = (float)(v[r] * len);
}

/* Appends scene instance i (mesh me) to merged mesh out at vertex vbase and triangle tbase. */
/* Copies the n vertices of attribute src (dim floats each; NULL: the attribute's default fill)
 * into the merged mesh's dst (NULL: the merged mesh has none) from vertex vbase on. */
static void copy_attribute(float *dst, const float *src, size_t dim, uint32_t vbase, uint32_t n, float fill)
{
    for (size_t i = 0; dst && i < dim * n; i++)
        dst[dim * vbase + i] = src ? src[i] : fill;
}

static void append_instance(const scene *s, uint32_t i, scene_mesh *out, uint32_t vbase, uint32_t tbase,
                            uint32_t *src_inst, uint32_t *src_tri)
{
    const scene_instance *in = &s->instances[i];
    const scene_mesh *me = &s->meshes[in->mesh];
    double nm[3][3];
    normal_matrix(&in->world, nm);
    for (uint32_t v = 0; v < me->n_vertices; v++) {
        const double p[3] = { me->positions[3 * (size_t)v], me->positions[3 * (size_t)v + 1],
                              me->positions[3 * (size_t)v + 2] };
        double q[3];
        affine_apply_point(&in->world, p, q);
        for (int k = 0; k < 3; k++)
            out->positions[3 * ((size_t)vbase + v) + (size_t)k] = (float)q[k];
        if (out->normals && me->normals)
            bake_normal(nm, &me->normals[3 * (size_t)v], &out->normals[3 * ((size_t)vbase + v)]);
    }
    copy_attribute(out->texcoords, me->texcoords, 2, vbase, me->n_vertices, 0.0f);
    copy_attribute(out->texcoords1, me->texcoords1, 2, vbase, me->n_vertices, 0.0f);
    copy_attribute(out->colours, me->colours, 3, vbase, me->n_vertices, 1.0f); /* glTF: no COLOR_0 is white */
    for (uint32_t t = 0; t < me->n_triangles; t++) {
        for (int k = 0; k < 3; k++)
            out->indices[3 * ((size_t)tbase + t) + (size_t)k] = vbase + me->indices[3 * (size_t)t + (size_t)k];
        out->material[tbase + t] = me->material[t];
        src_inst[tbase + t] = i;
        src_tri[tbase + t] = t;
    }
}

/* The merged object a mesh goes to: 1 if it has no texture coordinates but a material with a
 * texture (the device textures the triangles of an object with texture coordinates), else 0:
 * meshes without texture coordinates whose materials have no texture join the others with
 * zeros, which the device never reads for them. */
static int class_of(const scene *s, const scene_mesh *me)
{
    if (me->texcoords || me->texcoords1)
        return 0;
    for (uint32_t t = 0; t < me->n_triangles; t++)
        if (me->material[t] < s->n_materials && (s->materials[me->material[t]].base_color_texture != SCENE_NONE ||
                                                 s->materials[me->material[t]].emissive_texture != SCENE_NONE))
            return 1;
    return 0;
}

/* Builds merged mesh cls from the baked instances of that class. */
static int build_class(const scene *s, const uint8_t *bake, int cls, mi_merge *m)
{
    uint64_t nv = 0, nt = 0;
    int normals = 0, texcoords = 0, texcoords1 = 0, colours = 0;
    for (uint32_t i = 0; i < s->n_instances; i++) {
        const scene_mesh *me = &s->meshes[s->instances[i].mesh];
        if (!bake[i] || class_of(s, me) != cls)
            continue;
        nv += me->n_vertices;
        nt += me->n_triangles;
        normals |= me->normals != NULL;
        texcoords |= me->texcoords != NULL;
        texcoords1 |= me->texcoords1 != NULL;
        colours |= me->colours != NULL;
    }
    if (nt == 0)
        return 0;
    if (nv > UINT32_MAX / 4 || nt > UINT32_MAX / 4)
        return -1;
    scene_mesh *out = &m->meshes[m->n_meshes];
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "static world geometry%s", cls ? " (no texture coordinates)" : "");
    out->n_vertices = (uint32_t)nv;
    out->n_triangles = (uint32_t)nt;
    out->positions = malloc(3 * nv * sizeof(float) + 1);
    out->normals = normals ? calloc(3 * nv + 1, sizeof(float)) : NULL;
    out->texcoords = texcoords ? calloc(2 * nv + 1, sizeof(float)) : NULL;
    out->texcoords1 = texcoords1 ? calloc(2 * nv + 1, sizeof(float)) : NULL;
    out->colours = colours ? calloc(3 * nv + 1, sizeof(float)) : NULL;
    out->indices = malloc(3 * nt * sizeof(uint32_t) + 1);
    out->material = malloc(nt * sizeof(uint32_t) + 1);
    uint32_t *si = malloc(nt * sizeof *si + 1), *st = malloc(nt * sizeof *st + 1);
    m->src_instance[m->n_meshes] = si;
    m->src_triangle[m->n_meshes] = st;
    m->n_meshes++; /* owned from here on: mi_merge_free releases a partial mesh */
    if (!out->positions || (normals && !out->normals) || (texcoords && !out->texcoords) ||
        (texcoords1 && !out->texcoords1) || (colours && !out->colours) || !out->indices || !out->material || !si || !st)
        return -1;
    uint32_t vb = 0, tb = 0;
    for (uint32_t i = 0; i < s->n_instances; i++) {
        const scene_mesh *me = &s->meshes[s->instances[i].mesh];
        if (!bake[i] || class_of(s, me) != cls)
            continue;
        append_instance(s, i, out, vb, tb, si, st);
        vb += me->n_vertices;
        tb += me->n_triangles;
        m->baked_instances++;
    }
    return 0;
}

int mi_merge_build(const scene *s, int enabled, mi_merge *out)
{
    memset(out, 0, sizeof *out);
    out->meshes = calloc(MI_MERGE_CLASSES, sizeof *out->meshes);
    out->src_instance = calloc(MI_MERGE_CLASSES, sizeof *out->src_instance);
    out->src_triangle = calloc(MI_MERGE_CLASSES, sizeof *out->src_triangle);
    out->baked_node = calloc((size_t)s->n_nodes + 1, 1);
    uint8_t *bake = calloc((size_t)s->n_instances + 1, 1);
    int rc = out->meshes && out->src_instance && out->src_triangle && out->baked_node && bake ? 0 : -1;
    if (rc == 0 && enabled)
        rc = plan(s, bake, out);
    for (int cls = 0; rc == 0 && enabled && cls < MI_MERGE_CLASSES; cls++)
        rc = build_class(s, bake, cls, out);
    for (uint32_t i = 0; rc == 0 && i < s->n_instances; i++)
        out->baked_node[s->instances[i].node] |= bake[i];
    free(bake);
    return rc;
}

void mi_merge_free(mi_merge *m)
{
    for (uint32_t k = 0; k < m->n_meshes; k++) {
        free(m->meshes[k].positions);
        free(m->meshes[k].normals);
        free(m->meshes[k].texcoords);
        free(m->meshes[k].texcoords1);
        free(m->meshes[k].colours);
        free(m->meshes[k].indices);
        free(m->meshes[k].material);
        free(m->src_instance[k]);
        free(m->src_triangle[k]);
    }
    free(m->meshes);
    free(m->src_instance);
    free(m->src_triangle);
    free(m->baked_node);
    memset(m, 0, sizeof *m);
}
