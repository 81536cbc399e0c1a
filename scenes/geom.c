/* Shared helpers of the scene generators (see geom.h). */
#include "geom.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- random numbers --------------------------------------------------------------------- */

void geom_rng_seed(geom_rng *r, uint64_t seed, uint64_t stream)
{
    r->state = seed * 0x9E3779B97F4A7C15ull ^ (stream + 0x632BE59BD9B4E019ull);
    (void)geom_rng_u64(r);
}

uint64_t geom_rng_u64(geom_rng *r)
{
    uint64_t z = (r->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

double geom_rand(geom_rng *r)
{
    return (double)(geom_rng_u64(r) >> 11) * (1.0 / 9007199254740992.0);
}

double geom_range(geom_rng *r, double lo, double hi)
{
    return lo + (hi - lo) * geom_rand(r);
}

/* ---- transformations -------------------------------------------------------------------- */

static double norm3(double v[3])
{
    const double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (n > 0)
        for (int i = 0; i < 3; i++)
            v[i] /= n;
    return n;
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    const double r[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
    memcpy(out, r, sizeof r);
}

void geom_quat_axis(double ax, double ay, double az, double angle, double q[4])
{
    double a[3] = { ax, ay, az };
    norm3(a);
    const double s = sin(0.5 * angle);
    q[0] = a[0] * s;
    q[1] = a[1] * s;
    q[2] = a[2] * s;
    q[3] = cos(0.5 * angle);
}

void geom_quat_mul(const double a[4], const double b[4], double out[4])
{
    const double r[4] = {
        a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
        a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
        a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
        a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2],
    };
    memcpy(out, r, sizeof r);
}

void geom_quat_look(const double dir[3], const double up[3], double q[4])
{
    double z[3] = { -dir[0], -dir[1], -dir[2] }, x[3], y[3];
    norm3(z);
    cross3(up, z, x);
    if (norm3(x) < 1e-9) { /* up parallel to dir: any perpendicular will do */
        const double alt[3] = { 1, 0, 0 };
        cross3(alt, z, x);
        if (norm3(x) < 1e-9) {
            const double alt2[3] = { 0, 0, 1 };
            cross3(alt2, z, x);
            norm3(x);
        }
    }
    cross3(z, x, y);
    /* rotation matrix with columns x, y, z -> quaternion */
    const double m00 = x[0], m11 = y[1], m22 = z[2], tr = m00 + m11 + m22;
    if (tr > 0) {
        const double s = 0.5 / sqrt(tr + 1.0);
        q[3] = 0.25 / s;
        q[0] = (y[2] - z[1]) * s;
        q[1] = (z[0] - x[2]) * s;
        q[2] = (x[1] - y[0]) * s;
    } else if (m00 > m11 && m00 > m22) {
        const double s = 2.0 * sqrt(1.0 + m00 - m11 - m22);
        q[3] = (y[2] - z[1]) / s;
        q[0] = 0.25 * s;
        q[1] = (y[0] + x[1]) / s;
        q[2] = (z[0] + x[2]) / s;
    } else if (m11 > m22) {
        const double s = 2.0 * sqrt(1.0 + m11 - m00 - m22);
        q[3] = (z[0] - x[2]) / s;
        q[0] = (y[0] + x[1]) / s;
        q[1] = 0.25 * s;
        q[2] = (z[1] + y[2]) / s;
    } else {
        const double s = 2.0 * sqrt(1.0 + m22 - m00 - m11);
        q[3] = (x[1] - y[0]) / s;
        q[0] = (z[0] + x[2]) / s;
        q[1] = (z[1] + y[2]) / s;
        q[2] = 0.25 * s;
    }
    const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int i = 0; i < 4; i++)
        q[i] /= n;
}

affine geom_place(double tx, double ty, double tz, double yaw, double sx, double sy, double sz)
{
    const double t[3] = { tx, ty, tz }, s[3] = { sx, sy, sz };
    double q[4];
    geom_quat_axis(0, 1, 0, yaw, q);
    return affine_from_trs(t, q, s);
}

affine geom_trs(double tx, double ty, double tz, double ax, double ay, double az, double angle, double sx, double sy,
                double sz)
{
    const double t[3] = { tx, ty, tz }, s[3] = { sx, sy, sz };
    double q[4];
    geom_quat_axis(ax, ay, az, angle, q);
    return affine_from_trs(t, q, s);
}

/* ---- mesh builder ----------------------------------------------------------------------- */

/* Grows *p (elements of elem bytes, capacity *cap) to hold need elements. 0 on failure. */
static int grow(void **p, uint32_t *cap, uint64_t need, size_t elem)
{
    if (need <= *cap)
        return 1;
    uint64_t c = *cap ? *cap : 16;
    while (c < need)
        c *= 2;
    if (c > UINT32_MAX)
        return 0;
    void *q = realloc(*p, (size_t)c * elem);
    if (!q)
        return 0;
    *p = q;
    *cap = (uint32_t)c;
    return 1;
}

void geom_mesh_init(geom_mesh *m)
{
    memset(m, 0, sizeof *m);
}

void geom_mesh_free(geom_mesh *m)
{
    free(m->pos);
    free(m->nrm);
    free(m->uv);
    free(m->idx);
    free(m->mat);
    geom_mesh_init(m);
}

uint32_t geom_vertex(geom_mesh *m, const double p[3], const double n[3], double u, double v)
{
    if (m->oom)
        return 0;
    uint32_t cap = m->cap_v, c2 = m->cap_v, c3 = m->cap_v;
    if (!grow((void **)&m->pos, &cap, (uint64_t)m->nv + 1, 3 * sizeof(float)) ||
        !grow((void **)&m->nrm, &c2, (uint64_t)m->nv + 1, 3 * sizeof(float)) ||
        !grow((void **)&m->uv, &c3, (uint64_t)m->nv + 1, 2 * sizeof(float))) {
        m->oom = 1;
        return 0;
    }
    m->cap_v = cap;
    double nn[3] = { 0, 1, 0 };
    if (n) {
        memcpy(nn, n, sizeof nn);
        if (norm3(nn) == 0)
            nn[1] = 1;
    }
    for (int i = 0; i < 3; i++) {
        m->pos[3 * m->nv + i] = (float)p[i];
        m->nrm[3 * m->nv + i] = (float)nn[i];
    }
    m->uv[2 * m->nv] = (float)u;
    m->uv[2 * m->nv + 1] = (float)v;
    return m->nv++;
}

void geom_tri(geom_mesh *m, uint32_t a, uint32_t b, uint32_t c, uint32_t material)
{
    if (m->oom)
        return;
    uint32_t cap = m->cap_t, c2 = m->cap_t;
    if (!grow((void **)&m->idx, &cap, (uint64_t)m->nt + 1, 3 * sizeof(uint32_t)) ||
        !grow((void **)&m->mat, &c2, (uint64_t)m->nt + 1, sizeof(uint32_t))) {
        m->oom = 1;
        return;
    }
    m->cap_t = cap;
    m->idx[3 * m->nt] = a;
    m->idx[3 * m->nt + 1] = b;
    m->idx[3 * m->nt + 2] = c;
    m->mat[m->nt++] = material;
}

/* A shape's placement: points by xf, normals by its inverse transpose, winding flipped by
 * mirroring transformations. */
typedef struct {
    affine xf;
    double nm[3][3];
    int flip;
} xform;

static void xform_init(xform *x, const affine *xf)
{
    x->xf = xf ? *xf : affine_identity();
    affine inv;
    const int ok = affine_invert(&x->xf, &inv);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            x->nm[i][j] = ok ? inv.m[j][i] : x->xf.m[i][j];
    const double(*a)[4] = x->xf.m;
    const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                       a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                       a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    x->flip = det < 0;
}

static uint32_t xvert(geom_mesh *m, const xform *x, const double p[3], const double n[3], double u, double v)
{
    double wp[3], wn[3];
    affine_apply_point(&x->xf, p, wp);
    for (int i = 0; i < 3; i++)
        wn[i] = x->nm[i][0] * n[0] + x->nm[i][1] * n[1] + x->nm[i][2] * n[2];
    return geom_vertex(m, wp, wn, u, v);
}

static void xtri(geom_mesh *m, const xform *x, uint32_t a, uint32_t b, uint32_t c, uint32_t material)
{
    if (x->flip)
        geom_tri(m, a, c, b, material);
    else
        geom_tri(m, a, b, c, material);
}

void geom_box(geom_mesh *m, const affine *xf, uint32_t material)
{
    static const double normals[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
    static const double tangents[6][3] = { { 0, 0, -1 }, { 0, 0, 1 }, { 1, 0, 0 }, { 1, 0, 0 }, { 1, 0, 0 }, { -1, 0, 0 } };
    static const double corner[4][2] = { { -0.5, -0.5 }, { 0.5, -0.5 }, { 0.5, 0.5 }, { -0.5, 0.5 } };
    xform x;
    xform_init(&x, xf);
    for (int f = 0; f < 6; f++) {
        const double *n = normals[f], *u = tangents[f];
        double v[3];
        cross3(n, u, v); /* u x v = n */
        uint32_t id[4];
        for (int k = 0; k < 4; k++) {
            double p[3];
            for (int i = 0; i < 3; i++)
                p[i] = 0.5 * n[i] + corner[k][0] * u[i] + corner[k][1] * v[i];
            id[k] = xvert(m, &x, p, n, corner[k][0] + 0.5, 0.5 - corner[k][1]);
        }
        xtri(m, &x, id[0], id[1], id[2], material);
        xtri(m, &x, id[0], id[2], id[3], material);
    }
}

void geom_lathe(geom_mesh *m, const affine *xf, const double (*profile)[2], uint32_t n, uint32_t segments,
                uint32_t material)
{
    if (n < 2 || segments < 3)
        return;
    xform x;
    xform_init(&x, xf);
    const uint32_t first = m->nv, row = segments + 1;
    for (uint32_t k = 0; k < n; k++) {
        /* profile tangent: average of the adjacent segments; outward normal (dy, -dr) */
        const uint32_t k0 = k > 0 ? k - 1 : k, k1 = k + 1 < n ? k + 1 : k;
        double dr = profile[k1][0] - profile[k0][0], dy = profile[k1][1] - profile[k0][1];
        const double len = sqrt(dr * dr + dy * dy);
        if (len > 0) {
            dr /= len;
            dy /= len;
        }
        for (uint32_t s = 0; s <= segments; s++) {
            const double th = 2.0 * M_PI * s / segments, sn = sin(th), cs = cos(th);
            const double p[3] = { profile[k][0] * sn, profile[k][1], profile[k][0] * cs };
            const double nn[3] = { dy * sn, -dr, dy * cs };
            xvert(m, &x, p, nn, (double)s / segments, 1.0 - (double)k / (n - 1));
        }
    }
    for (uint32_t k = 0; k + 1 < n; k++) {
        for (uint32_t s = 0; s < segments; s++) {
            const uint32_t a = first + k * row + s, b = a + 1, c = b + row, d = a + row;
            if (profile[k][0] != 0)
                xtri(m, &x, a, b, c, material);
            if (profile[k + 1][0] != 0)
                xtri(m, &x, a, c, d, material);
        }
    }
}

static void disk_at(geom_mesh *m, const xform *x, double radius, double y, uint32_t segments, int down,
                    uint32_t material)
{
    const double n[3] = { 0, down ? -1 : 1, 0 }, c[3] = { 0, y, 0 };
    const uint32_t centre = xvert(m, x, c, n, 0.5, 0.5), first = m->nv;
    for (uint32_t s = 0; s < segments; s++) {
        const double th = 2.0 * M_PI * s / segments;
        const double p[3] = { radius * sin(th), y, radius * cos(th) };
        xvert(m, x, p, n, 0.5 + 0.5 * sin(th), 0.5 - 0.5 * cos(th));
    }
    for (uint32_t s = 0; s < segments; s++) {
        const uint32_t a = first + s, b = first + (s + 1) % segments;
        if (down)
            xtri(m, x, centre, b, a, material);
        else
            xtri(m, x, centre, a, b, material);
    }
}

void geom_disk(geom_mesh *m, const affine *xf, uint32_t segments, int down, uint32_t material)
{
    if (segments < 3)
        return;
    xform x;
    xform_init(&x, xf);
    disk_at(m, &x, 1.0, 0.0, segments, down, material);
}

void geom_frustum(geom_mesh *m, const affine *xf, double r0, double r1, uint32_t segments, int caps,
                  uint32_t material)
{
    const double profile[2][2] = { { r0, 0 }, { r1, 1 } };
    geom_lathe(m, xf, profile, 2, segments, material);
    if (!caps || segments < 3)
        return;
    xform x;
    xform_init(&x, xf);
    if (r0 > 0)
        disk_at(m, &x, r0, 0.0, segments, 1, material);
    if (r1 > 0)
        disk_at(m, &x, r1, 1.0, segments, 0, material);
}

void geom_pyramid(geom_mesh *m, const affine *xf, uint32_t material)
{
    static const double corner[4][3] = { { -0.5, 0, -0.5 }, { 0.5, 0, -0.5 }, { 0.5, 0, 0.5 }, { -0.5, 0, 0.5 } };
    const double apex[3] = { 0, 1, 0 };
    xform x;
    xform_init(&x, xf);
    const uint32_t a = xvert(m, &x, apex, apex, 0.5, 0.0);
    uint32_t c[4];
    for (int k = 0; k < 4; k++) {
        const double n[3] = { corner[k][0], 0.5, corner[k][2] };
        c[k] = xvert(m, &x, corner[k], n, k == 1 || k == 2 ? 1.0 : 0.0, 1.0);
    }
    for (int k = 0; k < 4; k++)
        xtri(m, &x, c[k], c[(k + 3) % 4], a, material);
}

void geom_patch(geom_mesh *m, const affine *xf, uint32_t nu, uint32_t nv,
                void (*surface)(double u, double v, const void *ctx, double p[3]), const void *ctx, uint32_t material)
{
    if (nu == 0 || nv == 0)
        return;
    xform x;
    xform_init(&x, xf);
    const uint32_t first = m->nv, row = nu + 1;
    const double e = 1e-4;
    for (uint32_t j = 0; j <= nv; j++) {
        for (uint32_t i = 0; i <= nu; i++) {
            const double u = (double)i / nu, v = (double)j / nv;
            const double u0 = fmax(0.0, u - e), u1 = fmin(1.0, u + e), v0 = fmax(0.0, v - e), v1 = fmin(1.0, v + e);
            double p[3], pu0[3], pu1[3], pv0[3], pv1[3], du[3], dv[3], n[3];
            surface(u, v, ctx, p);
            surface(u0, v, ctx, pu0);
            surface(u1, v, ctx, pu1);
            surface(u, v0, ctx, pv0);
            surface(u, v1, ctx, pv1);
            for (int k = 0; k < 3; k++) {
                du[k] = pu1[k] - pu0[k];
                dv[k] = pv1[k] - pv0[k];
            }
            cross3(du, dv, n);
            xvert(m, &x, p, n, u, v);
        }
    }
    for (uint32_t j = 0; j < nv; j++) {
        for (uint32_t i = 0; i < nu; i++) {
            const uint32_t a = first + j * row + i, b = a + 1, c = b + row, d = a + row;
            xtri(m, &x, a, b, c, material);
            xtri(m, &x, a, c, d, material);
        }
    }
}

/* Icosphere: subdivision with shared edge midpoints (open-addressing table on the edge). */
typedef struct {
    double (*p)[3];
    uint32_t np;
    uint64_t *keys;
    uint32_t *vals, mask;
} ico;

static uint32_t ico_mid(ico *s, uint32_t a, uint32_t b)
{
    const uint64_t key = a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a);
    uint32_t h = (uint32_t)((key * 0x9E3779B97F4A7C15ull) >> 32) & s->mask;
    while (s->keys[h] != UINT64_MAX) {
        if (s->keys[h] == key)
            return s->vals[h];
        h = (h + 1) & s->mask;
    }
    double *p = s->p[s->np];
    for (int i = 0; i < 3; i++)
        p[i] = 0.5 * (s->p[a][i] + s->p[b][i]);
    norm3(p);
    s->keys[h] = key;
    s->vals[h] = s->np;
    return s->np++;
}

void geom_sphere(geom_mesh *m, const affine *xf, uint32_t subdiv, uint32_t material)
{
    static const uint8_t faces[20][3] = {
        { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 }, { 1, 5, 9 }, { 5, 11, 4 },
        { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 }, { 3, 9, 4 }, { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 },
        { 3, 8, 9 }, { 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 },
    };
    if (m->oom)
        return;
    if (subdiv > 7)
        subdiv = 7;
    const double t = (1.0 + sqrt(5.0)) / 2.0;
    const double base[12][3] = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 }, { 0, -1, t }, { 0, 1, t },
                                 { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 }, { -t, 0, -1 }, { -t, 0, 1 } };
    const uint32_t nt = 20u << (2 * subdiv), nv = 10u * (nt / 20) + 2; /* V = 10 * 4^k + 2 */
    uint32_t tabsize = 1;
    while (tabsize < 2 * (3 * nt / 2))
        tabsize *= 2;
    ico s = { malloc(nv * sizeof *s.p), 12, malloc(tabsize * sizeof(uint64_t)), malloc(tabsize * sizeof(uint32_t)),
              tabsize - 1 };
    uint32_t *tri = malloc(3 * (size_t)nt * sizeof *tri), *next = malloc(3 * (size_t)nt * sizeof *next);
    if (!s.p || !s.keys || !s.vals || !tri || !next) {
        m->oom = 1;
        goto done;
    }
    for (int i = 0; i < 12; i++) {
        memcpy(s.p[i], base[i], sizeof base[i]);
        norm3(s.p[i]);
    }
    for (int f = 0; f < 20; f++)
        for (int k = 0; k < 3; k++)
            tri[3 * f + k] = faces[f][k];
    uint32_t n = 20;
    for (uint32_t level = 0; level < subdiv; level++) {
        memset(s.keys, 0xFF, tabsize * sizeof(uint64_t));
        for (uint32_t f = 0; f < n; f++) {
            const uint32_t a = tri[3 * f], b = tri[3 * f + 1], c = tri[3 * f + 2];
            const uint32_t ab = ico_mid(&s, a, b), bc = ico_mid(&s, b, c), ca = ico_mid(&s, c, a);
            const uint32_t out[4][3] = { { a, ab, ca }, { b, bc, ab }, { c, ca, bc }, { ab, bc, ca } };
            memcpy(&next[12 * f], out, sizeof out);
        }
        n *= 4;
        uint32_t *tmp = tri;
        tri = next;
        next = tmp;
    }
    xform x;
    xform_init(&x, xf);
    const uint32_t first = m->nv;
    for (uint32_t i = 0; i < s.np; i++) {
        const double *p = s.p[i];
        xvert(m, &x, p, p, 0.5 + atan2(p[0], p[2]) / (2 * M_PI), acos(fmax(-1.0, fmin(1.0, p[1]))) / M_PI);
    }
    for (uint32_t f = 0; f < n; f++)
        xtri(m, &x, first + tri[3 * f], first + tri[3 * f + 1], first + tri[3 * f + 2], material);
