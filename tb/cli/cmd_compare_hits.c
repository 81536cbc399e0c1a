/*
 * saarcor compare-hits SCENE: per primary ray, the hit of the hardware units (RGS primary rays +
 * trace_packet on the memory image, fp24) against the double-precision reference's (own BVH,
 * watertight test) on the same pixel: agreement of the hit triangle (same scene instance and
 * mesh triangle), misses on one side only, and the distributions of the relative distance error
 * and the barycentric error over the rays that hit the same triangle.
 */
#define _GNU_SOURCE
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "f24_fast.h"
#include "ref_render.h"
#include "interrupt.h"
#include "ref_setup.h"
#include "rgs.h"
#include "shading_model.h"

typedef struct {
    uint64_t rays, both_miss, same, different, units_only, ref_only;
    double *t_err, *uv_err; /* per same-triangle hit */
} hit_stats;

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double quantile(const double *v, uint64_t n, double q)
{
    return n ? v[(uint64_t)fmin((double)n - 1, floor(q * (double)n))] : NAN;
}

/* One pixel: the units' hit h (image indices) against the reference's. */
static void tally(const mi_builder *b, const hit_record *h, const ref_hit *r,
                  hit_stats *st)
{
    st->rays++;
    const int uh = h->instance != TRACE_NO_HIT, rh = r->instance != UINT32_MAX;
    if (!uh || !rh) {
        st->both_miss += !uh && !rh;
        st->units_only += uh && !rh;
        st->ref_only += rh && !uh;
        return;
    }
    uint32_t si, tri;
    mi_hit_source(b, h->instance, h->triangle, &si, &tri);
    if (si != r->instance || tri != r->triangle) {
        st->different++;
        return;
    }
    const double t = f24_fast_decode(h->t), du = f24_fast_decode(h->u) - r->u, dv = f24_fast_decode(h->v) - r->v;
    st->t_err[st->same] = fabs(t - r->t) / r->t;
    st->uv_err[st->same] = fmax(fabs(du), fabs(dv));
    st->same++;
}

static int compare(const mi_builder *b, const ref_scene *r, const ref_params *p, hit_stats *st)
{
    uint32_t n;
    const uint32_t *mem = mi_words(b, &n);
    char err[512];
    if (mi_validate(mem, n, err, sizeof err) != 0) {
        cli_error("compare-hits", "%s", err);
        return SAARCOR_EXIT_INTERNAL;
    }
    const uint32_t w = p->cam.width, hgt = p->cam.height;
    trace_counters c;
    memset(&c, 0, sizeof c);
    for (uint32_t y = 0; y < hgt; y += 2) {
        if (interrupt_signal()) /* Ctrl-C: at the next block row */
            return interrupt_exit("compare-hits", "nothing written");
        for (uint32_t x = 0; x < w; x += 2) {
            ray_packet rp;
            hit_record h[TRACE_PACKET];
            rgs_primary(mem, x, y, &rp);
            trace_packet(mem, &rp, h, &c);
            for (int i = 0; i < TRACE_PACKET; i++) {
                if (!(rp.active >> i & 1u))
                    continue;
                double o[3], d[3];
                ref_hit rh;
                ref_primary(&p->cam, x + (uint32_t)(i & 1), y + (uint32_t)(i >> 1), o, d);
                ref_intersect(r, o, d, 0, INFINITY, &rh);
                tally(b, &h[i], &rh, st);
            }
        }
    }
    return SAARCOR_EXIT_OK;
}

