/*
 * saarcor reference SCENE: the double-precision reference renderer (tb/ref): its own two-level
 * BVH and watertight triangle test in binary64, the shading model of docs/shading.md
 * unquantized. Shares with `saarcor render` only the scene loader, the shading model and the
 * camera, so `saarcor compare` of the two images measures the hardware's arithmetic and
 * algorithms. Host threads take interleaved rows; the image does not depend on their number.
 */
#define _GNU_SOURCE
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "img.h"
#include "interrupt.h"
#include "ref_render.h"
#include "ref_setup.h"
#include "scene_opts.h"
#include "shading_model.h"

/* The AOV channels of `saarcor render --aov` from the reference's primary hits. */
static int write_ref_aov(const char *path, const ref_scene *r, const ref_params *p, const ref_hit *hits)
{
    static const char *const names[] = { "t", "N.X", "N.Y", "N.Z", "node", "triangle", "u", "v" };
    enum { NCH = 8 };
    const uint32_t w = p->cam.width, h = p->cam.height;
    img_t img = { (int)w, (int)h, NCH, calloc((size_t)w * h * NCH, sizeof(float)) };
    if (!img.pixels)
        return -1;
    for (size_t i = 0; i < (size_t)w * h; i++) {
        float *o = &img.pixels[NCH * i];
        if (hits[i].instance == UINT32_MAX) {
            o[0] = INFINITY;
            o[4] = o[5] = -1.0f;
            continue;
        }
        double n[3];
        ref_geometric_normal(r, &hits[i], n);
        o[0] = (float)hits[i].t;
        for (int k = 0; k < 3; k++)
            o[1 + k] = (float)n[k];
        o[4] = (float)r->s->instances[hits[i].instance].node;
        o[5] = (float)hits[i].triangle;
        o[6] = (float)hits[i].u;
        o[7] = (float)hits[i].v;
    }
    char err[256];
    const int rc = img_write_channels(path, &img, names, err, sizeof err);
    if (rc != 0)
        cli_error("reference", "%s", err);
    img_free(&img);
    return rc;
}

static int write_rgb(const char *path, const float *rgb, uint32_t w, uint32_t h, int eight_bit)
{
    img_t img = { (int)w, (int)h, 3, malloc((size_t)w * h * 3 * sizeof(float)) };
    if (!img.pixels)
        return -1;
    for (size_t i = 0; i < (size_t)w * h * 3; i++) /* 8 bits: round(255 x value), docs/shading.md */
        img.pixels[i] = eight_bit ? (float)(floor(255.0 * rgb[i] + 0.5) / 255.0) : rgb[i];
    char err[256];
    const int rc = eight_bit ? img_write(path, &img, err, sizeof err)
                             : img_write_channels(path, &img, (const char *const[]){ "R", "G", "B" }, err, sizeof err);
    if (rc != 0)
        cli_error("reference", "%s", err);
    img_free(&img);
    return rc;
}

