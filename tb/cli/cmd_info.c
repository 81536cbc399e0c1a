/*
 * saarcor info SCENE: what the host makes of a scene: objects, instances, triangles (and the
 * degenerate ones dropped), kd-tree statistics of both levels, build times, and the memory image
 * region by region. With --frames N it also steps the animation and reports the bytes each frame
 * uploads; --validate runs the image validator; --json writes the figures.
 */
#define _GNU_SOURCE
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "interrupt.h"
#include "scene_opts.h"
#include "shade_rec.h"

typedef struct {
    uint32_t frames;
    double fps;
    const char *json, *image_out;
} info_opts;

static void print_tree(const char *name, uint32_t nodes, uint32_t leaves, uint32_t empty, uint32_t depth,
                       uint64_t refs, double sah)
{
    const uint32_t full = leaves - empty;
    printf("%-12s nodes %u, leaves %u (%u empty), depth %u, references %llu (%.2f per non-empty leaf), "
           "SAH cost %.2f\n", name, nodes, leaves, empty, depth, (unsigned long long)refs,
           full ? (double)refs / full : 0.0, sah);
}

/* Words of the geometry regions by record type, summed over the object descriptors. */
enum { REC_NODES, REC_LISTS, REC_TRIANGLES, REC_SHADING, REC_OTHER, REC_KINDS };
static const char *const rec_names[REC_KINDS] = { "kd_nodes", "lists", "triangle_transformations", "shading_records",
                                                  "other_geometry" };

static void record_words(const uint32_t *w, const mi_stats *st, uint64_t words[REC_KINDS])
{
    const uint32_t *od = w + w[MI_H_REGION_TABLE + 2 * MI_R_OBJECTS];
    for (int k = 0; k < REC_KINDS; k++)
        words[k] = 0;
    for (uint32_t i = 0; i < w[MI_H_OBJECTS]; i++, od += MI_OBJECT_WORDS) {
        words[REC_NODES] += (uint64_t)MI_NODE_WORDS * od[MI_O_N_NODES];
        words[REC_LISTS] += od[MI_O_N_LIST];
        words[REC_TRIANGLES] += (uint64_t)MI_TRIANGLE_WORDS * od[MI_O_N_TRIANGLES];
        words[REC_SHADING] += (uint64_t)shade_rec_words(od[MI_O_FLAGS]) * od[MI_O_N_TRIANGLES];
    }
    /* grids and the padding before each object's triangle transformations */
    words[REC_OTHER] = (uint64_t)st->region_words[MI_R_STATIC_GEOMETRY] + st->region_words[MI_R_DYNAMIC_GEOMETRY] -
                       words[REC_NODES] - words[REC_LISTS] - words[REC_TRIANGLES] - words[REC_SHADING];
}

static double per_triangle(const mi_stats *st, uint64_t words) { return st->triangles ? 4.0 * (double)words / st->triangles : 0.0; }

/* What the host merged into world-space objects (--merge, host/memimage/mi_merge.h) and why the
 * other instances kept their own object. */
static void print_merge(const mi_stats *st, int merge)
{
    if (!merge) {
        printf("merged       nothing (every mesh instance is its own object; --merge bakes static, axis-aligned ones)\n");
        return;
    }
    printf("merged       %u instances into %u world-space object(s) (%llu triangles of baked copies); kept: "
           "%u animated, %u deforming (morphed, skinned), %u mirrored, %u turned, %u instanced copies beyond the memory budget\n",
           st->merged_instances, st->merged_objects, (unsigned long long)st->merged_copy_triangles, st->kept_animated,
           st->kept_morphing, st->kept_mirrored, st->kept_turned, st->kept_instanced);
}

/* The line of a scene whose image is larger than the device memory (built in the largest one). */
static void print_fit(const scene_opts *o, uint32_t n_words)
{
    printf("fits         no: the image needs %.2f MB, more than the %.2f MB device memory; render it with --mem-mb %u\n",
           n_words * 4.0 / 1048576.0, (double)o->mi.memory_bytes / 1048576.0, scene_mem_mb_for(n_words));
}

