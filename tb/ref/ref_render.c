/* The shading model of docs/shading.md in binary64: see ref_render.h. */
#include "ref_render.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "shading_model.h"

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double clamp01(double x) { return x > 0 ? (x < 1 ? x : 1) : 0; }

static void normalize(double v[3])
{
    const double l = sqrt(dot(v, v));
    for (int k = 0; k < 3 && l > 0; k++)
        v[k] /= l;
}

int ref_params_init(ref_params *p, const mi_builder *b, const ref_scene *r, uint32_t max_depth, int shadows)
{
    memset(p, 0, sizeof *p);
    p->max_depth = max_depth;
    p->shadows = shadows;
    mi_camera_frame(b, r->s, &p->cam);
    p->n_lights = r->s->n_lights ? r->s->n_lights : 1;
    p->lights = malloc(p->n_lights * sizeof *p->lights);
    if (!p->lights)
        return -1;
    if (r->s->n_lights)
        memcpy(p->lights, r->s->lights, p->n_lights * sizeof *p->lights);
    else
        mi_default_light(b, r->s, &p->lights[0]);
    double extent = 0;
    for (int k = 0; k < 3; k++)
        extent = fmax(extent, r->hi[k] - r->lo[k]);
    p->eps = isfinite(extent) ? ldexp(extent, -SHADE_EPS_SHIFT) : 0;
    return 0;
}

void ref_params_free(ref_params *p)
{
    free(p->lights);
    p->lights = NULL;
}

void ref_primary(const mi_camera *c, uint32_t x, uint32_t y, double o[3], double d[3])
{
    const double px = x + 0.5, py = y + 0.5;
    for (int k = 0; k < 3; k++) {
        if (c->orthographic) {
            o[k] = c->o[k] + px * c->u[k] + py * c->v[k];
            d[k] = c->w[k];
        } else {
            o[k] = c->o[k];
            d[k] = c->w[k] + px * c->u[k] + py * c->v[k];
        }
    }
}

/* Transposed 3x3 of the world-to-object matrix applied to an object-space normal. */
static void to_world_normal(const affine *w2o, const double n[3], double out[3])
{
    for (int j = 0; j < 3; j++)
        out[j] = w2o->m[0][j] * n[0] + w2o->m[1][j] * n[1] + w2o->m[2][j] * n[2];
}

static void object_geometric_normal(const scene_mesh *m, uint32_t t, double n[3])
{
    double a[3], b[3], c[3];
    ref_vertex(m, t, 0, a);
    ref_vertex(m, t, 1, b);
    ref_vertex(m, t, 2, c);
    const double e1[3] = { a[0] - c[0], a[1] - c[1], a[2] - c[2] }, e2[3] = { b[0] - c[0], b[1] - c[1], b[2] - c[2] };
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    normalize(n);
}

void ref_geometric_normal(const ref_scene *r, const ref_hit *h, double n[3])
{
    double on[3];
    object_geometric_normal(&r->s->meshes[r->s->instances[h->instance].mesh], h->triangle, on);
    to_world_normal(&r->w2o[h->instance], on, n);
    normalize(n);
}

/* Interpolated vertex attribute (dim components) at barycentrics (u, v) of A, B. */
static void interpolate(const float *attr, int dim, const scene_mesh *m, const ref_hit *h, double out[])
{
    const double w[3] = { h->u, h->v, 1 - h->u - h->v };
    for (int k = 0; k < dim; k++) {
        out[k] = 0;
        for (int j = 0; j < 3; j++)
            out[k] += w[j] * attr[dim * (size_t)m->indices[3 * h->triangle + (uint32_t)j] + (size_t)k];
    }
}

