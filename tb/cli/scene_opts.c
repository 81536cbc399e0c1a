/* Shared scene/tree options (see scene_opts.h). */
#define _GNU_SOURCE /* strtok_r */
#include "scene_opts.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "f24_double.h"
#include "scenes.h"
#include "trace.h"

void scene_opts_default(scene_opts *o)
{
    memset(o, 0, sizeof *o);
    mi_params_default(&o->mi);
    limits_default(&o->lim);
    o->mi.up[1] = 1.0;
    o->mi.fov_degrees = 45.0;
}

/* "x,y,z" with finite numbers. */
static int vector3(const char *cmd, const char *name, const char *arg, double v[3])
{
    char buf[128], *save = NULL;
    snprintf(buf, sizeof buf, "%s", arg);
    int k = 0;
    for (char *tok = strtok_r(buf, ",", &save); tok && k < 4; tok = strtok_r(NULL, ",", &save), k++)
        if (k < 3 && !cli_parse_double(tok, &v[k]))
            k = 4;
    if (k != 3) {
        cli_usage_error(cmd, "bad --%s '%s' (expected x,y,z)", name, arg);
        return -1;
    }
    return 1;
}

static int number(const char *cmd, const char *name, const char *arg, double lo, double hi, double *out)
{
    if (!cli_parse_double(arg, out) || *out < lo || *out > hi) {
        cli_usage_error(cmd, "bad --%s '%s' (expected %g..%g)", name, arg, lo, hi);
        return -1;
    }
    return 1;
}

static int count(const char *cmd, const char *name, const char *arg, uint64_t lo, uint64_t hi, uint32_t *out)
{
    uint64_t v;
    if (!cli_parse_u64(arg, lo, hi, &v)) {
        cli_usage_error(cmd, "bad --%s '%s' (expected %llu..%llu)", name, arg, (unsigned long long)lo,
                        (unsigned long long)hi);
        return -1;
    }
    *out = (uint32_t)v;
    return 1;
}

int scene_opts_parse(scene_opts *o, const char *cmd, int c, const char *arg)
{
    double d;
    uint32_t u;
    int r;
    switch (c - SCENE_OPT_BASE) {
    case 0:
        if ((r = count(cmd, "mem-mb", arg, 1, 2047, &u)) > 0)
            o->mi.memory_bytes = (uint64_t)u << 20;
        return r;
    case 1:
        if ((r = number(cmd, "ct", arg, 1e-6, 1e6, &d)) > 0)
            o->mi.bottom.cost_traversal = o->mi.top.cost_traversal = d;
        return r;
    case 2:
        if ((r = number(cmd, "ci", arg, 1e-6, 1e6, &d)) > 0)
            o->mi.bottom.cost_intersection = o->mi.top.cost_intersection = d;
        return r;
    case 3:
        if ((r = number(cmd, "empty-bonus", arg, 0, 1, &d)) > 0)
            o->mi.bottom.empty_bonus = o->mi.top.empty_bonus = d;
        return r;
    case 4:
        if ((r = count(cmd, "kd-max-depth", arg, 0, 1000, &u)) > 0) /* limit kd-depth: scene_opts_load */
            o->mi.bottom.max_depth = o->mi.top.max_depth = u;
        return r;
    case 5:
        if ((r = count(cmd, "leaf-size", arg, 1, 1u << 20, &u)) > 0)
            o->mi.bottom.leaf_size = o->mi.top.leaf_size = u;
        return r;
    case 6: return count(cmd, "top-bins", arg, 2, 1024, &o->mi.top.bins);
    case 7: return count(cmd, "width", arg, 1, 1u << 30, &o->mi.width); /* limits: scene_opts_load */
    case 8: return count(cmd, "height", arg, 1, 1u << 30, &o->mi.height);
    case 9: return number(cmd, "time", arg, 0, 1e9, &o->time);
    case 10:
        if ((r = number(cmd, "max-condition", arg, 1, 1e30, &d)) > 0)
            o->mi.max_condition = d;
        return r;
    case 11: return count(cmd, "camera", arg, 0, 1u << 20, &o->mi.camera);
    case 12: o->mi.explicit_view = 1; return vector3(cmd, "eye", arg, o->mi.eye);
    case 13: o->mi.explicit_view = 1; return vector3(cmd, "at", arg, o->mi.at);
    case 14: return vector3(cmd, "up", arg, o->mi.up);
    case 15: return number(cmd, "fov", arg, 1, 179, &o->mi.fov_degrees);
    case 16: o->ground = 1; return 1;
    case 17: o->mi.skip = 0; return 1;
    case 18: return limits_parse(&o->lim, cmd, arg) ? 1 : -1;
    case 19: o->mi.merge = 1; return 1;
    case 20: return number(cmd, "top-ci", arg, 1e-6, 1e6, &o->mi.top.cost_intersection);
    case 21: o->animation = arg; return 1;
    case 22:
        if ((r = count(cmd, "kd-bins", arg, 0, 1024, &u)) > 0 && u == 1) {
            cli_usage_error(cmd, "bad --kd-bins '%s' (expected 0 or 2..1024)", arg);
            return -1;
        }
        if (r > 0) { /* every object's tree, not only the large meshes' (mi_params_default) */
            o->mi.bottom.bins = u;
            o->mi.bottom.bins_from = 0;
        }
        return r;
    default: return 0;
    }
}

