/*
 * saarcor compare-hits SCENE: per primary ray, the hit of the hardware units (RGS primary rays +
 * trace_packet on the memory image, fp24) against the double-precision reference's (own BVH,
 * watertight test) on the same ray (the units' fp24 ray, read exactly; --camera-rays: the
 * reference's own binary64 ray through the pixel): agreement of the hit triangle (same scene
 * instance and mesh triangle), misses on one side only, and the distributions of the relative
 * distance error and the barycentric error over the rays that hit the same triangle.
 * A disagreement is ambiguous when both answers are right to within the tolerances (distance
 * 1e-4 (t + |o|), barycentric 1e-3): the units' triangle, tested exactly, is met as near as the
 * reference's (a shared edge, a coplanar overlap), or the ray grazes the one triangle's edge (a
 * silhouette). The agreement over the unambiguous rays is the accuracy target (docs/numerics.md).
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
    uint64_t rays, both_miss, same, different, units_only, ref_only, ambiguous;
    double *t_err, *uv_err; /* per same-triangle hit */
    FILE *classes;          /* --classes: one line per pixel whose answers differ */
} hit_stats;

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

#define T_TOLERANCE 1e-4  /* of t + |o| */
#define UV_TOLERANCE 1e-3

/* Ray (o, d) against triangle tri of scene instance si in binary64, not watertight (a judge of
 * the answers, not a renderer): 1 if the plane is met, with t and the barycentrics of A and B. */
static int exact_triangle(const ref_scene *r, uint32_t si, uint32_t tri, const double o[3], const double d[3], double *t,
                          double *u, double *v)
{
    const scene_mesh *m = &r->s->meshes[r->s->instances[si].mesh];
    double oo[3], dd[3], a[3], b[3], c[3], e1[3], e2[3], q[3], p[3], s[3];
    affine_apply_point(&r->w2o[si], o, oo);
    affine_apply_vector(&r->w2o[si], d, dd);
    ref_vertex(m, tri, 0, a);
    ref_vertex(m, tri, 1, b);
    ref_vertex(m, tri, 2, c);
    for (int k = 0; k < 3; k++) {
        e1[k] = a[k] - c[k];
        e2[k] = b[k] - c[k];
        s[k] = oo[k] - c[k];
    }
    cross3(dd, e2, p);
    const double det = dot3(e1, p);
    if (det == 0)
        return 0;
    cross3(s, e1, q);
    *u = dot3(s, p) / det;
    *v = dot3(dd, q) / det;
    *t = dot3(e2, q) / det;
    return 1;
}

static double edge_distance(double u, double v) { return fmin(fmin(u, v), 1 - u - v); }

/* 1 if the units' answer (triangle si/tri, or a miss) and the reference's differ only by what the
 * tolerances allow. */
static int ambiguous(const ref_scene *r, const double o[3], const double d[3], int units_hit, uint32_t si, uint32_t tri,
                     const ref_hit *rh)
{
    const double scale = T_TOLERANCE * sqrt(dot3(o, o));
    double t, u, v;
    if (units_hit && !exact_triangle(r, si, tri, o, d, &t, &u, &v))
        return 0;
    if (units_hit && rh->instance != UINT32_MAX) /* another triangle as near as the reference's */
        return edge_distance(u, v) >= -UV_TOLERANCE && fabs(t - rh->t) <= T_TOLERANCE * rh->t + scale;
    if (units_hit) /* the units graze a triangle the reference misses */
        return edge_distance(u, v) >= -UV_TOLERANCE && edge_distance(u, v) <= UV_TOLERANCE;
    return edge_distance(rh->u, rh->v) <= UV_TOLERANCE; /* the units miss a graze */
}

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double quantile(const double *v, uint64_t n, double q)
{
    return n ? v[(uint64_t)fmin((double)n - 1, floor(q * (double)n))] : NAN;
}

/* One ray (o, d) of pixel (x, y): the units' hit h (image indices) against the reference's. */
static void tally(const mi_builder *b, const ref_scene *rs, const double o[3], const double d[3], uint32_t x, uint32_t y,
                  const hit_record *h, const ref_hit *r, hit_stats *st)
{
    st->rays++;
    const int uh = h->instance != TRACE_NO_HIT, rh = r->instance != UINT32_MAX;
    uint32_t si = UINT32_MAX, tri = UINT32_MAX;
    if (uh)
        mi_hit_source(b, h->instance, h->triangle, &si, &tri);
    if (!uh || !rh || si != r->instance || tri != r->triangle) {
        st->both_miss += !uh && !rh;
        st->units_only += uh && !rh;
        st->ref_only += rh && !uh;
        st->different += uh && rh;
        const int amb = (uh || rh) && ambiguous(rs, o, d, uh, si, tri, r);
        st->ambiguous += amb;
        if (st->classes && (uh || rh))
            fprintf(st->classes, "%u %u %s\n", x, y, amb ? "ambiguous" : "disagree");
        return;
    }
    const double t = f24_fast_decode(h->t), du = f24_fast_decode(h->u) - r->u, dv = f24_fast_decode(h->v) - r->v;
    st->t_err[st->same] = fabs(t - r->t) / r->t;
    st->uv_err[st->same] = fmax(fabs(du), fabs(dv));
    st->same++;
}