static void print_report(const scene *s, const mi_builder *b, const scene_opts *o, int fits)
{
    const mi_stats *st = mi_get_stats(b);
    uint64_t inst_tris = 0;
    for (uint32_t i = 0; i < s->n_instances; i++)
        inst_tris += s->meshes[s->instances[i].mesh].n_triangles;
    printf("scene        %s\n", o->scene);
    printf("objects      %u (meshes), instances %u, triangles %u unique / %llu instanced, degenerate dropped %u\n",
           st->objects, st->instances, st->triangles, (unsigned long long)inst_tris, st->degenerate_triangles);
    printf("content      %u materials, %u textures, %u cameras, %u lights, %u animations, %u skins, %u nodes, %u warnings\n",
           s->n_materials, s->n_textures, s->n_cameras, s->n_lights, s->n_animations, s->n_skins, s->n_nodes, s->warnings);
    print_merge(st, o->mi.merge);
    print_tree("bottom level", st->bottom_nodes, st->bottom_leaves, st->bottom_empty_leaves, st->bottom_depth,
               st->bottom_references, st->triangles ? st->bottom_sah / st->triangles : 0.0);
    print_tree("top level", st->top_nodes, st->top_leaves, st->top_empty_leaves, st->top_depth, st->top_references,
               st->top_sah);
    printf("build        triangle transformations %.3f s, bottom-level trees %.3f s, top-level tree %.3f ms\n",
           st->transform_seconds, st->bottom_build_seconds, 1e3 * st->top_build_seconds);
    uint32_t n_words;
    const uint32_t *w = mi_words(b, &n_words);
    printf("memory image %.3f MB of %.1f MB (%.1f%%), %.1f bytes per unique triangle (all regions)\n",
           n_words * 4.0 / 1048576.0, (double)o->mi.memory_bytes / 1048576.0,
           100.0 * n_words * 4.0 / (double)o->mi.memory_bytes, per_triangle(st, n_words));
    if (!fits)
        print_fit(o, n_words);
    for (int r = 0; r < MI_REGION_COUNT; r++)
        printf("  %-17s %10u words %10.1f KB %8.1f B/triangle\n", mi_region_name((mi_region)r), st->region_words[r],
               st->region_words[r] * 4.0 / 1024.0, per_triangle(st, st->region_words[r]));
    uint64_t rec[REC_KINDS];
    record_words(w, st, rec);
    printf("geometry by record type, bytes per unique triangle:");
    for (int k = 0; k < REC_KINDS; k++)
        printf("%s %s %.1f", k ? "," : "", rec_names[k], per_triangle(st, rec[k]));
    printf("\n");
}

/* A JSON string: the names come from the file and may hold anything. */
static void json_string(FILE *f, const char *str)
{
    fputc('"', f);
    for (const unsigned char *c = (const unsigned char *)str; *c; c++)
        fprintf(f, *c == '"' || *c == '\\' ? "\\%c" : *c < 0x20 ? "\\u%04x" : "%c", *c);
    fputc('"', f);
}