done:
    free(s.p);
    free(s.keys);
    free(s.vals);
    free(tri);
    free(next);
}

void geom_grid(geom_mesh *m, const affine *xf, uint32_t nx, uint32_t nz, const float *heights,
               uint32_t material, uint32_t (*material_of)(double height, double up, const void *ctx),
               const void *ctx)
{
    if (nx == 0 || nz == 0)
        return;
    xform x;
    xform_init(&x, xf);
    const uint32_t first = m->nv, row = nx + 1;
    const double dx = 1.0 / nx, dz = 1.0 / nz;
#define H(i, j) (heights ? (double)heights[(size_t)(j) * row + (i)] : 0.0)
    for (uint32_t j = 0; j <= nz; j++) {
        for (uint32_t i = 0; i <= nx; i++) {
            const uint32_t i0 = i > 0 ? i - 1 : i, i1 = i < nx ? i + 1 : i;
            const uint32_t j0 = j > 0 ? j - 1 : j, j1 = j < nz ? j + 1 : j;
            const double gx = (H(i1, j) - H(i0, j)) / ((i1 - i0) * dx), gz = (H(i, j1) - H(i, j0)) / ((j1 - j0) * dz);
            const double p[3] = { -0.5 + i * dx, H(i, j), -0.5 + j * dz }, n[3] = { -gx, 1, -gz };
            xvert(m, &x, p, n, (double)i / nx, (double)j / nz);
        }
    }
    for (uint32_t j = 0; j < nz; j++) {
        for (uint32_t i = 0; i < nx; i++) {
            const uint32_t a = first + j * row + i, b = a + row, c = b + 1, d = a + 1;
            uint32_t mat = material;
            if (material_of) {
                const double h = 0.25 * (H(i, j) + H(i + 1, j) + H(i, j + 1) + H(i + 1, j + 1));
                const double gx = (H(i + 1, j) + H(i + 1, j + 1) - H(i, j) - H(i, j + 1)) / (2 * dx);
                const double gz = (H(i, j + 1) + H(i + 1, j + 1) - H(i, j) - H(i + 1, j)) / (2 * dz);
                const double ln[3] = { -gx, 1, -gz }, lc[3] = { -0.5 + (i + 0.5) * dx, h, -0.5 + (j + 0.5) * dz };
                double wn[3], wc[3];
                for (int k = 0; k < 3; k++)
                    wn[k] = x.nm[k][0] * ln[0] + x.nm[k][1] * ln[1] + x.nm[k][2] * ln[2];
                norm3(wn);
                affine_apply_point(&x.xf, lc, wc);
                mat = material_of(wc[1], wn[1], ctx);
            }
            xtri(m, &x, a, b, c, mat);
            xtri(m, &x, a, c, d, mat);
        }
    }
#undef H
}