/* Bilinear sample of a texture at (s, t): texel centres at +1/2, repeat wrapping, texels / 255. */
static void sample_bilinear(const scene_texture *tx, double s, double t, double out[3])
{
    const double x = s * tx->width - 0.5, y = t * tx->height - 0.5;
    const double x0 = floor(x), y0 = floor(y), fx = x - x0, fy = y - y0;
    long xi[2], yi[2];
    for (int i = 0; i < 2; i++) {
        xi[i] = (long)fmod(fmod(x0 + i, tx->width) + tx->width, tx->width);
        yi[i] = (long)fmod(fmod(y0 + i, tx->height) + tx->height, tx->height);
    }
    for (int k = 0; k < 3; k++) {
        double c[2][2];
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++)
                c[j][i] = tx->rgba[4 * ((size_t)yi[j] * (size_t)tx->width + (size_t)xi[i]) + (size_t)k] / 255.0;
        out[k] = (c[0][0] * (1 - fx) + c[0][1] * fx) * (1 - fy) + (c[1][0] * (1 - fx) + c[1][1] * fx) * fy;
    }
}

typedef struct {
    double p[3], d[3], n[3]; /* hit point, unit direction, unit shading normal facing the ray */
    int entering;
    const scene_material *mat;
    shading_params sp;
    double base[3], emission[3], tint[3];
} surface;

/* Multiplies c by the bilinear sample of texture t at the hit, read through TEXCOORD_set and map
 * uv, if t is a texture and the mesh has texture coordinates (of any set: the device's rule). */
static void modulate_texture(const ref_scene *r, const scene_mesh *m, const ref_hit *h, uint32_t t, uint32_t set,
                             const scene_uv_map *uv, double c[3])
{
    if (t >= r->s->n_textures || !(m->texcoords || m->texcoords1))
        return;
    const double w[3] = { h->u, h->v, 1 - h->u - h->v };
    double st[2] = { 0, 0 }, tex[3];
    for (uint32_t j = 0; j < 3; j++) {
        double v[2];
        scene_texcoord(m, set, uv, m->indices[3 * h->triangle + j], v);
        st[0] += w[j] * v[0];
        st[1] += w[j] * v[1];
    }
    sample_bilinear(&r->s->textures[t], st[0], st[1], tex);
    for (int k = 0; k < 3; k++)
        c[k] *= tex[k];
}

/* Base colour (factor x vertex colours x texture) and emission (factor x texture) at the hit. */
static void surface_colours(const ref_scene *r, const scene_mesh *m, const ref_hit *h, surface *sf)
{
    const scene_material *mat = sf->mat;
    double rgb[3] = { 1, 1, 1 };
    if (m->colours)
        interpolate(m->colours, 3, m, h, rgb);
    for (int k = 0; k < 3; k++) {
        sf->base[k] = fmax(0, mat->base_color[k]) * rgb[k];
        sf->emission[k] = fmax(0, mat->emissive[k]);
    }
    modulate_texture(r, m, h, mat->base_color_texture, mat->texcoord_set, &mat->base_uv, sf->base);
    modulate_texture(r, m, h, mat->emissive_texture, mat->emissive_texcoord, &mat->emissive_uv, sf->emission);
}

static void surface_at(const ref_scene *r, const double o[3], const double d[3], const ref_hit *h, surface *sf)
{
    const scene_instance *in = &r->s->instances[h->instance];
    const scene_mesh *m = &r->s->meshes[in->mesh];
    double on[3] = { 0, 0, 0 }, gn[3];
    memcpy(sf->d, d, sizeof sf->d);
    normalize(sf->d);
    for (int k = 0; k < 3; k++)
        sf->p[k] = o[k] + h->t * d[k];
    object_geometric_normal(m, h->triangle, gn);
    if (m->normals)
        interpolate(m->normals, 3, m, h, on);
    if (dot(on, on) == 0 || !isfinite(dot(on, on)))
        memcpy(on, gn, sizeof on);
    to_world_normal(&r->w2o[h->instance], on, sf->n);
    if (dot(sf->n, sf->d) >= 0)
        for (int k = 0; k < 3; k++)
            sf->n[k] = -sf->n[k];
    normalize(sf->n);
    double wg[3];
    to_world_normal(&r->w2o[h->instance], gn, wg);
    sf->entering = dot(wg, d) < 0;
    sf->mat = &r->s->materials[m->material[h->triangle] < r->s->n_materials ? m->material[h->triangle] : 0];
    shading_params_of(sf->mat, &sf->sp);
    surface_colours(r, m, h, sf);
    for (int k = 0; k < 3; k++)
        sf->tint[k] = 1 + sf->sp.metallic * (sf->base[k] - 1);
}