static int write_json(const char *path, const scene_opts *o, const scene *s, const mi_builder *b,
                      const double *upload, uint32_t frames)
{
    const mi_stats *st = mi_get_stats(b);
    uint32_t n_words;
    uint64_t rec[REC_KINDS];
    record_words(mi_words(b, &n_words), st, rec);
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fprintf(f, "{\n  \"scene\": \"%s\", \"objects\": %u, \"instances\": %u, \"triangles\": %u, \"degenerate\": %u,\n",
            o->scene, st->objects, st->instances, st->triangles, st->degenerate_triangles);
    fprintf(f, "  \"bottom\": {\"nodes\": %u, \"leaves\": %u, \"empty_leaves\": %u, \"depth\": %u, \"references\": %llu, "
               "\"build_seconds\": %.6f},\n", st->bottom_nodes, st->bottom_leaves, st->bottom_empty_leaves,
            st->bottom_depth, (unsigned long long)st->bottom_references, st->bottom_build_seconds);
    fprintf(f, "  \"top\": {\"nodes\": %u, \"leaves\": %u, \"empty_leaves\": %u, \"depth\": %u, \"references\": %llu, "
               "\"sah\": %.4f, \"build_seconds\": %.6f},\n", st->top_nodes, st->top_leaves, st->top_empty_leaves,
            st->top_depth, (unsigned long long)st->top_references, st->top_sah, st->top_build_seconds);
    fprintf(f, "  \"merged\": {\"objects\": %u, \"instances\": %u, \"copy_triangles\": %llu, \"kept_animated\": %u, "
               "\"kept_morphing\": %u, \"kept_mirrored\": %u, \"kept_turned\": %u, \"kept_instanced\": %u},\n",
            st->merged_objects, st->merged_instances, (unsigned long long)st->merged_copy_triangles, st->kept_animated,
            st->kept_morphing, st->kept_mirrored, st->kept_turned, st->kept_instanced);
    fprintf(f, "  \"transform_seconds\": %.6f,\n  \"regions\": {", st->transform_seconds);
    for (int r = 0; r < MI_REGION_COUNT; r++)
        fprintf(f, "%s\"%s\": %u", r ? ", " : "", mi_region_name((mi_region)r), st->region_words[r]);
    fprintf(f, "},\n  \"image_bytes\": %llu, \"device_memory_bytes\": %llu, \"fits\": %s, \"mem_mb_needed\": %u,",
            4ull * n_words, (unsigned long long)o->mi.memory_bytes, 4ull * n_words <= o->mi.memory_bytes ? "true" : "false",
            scene_mem_mb_for(n_words));
    fprintf(f, "\n  \"bytes_per_triangle\": {\"total\": %.4f", per_triangle(st, n_words));
    for (int k = 0; k < REC_KINDS; k++)
        fprintf(f, ", \"%s\": %.4f", rec_names[k], per_triangle(st, rec[k]));
    fprintf(f, "},\n  \"ignored_features\": [");
    for (uint32_t i = 0; i < s->n_ignored; i++) {
        fputs(i ? ", " : "", f);
        json_string(f, s->ignored[i]);
    }
    fprintf(f, "],\n  \"frame_upload_bytes\": [");
    for (uint32_t i = 0; i < frames; i++)
        fprintf(f, "%s%.0f", i ? ", " : "", upload[i]);
    fprintf(f, "]\n}\n");
    return fclose(f);
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Steps the animation over `frames` frames and reports the upload per frame. */
static int run_frames(scene *s, mi_builder *b, const scene_opts *o, const info_opts *io, double *upload)
{
    char err[512];
    uint32_t rebuilt = 0;
    for (uint32_t f = 0; f < io->frames; f++) {
        if (interrupt_signal()) /* Ctrl-C: between frames, before the report and --json */
            return interrupt_exit("info", "frames not reported");
        if (scene_evaluate(s, o->time + (f + 1) / io->fps, 1) != 0 || mi_update(b, s, err, sizeof err) != 0) {
            cli_error("info", "frame %u: %s", f + 1, err);
            return SAARCOR_EXIT_INTERNAL;
        }
        upload[f] = (double)mi_get_stats(b)->frame_upload_bytes;
        rebuilt += mi_get_stats(b)->rebuilt_objects;
    }
    double *sorted = malloc(io->frames * sizeof *sorted);
    if (!sorted)
        return SAARCOR_EXIT_INTERNAL;
    for (uint32_t f = 0; f < io->frames; f++)
        sorted[f] = upload[f];
    qsort(sorted, io->frames, sizeof *sorted, cmp_double);
    printf("frames       %u at %.0f fps: upload per frame min %.1f KB, median %.1f KB, max %.1f KB; "
           "deforming (morphed, skinned) objects rebuilt %u times\n", io->frames, io->fps, sorted[0] / 1024.0,
           sorted[io->frames / 2] / 1024.0, sorted[io->frames - 1] / 1024.0, rebuilt);
    free(sorted);
    return SAARCOR_EXIT_OK;
}

static int usage(void)
{
    printf("usage: saarcor info SCENE [options]\n\n"
           "Loads a scene, builds its kd-trees and memory image, and prints objects, instances,\n"
           "triangles (degenerate ones dropped), tree statistics of both levels, build times and the\n"
           "memory image region by region.\n\n"
           "  --frames N      step the animation N frames and report bytes uploaded per frame\n"
           "  --fps F         frame rate for --frames (default 30)\n"
           "  --validate      check the memory image with the validator\n"
           "  --json FILE     write the figures as JSON\n"
           "  --image FILE    write the memory image (little-endian 32-bit words)\n"
           "  --traversal A   the image for render --traversal A (ropes, grid and grid2 add their\n"
           "                  structures; default stack)\n\n%s", SCENE_OPTIONS_HELP);
    return SAARCOR_EXIT_OK;
}

int cmd_info(int argc, char **argv)
{
    static const struct option opts[] = {
        SCENE_LONG_OPTIONS, SCENE_KD_DEPTH_ALIAS, { "frames", required_argument, NULL, 'f' }, { "fps", required_argument, NULL, 'r' },
        { "validate", no_argument, NULL, 'v' }, { "json", required_argument, NULL, 'j' },
        { "image", required_argument, NULL, 'i' }, { "traversal", required_argument, NULL, 'T' },
        { "help", no_argument, NULL, 'h' }, { 0, 0, 0, 0 }
    };
    scene_opts o;
    info_opts io = { 0, 30.0, NULL, NULL };
    int validate = 0, c;
    scene_opts_default(&o);
    optind = 0;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        uint64_t v;
        const int r = c >= SCENE_OPT_BASE ? scene_opts_parse(&o, "info", c, optarg) : 0;
        if (r < 0)
            return SAARCOR_EXIT_USAGE;
        if (r > 0)
            continue;
        switch (c) {
        case 'f':
            if (!cli_parse_u64(optarg, 1, 1u << 30, &v)) /* limit frames: after the options */
                return cli_usage_error("info", "bad --frames '%s'", optarg);
            io.frames = (uint32_t)v;
            break;
        case 'r':
            if (!cli_parse_double(optarg, &io.fps) || io.fps <= 0 || io.fps > 1e4)
                return cli_usage_error("info", "bad --fps '%s'", optarg);
            break;
        case 'v': validate = 1; break;
        case 'j': io.json = optarg; break;
        case 'i': io.image_out = optarg; break;
        case 'T':
            if (scene_opts_traversal(&o, "info", optarg) < 0)
                return SAARCOR_EXIT_USAGE;
            break;
        case 'h': return usage();
        default: return cli_bad_option("info", argc, argv);
        }
    }
    if (argc - optind != 1)
        return cli_usage_error("info", "expected one SCENE");
    if (limit_check(&o.lim, "info", LIMIT_FRAMES, io.frames, "--frames") != SAARCOR_EXIT_OK)
        return SAARCOR_EXIT_LIMIT;
    if (cli_parse_only)
        return SAARCOR_EXIT_OK;
    o.scene = argv[optind];
    if (io.frames && interrupt_catch() != 0)
        cli_error("info", "cannot catch SIGINT/SIGTERM: Ctrl-C will not stop cleanly");

    scene s;
    int rc = scene_opts_load(&o, "info", &s);
    if (rc != SAARCOR_EXIT_OK)
        return rc;
    char err[512];
    int fits;
    mi_builder *b = scene_opts_build(&o, "info", &s, &fits, &rc); /* one too large for the device: reported */
    if (!b) {
        scene_free(&s);
        return rc;
    }
    print_report(&s, b, &o, fits);
    uint32_t n_words;
    const uint32_t *w = mi_words(b, &n_words);
    if (validate) {
        if (mi_validate(w, n_words, err, sizeof err) != 0) {
            printf("validate     FAILED: %s\n", err);
            rc = SAARCOR_EXIT_FAIL;
        } else {
            printf("validate     ok\n");
        }
    }
    if (io.image_out) {
        FILE *f = fopen(io.image_out, "wb");
        if (!f || fwrite(w, 4, n_words, f) != n_words || fclose(f) != 0) {
            cli_error("info", "cannot write '%s'", io.image_out);
            rc = SAARCOR_EXIT_INPUT;
        }
    }
    double *upload = calloc(io.frames + 1, sizeof *upload);
    if (!upload)
        rc = SAARCOR_EXIT_INTERNAL;
    if (rc == SAARCOR_EXIT_OK && io.frames)
        rc = run_frames(&s, b, &o, &io, upload);
    if (rc == SAARCOR_EXIT_OK && io.json && write_json(io.json, &o, &s, b, upload, io.frames) != 0) {
        cli_error("info", "cannot write '%s'", io.json);
        rc = SAARCOR_EXIT_INPUT;
    }
    free(upload);
    mi_free(b);
    scene_free(&s);
    return rc;
}
