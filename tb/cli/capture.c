/* Capture of the units' transactions through linker wrappers: see capture.h. */
#include "capture.h"

#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "isect_unit.h"
#include "trav_node.h"
#include "xform_unit.h"

enum { CAP_XFORM, CAP_ISECT, CAP_TRAV, CAP_UNITS };

static struct {
    int on;
    FILE *f[CAP_UNITS];
    uint64_t n[CAP_UNITS], limit;
    pthread_mutex_t lock;
} cap = { .lock = PTHREAD_MUTEX_INITIALIZER };

static const char *const cap_files[CAP_UNITS] = { "xform.hex", "isect.hex", "trav.hex" };

int capture_start(const char *dir, uint64_t limit, char *err, unsigned errlen)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        snprintf(err, errlen, "cannot make directory '%s': %s", dir, strerror(errno));
        return -1;
    }
    for (int u = 0; u < CAP_UNITS; u++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, cap_files[u]);
        if (!(cap.f[u] = fopen(path, "w"))) {
            snprintf(err, errlen, "cannot write '%s': %s", path, strerror(errno));
            capture_stop();
            return -1;
        }
        cap.n[u] = 0;
    }
    cap.limit = limit;
    cap.on = 1;
    return 0;
}

void capture_counts(uint64_t out[3])
{
    for (int u = 0; u < CAP_UNITS; u++)
        out[u] = cap.n[u];
}

int capture_stop(void)
{
    int rc = 0;
    cap.on = 0;
    for (int u = 0; u < CAP_UNITS; u++) {
        if (cap.f[u] && (ferror(cap.f[u]) || fclose(cap.f[u]) != 0))
            rc = -1;
        cap.f[u] = NULL;
    }
    return rc;
}

static void words(FILE *f, const uint32_t *w, int n)
{
    for (int i = 0; i < n; i++)
        fprintf(f, "%s%06x", i ? " " : "", w[i]);
}

/* Locks and returns the file of unit u if this transaction is to be recorded. */
static FILE *begin(int u)
{
    if (!cap.on)
        return NULL;
    pthread_mutex_lock(&cap.lock);
    if (cap.n[u] >= cap.limit) {
        pthread_mutex_unlock(&cap.lock);
        return NULL;
    }
    cap.n[u]++;
    return cap.f[u];
}

static void end(FILE *f)
{
    fputc('\n', f);
    pthread_mutex_unlock(&cap.lock);
}

f24_vec3 __real_xform_point(const f24_affine *m, f24_vec3 p);
f24_vec3 __real_xform_vector(const f24_affine *m, f24_vec3 v);
isect_result __real_isect_unit_rebased(const f24_triangle *m, f24_vec3x2 p, f24_t te, f24_vec3 d, f24_t tmin, f24_t tmax);
void __real_trav_node_split(const trav_entry *e, uint32_t axis, f24_t split, const f24_vec3 o[], const f24_vec3 d[],
                            trav_entry *l, trav_entry *r, uint32_t *near_left);
f24_vec3 __wrap_xform_point(const f24_affine *m, f24_vec3 p);
f24_vec3 __wrap_xform_vector(const f24_affine *m, f24_vec3 v);
isect_result __wrap_isect_unit_rebased(const f24_triangle *m, f24_vec3x2 p, f24_t te, f24_vec3 d, f24_t tmin, f24_t tmax);
void __wrap_trav_node_split(const trav_entry *e, uint32_t axis, f24_t split, const f24_vec3 o[], const f24_vec3 d[],
                            trav_entry *l, trav_entry *r, uint32_t *near_left);

static void record_xform(const f24_affine *m, f24_vec3 v, uint32_t point, f24_vec3 r)
{
    FILE *f = begin(CAP_XFORM);
    if (!f)
        return;
    const uint32_t in[4] = { v.x, v.y, v.z, point }, out[3] = { r.x, r.y, r.z };
    words(f, &m->m[0][0], 12);
    fputc(' ', f);
    words(f, in, 4);
    fputc(' ', f);
    words(f, out, 3);
    end(f);
}

f24_vec3 __wrap_xform_point(const f24_affine *m, f24_vec3 p)
{
    const f24_vec3 r = __real_xform_point(m, p);
    record_xform(m, p, 1, r);
    return r;
}

f24_vec3 __wrap_xform_vector(const f24_affine *m, f24_vec3 v)
{
    const f24_vec3 r = __real_xform_vector(m, v);
    record_xform(m, v, 0, r);
    return r;
}

/* The intersection unit's datapath sees the ray after the triangle's matrix: the origin from the
 * rebased origin (isect_origin), the direction from the transformation unit (recorded as its
 * transaction), then the test, recorded in full (not early-out), whose hit flag equals the one
 * returned. */
isect_result __wrap_isect_unit_rebased(const f24_triangle *m, f24_vec3x2 p, f24_t te, f24_vec3 d, f24_t tmin, f24_t tmax)
{
    const isect_result r = __real_isect_unit_rebased(m, p, te, d, tmin, tmax);
    if (!cap.on)
        return r;
    const f24_vec3 ot = isect_origin(m, p), dt = __wrap_xform_vector(&m->m, d);
    const isect_result full = isect_unit_triangle(ot, dt, te, tmin, tmax, m->shared);
    FILE *f = begin(CAP_ISECT);
    if (!f)
        return r;
    const uint32_t w[15] = { ot.x,      ot.y,  ot.z,  dt.x,   dt.y,   dt.z,   te,        tmin, tmax,
                             m->shared, (uint32_t)full.hit, full.t, full.u, full.v, full.cos_n };
    words(f, w, 15);
    end(f);
    return r;
}

void __wrap_trav_node_split(const trav_entry *e, uint32_t axis, f24_t split, const f24_vec3 o[], const f24_vec3 d[],
                            trav_entry *l, trav_entry *r, uint32_t *near_left)
{
    __real_trav_node_split(e, axis, split, o, d, l, r, near_left);
    FILE *f = begin(CAP_TRAV);
    if (!f)
        return;
    const uint32_t head[3] = { axis, split, e->mask };
    words(f, head, 3);
    for (int i = 0; i < TRACE_PACKET; i++)
        fprintf(f, " %06x %06x %06x", o[i].x, o[i].y, o[i].z);
    for (int i = 0; i < TRACE_PACKET; i++)
        fprintf(f, " %06x %06x %06x", d[i].x, d[i].y, d[i].z);
    fputc(' ', f);
    words(f, e->tn, TRACE_PACKET);
    fputc(' ', f);
    words(f, e->tf, TRACE_PACKET);
    fprintf(f, " %06x %06x %06x ", l->mask, r->mask, *near_left);
    words(f, l->tn, TRACE_PACKET);
    fputc(' ', f);
    words(f, l->tf, TRACE_PACKET);
    fputc(' ', f);
    words(f, r->tn, TRACE_PACKET);
    fputc(' ', f);
    words(f, r->tf, TRACE_PACKET);
    end(f);
}