static int compare(const mi_builder *b, const ref_scene *r, const ref_params *p, int camera_rays, hit_stats *st)
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
                if (camera_rays) {
                    ref_primary(&p->cam, x + (uint32_t)(i & 1), y + (uint32_t)(i >> 1), o, d);
                } else {
                    const f24_t ro[3] = { rp.o[i].x, rp.o[i].y, rp.o[i].z }, rd[3] = { rp.d[i].x, rp.d[i].y, rp.d[i].z };
                    for (int k = 0; k < 3; k++) {
                        o[k] = f24_fast_decode(ro[k]);
                        d[k] = f24_fast_decode(rd[k]);
                    }
                }
                ref_intersect(r, o, d, 0, INFINITY, &rh);
                tally(b, r, o, d, x + (uint32_t)(i & 1), y + (uint32_t)(i >> 1), &h[i], &rh, st);
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
    const uint64_t clear = st->rays - st->ambiguous;
    const double agree_clear = clear ? (double)(st->both_miss + st->same) / (double)clear : 1;
    static const double qs[] = { 0.5, 0.9, 0.99, 1.0 };
    printf("compare-hits %s: %llu primary rays\n", scene_name, (unsigned long long)st->rays);
    printf("  agreement (same triangle or both miss) %.4f%%, %.4f%% of the %llu unambiguous rays\n", 100 * agree,
           100 * agree_clear, (unsigned long long)clear);
    printf("  both miss %llu, same triangle %llu, different triangle %llu, units only %llu, reference only %llu "
           "(ambiguous %llu)\n",
           (unsigned long long)st->both_miss, (unsigned long long)st->same, (unsigned long long)st->different,
           (unsigned long long)st->units_only, (unsigned long long)st->ref_only, (unsigned long long)st->ambiguous);
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
    fprintf(json, "{\"scene\": \"%s\", \"rays\": %llu, \"agreement\": %.8f, \"agreement_unambiguous\": %.8f, "
                  "\"ambiguous\": %llu, \"both_miss\": %llu, \"same_triangle\": %llu, "
                  "\"different_triangle\": %llu, \"units_only\": %llu, \"reference_only\": %llu, ",
            scene_name, (unsigned long long)st->rays, agree, agree_clear, (unsigned long long)st->ambiguous,
            (unsigned long long)st->both_miss, (unsigned long long)st->same, (unsigned long long)st->different,
            (unsigned long long)st->units_only, (unsigned long long)st->ref_only);
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
                                          { "camera-rays", no_argument, NULL, 'c' },
                                          { "classes", required_argument, NULL, 'C' },
                                          { "help", no_argument, NULL, 'h' }, { 0, 0, 0, 0 } };
    scene_opts o;
    const char *json_path = NULL, *classes_path = NULL;
    int c, camera_rays = 0;
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
        case 'c': camera_rays = 1; break;
        case 'C': classes_path = optarg; break;
        case 'h':
            printf("usage: saarcor compare-hits SCENE [--json FILE] [--camera-rays] [--classes FILE] [scene options]\n\n"
                   "Traces every pixel's primary ray through the hardware units (fp24) and with the\n"
                   "double-precision reference (own BVH, watertight test) and reports the agreement of\n"
                   "the hit triangle (same instance and mesh triangle, or both miss), also over the rays\n"
                   "whose answers are not ambiguous (both right within distance 1e-4 (t + |o|) and\n"
                   "barycentric 1e-3: shared edges, coplanar overlaps, grazes), the rays only one side\n"
                   "hits, and the relative t error and barycentric error (max |du|, |dv|) over the rays\n"
                   "that hit the same triangle (median, p90, p99, max). Both trace the units' fp24 ray;\n"
                   "--camera-rays gives the reference its own binary64 ray through the pixel. --classes\n"
                   "writes a line 'x y ambiguous|disagree' for every pixel whose answers differ.\n"
                   "--json writes the same.\n\n%s",
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
    hit_stats st = { 0, 0, 0, 0, 0, 0, 0, malloc(n * sizeof(double)), malloc(n * sizeof(double)), NULL };
    FILE *json = NULL;
    if (!st.t_err || !st.uv_err || ref_params_init(&p, b, &r, 0, 0) != 0) {
        cli_error("compare-hits", "out of memory");
        rc = SAARCOR_EXIT_INTERNAL;
    } else if (classes_path && !(st.classes = fopen(classes_path, "w"))) {
        cli_error("compare-hits", "cannot write '%s'", classes_path);
        rc = SAARCOR_EXIT_INPUT;
        ref_params_free(&p);
    } else {
        rc = compare(b, &r, &p, camera_rays, &st);
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
        if (st.classes && fclose(st.classes) != 0) {
            cli_error("compare-hits", "cannot write '%s'", classes_path);
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