static void reflect(const double d[3], const double n[3], double out[3])
{
    const double c = dot(n, d);
    for (int k = 0; k < 3; k++)
        out[k] = d[k] - 2 * c * n[k];
}

/* Refraction of docs/shading.md: eta_r d + mu n, mu = -eta_r c - sqrt(k); 0 on total internal
 * reflection. */
static int refract(const double d[3], const double n[3], double eta_r, double out[3])
{
    const double c = dot(n, d), k = 1 - eta_r * eta_r * (1 - c * c);
    if (k < 0)
        return 0;
    const double mu = -eta_r * c - sqrt(k);
    for (int j = 0; j < 3; j++)
        out[j] = eta_r * d[j] + mu * n[j];
    return 1;
}

/* Diffuse (ambient included) and highlight light at a surface. */
static void gather_light(const ref_scene *r, const ref_params *p, const surface *sf, double diffuse[3], double highlight[3])
{
    const double n_exp = ldexp(1.0, (int)sf->sp.exp_shift);
    double refl[3];
    reflect(sf->d, sf->n, refl);
    for (int k = 0; k < 3; k++) {
        diffuse[k] = sf->sp.unlit ? 1 : SHADE_AMBIENT; /* unlit: kd B alone */
        highlight[k] = 0;
    }
    for (uint32_t li = 0; li < p->n_lights && !sf->sp.unlit; li++) {
        const scene_light *l = &p->lights[li];
        const int directional = l->kind == LIGHT_DIRECTIONAL;
        double L[3], colour[3], m = 0;
        for (int k = 0; k < 3; k++) {
            L[k] = directional ? -l->direction[k] : l->position[k] - sf->p[k];
            colour[k] = (double)l->color[k] * l->intensity;
            m = fmax(m, colour[k]);
        }
        const double dist = sqrt(dot(L, L));
        double w = dot(sf->n, L) / dist;
        if (!(w > 0))
            continue;
        if (l->kind == LIGHT_SPOT) {
            const double c = -dot(l->direction, L) / dist, ci = cos(l->inner_cone), co = cos(l->outer_cone);
            w *= clamp01((c - co) / (ci - co));
        }
        const double diff = SHADE_DIFFUSE * w, spec = pow(fmax(0, dot(refl, L) / dist), n_exp);
        if (!(diff > 0 || spec > 0))
            continue;
        if (p->shadows && ref_occluded(r, sf->p, L, directional ? p->eps : p->eps / dist, directional ? INFINITY : 1))
            continue;
        for (int k = 0; k < 3; k++) {
            const double c = m > 0 ? colour[k] / m : 0;
            diffuse[k] += diff * c;
            highlight[k] += spec * c;
        }
    }
}

static int heavy(const double w[3]) { return fmax(w[0], fmax(w[1], w[2])) >= SHADE_MIN_WEIGHT; }