/* ---- scene under construction ----------------------------------------------------------- */

scene_material geom_material(float r, float g, float b, float metallic, float roughness)
{
    scene_material m;
    memset(&m, 0, sizeof m);
    m.base_color[0] = r;
    m.base_color[1] = g;
    m.base_color[2] = b;
    m.base_color[3] = 1.0f;
    m.base_color_texture = m.emissive_texture = SCENE_NONE;
    m.alpha = ALPHA_OPAQUE;
    m.alpha_cutoff = 0.5f;
    m.metallic = metallic;
    m.roughness = roughness;
    m.ior = 1.5f;
    return m;
}

void geom_scene_begin(geom_scene *g, scene *out)
{
    memset(out, 0, sizeof *out);
    memset(g, 0, sizeof *g);
    g->s = out;
    const scene_material def = geom_material(0.8f, 0.8f, 0.8f, 0.0f, 1.0f);
    geom_add_material(g, &def);
}

/* Appends one zeroed element to an array of the scene; NULL (and oom) on failure. */
static void *append(geom_scene *g, void **array, uint32_t *count, uint32_t *cap, size_t elem)
{
    if (g->oom || !grow(array, cap, (uint64_t)*count + 1, elem)) {
        g->oom = 1;
        return NULL;
    }
    void *p = (char *)*array + (size_t)*count * elem;
    memset(p, 0, elem);
    (*count)++;
    return p;
}