static int usage(void)
{
    printf("usage: saarcor reference SCENE [-o ref.exr] [--png FILE] [--aov FILE.exr] [--max-depth D]\n"
           "                         [--no-shadows] [--threads N] [scene options]\n\n"
           "Renders the scene with the double-precision reference: its own two-level BVH and a\n"
           "watertight ray/triangle test in binary64, and the shading model of docs/shading.md\n"
           "unquantized. It shares with `saarcor render` only the scene loader, the shading model and\n"
           "the camera, so the difference of the two images measures the hardware's arithmetic.\n"
           "  -o FILE           float RGB image, each channel clamped to [0, 1] (default ref.exr)\n"
           "  --png FILE        the same rounded to 8 bits as the hardware rounds\n"
           "  --aov FILE.exr    primary hits, the channels of `saarcor render --aov`\n"
           "  --max-depth D     levels of secondary rays, 0..%u (default %u)\n"
           "  --no-shadows      lights are not occluded\n"
           "  --threads N       host threads (default: the number of cores); the image does not depend on it\n\n%s",
           SHADE_MAX_DEPTH, SHADE_DEFAULT_DEPTH, SCENE_OPTIONS_HELP);
    return SAARCOR_EXIT_OK;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int ref_setup(const char *cmd, const scene_opts *o, scene *s, mi_builder **b, ref_scene *r)
{
    if (cli_parse_only) /* the command line fuzzer: stop before loading (callers return this code) */
        return SAARCOR_EXIT_USAGE;
    int rc = scene_opts_load(o, cmd, s);
    if (rc != SAARCOR_EXIT_OK)
        return rc;
    *b = scene_opts_build(o, cmd, s, NULL, &rc); /* for the camera and the default light */
    if (!*b) {
        scene_free(s);
        return rc;
    }
    if (ref_scene_build(r, s) != 0) {
        cli_error(cmd, "out of memory");
        mi_free(*b);
        scene_free(s);
        return SAARCOR_EXIT_INTERNAL;
    }
    return SAARCOR_EXIT_OK;
}

int cmd_reference(int argc, char **argv)
{
    static const struct option opts[] = {
        SCENE_LONG_OPTIONS, { "output", required_argument, NULL, 'o' }, { "png", required_argument, NULL, 'P' },
        { "aov", required_argument, NULL, 'a' }, { "max-depth", required_argument, NULL, 'd' },
        { "no-shadows", no_argument, NULL, 'S' }, { "threads", required_argument, NULL, 't' },
        { "help", no_argument, NULL, 'h' }, { 0, 0, 0, 0 }
    };
    scene_opts o;
    const char *out = "ref.exr", *png = NULL, *aov = NULL;
    const long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    uint32_t threads = ncpu > 0 && ncpu < 256 ? (uint32_t)ncpu : 1, depth = SHADE_DEFAULT_DEPTH;
    int shadows = 1, c;
    scene_opts_default(&o);
    optind = 0;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "o:h", opts, NULL)) != -1) {
        uint64_t v;
        const int r = c >= SCENE_OPT_BASE ? scene_opts_parse(&o, "reference", c, optarg) : 0;
        if (r < 0)
            return SAARCOR_EXIT_USAGE;
        if (r > 0)
            continue;
        switch (c) {
        case 'o': out = optarg; break;
        case 'P': png = optarg; break;
        case 'a': aov = optarg; break;
        case 'S': shadows = 0; break;
        case 'd':
            if (!cli_parse_u64(optarg, 0, 1000000, &v)) /* limit ray-depth: after the options */
                return cli_usage_error("reference", "bad --max-depth '%s'", optarg);
            depth = (uint32_t)v;
            break;
        case 't':
            if (!cli_parse_u64(optarg, 1, 256, &v))
                return cli_usage_error("reference", "bad --threads '%s'", optarg);
            threads = (uint32_t)v;
            break;
        case 'h': return usage();
        default: return cli_bad_option("reference", argc, argv);
        }
    }
    if (argc - optind != 1)
        return cli_usage_error("reference", "expected one SCENE");
    if (limit_check(&o.lim, "reference", LIMIT_RAY_DEPTH, depth, "--max-depth") != SAARCOR_EXIT_OK)
        return SAARCOR_EXIT_LIMIT;
    o.scene = argv[optind];
    o.mi.memory_bytes = SCENE_MAX_MEM_BYTES; /* binary64 on the host: not bound by the device's memory */
    if (!cli_parse_only && interrupt_catch() != 0)
        cli_error("reference", "cannot catch SIGINT/SIGTERM: Ctrl-C will not stop cleanly");
    scene s;
    mi_builder *b;
    ref_scene r;
    char err[600];
    /* before the render, not after it: -o and --aov are written with named channels */
    if (!cli_parse_only &&
        (img_ready_for(out, 0, 1, err, sizeof err) != 0 || img_ready_for(png, 3, 0, err, sizeof err) != 0 ||
         img_ready_for(aov, 0, 1, err, sizeof err) != 0)) {
        cli_error("reference", "%s", err);
        return SAARCOR_EXIT_INTERNAL;
    }
    int rc = ref_setup("reference", &o, &s, &b, &r);
    if (rc != SAARCOR_EXIT_OK)
        return rc;
    ref_params p;
    const uint32_t w = o.mi.width, h = o.mi.height;
    float *rgb = malloc((size_t)w * h * 3 * sizeof *rgb);
    ref_hit *hits = aov ? malloc((size_t)w * h * sizeof *hits) : NULL;
    const double t0 = now();
    const int ready = rgb && (!aov || hits) && ref_params_init(&p, b, &r, depth, shadows) == 0;
    if (ready)
        p.stop = interrupt_signal; /* Ctrl-C: stop at the next row, write nothing */
    const int st = ready ? ref_render_image(&r, &p, threads, rgb, hits) : -1;
    const double secs = now() - t0;
    if (st < 0) {
        cli_error("reference", "out of memory");
        rc = SAARCOR_EXIT_INTERNAL;
    } else if (st > 0) {
        rc = interrupt_exit("reference", "nothing written");
    } else if (write_rgb(out, rgb, w, h, 0) != 0 || (png && write_rgb(png, rgb, w, h, 1) != 0) ||
               (aov && write_ref_aov(aov, &r, &p, hits) != 0)) {
        rc = SAARCOR_EXIT_INPUT;
    } else {
        printf("reference %s: %ux%u in %.3f s (%u threads, binary64, max depth %u%s) -> %s\n", o.scene, w, h, secs,
               threads, depth, shadows ? "" : ", no shadows", out);
    }
    if (ready)
        ref_params_free(&p);
    free(rgb);
    free(hits);
    ref_scene_free(&r);
    mi_free(b);
    scene_free(&s);
    return rc;
}
