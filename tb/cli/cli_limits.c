/* Hard limits of scene, tree, image and animation sizes: see cli_limits.h and docs/limits.md. */
#include "cli_limits.h"

#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "rgs.h"

typedef struct {
    const char *name;
    uint64_t def, ceiling; /* default; the most --limit may set */
} limit_info;

/* Defaults and ceilings: docs/limits.md says why. */
static const limit_info info[LIMIT_COUNT] = {
    [LIMIT_TRIANGLES] = { "triangles", 1u << 24, 1u << 28 },
    [LIMIT_INSTANCES] = { "instances", 1u << 20, SCENE_MAX_INSTANCES },
    [LIMIT_KD_NODES] = { "kd-nodes", 1u << 25, 1u << 28 },
    [LIMIT_KD_DEPTH] = { "kd-depth", 48, 64 },
    [LIMIT_TEXTURE_SIZE] = { "texture-size", 8192, SCENE_MAX_TEXTURE_SIDE },
    [LIMIT_RAY_DEPTH] = { "ray-depth", RGS_MAX_DEPTH, RGS_MAX_DEPTH },
    [LIMIT_WIDTH] = { "width", 16384, 65536 },
    [LIMIT_HEIGHT] = { "height", 16384, 65536 },
    [LIMIT_FRAMES] = { "frames", 100000, 1000001 },
};

void limits_default(limits *l)
{
    for (int i = 0; i < LIMIT_COUNT; i++)
        l->value[i] = info[i].def;
}

int limits_parse(limits *l, const char *cmd, const char *arg)
{
    const char *eq = strchr(arg, '=');
    for (int i = 0; eq && i < LIMIT_COUNT; i++) {
        if (strlen(info[i].name) != (size_t)(eq - arg) || strncmp(arg, info[i].name, (size_t)(eq - arg)) != 0)
            continue;
        uint64_t v;
        if (!cli_parse_u64(eq + 1, 1, info[i].ceiling, &v)) {
            cli_usage_error(cmd, "bad --limit '%s' (%s is 1..%llu)", arg, info[i].name,
                            (unsigned long long)info[i].ceiling);
            return 0;
        }
        l->value[i] = v;
        return 1;
    }
    cli_usage_error(cmd, "bad --limit '%s' (expected NAME=N; names: triangles, instances, kd-nodes, kd-depth, "
                         "texture-size, ray-depth, width, height, frames)", arg);
    return 0;
}

int limit_check(const limits *l, const char *cmd, limit_id id, uint64_t value, const char *what)
{
    if (value <= l->value[id])
        return SAARCOR_EXIT_OK;
    if (value > info[id].ceiling)
        cli_error(cmd, "limit %s exceeded: %s is %llu, the limit is %llu (at most %llu in this build)", info[id].name,
                  what, (unsigned long long)value, (unsigned long long)l->value[id],
                  (unsigned long long)info[id].ceiling);
    else
        cli_error(cmd, "limit %s exceeded: %s is %llu, the limit is %llu (raise it with --limit %s=N, up to %llu)",
                  info[id].name, what, (unsigned long long)value, (unsigned long long)l->value[id], info[id].name,
                  (unsigned long long)info[id].ceiling);
    return SAARCOR_EXIT_LIMIT;
}

int limits_check_scene(const limits *l, const char *cmd, const scene *s, uint32_t extra)
{
    uint64_t triangles = 0;
    for (uint32_t i = 0; i < s->n_meshes; i++)
        triangles += s->meshes[i].n_triangles;
    int rc = limit_check(l, cmd, LIMIT_TRIANGLES, triangles, "the scene's triangle count");
    if (rc == SAARCOR_EXIT_OK)
        rc = limit_check(l, cmd, LIMIT_INSTANCES, (uint64_t)scene_count_instances(s) + extra,
                         "the scene's instance count");
    for (uint32_t i = 0; i < s->n_textures && rc == SAARCOR_EXIT_OK; i++) {
        const scene_texture *t = &s->textures[i];
        const uint64_t side = (uint64_t)(t->width > t->height ? t->width : t->height);
        rc = limit_check(l, cmd, LIMIT_TEXTURE_SIZE, side, "a texture's width or height");
    }
    return rc;
}

int limits_check_params(const limits *l, const char *cmd, const mi_params *p)
{
    int rc = limit_check(l, cmd, LIMIT_WIDTH, p->width, "the image width");
    if (rc == SAARCOR_EXIT_OK)
        rc = limit_check(l, cmd, LIMIT_HEIGHT, p->height, "the image height");
    if (rc == SAARCOR_EXIT_OK)
        rc = limit_check(l, cmd, LIMIT_KD_DEPTH, p->bottom.max_depth, "--kd-max-depth");
    return rc;
}

int limits_check_depth(const limits *l, const char *cmd, const mi_params *p, const scene *s)
{
    uint64_t largest = 0, all = 0;
    for (uint32_t i = 0; i < s->n_instances; i++) {
        const uint64_t n = s->meshes[s->instances[i].mesh].n_triangles;
        largest = n > largest ? n : largest;
        all += n;
    }
    const uint64_t objects = p->merge ? all : largest; /* a merged object holds the copies of many */
    const uint32_t bottom = kd_depth_bound(&p->bottom, objects > UINT32_MAX ? UINT32_MAX : (uint32_t)objects);
    const uint32_t top = kd_depth_bound(&p->top, s->n_instances);
    return limit_check(l, cmd, LIMIT_KD_DEPTH, bottom > top ? bottom : top,
                       "the depth the kd-tree builder may reach (--kd-max-depth, or automatic: 8 + 1.3 log2 N)");
}

int limits_check_build(const limits *l, const char *cmd, const mi_stats *st)
{
    const uint32_t depth = st->bottom_depth > st->top_depth ? st->bottom_depth : st->top_depth;
    return limit_check(l, cmd, LIMIT_KD_DEPTH, depth, "the kd-tree depth");
}