int scene_opts_load(const scene_opts *o, const char *cmd, scene *s)
{
    char err[512];
    memset(s, 0, sizeof *s);
    int rc = limits_check_params(&o->lim, cmd, &o->mi);
    if (rc != SAARCOR_EXIT_OK)
        return rc;
    struct stat st;
    if (stat(o->scene, &st) == 0 && S_ISDIR(st.st_mode)) { /* the loader would read it as an empty file */
        cli_error(cmd, "%s: is a directory, not a .gltf/.glb file", o->scene);
        return SAARCOR_EXIT_INPUT;
    }
    const scene_generator *g = access(o->scene, F_OK) != 0 ? scene_generator_find(o->scene) : NULL;
    if (g) {
        const scene_gen_params gp = { 1, 0 };
        if (g->build(s, &gp, err, sizeof err) != 0) {
            cli_error(cmd, "generator %s: %s", o->scene, err);
            scene_free(s);
            return SAARCOR_EXIT_INTERNAL;
        }
    } else if (scene_load_gltf(o->scene, s, err, sizeof err) != 0) {
        cli_error(cmd, "%s", err);
        return SAARCOR_EXIT_INPUT;
    }
    if ((rc = limits_check_scene(&o->lim, cmd, s, (uint32_t)o->ground)) != SAARCOR_EXIT_OK) {
        scene_free(s);
        return rc;
    }
    if (o->animation && scene_select_animation(s, o->animation) != 0) {
        cli_error(cmd, "%s has no animation '%s' (%u animations)", o->scene, o->animation, s->n_animations);
        scene_free(s);
        return SAARCOR_EXIT_USAGE;
    }
    if (scene_evaluate(s, o->time, 1) != 0 ||
        (o->ground && (scene_add_ground(s) != 0 || scene_evaluate(s, o->time, 1) != 0))) {
        cli_error(cmd, "out of memory");
        scene_free(s);
        return SAARCOR_EXIT_INTERNAL;
    }
    return SAARCOR_EXIT_OK;
}

uint32_t scene_mem_mb_for(uint64_t n_words) { return (uint32_t)((n_words * 4 + (1u << 20) - 1) >> 20); }

/* The image of a scene that did not fit p's device memory, in the largest one (NULL if it does not
 * fit there either: err then says why). */
static mi_builder *build_unbound(const mi_params *p, const scene *s, char *err, size_t errlen)
{
    mi_params q = *p;
    if (q.memory_bytes >= SCENE_MAX_MEM_BYTES)
        return NULL;
    q.memory_bytes = SCENE_MAX_MEM_BYTES;
    return mi_build(s, &q, err, errlen);
}