uint32_t geom_add_material(geom_scene *g, const scene_material *m)
{
    scene_material *d = append(g, (void **)&g->s->materials, &g->s->n_materials, &g->cap_materials, sizeof *d);
    if (!d)
        return 0;
    *d = *m;
    return g->s->n_materials - 1;
}

uint32_t geom_add_texture(geom_scene *g, int width, int height, const uint8_t *rgba)
{
    const size_t n = (size_t)width * (size_t)height * 4;
    uint8_t *copy = malloc(n);
    scene_texture *t = copy ? append(g, (void **)&g->s->textures, &g->s->n_textures, &g->cap_textures, sizeof *t) : NULL;
    if (!t) {
        free(copy);
        g->oom = 1;
        return SCENE_NONE;
    }
    memcpy(copy, rgba, n);
    t->width = width;
    t->height = height;
    t->rgba = copy;
    return g->s->n_textures - 1;
}

/* Shrinks an array to n elements (keeps the old block if realloc fails). */
static void *fit(void *p, size_t n, size_t elem)
{
    void *q = n ? realloc(p, n * elem) : NULL;
    if (!n) {
        free(p);
        return NULL;
    }
    return q ? q : p;
}

uint32_t geom_add_mesh(geom_scene *g, geom_mesh *m, const char *name)
{
    scene_mesh *d = m->oom ? NULL : append(g, (void **)&g->s->meshes, &g->s->n_meshes, &g->cap_meshes, sizeof *d);
    if (!d) {
        g->oom = 1;
        geom_mesh_free(m);
        return SCENE_NONE;
    }
    snprintf(d->name, sizeof d->name, "%s", name);
    d->n_vertices = m->nv;
    d->n_triangles = m->nt;
    d->positions = fit(m->pos, 3 * (size_t)m->nv, sizeof(float));
    d->normals = fit(m->nrm, 3 * (size_t)m->nv, sizeof(float));
    int textured = 0; /* texture coordinates only where a material samples a texture */
    for (uint32_t t = 0; t < m->nt && !textured; t++)
        textured = m->mat[t] < g->s->n_materials && (g->s->materials[m->mat[t]].base_color_texture != SCENE_NONE ||
                                                     g->s->materials[m->mat[t]].emissive_texture != SCENE_NONE);
    if (textured) {
        d->texcoords = fit(m->uv, 2 * (size_t)m->nv, sizeof(float));
    } else {
        free(m->uv);
        d->texcoords = NULL;
    }
    d->indices = fit(m->idx, 3 * (size_t)m->nt, sizeof(uint32_t));
    d->material = fit(m->mat, m->nt, sizeof(uint32_t));
    geom_mesh_init(m);
    return g->s->n_meshes - 1;
}