static void report(const char *scene_name, hit_stats *st, FILE *json)
{
    qsort(st->t_err, st->same, sizeof *st->t_err, by_value);
    qsort(st->uv_err, st->same, sizeof *st->uv_err, by_value);
    const double agree = st->rays ? (double)(st->both_miss + st->same) / (double)st->rays : 1;
    static const double qs[] = { 0.5, 0.9, 0.99, 1.0 };
    printf("compare-hits %s: %llu primary rays\n", scene_name, (unsigned long long)st->rays);
    printf("  agreement (same triangle or both miss) %.4f%%\n", 100 * agree);
    printf("  both miss %llu, same triangle %llu, different triangle %llu, units only %llu, reference only %llu\n",
           (unsigned long long)st->both_miss, (unsigned long long)st->same, (unsigned long long)st->different,
           (unsigned long long)st->units_only, (unsigned long long)st->ref_only);
    printf("  %-26s %12s %12s %12s %12s\n", "same triangle", "median", "p90", "p99", "max");
    printf("  %-26s", "relative t error");
    for (int i = 0; i < 4; i++)
        printf(" %12.3e", quantile(st->t_err, st->same, qs[i]));
    printf("\n  %-26s", "barycentric error");
    for (int i = 0; i < 4; i++)
        printf(" %12.3e", quantile(st->uv_err, st->same, qs[i]));
    printf("\n");
    if (!json)
        return;
    fprintf(json, "{\"scene\": \"%s\", \"rays\": %llu, \"agreement\": %.8f, \"both_miss\": %llu, \"same_triangle\": %llu, "
                  "\"different_triangle\": %llu, \"units_only\": %llu, \"reference_only\": %llu, ",
            scene_name, (unsigned long long)st->rays, agree, (unsigned long long)st->both_miss,
            (unsigned long long)st->same, (unsigned long long)st->different, (unsigned long long)st->units_only,
            (unsigned long long)st->ref_only);
    fprintf(json, "\"t_rel_error\": {\"median\": %.6e, \"p90\": %.6e, \"p99\": %.6e, \"max\": %.6e}, ",
            quantile(st->t_err, st->same, .5), quantile(st->t_err, st->same, .9), quantile(st->t_err, st->same, .99),
            quantile(st->t_err, st->same, 1));
    fprintf(json, "\"uv_error\": {\"median\": %.6e, \"p90\": %.6e, \"p99\": %.6e, \"max\": %.6e}}\n",
            quantile(st->uv_err, st->same, .5), quantile(st->uv_err, st->same, .9),
            quantile(st->uv_err, st->same, .99), quantile(st->uv_err, st->same, 1));
}

int cmd_compare_hits(int argc, char **argv)
{
    static const struct option opts[] = { SCENE_LONG_OPTIONS, { "json", required_argument, NULL, 'j' },
                                          { "help", no_argument, NULL, 'h' }, { 0, 0, 0, 0 } };
    scene_opts o;
    const char *json_path = NULL;
    int c;
    scene_opts_default(&o);
    optind = 0;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        const int r = c >= SCENE_OPT_BASE ? scene_opts_parse(&o, "compare-hits", c, optarg) : 0;
        if (r < 0)
            return SAARCOR_EXIT_USAGE;
        if (r > 0)
            continue;
        switch (c) {
        case 'j': json_path = optarg; break;
        case 'h':
            printf("usage: saarcor compare-hits SCENE [--json FILE] [scene options]\n\n"
                   "Traces every pixel's primary ray through the hardware units (fp24) and with the\n"
                   "double-precision reference (own BVH, watertight test) and reports the agreement of\n"
                   "the hit triangle (same instance and mesh triangle, or both miss), the rays only one\n"
                   "side hits, and the relative t error and barycentric error (max |du|, |dv|) over the\n"
                   "rays that hit the same triangle (median, p90, p99, max). --json writes the same.\n\n%s",
                   SCENE_OPTIONS_HELP);
            return SAARCOR_EXIT_OK;
        default: return cli_bad_option("compare-hits", argc, argv);
        }
    }
    if (argc - optind != 1)
        return cli_usage_error("compare-hits", "expected one SCENE");
    o.scene = argv[optind];
    if (!cli_parse_only && interrupt_catch() != 0)
        cli_error("compare-hits", "cannot catch SIGINT/SIGTERM: Ctrl-C will not stop cleanly");
    scene s;
    mi_builder *b;
    ref_scene r;
    int rc = ref_setup("compare-hits", &o, &s, &b, &r);
    if (rc != SAARCOR_EXIT_OK)
        return rc;
    ref_params p;
    const size_t n = (size_t)o.mi.width * o.mi.height;
    hit_stats st = { 0, 0, 0, 0, 0, 0, malloc(n * sizeof(double)), malloc(n * sizeof(double)) };
    FILE *json = NULL;
    if (!st.t_err || !st.uv_err || ref_params_init(&p, b, &r, 0, 0) != 0) {
        cli_error("compare-hits", "out of memory");
        rc = SAARCOR_EXIT_INTERNAL;
    } else {
        rc = compare(b, &r, &p, &st);
        if (rc == SAARCOR_EXIT_OK && json_path && !(json = fopen(json_path, "w"))) {
            cli_error("compare-hits", "cannot write '%s'", json_path);
            rc = SAARCOR_EXIT_INPUT;
        }
        if (rc == SAARCOR_EXIT_OK)
            report(o.scene, &st, json);
        if (json && fclose(json) != 0) {
            cli_error("compare-hits", "cannot write '%s'", json_path);
            rc = SAARCOR_EXIT_INPUT;
        }
        ref_params_free(&p);
    }
    free(st.t_err);
    free(st.uv_err);
    ref_scene_free(&r);
    mi_free(b);
    scene_free(&s);
    return rc;
}