mi_builder *scene_opts_build(const scene_opts *o, const char *cmd, const scene *s, int *fits, int *rc)
{
    char err[512], err2[512];
    if ((*rc = limits_check_depth(&o->lim, cmd, &o->mi, s)) != SAARCOR_EXIT_OK)
        return NULL;
    mi_params p = o->mi;
    p.max_nodes = o->lim.value[LIMIT_KD_NODES]; /* checked as the trees grow */
    mi_failure why;
    mi_builder *b = mi_build_why(s, &p, &why, err, sizeof err);
    if (fits)
        *fits = b != NULL;
    if (!b && why != MI_FAIL_NODE_LIMIT && (b = build_unbound(&p, s, err2, sizeof err2)) != NULL && !fits) {
        uint32_t n;
        mi_words(b, &n);
        cli_error(cmd, "scene does not fit the %.2f MB device memory: the image needs %.2f MB (pass --mem-mb %u)",
                  (double)p.memory_bytes / 1048576.0, n * 4.0 / 1048576.0, scene_mem_mb_for(n));
        mi_free(b);
        *rc = SAARCOR_EXIT_INPUT;
        return NULL;
    }
    if (!b) {
        cli_error(cmd, "%s", err);
        *rc = why == MI_FAIL_NODE_LIMIT ? SAARCOR_EXIT_LIMIT : SAARCOR_EXIT_INPUT;
        return NULL;
    }
    if ((*rc = limits_check_build(&o->lim, cmd, mi_get_stats(b))) != SAARCOR_EXIT_OK) {
        mi_free(b);
        return NULL;
    }
    return b;
}

/* Triangles of one mesh the builder drops although they have an area: over the condition limit,
 * or a transformation entry beyond the fp24 range (the builder's rule, memimage.c object_prepare). */
static void count_drops(const scene_mesh *m, double max_condition, uint64_t *condition, uint64_t *range)
{
    for (uint32_t t = 0; t < m->n_triangles; t++) {
        double v[3][3];
        affine x;
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 3; i++)
                v[k][i] = m->positions[3 * (size_t)m->indices[3 * (size_t)t + (size_t)k] + (size_t)i];
        if (!mi_triangle_transform(v[0], v[1], v[2], INFINITY, &x))
            continue; /* no area: nothing to draw */
        if (!mi_triangle_transform(v[0], v[1], v[2], max_condition, &x)) {
            (*condition)++;
            continue;
        }
        int fits = 1;
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 4; j++)
                fits &= isfinite(x.m[i][j]) && !f24_is_inf(f24_fast_encode(x.m[i][j]));
        *range += (uint64_t)!fits;
    }
}

void scene_opts_warn_dropped(const scene_opts *o, const char *cmd, const scene *s)
{
    uint64_t condition = 0, range = 0;
    char *seen = calloc(s->n_meshes + 1, 1);
    if (!seen)
        return; /* only a warning */
    for (uint32_t i = 0; i < s->n_instances; i++) {
        const uint32_t m = s->instances[i].mesh;
        if (m < s->n_meshes && !seen[m]) {
            seen[m] = 1;
            count_drops(&s->meshes[m], o->mi.max_condition, &condition, &range);
        }
    }
    free(seen);
    if (condition + range)
        fprintf(stderr, "saarcor %s: warning: %llu triangles dropped, fp24 cannot hold them: %llu with a "
                        "transformation beyond its range, %llu over the condition limit %g (--max-condition)\n", cmd,
                (unsigned long long)(condition + range), (unsigned long long)range, (unsigned long long)condition,
                o->mi.max_condition);
}

int scene_opts_traversal(scene_opts *o, const char *cmd, const char *arg)
{
    static const char *const names[TRAV_KINDS] = { "stack", "short-stack", "restart", "push-down", "ropes", "grid",
                                                   "grid2" };
    for (uint32_t k = 0; k < TRAV_KINDS; k++)
        if (strcmp(arg, names[k]) == 0) {
            o->mi.accel = mi_accel_for(k);
            o->mi.traversal = k;
            return (int)k;
        }
    cli_usage_error(cmd, "bad --traversal '%s' (stack, short-stack, restart, push-down, ropes, grid or grid2)", arg);
    return -1;
}