void geom_set_morph(geom_scene *g, uint32_t mesh, uint32_t n_targets, const float *deltas)
{
    if (g->oom || mesh >= g->s->n_meshes || n_targets == 0)
        return;
    scene_mesh *m = &g->s->meshes[mesh];
    const size_t nf = 3 * (size_t)m->n_vertices;
    m->base_positions = malloc(nf * sizeof(float));
    m->target_deltas = malloc((size_t)n_targets * nf * sizeof(float));
    m->weights = calloc(n_targets, sizeof(float));
    if (!m->base_positions || !m->target_deltas || !m->weights) {
        g->oom = 1; /* scene_free releases what was allocated */
        return;
    }
    memcpy(m->base_positions, m->positions, nf * sizeof(float));
    memcpy(m->target_deltas, deltas, (size_t)n_targets * nf * sizeof(float));
    m->n_targets = n_targets;
}

uint32_t geom_add_node(geom_scene *g, const char *name, int parent, uint32_t mesh, const double t[3],
                       const double q[4], const double sc[3])
{
    scene_node *n = append(g, (void **)&g->s->nodes, &g->s->n_nodes, &g->cap_nodes, sizeof *n);
    if (!n)
        return 0;
    snprintf(n->name, sizeof n->name, "%s", name);
    n->parent = parent;
    n->mesh = mesh < g->s->n_meshes ? mesh : SCENE_NONE;
    n->camera = n->light = SCENE_NONE;
    n->world = affine_identity();
    n->matrix = affine_identity();
    for (int i = 0; i < 3; i++) {
        n->translation[i] = t ? t[i] : 0.0;
        n->scale[i] = sc ? sc[i] : 1.0;
    }
    for (int i = 0; i < 4; i++)
        n->rotation[i] = q ? q[i] : (i == 3 ? 1.0 : 0.0);
    if (n->mesh != SCENE_NONE && g->s->meshes[n->mesh].n_targets) {
        const scene_mesh *m = &g->s->meshes[n->mesh];
        n->weights = malloc(m->n_targets * sizeof(double));
        if (!n->weights) {
            g->oom = 1;
            return g->s->n_nodes - 1;
        }
        n->n_weights = m->n_targets;
        for (uint32_t k = 0; k < m->n_targets; k++)
            n->weights[k] = m->weights[k];
    }
    return g->s->n_nodes - 1;
}