/* Adds the colour of a ray with weight w to acc (the ray tree, depth first). */
static void shade_ray(const ref_scene *r, const ref_params *p, const double o[3], const double d[3], const double w[3],
                      uint32_t depth, double acc[3], ref_hit *first)
{
    ref_hit h;
    if (!ref_intersect(r, o, d, 0, INFINITY, &h)) {
        for (int k = 0; k < 3; k++)
            acc[k] += w[k] * (double)(SHADE_BACKGROUND >> (16 - 8 * k) & 0xFFu) / 255.0;
        if (first)
            *first = h;
        return;
    }
    if (first)
        *first = h;
    surface sf;
    surface_at(r, o, d, &h, &sf);
    double diffuse[3], highlight[3];
    gather_light(r, p, &sf, diffuse, highlight);
    for (int k = 0; k < 3; k++)
        acc[k] += w[k] * (sf.emission[k] + sf.sp.kd * sf.base[k] * diffuse[k] +
                          sf.sp.ks * sf.tint[k] * highlight[k]);
    if (depth + 1 > p->max_depth)
        return;
    double wr[3], wt[3], back[3], ahead[3], mirror[3], dir[3];
    for (int k = 0; k < 3; k++) {
        wr[k] = w[k] * sf.sp.kr * sf.tint[k];
        wt[k] = w[k] * sf.sp.kt * sf.base[k];
        back[k] = sf.p[k] - p->eps * sf.d[k];
        ahead[k] = sf.p[k] + p->eps * sf.d[k];
    }
    reflect(sf.d, sf.n, mirror);
    if (heavy(wr))
        shade_ray(r, p, back, mirror, wr, depth + 1, acc, NULL);
    if (!heavy(wt))
        return;
    const double eta_r = sf.entering ? 1 / sf.sp.eta : sf.sp.eta;
    if (sf.sp.eta == 1)
        shade_ray(r, p, ahead, sf.d, wt, depth + 1, acc, NULL);
    else if (refract(sf.d, sf.n, eta_r, dir))
        shade_ray(r, p, ahead, dir, wt, depth + 1, acc, NULL);
    else
        shade_ray(r, p, back, mirror, wt, depth + 1, acc, NULL); /* total internal reflection */
}

void ref_pixel(const ref_scene *r, const ref_params *p, uint32_t x, uint32_t y, double rgb[3], ref_hit *hit)
{
    double o[3], d[3];
    const double one[3] = { 1, 1, 1 };
    ref_primary(&p->cam, x, y, o, d);
    rgb[0] = rgb[1] = rgb[2] = 0;
    shade_ray(r, p, o, d, one, 0, rgb, hit);
    for (int k = 0; k < 3; k++)
        rgb[k] = fmin(1, rgb[k]);
}

typedef struct {
    const ref_scene *r;
    const ref_params *p;
    uint32_t thread, threads;
    float *rgb;     /* 3 per pixel */
    ref_hit *hits;  /* per pixel, or NULL */
} ref_job;

static void *ref_rows(void *arg)
{
    const ref_job *j = arg;
    const uint32_t w = j->p->cam.width, h = j->p->cam.height;
    for (uint32_t y = j->thread; y < h && !(j->p->stop && j->p->stop()); y += j->threads)
        for (uint32_t x = 0; x < w; x++) {
            double c[3];
            ref_hit hit;
            ref_pixel(j->r, j->p, x, y, c, &hit);
            for (int k = 0; k < 3; k++)
                j->rgb[3 * ((size_t)y * w + x) + (size_t)k] = (float)c[k];
            if (j->hits)
                j->hits[(size_t)y * w + x] = hit;
        }
    return NULL;
}

int ref_render_image(const ref_scene *r, const ref_params *p, uint32_t threads, float *rgb, ref_hit *hits)
{
    ref_job *jobs = calloc(threads, sizeof *jobs);
    pthread_t *tid = calloc(threads, sizeof *tid);
    if (!jobs || !tid) {
        free(jobs);
        free(tid);
        return -1;
    }
    for (uint32_t t = 0; t < threads; t++) {
        jobs[t] = (ref_job){ r, p, t, threads, rgb, hits };
        if (t > 0 && pthread_create(&tid[t], NULL, ref_rows, &jobs[t]) != 0)
            jobs[t].threads = 0; /* could not start: run below in this thread */
    }
    ref_rows(&jobs[0]);
    for (uint32_t t = 1; t < threads; t++) {
        if (jobs[t].threads)
            pthread_join(tid[t], NULL);
        else {
            jobs[t].threads = threads;
            ref_rows(&jobs[t]);
        }
    }
    free(jobs);
    free(tid);
    return p->stop && p->stop() ? 1 : 0;
}

