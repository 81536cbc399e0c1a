/*
 * Scene model helpers: affine algebra, animation sampling (glTF LINEAR / STEP / CUBICSPLINE,
 * quaternion slerp for rotations), scene evaluation at a time (node hierarchy -> world
 * transforms, morph weights and skins -> positions, instances, cameras, lights) and freeing.
 */
#include "scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

affine affine_identity(void)
{
    affine a = { { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 } } };
    return a;
}

affine affine_mul(const affine *a, const affine *b)
{
    affine r;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 4; j++) {
            double v = j == 3 ? a->m[i][3] : 0.0;
            for (int k = 0; k < 3; k++)
                v += a->m[i][k] * b->m[k][j];
            r.m[i][j] = v;
        }
    }
    return r;
}

affine affine_from_trs(const double t[3], const double q[4], const double s[3])
{
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const double r[3][3] = {
        { 1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w) },
        { 2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w) },
        { 2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y) },
    };
    affine a;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            a.m[i][j] = r[i][j] * s[j];
        a.m[i][3] = t[i];
    }
    return a;
}

int affine_invert(const affine *a, affine *inv)
{
    const double(*m)[4] = a->m;
    const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    if (det == 0.0 || !isfinite(det))
        return 0;
    const double d = 1.0 / det;
    double r[3][3] = {
        { c00 * d, (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * d, (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * d },
        { c01 * d, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * d, (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * d },
        { c02 * d, (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * d, (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * d },
    };
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            inv->m[i][j] = r[i][j];
        inv->m[i][3] = -(r[i][0] * m[0][3] + r[i][1] * m[1][3] + r[i][2] * m[2][3]);
    }
    return 1;
}

void affine_apply_point(const affine *a, const double p[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = a->m[i][0] * p[0] + a->m[i][1] * p[1] + a->m[i][2] * p[2] + a->m[i][3];
    memcpy(out, r, sizeof r);
}

void affine_apply_vector(const affine *a, const double v[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = a->m[i][0] * v[0] + a->m[i][1] * v[1] + a->m[i][2] * v[2];
    memcpy(out, r, sizeof r);
}

/* ---- animation sampling ------------------------------------------------------------------ */

static void normalize4(double q[4])
{
    const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (n > 0)
        for (int i = 0; i < 4; i++)
            q[i] /= n;
}

static void slerp(const float *a, const float *b, double u, double out[4])
{
    double dot = 0, qb[4];
    for (int i = 0; i < 4; i++)
        dot += (double)a[i] * b[i];
    for (int i = 0; i < 4; i++)
        qb[i] = dot < 0 ? -(double)b[i] : (double)b[i]; /* shortest arc */
    dot = fabs(dot);
    double wa = 1 - u, wb = u;
    if (dot < 0.9995) {
        const double th = acos(dot), s = sin(th);
        wa = sin((1 - u) * th) / s;
        wb = sin(u * th) / s;
    }
    for (int i = 0; i < 4; i++)
        out[i] = wa * a[i] + wb * qb[i];
    normalize4(out);
}

/* Samples channel c at time t into out[c->components]. */
static void sample_channel(const scene_channel *c, double t, double *out)
{
    const uint32_t n = c->components, stride = c->interp == INTERP_CUBICSPLINE ? 3 * n : n;
    const uint32_t vo = c->interp == INTERP_CUBICSPLINE ? n : 0; /* value within a key */
    uint32_t k = 0;
    if (c->n_keys == 0)
        return;
    if (t <= c->times[0] || c->n_keys == 1) {
        for (uint32_t i = 0; i < n; i++)
            out[i] = c->values[vo + i];
        if (c->path == ANIM_ROTATION)
            normalize4(out);
        return;
    }
    while (k + 1 < c->n_keys && c->times[k + 1] <= t)
        k++;
    if (k + 1 >= c->n_keys) {
        for (uint32_t i = 0; i < n; i++)
            out[i] = c->values[k * stride + vo + i];
        if (c->path == ANIM_ROTATION)
            normalize4(out);
        return;
    }
    const double t0 = c->times[k], t1 = c->times[k + 1], dt = t1 - t0;
    const double u = dt > 0 ? (t - t0) / dt : 0;
    const float *v0 = &c->values[k * stride], *v1 = &c->values[(k + 1) * stride];
    switch (c->interp) {
    case INTERP_STEP:
        for (uint32_t i = 0; i < n; i++)
            out[i] = v0[vo + i];
        break;
    case INTERP_LINEAR:
        if (c->path == ANIM_ROTATION)
            slerp(v0, v1, u, out);
        else
            for (uint32_t i = 0; i < n; i++)
                out[i] = (1 - u) * v0[i] + u * v1[i];
        break;
    case INTERP_CUBICSPLINE: { /* Hermite: value v, out-tangent b of key k, in-tangent a of k+1 */
        const double u2 = u * u, u3 = u2 * u;
        const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
        for (uint32_t i = 0; i < n; i++)
            out[i] = h00 * v0[n + i] + h10 * dt * v0[2 * n + i] + h01 * v1[n + i] + h11 * dt * v1[i];
        if (c->path == ANIM_ROTATION)
            normalize4(out);
        break;
    }
    }
}

static void apply_animation(scene *s, const scene_animation *a, double t)
{
    for (uint32_t i = 0; i < a->n_channels; i++) {
        const scene_channel *c = &a->channels[i];
        if (c->node >= s->n_nodes)
            continue;
        scene_node *nd = &s->nodes[c->node];
        double v[64];
        if (c->components > 64)
            continue;
        sample_channel(c, t, v);
        switch (c->path) {
        case ANIM_TRANSLATION: memcpy(nd->translation, v, sizeof nd->translation); break;
        case ANIM_ROTATION: memcpy(nd->rotation, v, sizeof nd->rotation); break;
        case ANIM_SCALE: memcpy(nd->scale, v, sizeof nd->scale); break;
        case ANIM_WEIGHTS:
            if (nd->weights && nd->n_weights == c->components)
                memcpy(nd->weights, v, c->components * sizeof(double));
            break;
        }
        if (c->path != ANIM_WEIGHTS)
            nd->has_matrix = 0; /* glTF: animated nodes use TRS */
    }
}

/* ---- evaluation -------------------------------------------------------------------------- */

static affine node_local(const scene_node *n)
{
    return n->has_matrix ? n->matrix : affine_from_trs(n->translation, n->rotation, n->scale);
}

int scene_mesh_deforms(const scene_mesh *m) { return m->n_targets > 0 || m->joints != NULL; }

/* A mesh with a usable skin: drawn with its joints' matrices. */
static int mesh_skinned(const scene *s, const scene_mesh *m)
{
    return m->joints && m->joint_weights && m->base_positions && m->skin < s->n_skins;
}

/* Takes the node's morph weights; 1 if they changed. */
static int take_weights(scene_mesh *m, const double *w)
{
    int changed = 0;
    for (uint32_t k = 0; k < m->n_targets; k++)
        if ((float)w[k] != m->weights[k]) {
            m->weights[k] = (float)w[k];
            changed = 1;
        }
    return changed;
}

/* Rest position of vertex v: base + sum_k w_k * delta_k (the base alone without morph targets). */
static void rest_position(const scene_mesh *m, uint32_t v, double p[3])
{
    const size_t n = 3 * (size_t)m->n_vertices;
    for (int c = 0; c < 3; c++) {
        const size_t i = 3 * (size_t)v + (size_t)c;
        p[c] = m->base_positions[i];
        for (uint32_t k = 0; k < m->n_targets; k++)
            p[c] += (double)m->weights[k] * m->target_deltas[k * n + i];
    }
}

/* Stores a vertex's new value; 1 if it differs from the old one. */
static int store3(float *dst, const double v[3])
{
    int changed = 0;
    for (int c = 0; c < 3; c++) {
        changed |= dst[c] != (float)v[c];
        dst[c] = (float)v[c];
    }
    return changed;
}

/* Positions = the rest positions. Returns 1 if the geometry changed. */
static int morph_mesh(scene_mesh *m)
{
    int changed = 0;
    for (uint32_t v = 0; v < m->n_vertices; v++) {
        double p[3];
        rest_position(m, v, p);
        changed |= store3(&m->positions[3 * (size_t)v], p);
    }
    return changed;
}

/* The skin matrix of vertex v: sum_i w_i * jointMatrix(joint_i), the weights scaled to sum 1
 * (quantized weights rarely sum to exactly 1); the identity for a vertex without weight. */
static affine skin_matrix(const scene_mesh *m, const affine *joint, uint32_t n_joints, uint32_t v)
{
    affine r = { { { 0 } } };
    double sum = 0;
    for (int i = 0; i < 4; i++) {
        const uint32_t j = m->joints[4 * (size_t)v + (size_t)i];
        const double w = m->joint_weights[4 * (size_t)v + (size_t)i];
        if (j >= n_joints || !(w > 0))
            continue;
        sum += w;
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 4; b++)
                r.m[a][b] += w * joint[j].m[a][b];
    }
    if (!(sum > 0))
        return affine_identity();
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 4; b++)
            r.m[a][b] /= sum;
    return r;
}

/* A normal moves with the inverse transpose of the skin matrix (kept if it is singular). */
static void skin_normal(const affine *k, const float *n, double out[3])
{
    affine inv;
    double len = 0;
    for (int a = 0; a < 3; a++) {
        out[a] = n[a];
        len += (double)n[a] * n[a];
    }
    if (len == 0 || !affine_invert(k, &inv))
        return;
    len = 0;
    for (int a = 0; a < 3; a++) {
        out[a] = inv.m[0][a] * n[0] + inv.m[1][a] * n[1] + inv.m[2][a] * n[2];
        len += out[a] * out[a];
    }
    for (int a = 0; a < 3 && len > 0; a++)
        out[a] /= sqrt(len);
}

/* Linear blend skinning (glTF 2.0, skins): world-space positions and normals from the rest pose
 * and the joints' current world transforms. 1 if the geometry changed, -1 if memory ran out. */
static int skin_mesh(const scene *s, scene_mesh *m)
{
    const scene_skin *sk = &s->skins[m->skin];
    affine *joint = malloc(((size_t)sk->n_joints + 1) * sizeof *joint);
    if (!joint)
        return -1;
    for (uint32_t j = 0; j < sk->n_joints; j++)
        joint[j] = sk->joints[j] < s->n_nodes ? affine_mul(&s->nodes[sk->joints[j]].world, &sk->inverse_bind[j])
                                              : affine_identity();
    int changed = 0;
    for (uint32_t v = 0; v < m->n_vertices; v++) {
        const affine k = skin_matrix(m, joint, sk->n_joints, v);
        double p[3], n[3];
        rest_position(m, v, p);
        affine_apply_point(&k, p, p);
        changed |= store3(&m->positions[3 * (size_t)v], p);
        if (m->normals && m->bind_normals) {
            skin_normal(&k, &m->bind_normals[3 * (size_t)v], n);
            store3(&m->normals[3 * (size_t)v], n); /* normals change only with the positions */
        }
    }
    free(joint);
    return changed;
}

/* Morphs and skins the mesh of instance node nd; a changed geometry bumps its revision.
 * 0, or -1 if memory ran out. */
static int deform_mesh(const scene *s, const scene_node *nd, scene_mesh *m)
{
    const int morphed = m->n_targets > 0 && nd->weights && nd->n_weights == m->n_targets &&
                        take_weights(m, nd->weights);
    const int changed = mesh_skinned(s, m) ? skin_mesh(s, m) : morphed ? morph_mesh(m) : 0;
    if (changed < 0)
        return -1;
    m->revision += (uint32_t)changed;
    return 0;
}

/* A node is displayed if the root of its hierarchy is one of the scene's roots. */
static int node_displayed(const scene *s, uint32_t i)
{
    uint32_t steps = 0;
    while (s->nodes[i].parent >= 0 && steps++ < s->n_nodes)
        i = (uint32_t)s->nodes[i].parent;
    for (uint32_t r = 0; r < s->n_roots; r++)
        if (s->roots[r] == i)
            return 1;
    return 0;
}

static int is_instance(const scene *s, uint32_t i)
{
    const scene_node *nd = &s->nodes[i];
    return nd->mesh != SCENE_NONE && nd->mesh < s->n_meshes && node_displayed(s, i);
}

/* The instances node i draws: one per EXT_mesh_gpu_instancing row, else one. */
static uint32_t node_instances(const scene *s, uint32_t i)
{
    return is_instance(s, i) ? (s->nodes[i].rows ? s->nodes[i].n_rows : 1) : 0;
}

uint32_t scene_count_instances(const scene *s)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->n_nodes; i++)
        n += node_instances(s, i);
    return n;
}

int scene_evaluate(scene *s, double t, int loop)
{
    const uint32_t n_instances = scene_count_instances(s); /* the same for every t */
    if (!s->instances && n_instances) {
        s->instances = calloc(n_instances, sizeof *s->instances);
        if (!s->instances)
            return -1;
    }
    for (uint32_t i = 0; i < s->n_animations; i++) {
        const scene_animation *a = &s->animations[i];
        double ta = loop && a->duration > 0 ? fmod(t, a->duration) : t;
        if (ta < 0 && loop && a->duration > 0)
            ta += a->duration;
        apply_animation(s, a, ta);
    }
    /* nodes are in file order, not parent-first: walk each node's parents (bounded by n) */
    for (uint32_t i = 0; i < s->n_nodes; i++) {
        affine w = node_local(&s->nodes[i]);
        uint32_t steps = 0;
        for (int p = s->nodes[i].parent; p >= 0 && steps < s->n_nodes; p = s->nodes[p].parent, steps++) {
            const affine lp = node_local(&s->nodes[p]);
            w = affine_mul(&lp, &w);
        }
        s->nodes[i].world = w;
    }
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->n_nodes; i++) {
        const scene_node *nd = &s->nodes[i];
        if (!is_instance(s, i))
            continue;
        scene_mesh *m = &s->meshes[nd->mesh];
        if (deform_mesh(s, nd, m) != 0)
            return -1;
        /* a skinned mesh is placed by its joints alone: the node's transformation is ignored */
        const affine place = mesh_skinned(s, m) ? affine_identity() : nd->world;
        if (!nd->rows)
            s->instances[n++] = (scene_instance){ nd->mesh, i, place };
        for (uint32_t r = 0; nd->rows && r < nd->n_rows; r++)
            s->instances[n++] = (scene_instance){ nd->mesh, i, affine_mul(&place, &nd->rows[r]) };
    }
    s->n_instances = n;
    for (uint32_t i = 0; i < s->n_cameras; i++)
        if (s->cameras[i].node < s->n_nodes)
            s->cameras[i].world = s->nodes[s->cameras[i].node].world;
    for (uint32_t i = 0; i < s->n_lights; i++) {
        scene_light *l = &s->lights[i];
        if (l->node >= s->n_nodes)
            continue;
        const affine *w = &s->nodes[l->node].world;
        const double o[3] = { 0, 0, 0 }, fwd[3] = { 0, 0, -1 };
        affine_apply_point(w, o, l->position);
        affine_apply_vector(w, fwd, l->direction);
        const double len = sqrt(l->direction[0] * l->direction[0] + l->direction[1] * l->direction[1] +
                                l->direction[2] * l->direction[2]);
        for (int k = 0; k < 3 && len > 0; k++)
            l->direction[k] /= len;
    }
    return 0;
}

int scene_texcoord(const scene_mesh *m, uint32_t set, const scene_uv_map *uv, uint32_t v, double st[2])
{
    const float *tc = set == 0 ? m->texcoords : set == 1 ? m->texcoords1 : NULL;
    st[0] = st[1] = 0;
    if (!tc)
        return 0;
    st[0] = tc[2 * (size_t)v];
    st[1] = tc[2 * (size_t)v + 1];
    if (uv->set) { /* translation x rotation x scale, the extension's ratified matrix */
        const double c = cos(uv->rotation), s = sin(uv->rotation), x = uv->scale[0] * st[0], y = uv->scale[1] * st[1];
        st[0] = c * x + s * y + uv->offset[0];
        st[1] = -s * x + c * y + uv->offset[1];
    }
    return 1;
}

static void free_animation(scene_animation *a)
{
    for (uint32_t c = 0; c < a->n_channels; c++) {
        free(a->channels[c].times);
        free(a->channels[c].values);
    }
    free(a->channels);
}

int scene_select_animation(scene *s, const char *which)
{
    char *end;
    const unsigned long index = strtoul(which, &end, 10);
    uint32_t keep = s->n_animations;
    for (uint32_t i = 0; i < s->n_animations && keep == s->n_animations; i++)
        if (strcmp(s->animations[i].name, which) == 0)
            keep = i;
    if (keep == s->n_animations && *which && !*end && index < s->n_animations)
        keep = (uint32_t)index;
    if (keep == s->n_animations)
        return -1;
    for (uint32_t i = 0; i < s->n_animations; i++)
        if (i != keep)
            free_animation(&s->animations[i]);
    s->animations[0] = s->animations[keep];
    s->n_animations = 1;
    return 0;
}

void scene_free(scene *s)
{
    for (uint32_t i = 0; i < s->n_meshes; i++) {
        scene_mesh *m = &s->meshes[i];
        free(m->positions);
        free(m->normals);
        free(m->texcoords);
        free(m->texcoords1);
        free(m->colours);
        free(m->indices);
        free(m->material);
        free(m->base_positions);
        free(m->target_deltas);
        free(m->weights);
        free(m->joints);
        free(m->joint_weights);
        free(m->bind_normals);
    }
    for (uint32_t i = 0; i < s->n_skins; i++) {
        free(s->skins[i].joints);
        free(s->skins[i].inverse_bind);
    }
    free(s->skins);
    for (uint32_t i = 0; i < s->n_nodes; i++) {
        free(s->nodes[i].weights);
        free(s->nodes[i].rows);
    }
    for (uint32_t i = 0; i < s->n_textures; i++)
        free(s->textures[i].rgba);
    for (uint32_t i = 0; i < s->n_animations; i++)
        free_animation(&s->animations[i]);
    free(s->meshes);
    free(s->nodes);
    free(s->materials);
    free(s->textures);
    free(s->cameras);
    free(s->lights);
    free(s->animations);
    free(s->roots);
    free(s->instances);
    free(s->ignored);
    memset(s, 0, sizeof *s);
}

/* World bounds of the evaluated instances; 0 if the scene has no vertex. */
static int world_bounds(const scene *s, double lo[3], double hi[3])
{
    int any = 0;
    for (uint32_t i = 0; i < s->n_instances; i++) {
        const scene_mesh *m = &s->meshes[s->instances[i].mesh];
        for (uint32_t v = 0; v < m->n_vertices; v++) {
            const double p[3] = { m->positions[3 * v], m->positions[3 * v + 1], m->positions[3 * v + 2] };
            double w[3];
            affine_apply_point(&s->instances[i].world, p, w);
            for (int k = 0; k < 3; k++) {
                if (!isfinite(w[k]))
                    continue;
                lo[k] = any ? fmin(lo[k], w[k]) : w[k];
                hi[k] = any ? fmax(hi[k], w[k]) : w[k];
            }
            any = 1;
        }
    }
    return any;
}

/* Grows an array of n elements of size sz by one zeroed element; NULL if memory ran out. */
static void *grow(void *p, uint32_t n, size_t sz)
{
    char *q = realloc(p, (n + 1) * sz);
    if (q)
        memset(q + n * sz, 0, sz);
    return q;
}

int scene_add_ground(scene *s)
{
    double lo[3], hi[3];
    if (!world_bounds(s, lo, hi))
        return 0;
    const double ext = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    const double cx = 0.5 * (lo[0] + hi[0]), cz = 0.5 * (lo[2] + hi[2]), y = lo[1] - 1e-3 * ext, r = 2 * ext;
    scene_material mat = { .base_color = { 0.6f, 0.6f, 0.62f, 1 }, .base_color_texture = SCENE_NONE,
                           .emissive_texture = SCENE_NONE, .metallic = 1, .roughness = 0.2f, .ior = 1.5f };
    scene_mesh mesh = { .name = "ground", .n_vertices = 4, .n_triangles = 2 };
    mesh.positions = malloc(12 * sizeof(float));
    mesh.normals = malloc(12 * sizeof(float));
    mesh.indices = malloc(6 * sizeof(uint32_t));
    mesh.material = malloc(2 * sizeof(uint32_t));
    scene_mesh *meshes = grow(s->meshes, s->n_meshes, sizeof *meshes);
    if (meshes)
        s->meshes = meshes;
    scene_material *mats = grow(s->materials, s->n_materials, sizeof *mats);
    if (mats)
        s->materials = mats;
    scene_camera *cams = s->n_cameras ? s->cameras : grow(s->cameras, 0, sizeof *cams);
    if (cams)
        s->cameras = cams;
    scene_node *nodes = grow(s->nodes, s->n_nodes, sizeof *nodes);
    if (nodes)
        s->nodes = nodes;
    uint32_t *roots = grow(s->roots, s->n_roots, sizeof *roots);
    if (roots)
        s->roots = roots;
    if (!mesh.positions || !mesh.normals || !mesh.indices || !mesh.material || !meshes || !mats || !cams || !nodes || !roots) {
        free(mesh.positions);
        free(mesh.normals);
        free(mesh.indices);
        free(mesh.material);
        return -1;
    }
    static const double corner[4][2] = { { -1, -1 }, { -1, 1 }, { 1, 1 }, { 1, -1 } };
    static const uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 }; /* counter-clockwise seen from above */
    for (int v = 0; v < 4; v++) {
        const float p[3] = { (float)(cx + r * corner[v][0]), (float)y, (float)(cz + r * corner[v][1]) };
        const float n[3] = { 0, 1, 0 };
        memcpy(mesh.positions + 3 * v, p, sizeof p);
        memcpy(mesh.normals + 3 * v, n, sizeof n);
    }
    memcpy(mesh.indices, idx, sizeof idx);
    if (s->n_cameras == 0) /* keep the default view on the scene, not on the ground */
        s->cameras[s->n_cameras++] = scene_default_camera(lo, hi);
    mesh.material[0] = mesh.material[1] = s->n_materials;
    s->materials[s->n_materials++] = mat;
    s->meshes[s->n_meshes] = mesh;
    s->nodes[s->n_nodes] = (scene_node){ .name = "ground", .parent = -1, .mesh = s->n_meshes++, .camera = SCENE_NONE,
                                         .light = SCENE_NONE, .rotation = { 0, 0, 0, 1 }, .scale = { 1, 1, 1 } };
    s->roots[s->n_roots++] = s->n_nodes++;
    free(s->instances); /* sized by the node count: scene_evaluate makes it anew */
    s->instances = NULL;
    return 0;
}