uint32_t geom_add_camera(geom_scene *g, const double eye[3], const double target[3], double yfov, double aspect,
                         double znear, double zfar)
{
    const double dir[3] = { target[0] - eye[0], target[1] - eye[1], target[2] - eye[2] }, up[3] = { 0, 1, 0 };
    double q[4];
    geom_quat_look(dir, up, q);
    const uint32_t node = geom_add_node(g, "camera", -1, SCENE_NONE, eye, q, NULL);
    scene_camera *c = append(g, (void **)&g->s->cameras, &g->s->n_cameras, &g->cap_cameras, sizeof *c);
    if (!c)
        return 0;
    c->kind = CAMERA_PERSPECTIVE;
    c->yfov = yfov;
    c->aspect = aspect;
    c->znear = znear;
    c->zfar = zfar;
    c->node = node;
    c->world = affine_identity();
    g->s->nodes[node].camera = g->s->n_cameras - 1;
    return g->s->n_cameras - 1;
}

static uint32_t add_light(geom_scene *g, const char *name, light_kind kind, const double t[3], const double q[4],
                          float r, float gr, float b, float intensity)
{
    const uint32_t node = geom_add_node(g, name, -1, SCENE_NONE, t, q, NULL);
    scene_light *l = append(g, (void **)&g->s->lights, &g->s->n_lights, &g->cap_lights, sizeof *l);
    if (!l)
        return 0;
    l->kind = kind;
    l->color[0] = r;
    l->color[1] = gr;
    l->color[2] = b;
    l->intensity = intensity;
    l->outer_cone = (float)(M_PI / 4);
    l->node = node;
    l->direction[2] = -1;
    g->s->nodes[node].light = g->s->n_lights - 1;
    return g->s->n_lights - 1;
}

