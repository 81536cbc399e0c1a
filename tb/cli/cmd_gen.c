/*
 * gen subcommand: build a procedural scene (scenes/) and write it as glTF.
 *   saarcor gen NAME -o FILE [--seed S] [--detail N]
 *   saarcor gen --list
 */
#define _GNU_SOURCE
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "scene.h"
#include "scenes.h"

static void list_generators(FILE *out)
{
    for (unsigned i = 0; i < scene_generator_count; i++)
        fprintf(out, "%-10s %s\n", scene_generators[i].name, scene_generators[i].summary);
}

int cmd_gen(int argc, char **argv)
{
    static const struct option opts[] = {
        { "output", required_argument, NULL, 'o' }, { "seed", required_argument, NULL, 's' },
        { "detail", required_argument, NULL, 'd' }, { "list", no_argument, NULL, 'l' },
        { "help", no_argument, NULL, 'h' }, { 0, 0, 0, 0 }
    };
    scene_gen_params gp = { 1, 0 };
    const char *path = NULL;
    int list = 0, c;
    uint64_t v;
    optind = 0;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "o:s:d:lh", opts, NULL)) != -1) {
        switch (c) {
        case 'o': path = optarg; break;
        case 's':
            if (!cli_parse_u64(optarg, 0, UINT64_MAX, &gp.seed))
                return cli_usage_error("gen", "bad --seed '%s'", optarg);
            break;
        case 'd':
            if (!cli_parse_u64(optarg, 0, UINT32_MAX, &v))
                return cli_usage_error("gen", "bad --detail '%s'", optarg);
            gp.detail = (uint32_t)v;
            break;
        case 'l': list = 1; break;
        case 'h':
            printf("usage: saarcor gen NAME -o FILE [--seed S] [--detail N]\n"
                   "       saarcor gen --list\n\n"
                   "Builds a procedural scene and writes it as glTF 2.0: FILE.glb (binary) or FILE.gltf\n"
                   "(JSON with embedded buffers). The scene is the same for the same seed (default 1).\n"
                   "--detail sets a generator's size (0 = default): the number of plants for 'plants',\n"
                   "the cells per side of the height field for 'terrain'; the others ignore it.\n"
                   "Prints the scene's counts. Generators:\n");
            list_generators(stdout);
            return SAARCOR_EXIT_OK;
        default: return cli_bad_option("gen", argc, argv);
        }
    }
    if (list) {
        if (optind != argc)
            return cli_usage_error("gen", "unexpected argument '%s'", argv[optind]);
        if (cli_parse_only)
            return SAARCOR_EXIT_OK;
        list_generators(stdout);
        return SAARCOR_EXIT_OK;
    }
    if (argc - optind != 1)
        return cli_usage_error("gen", argc - optind ? "expected one generator name" : "missing generator name");
    if (cli_parse_only)
        return SAARCOR_EXIT_OK;
    const char *name = argv[optind];
    const scene_generator *g = scene_generator_find(name);
    if (!g) {
        char known[256] = "";
        for (unsigned i = 0; i < scene_generator_count; i++)
            snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", i ? ", " : "", scene_generators[i].name);
        return cli_usage_error("gen", "unknown generator '%s' (one of: %s)", name, known);
    }
    if (!path)
        return cli_usage_error("gen", "missing -o FILE");

    scene s;
    char err[512];
    if (g->build(&s, &gp, err, sizeof err) != 0) {
        cli_error("gen", "%s: %s", name, err);
        return strstr(err, "out of memory") ? SAARCOR_EXIT_INTERNAL : SAARCOR_EXIT_USAGE;
    }
    uint64_t tris = 0, inst_tris = 0;
    for (uint32_t i = 0; i < s.n_meshes; i++)
        tris += s.meshes[i].n_triangles;
    for (uint32_t i = 0; i < s.n_instances; i++)
        inst_tris += s.meshes[s.instances[i].mesh].n_triangles;
    if (scene_write_gltf(&s, path, err, sizeof err) != 0) {
        cli_error("gen", "%s", err);
        scene_free(&s);
        return SAARCOR_EXIT_INPUT;
    }
    struct stat st;
    const long long bytes = stat(path, &st) == 0 ? (long long)st.st_size : -1;
    printf("%s (seed %llu): %u objects, %llu triangles (%llu in the scene), %u instances, %u nodes, "
           "%u materials, %u textures, %u cameras, %u lights, %u animations -> %s (%lld bytes)\n",
           name, (unsigned long long)gp.seed, s.n_meshes, (unsigned long long)tris, (unsigned long long)inst_tris,
           s.n_instances, s.n_nodes, s.n_materials, s.n_textures, s.n_cameras, s.n_lights, s.n_animations, path, bytes);
    scene_free(&s);
    return SAARCOR_EXIT_OK;
}