scene_camera scene_default_camera(const double lo[3], const double hi[3])
{
    /* from the front, turned right and raised, as model viewers open a file: a plane at y = 0
     * (or any flat model along an axis) is seen from above, not edge-on */
    const double deg = 3.14159265358979323846 / 180.0, azimuth = 30.0 * deg, elevation = 25.0 * deg;
    const double back[3] = { sin(azimuth) * cos(elevation), sin(elevation), cos(azimuth) * cos(elevation) };
    const double right[3] = { cos(azimuth), 0, -sin(azimuth) }; /* (0,1,0) x back, normalized */
    const double up[3] = { back[1] * right[2] - back[2] * right[1], back[2] * right[0] - back[0] * right[2],
                           back[0] * right[1] - back[1] * right[0] };
    scene_camera c = { 0 };
    c.kind = CAMERA_PERSPECTIVE;
    c.yfov = 45.0 * deg;
    c.node = SCENE_NONE;
    double diag = 0;
    for (int k = 0; k < 3; k++)
        diag += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    const double dist = diag > 0 ? 1.2 * sqrt(diag) : 1.0;
    for (int k = 0; k < 3; k++) { /* camera-to-world: columns right, up, back (it looks down -Z) */
        c.world.m[k][0] = right[k];
        c.world.m[k][1] = up[k];
        c.world.m[k][2] = back[k];
        c.world.m[k][3] = 0.5 * (lo[k] + hi[k]) + dist * back[k];
    }
    return c;
}