uint32_t geom_add_point_light(geom_scene *g, const char *name, const double pos[3], float r, float gr, float b,
                              float intensity)
{
    return add_light(g, name, LIGHT_POINT, pos, NULL, r, gr, b, intensity);
}

uint32_t geom_add_dir_light(geom_scene *g, const char *name, const double dir[3], float r, float gr, float b,
                            float intensity)
{
    const double up[3] = { 0, 1, 0 };
    double q[4];
    geom_quat_look(dir, up, q);
    return add_light(g, name, LIGHT_DIRECTIONAL, NULL, q, r, gr, b, intensity);
}

uint32_t geom_add_animation(geom_scene *g, const char *name)
{
    scene_animation *a = append(g, (void **)&g->s->animations, &g->s->n_animations, &g->cap_animations, sizeof *a);
    if (!a)
        return 0;
    snprintf(a->name, sizeof a->name, "%s", name);
    return g->s->n_animations - 1;
}

void geom_add_channel(geom_scene *g, uint32_t anim, uint32_t node, anim_path path, anim_interp interp,
                      uint32_t n_keys, const float *times, const float *values)
{
    if (g->oom)
        return;
    if (anim >= g->s->n_animations || node >= g->s->n_nodes || n_keys == 0) {
        g->invalid = 1;
        return;
    }
    scene_animation *a = &g->s->animations[anim];
    const uint32_t comp = path == ANIM_ROTATION ? 4 : path == ANIM_WEIGHTS ? g->s->nodes[node].n_weights : 3;
    const size_t nval = (size_t)n_keys * comp * (interp == INTERP_CUBICSPLINE ? 3 : 1);
    if (comp == 0) { /* a weights channel on a node without morph targets */
        g->invalid = 1;
        return;
    }
    scene_channel *ch = realloc(a->channels, (a->n_channels + 1) * sizeof *ch);
    if (!ch) {
        g->oom = 1;
        return;
    }
    a->channels = ch;
    scene_channel *c = &ch[a->n_channels];
    memset(c, 0, sizeof *c);
    c->times = malloc(n_keys * sizeof(float));
    c->values = malloc(nval * sizeof(float));
    if (!c->times || !c->values) {
        free(c->times);
        free(c->values);
        g->oom = 1;
        return;
    }
    a->n_channels++;
    memcpy(c->times, times, n_keys * sizeof(float));
    memcpy(c->values, values, nval * sizeof(float));
    c->node = node;
    c->path = path;
    c->interp = interp;
    c->n_keys = n_keys;
    c->components = comp;
    if (times[n_keys - 1] > a->duration)
        a->duration = times[n_keys - 1];
}

int geom_scene_end(geom_scene *g, char *err, size_t errlen)
{
    scene *s = g->s;
    if (!g->oom && !g->invalid) {
        free(s->roots);
        s->roots = malloc((s->n_nodes ? s->n_nodes : 1) * sizeof *s->roots);
        s->n_roots = 0;
        if (!s->roots)
            g->oom = 1;
        for (uint32_t i = 0; !g->oom && i < s->n_nodes; i++)
            if (s->nodes[i].parent < 0)
                s->roots[s->n_roots++] = i;
    }
    if (!g->oom && scene_evaluate(s, 0.0, 0) != 0)
        g->oom = 1;
    if (g->oom || g->invalid) {
        if (err && errlen)
            snprintf(err, errlen, "%s", g->oom ? "out of memory" : "internal error: invalid animation channel");
        scene_free(s);
        return -1;
    }
    return 0;
}
