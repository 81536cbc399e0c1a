/* Capture of the units' transactions through linker wrappers: see capture.h. */
#include "capture.h"

#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include <stddef.h>

#include "isect_unit.h"
#include "list_unit.h"
#include "cycle_sim.h"
#include "mem_iface.h"
#include "memimage.h"
#include "rebase_unit.h"
#include "rgs.h"
#include "rgs_ops.h"
#include "shade_rec.h"
#include "trav_node.h"
#include "trav_unit.h"
#include "xform_unit.h"

enum {
    CAP_XFORM, CAP_ISECT, CAP_TRAV, CAP_LIST, CAP_MEM, CAP_SCHED, CAP_RGS, CAP_REBASE, CAP_WIDE, CAP_TRAV_UNIT, CAP_TRACE,
    CAP_SHADE_REC, CAP_TEX, CAP_FRAME, CAP_LIGHT, CAP_LERP, CAP_COLOUR, CAP_ACCUM, CAP_SPAWN, CAP_SURFACE, CAP_ACCUMULATE, CAP_UNITS
};

static struct {
    int on;
    FILE *f[CAP_UNITS];
    uint64_t n[CAP_UNITS], limit;
    pthread_mutex_t lock;
} cap = { .lock = PTHREAD_MUTEX_INITIALIZER };

const char *const capture_unit_names[CAPTURE_UNITS] = {
    "xform", "isect", "trav",  "list", "mem",  "sched",  "rgs",   "rebase", "wide", "trav_unit",
    "trace", "shade_rec", "tex", "frame", "light", "lerp", "colour", "accum", "spawn", "surface", "accumulate"
};

/* The list unit's threads: trace_state addresses in the order first seen (the RTL's thread ids),
 * and the memory interfaces (pipes) likewise. */
#define CAP_MAX_IDS 4096
static const void *cap_state[CAP_MAX_IDS], *cap_pipe[CAP_MAX_IDS];
static uint32_t cap_states, cap_pipes;

/* The core's packets being traced (trace_begin to trace_step's end), by trace_state, and the
 * memory images they read (DIR/image_N.bin: a new one per image address or frame). */
#define CAP_TRACES 256
static struct {
    const trace_state *s;
    uint32_t image, id, flags, stepped;
    ray_packet rays;
    trace_counters c;
} cap_trace[CAP_TRACES];
static const uint32_t *cap_image;
static uint32_t cap_image_frame, cap_images;
static char cap_dir[1024];

int capture_start(const char *dir, uint64_t limit, char *err, unsigned errlen)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        snprintf(err, errlen, "cannot make directory '%s': %s", dir, strerror(errno));
        return -1;
    }
    for (int u = 0; u < CAP_UNITS; u++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s.hex", dir, capture_unit_names[u]);
        if (!(cap.f[u] = fopen(path, "w"))) {
            snprintf(err, errlen, "cannot write '%s': %s", path, strerror(errno));
            capture_stop();
            return -1;
        }
        cap.n[u] = 0;
    }
    cap_states = cap_pipes = cap_images = 0;
    cap_image = NULL;
    memset(cap_trace, 0, sizeof cap_trace);
    snprintf(cap_dir, sizeof cap_dir, "%s", dir);
    cap.limit = limit;
    cap.on = 1;
    return 0;
}

void capture_counts(uint64_t out[CAPTURE_UNITS])
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

/* a held packet value (the traversal's intervals) as its fp24 words */
static void held_words(FILE *f, const f24h *h)
{
    f24_t w[F24Q_LANES];
    f24h_words(h, w);
    words(f, w, F24Q_LANES);
}

/* The wrappers sit on every render's path in the capture build, capturing or not (the default
 * program has none and runs the capture build for --capture-unit-io): each tests this flag and
 * tail-calls either the unit or its recording path (CAPTURE_PATH: out of line, so that the
 * wrapper needs no stack frame and keeps no argument). */
static inline int capturing(void) { return __builtin_expect(cap.on, 0); }
#define CAPTURE_PATH static __attribute__((noinline, cold))

/* Locks and returns the file of unit u if this transaction is to be recorded (capturing again:
 * a wrapper that records after the unit's call reaches it also when nothing is captured). */
static FILE *begin(int u)
{
    if (!capturing())
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
void __real_trav_node_split_held(const trav_entry *e, uint32_t axis, f24_t split, const trav_rays *rays, trav_entry *l,
                                 trav_entry *r, uint32_t *near_left);
f24_vec3 __wrap_xform_point(const f24_affine *m, f24_vec3 p);
f24_vec3 __wrap_xform_vector(const f24_affine *m, f24_vec3 v);
isect_result __wrap_isect_unit_rebased(const f24_triangle *m, f24_vec3x2 p, f24_t te, f24_vec3 d, f24_t tmin, f24_t tmax);
void __wrap_trav_node_split_held(const trav_entry *e, uint32_t axis, f24_t split, const trav_rays *rays, trav_entry *l,
                                 trav_entry *r, uint32_t *near_left);

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

CAPTURE_PATH f24_vec3 captured_xform(const f24_affine *m, f24_vec3 v, uint32_t point)
{
    const f24_vec3 r = point ? __real_xform_point(m, v) : __real_xform_vector(m, v);
    record_xform(m, v, point, r);
    return r;
}

f24_vec3 __wrap_xform_point(const f24_affine *m, f24_vec3 p)
{
    return capturing() ? captured_xform(m, p, 1) : __real_xform_point(m, p);
}

f24_vec3 __wrap_xform_vector(const f24_affine *m, f24_vec3 v)
{
    return capturing() ? captured_xform(m, v, 0) : __real_xform_vector(m, v);
}

/* ---- the accuracy datapath: the rebase unit and the transformation unit's wide mode ---- */

f24_vec3x2 __real_rebase_origin(f24_vec3x2 o, f24_vec3x2 d, f24_t t);
f24_vec3x2 __real_xform_point_wide(const f24_affine *m, f24_vec3 tlo, f24_vec3x2 p);
f24_vec3x2 __real_xform_vector_wide(const f24_affine *m, f24_vec3 v);
f24_vec3x2 __wrap_rebase_origin(f24_vec3x2 o, f24_vec3x2 d, f24_t t);
f24_vec3x2 __wrap_xform_point_wide(const f24_affine *m, f24_vec3 tlo, f24_vec3x2 p);
f24_vec3x2 __wrap_xform_vector_wide(const f24_affine *m, f24_vec3 v);

/* With the distance the unit passes on beside p: rebase_distance(t), what trace.c stores as te. */
CAPTURE_PATH f24_vec3x2 captured_rebase(f24_vec3x2 o, f24_vec3x2 d, f24_t t)
{
    const f24_vec3x2 p = __real_rebase_origin(o, d, t);
    FILE *f = begin(CAP_REBASE);
    if (!f)
        return p;
    const uint32_t w[20] = { o.hi.x, o.hi.y, o.hi.z, o.lo.x, o.lo.y, o.lo.z, d.hi.x, d.hi.y, d.hi.z, d.lo.x,
                             d.lo.y, d.lo.z, t, p.hi.x, p.hi.y, p.hi.z, p.lo.x, p.lo.y, p.lo.z, rebase_distance(t) };
    words(f, w, 20);
    end(f);
    return p;
}

f24_vec3x2 __wrap_rebase_origin(f24_vec3x2 o, f24_vec3x2 d, f24_t t)
{
    return capturing() ? captured_rebase(o, d, t) : __real_rebase_origin(o, d, t);
}

/* A vector is recorded as a point would be, with zero low words and translation low words. */
static void record_wide(const f24_affine *m, f24_vec3 tlo, f24_vec3x2 p, uint32_t point, f24_vec3x2 r)
{
    FILE *f = begin(CAP_WIDE);
    if (!f)
        return;
    const uint32_t w[16] = { tlo.x, tlo.y, tlo.z, p.hi.x, p.hi.y, p.hi.z, p.lo.x, p.lo.y, p.lo.z, point,
                             r.hi.x, r.hi.y, r.hi.z, r.lo.x, r.lo.y, r.lo.z };
    words(f, &m->m[0][0], 12);
    fputc(' ', f);
    words(f, w, 16);
    end(f);
}

CAPTURE_PATH f24_vec3x2 captured_wide(const f24_affine *m, f24_vec3 tlo, f24_vec3x2 p, uint32_t point)
{
    const f24_vec3x2 r = point ? __real_xform_point_wide(m, tlo, p) : __real_xform_vector_wide(m, p.hi);
    record_wide(m, tlo, p, point, r);
    return r;
}

f24_vec3x2 __wrap_xform_point_wide(const f24_affine *m, f24_vec3 tlo, f24_vec3x2 p)
{
    return capturing() ? captured_wide(m, tlo, p, 1) : __real_xform_point_wide(m, tlo, p);
}

f24_vec3x2 __wrap_xform_vector_wide(const f24_affine *m, f24_vec3 v)
{
    const f24_vec3 none = { 0, 0, 0 };
    return capturing() ? captured_wide(m, none, (f24_vec3x2){ v, none }, 0) : __real_xform_vector_wide(m, v);
}

/* The packet-level calls of the core (trace.c) into the wide mode: recorded as the per-ray
 * datapath issues them, each ray's transactions in ray order (rebase, then the origin's and the
 * direction's wide transformation), recomputed by the units, which give the same bits. The
 * simulation versions with vector lanes (tb/sim/wide_lanes.c) call no unit; the per-ray ones call
 * the units of their own object file, which no wrapper sees, except xform_enter_rays's
 * rebase_origin (rebase_unit.c: its wrapper records it). */
void __real_xform_enter_rays(const f24_affine *w2o, f24_vec3 t_lo, uint32_t rays, const f24_vec3 o[], const f24_vec3 d[],
                             const f24_t tn[], f24_vec3 o_hi[], f24_vec3 o_lo[], f24_vec3 d_hi[], f24_vec3 d_lo[],
                             f24_t t0[]);
void __wrap_xform_enter_rays(const f24_affine *w2o, f24_vec3 t_lo, uint32_t rays, const f24_vec3 o[], const f24_vec3 d[],
                             const f24_t tn[], f24_vec3 o_hi[], f24_vec3 o_lo[], f24_vec3 d_hi[], f24_vec3 d_lo[],
                             f24_t t0[]);
void __real_rebase_rays(uint32_t rays, const f24_vec3 o[], const f24_vec3 o_lo[], const f24_vec3 d[],
                        const f24_vec3 d_lo[], const f24_t t[], f24_vec3x2 p[], f24_t te[]);
void __wrap_rebase_rays(uint32_t rays, const f24_vec3 o[], const f24_vec3 o_lo[], const f24_vec3 d[],
                        const f24_vec3 d_lo[], const f24_t t[], f24_vec3x2 p[], f24_t te[]);

CAPTURE_PATH void captured_enter_rays(const f24_affine *w2o, f24_vec3 t_lo, uint32_t rays, const f24_vec3 o[],
                                      const f24_vec3 d[], const f24_t tn[])
{
    const f24_vec3 none = { 0, 0, 0 };
    for (int i = 0; i < F24Q_LANES; i++) {
        if (!(rays >> i & 1u))
            continue;
        const f24_vec3x2 r_o = { o[i], none }, r_d = { d[i], none };
#ifdef F24_SIM_LANES
        const f24_vec3x2 p = captured_rebase(r_o, r_d, rebase_distance(tn[i]));
#else
        const f24_vec3x2 p = __real_rebase_origin(r_o, r_d, rebase_distance(tn[i])); /* recorded by its wrapper */
#endif
        captured_wide(w2o, t_lo, p, 1);
        captured_wide(w2o, none, (f24_vec3x2){ d[i], none }, 0);
    }
}

void __wrap_xform_enter_rays(const f24_affine *w2o, f24_vec3 t_lo, uint32_t rays, const f24_vec3 o[], const f24_vec3 d[],
                             const f24_t tn[], f24_vec3 o_hi[], f24_vec3 o_lo[], f24_vec3 d_hi[], f24_vec3 d_lo[],
                             f24_t t0[])
{
    __real_xform_enter_rays(w2o, t_lo, rays, o, d, tn, o_hi, o_lo, d_hi, d_lo, t0);
    if (capturing())
        captured_enter_rays(w2o, t_lo, rays, o, d, tn);
}

CAPTURE_PATH void captured_rebase_rays(uint32_t rays, const f24_vec3 o[], const f24_vec3 o_lo[], const f24_vec3 d[],
                                       const f24_vec3 d_lo[], const f24_t t[])
{
    for (int i = 0; i < F24Q_LANES; i++)
        if (rays >> i & 1u)
            captured_rebase((f24_vec3x2){ o[i], o_lo[i] }, (f24_vec3x2){ d[i], d_lo[i] }, t[i]);
}

void __wrap_rebase_rays(uint32_t rays, const f24_vec3 o[], const f24_vec3 o_lo[], const f24_vec3 d[],
                        const f24_vec3 d_lo[], const f24_t t[], f24_vec3x2 p[], f24_t te[])
{
    __real_rebase_rays(rays, o, o_lo, d, d_lo, t, p, te);
    if (capturing())
        captured_rebase_rays(rays, o, o_lo, d, d_lo, t);
}

/* The intersection unit's datapath sees the ray after the triangle's matrix: the origin from the
 * rebased origin (isect_origin), the direction from the transformation unit (recorded as its
 * transaction), then the test, recorded in full (not early-out), whose hit flag equals the one
 * returned. */
CAPTURE_PATH isect_result captured_isect(const f24_triangle *m, f24_vec3x2 p, f24_t te, f24_vec3 d, f24_t tmin,
                                         f24_t tmax)
{
    const isect_result r = __real_isect_unit_rebased(m, p, te, d, tmin, tmax);
    const f24_vec3 ot = isect_origin(m, p), dt = captured_xform(&m->m, d, 0);
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

isect_result __wrap_isect_unit_rebased(const f24_triangle *m, f24_vec3x2 p, f24_t te, f24_vec3 d, f24_t tmin, f24_t tmax)
{
    return capturing() ? captured_isect(m, p, te, d, tmin, tmax) : __real_isect_unit_rebased(m, p, te, d, tmin, tmax);
}

/* The packet form records ray by ray, through the one-ray function it equals bit for bit: the
 * same transactions in the same order as the unit's stream of rays. */
void __real_isect_unit_packet(const f24_triangle *m, uint32_t need, const f24_vec3x2 p[F24Q_LANES], const f24_t te[F24Q_LANES],
                              const f24_vec3 d[F24Q_LANES], const f24_t tmin[F24Q_LANES], const f24_t tmax[F24Q_LANES],
                              isect_result r[F24Q_LANES]);
void __wrap_isect_unit_packet(const f24_triangle *m, uint32_t need, const f24_vec3x2 p[F24Q_LANES], const f24_t te[F24Q_LANES],
                              const f24_vec3 d[F24Q_LANES], const f24_t tmin[F24Q_LANES], const f24_t tmax[F24Q_LANES],
                              isect_result r[F24Q_LANES]);

CAPTURE_PATH void captured_isect_packet(const f24_triangle *m, uint32_t need, const f24_vec3x2 p[F24Q_LANES],
                                        const f24_t te[F24Q_LANES], const f24_vec3 d[F24Q_LANES],
                                        const f24_t tmin[F24Q_LANES], const f24_t tmax[F24Q_LANES],
                                        isect_result r[F24Q_LANES])
{
    for (int i = 0; i < F24Q_LANES; i++)
        r[i] = need >> i & 1u ? captured_isect(m, p[i], te[i], d[i], tmin[i], tmax[i]) : (isect_result){ 0, 0, 0, 0, 0 };
}

void __wrap_isect_unit_packet(const f24_triangle *m, uint32_t need, const f24_vec3x2 p[F24Q_LANES], const f24_t te[F24Q_LANES],
                              const f24_vec3 d[F24Q_LANES], const f24_t tmin[F24Q_LANES], const f24_t tmax[F24Q_LANES],
                              isect_result r[F24Q_LANES])
{
    if (capturing())
        captured_isect_packet(m, need, p, te, d, tmin, tmax, r);
    else
        __real_isect_unit_packet(m, need, p, te, d, tmin, tmax, r);
}

/* the rays' components by axis as fp24 words, ray by ray */
static void held_rays(FILE *f, const f24h v[3])
{
    f24_t c[3][TRACE_PACKET];
    for (int k = 0; k < 3; k++)
        f24h_words(&v[k], c[k]);
    for (int i = 0; i < TRACE_PACKET; i++)
        fprintf(f, " %06x %06x %06x", c[0][i], c[1][i], c[2][i]);
}

CAPTURE_PATH void captured_trav(const trav_entry *e, uint32_t axis, f24_t split, const trav_rays *rays, trav_entry *l,
                                trav_entry *r, uint32_t *near_left)
{
    __real_trav_node_split_held(e, axis, split, rays, l, r, near_left);
    FILE *f = begin(CAP_TRAV);
    if (!f)
        return;
    const uint32_t head[3] = { axis, split, e->mask };
    words(f, head, 3);
    held_rays(f, rays->o);
    held_rays(f, rays->d);
    fputc(' ', f);
    held_words(f, &e->tn);
    fputc(' ', f);
    held_words(f, &e->tf);
    fprintf(f, " %06x %06x %06x ", l->mask, r->mask, *near_left);
    held_words(f, &l->tn);
    fputc(' ', f);
    held_words(f, &l->tf);
    fputc(' ', f);
    held_words(f, &r->tn);
    fputc(' ', f);
    held_words(f, &r->tf);
    end(f);
}

void __wrap_trav_node_split_held(const trav_entry *e, uint32_t axis, f24_t split, const trav_rays *rays, trav_entry *l,
                                 trav_entry *r, uint32_t *near_left)
{
    if (capturing())
        captured_trav(e, axis, split, rays, l, r, near_left);
    else
        __real_trav_node_split_held(e, axis, split, rays, l, r, near_left);
}

/* ---- list unit: list_unit_entry and list_mailboxes_clear, per trace_state ---- */

uint32_t __real_list_unit_entry(const uint32_t *mem, trav_walker *w, trace_mailbox box[TRACE_PACKET], uint32_t alive,
                                uint32_t *key, unit_op *op, trace_counters *c);
void __real_list_mailboxes_clear(trace_mailbox box[TRACE_PACKET]);
uint32_t __wrap_list_unit_entry(const uint32_t *mem, trav_walker *w, trace_mailbox box[TRACE_PACKET], uint32_t alive,
                                uint32_t *key, unit_op *op, trace_counters *c);
void __wrap_list_mailboxes_clear(trace_mailbox box[TRACE_PACKET]);

/* The id of the trace_state at base (called with the lock held); -1 if unknown and not to add. */
static int state_id(const char *base, int add)
{
    for (uint32_t i = 0; i < cap_states; i++)
        if (cap_state[i] == base)
            return (int)i;
    if (!add || cap_states >= CAP_MAX_IDS)
        return -1;
    cap_state[cap_states] = base;
    return (int)cap_states++;
}

#define BOX_OFF(l) (offsetof(trace_state, box) + (size_t)(l) * TRACE_PACKET * sizeof(trace_mailbox))
#define WALK_OFF(l) (offsetof(trace_state, walk) + (size_t)(l) * sizeof(trav_walker))

static void record_list(int id, uint32_t level, const uint32_t in[7], const uint32_t out[4])
{
    FILE *f = cap.f[CAP_LIST];
    fprintf(f, "%x %x", (unsigned)id, level);
    for (int i = 0; i < 7; i++)
        fprintf(f, " %x", in[i]);
    for (int i = 0; i < 4; i++)
        fprintf(f, " %x", out[i]);
    end(f);
}

CAPTURE_PATH void captured_clear(trace_mailbox box[TRACE_PACKET])
{
    __real_list_mailboxes_clear(box);
    FILE *f = begin(CAP_LIST);
    if (!f)
        return;
    /* level 1 if the state it would belong to is known (its level 0 is cleared first, by
     * trace_begin); else level 0 of a (possibly new) state */
    const char *p = (const char *)box;
    int id = state_id(p - BOX_OFF(1), 0);
    uint32_t level = 1;
    if (id < 0)
        id = state_id(p - BOX_OFF(0), 1), level = 0;
    const uint32_t in[7] = { 1, 0, 0, 0, 0, 0, 0 }, out[4] = { 0, 0, 0, 0 };
    record_list(id, level, in, out);
}

void __wrap_list_mailboxes_clear(trace_mailbox box[TRACE_PACKET])
{
    if (capturing())
        captured_clear(box);
    else
        __real_list_mailboxes_clear(box);
}

CAPTURE_PATH uint32_t captured_list(const uint32_t *mem, trav_walker *w, trace_mailbox box[TRACE_PACKET], uint32_t alive,
                                    uint32_t *key, unit_op *op, trace_counters *c)
{
    const trav_walker before = *w;
    const uint64_t skips = c->mailbox_skips;
    const uint32_t need = __real_list_unit_entry(mem, w, box, alive, key, op, c);
    FILE *f = begin(CAP_LIST);
    if (!f)
        return need;
    const ptrdiff_t d = (const char *)box - (const char *)w;
    const uint32_t level = d == (ptrdiff_t)(BOX_OFF(1) - WALK_OFF(1));
    const int id = state_id((const char *)box - BOX_OFF(level), 1);
    const uint32_t in[7] = { 0, before.lists, before.leaf_first, before.k, before.leaf_mask, alive,
                             mem[before.lists + before.leaf_first + before.k] },
                   out[4] = { *key, need, (uint32_t)(c->mailbox_skips - skips), w->k };
    record_list(id, level, in, out);
    return need;
}

uint32_t __wrap_list_unit_entry(const uint32_t *mem, trav_walker *w, trace_mailbox box[TRACE_PACKET], uint32_t alive,
                                uint32_t *key, unit_op *op, trace_counters *c)
{
    return capturing() ? captured_list(mem, w, box, alive, key, op, c) : __real_list_unit_entry(mem, w, box, alive, key, op, c);
}

/* ---- memory interface (cycle mode): every read with its timing and cache lookups ---- */

uint64_t __real_mem_iface_read(mem_iface *m, uint32_t kind, uint32_t word_addr, uint32_t words, uint64_t now);
uint64_t __wrap_mem_iface_read(mem_iface *m, uint32_t kind, uint32_t word_addr, uint32_t words, uint64_t now);
void __real_mem_iface_flush(mem_iface *m);
void __wrap_mem_iface_flush(mem_iface *m);
void __real_mem_iface_new_frame(mem_iface *m);
void __wrap_mem_iface_new_frame(mem_iface *m);

/* The pipe number of m (called with the lock held); a new pipe's configuration line first. */
static uint32_t pipe_id(FILE *f, const mem_iface *m)
{
    uint32_t pipe = 0;
    while (pipe < cap_pipes && cap_pipe[pipe] != m)
        pipe++;
    if (pipe == cap_pipes && cap_pipes < CAP_MAX_IDS) {
        cap_pipe[cap_pipes++] = m;
        fprintf(f, "C %x", pipe);
        for (int k = 0; k < MI_CACHED_KINDS; k++)
            fprintf(f, " %x %x", m->cfg.cache[k].size_bytes, m->cfg.cache[k].line_bytes);
        fprintf(f, " %x %llx\n", m->cfg.latency, (unsigned long long)m->fx_per_byte);
    }
    return pipe;
}

/* The caches emptied (a new memory image: "F pipe") and a new frame (the port and the cycle
 * count start again: "N pipe"). */
void __wrap_mem_iface_flush(mem_iface *m)
{
    __real_mem_iface_flush(m);
    FILE *f = begin(CAP_MEM);
    if (!f)
        return;
    fprintf(f, "F %x", pipe_id(f, m));
    end(f);
}

void __wrap_mem_iface_new_frame(mem_iface *m)
{
    __real_mem_iface_new_frame(m);
    FILE *f = begin(CAP_MEM);
    if (!f)
        return;
    fprintf(f, "N %x", pipe_id(f, m));
    end(f);
}

CAPTURE_PATH uint64_t captured_read(mem_iface *m, uint32_t kind, uint32_t word_addr, uint32_t words, uint64_t now)
{
    const uint64_t l0 = kind < MEM_KINDS ? m->stats.lookups[kind] : 0, h0 = kind < MEM_KINDS ? m->stats.hits[kind] : 0;
    const uint64_t at = __real_mem_iface_read(m, kind, word_addr, words, now);
    FILE *f = begin(CAP_MEM);
    if (!f)
        return at;
    const uint32_t pipe = pipe_id(f, m);
    fprintf(f, "%x %x %x %x %llx %llx %llx %llx", pipe, kind, word_addr, words, (unsigned long long)now,
            (unsigned long long)at, (unsigned long long)(m->stats.lookups[kind] - l0),
            (unsigned long long)(m->stats.hits[kind] - h0));
    end(f);
    return at;
}

uint64_t __wrap_mem_iface_read(mem_iface *m, uint32_t kind, uint32_t word_addr, uint32_t words, uint64_t now)
{
    return capturing() ? captured_read(m, kind, word_addr, words, now) : __real_mem_iface_read(m, kind, word_addr, words, now);
}

/* The scheduler's events (cycle_sim.h): "N pipe threads" where a pipe starts a frame, "R pipe
 * cycle unit thread slots" where a thread joins a unit's ready set (cycle: the first the unit can
 * issue it), "I pipe cycle unit thread slots" where the unit issues it. */
void capture_sched_probe(void *arg, uint32_t pipe, int what, uint64_t cycle, uint32_t unit, uint32_t thread,
                         uint32_t slots)
{
    (void)arg;
    FILE *f = begin(CAP_SCHED);
    if (!f)
        return;
    if (what == SCHED_FRAME)
        fprintf(f, "N %x %x", pipe, thread);
    else
        fprintf(f, "%c %x %llx %x %x %x", what == SCHED_READY ? 'R' : 'I', pipe, (unsigned long long)cycle, unit, thread,
                slots);
    end(f);
}

/* ---- RGS: the primary packet of every block a thread takes, with the camera block ---- */

void __real_rgs_block_begin(const uint32_t *mem, uint32_t x0, uint32_t y0, rgs_block *b);
void __wrap_rgs_block_begin(const uint32_t *mem, uint32_t x0, uint32_t y0, rgs_block *b);

void __wrap_rgs_block_begin(const uint32_t *mem, uint32_t x0, uint32_t y0, rgs_block *b)
{
    __real_rgs_block_begin(mem, x0, y0, b);
    FILE *f = begin(CAP_RGS);
    if (!f)
        return;
    const ray_packet *rp = &b->stack[0].rays; /* the primary packet, the block's first task */
    fprintf(f, "%x %x ", x0, y0);
    words(f, &mem[mem[MI_H_REGION_TABLE + 2 * MI_R_CAMERA]], MI_CAMERA_WORDS);
    fprintf(f, " %x", rp->active);
    for (int i = 0; i < TRACE_PACKET; i++)
        fprintf(f, " %06x %06x %06x", rp->o[i].x, rp->o[i].y, rp->o[i].z);
    for (int i = 0; i < TRACE_PACKET; i++)
        fprintf(f, " %06x %06x %06x", rp->d[i].x, rp->d[i].y, rp->d[i].z);
    fputc(' ', f);
    words(f, rp->tmin, TRACE_PACKET);
    fputc(' ', f);
    words(f, rp->tmax, TRACE_PACKET);
    end(f);
}

/* ---- RGS shading: each vertex normal decoded from a compact shading record (surface_at's
 * rgs_vertex_normals decodes the three side by side, shade_rec_normals; for rtl/tb/tb_shade.cpp a line per
 * normal): the record's 4 normal words, the vertex k, the unit normal ---- */

void __real_shade_rec_normals(const uint32_t *normals, f24_t out[3][F24Q_LANES]);
void __wrap_shade_rec_normals(const uint32_t *normals, f24_t out[3][F24Q_LANES]);

CAPTURE_PATH void captured_shade_rec_normals(const uint32_t *normals, f24_t out[3][F24Q_LANES])
{
    __real_shade_rec_normals(normals, out);
    for (uint32_t k = 0; k < 3; k++) {
        FILE *f = begin(CAP_SHADE_REC);
        if (!f)
            return;
        const uint32_t n[3] = { out[0][k], out[1][k], out[2][k] };
        words(f, normals, SHADE_NORMAL_WORDS);
        fprintf(f, " %x ", k);
        words(f, n, 3);
        end(f);
    }
}

void __wrap_shade_rec_normals(const uint32_t *normals, f24_t out[3][F24Q_LANES])
{
    if (capturing())
        captured_shade_rec_normals(normals, out);
    else
        __real_shade_rec_normals(normals, out);
}

/* The RGS's bilinear texture samples (for rtl/tb/tb_shade.cpp): s, t, the texture entry's width,
 * height and texel address; the 4 texel words read (t00, t10, t01, t11); the two axes' x0, x1, fx
 * and y0, y1, fy (rgs_texel_axis); the Q12 sample. */
void __real_rgs_sample_bilinear(const uint32_t *mem, const uint32_t *tex, f24_t s, f24_t t, uint32_t out[3], unit_op *op,
                                trace_counters *c);
void __wrap_rgs_sample_bilinear(const uint32_t *mem, const uint32_t *tex, f24_t s, f24_t t, uint32_t out[3], unit_op *op,
                                trace_counters *c);

CAPTURE_PATH void captured_sample(const uint32_t *mem, const uint32_t *tex, f24_t s, f24_t t, uint32_t out[3],
                                  unit_op *op, trace_counters *c)
{
    __real_rgs_sample_bilinear(mem, tex, s, t, out, op, c);
    FILE *f = begin(CAP_TEX);
    if (!f)
        return;
    uint32_t a[6];
    rgs_texel_axis(s, tex[0], &a[0], &a[1], &a[2]);
    rgs_texel_axis(t, tex[1], &a[3], &a[4], &a[5]);
    const uint32_t in[5] = { s, t, tex[0], tex[1], tex[2] };
    const uint32_t texels[4] = { mem[tex[2] + a[3] * tex[0] + a[0]], mem[tex[2] + a[3] * tex[0] + a[1]],
                                 mem[tex[2] + a[4] * tex[0] + a[0]], mem[tex[2] + a[4] * tex[0] + a[1]] };
    fprintf(f, "%x %x %x %x %x %x %x %x %x", in[0], in[1], in[2], in[3], in[4], texels[0], texels[1], texels[2], texels[3]);
    for (int k = 0; k < 6; k++)
        fprintf(f, " %x", a[k]);
    fprintf(f, " %x %x %x", out[0], out[1], out[2]);
    end(f);
}

void __wrap_rgs_sample_bilinear(const uint32_t *mem, const uint32_t *tex, f24_t s, f24_t t, uint32_t out[3], unit_op *op,
                                trace_counters *c)
{
    if (capturing())
        captured_sample(mem, tex, s, t, out, op, c);
    else
        __real_rgs_sample_bilinear(mem, tex, s, t, out, op, c);
}

/* The frame of each hit the RGS shades (for rtl/tb/tb_shade.cpp): o, d, t, cos_n, the object-space
 * normal, the world-to-object matrix's 3x3 (row by row); the unit direction, the unit shading
 * normal, entering, t_hat, the hit point. */
void __real_rgs_surface_frame(f24_vec3 o, f24_vec3 d, f24_t t, f24_t cos_n, f24_vec3 n, const f24_affine *w2o,
                              surface *sf);
void __wrap_rgs_surface_frame(f24_vec3 o, f24_vec3 d, f24_t t, f24_t cos_n, f24_vec3 n, const f24_affine *w2o,
                              surface *sf);

CAPTURE_PATH void captured_frame(f24_vec3 o, f24_vec3 d, f24_t t, f24_t cos_n, f24_vec3 n, const f24_affine *w2o,
                                 surface *sf)
{
    __real_rgs_surface_frame(o, d, t, cos_n, n, w2o, sf);
    FILE *f = begin(CAP_FRAME);
    if (!f)
        return;
    const uint32_t w[31] = { o.x, o.y, o.z, d.x, d.y, d.z, t, cos_n, n.x, n.y, n.z,
                             w2o->m[0][0], w2o->m[0][1], w2o->m[0][2], w2o->m[1][0], w2o->m[1][1], w2o->m[1][2],
                             w2o->m[2][0], w2o->m[2][1], w2o->m[2][2],
                             sf->d.x, sf->d.y, sf->d.z, sf->n.x, sf->n.y, sf->n.z, (uint32_t)sf->entering, sf->t_hat,
                             sf->p.x, sf->p.y, sf->p.z };
    words(f, w, 31);
    end(f);
}

void __wrap_rgs_surface_frame(f24_vec3 o, f24_vec3 d, f24_t t, f24_t cos_n, f24_vec3 n, const f24_affine *w2o,
                              surface *sf)
{
    if (capturing())
        captured_frame(o, d, t, cos_n, n, w2o, sf);
    else
        __real_rgs_surface_frame(o, d, t, cos_n, n, w2o, sf);
}

/* The child rays of each surface (for rtl/tb/tb_shade.cpp): the material's words 13..15, the ray's
 * weight, e, the surface's T_R origin, D^, N^, t_hat, entering, tint, base; the reflection ray's o,
 * d, weight, active bit, the transmission ray's likewise. */
void __real_rgs_spawn_children(const uint32_t *m, const uint32_t weight[3], f24_t eps, int i, const surface *sf,
                               rgs_task *refl, rgs_task *trans);
void __wrap_rgs_spawn_children(const uint32_t *m, const uint32_t weight[3], f24_t eps, int i, const surface *sf,
                               rgs_task *refl, rgs_task *trans);

static void task_ray(FILE *f, const rgs_task *t, int i)
{
    fprintf(f, " %06x %06x %06x %06x %06x %06x %x %x %x %x", t->rays.o[i].x, t->rays.o[i].y, t->rays.o[i].z, t->rays.d[i].x,
            t->rays.d[i].y, t->rays.d[i].z, t->weight[i][0], t->weight[i][1], t->weight[i][2], t->rays.active >> i & 1u);
}

CAPTURE_PATH void captured_spawn(const uint32_t *m, const uint32_t weight[3], f24_t eps, int i, const surface *sf,
                                 rgs_task *refl, rgs_task *trans)
{
    __real_rgs_spawn_children(m, weight, eps, i, sf, refl, trans);
    FILE *f = begin(CAP_SPAWN);
    if (!f)
        return;
    const uint32_t w[24] = { m[13], m[14], m[15], weight[0], weight[1], weight[2], eps, sf->tr.m[0][3], sf->tr.m[1][3],
                             sf->tr.m[2][3], sf->d.x, sf->d.y, sf->d.z, sf->n.x, sf->n.y, sf->n.z, sf->t_hat,
                             (uint32_t)sf->entering, sf->tint[0], sf->tint[1], sf->tint[2], sf->base[0], sf->base[1],
                             sf->base[2] };
    words(f, w, 24);
    task_ray(f, refl, i);
    task_ray(f, trans, i);
    end(f);
}

void __wrap_rgs_spawn_children(const uint32_t *m, const uint32_t weight[3], f24_t eps, int i, const surface *sf,
                               rgs_task *refl, rgs_task *trans)
{
    if (capturing())
        captured_spawn(m, weight, eps, i, sf, refl, trans);
    else
        __real_rgs_spawn_children(m, weight, eps, i, sf, refl, trans);
}

/* Each light's colour (for rtl/tb/tb_shade.cpp): the record's words 1..3; the Q12 colour. */
void __real_rgs_light_colour(const uint32_t *l, uint32_t out[3]);
void __wrap_rgs_light_colour(const uint32_t *l, uint32_t out[3]);

CAPTURE_PATH void captured_colour(const uint32_t *l, uint32_t out[3])
{
    __real_rgs_light_colour(l, out);
    FILE *f = begin(CAP_COLOUR);
    if (!f)
        return;
    words(f, &l[1], 3);
    fputc(' ', f);
    words(f, out, 3);
    end(f);
}

void __wrap_rgs_light_colour(const uint32_t *l, uint32_t out[3])
{
    if (capturing())
        captured_colour(l, out);
    else
        __real_rgs_light_colour(l, out);
}

/* Each visible light added to a ray's sums (for rtl/tb/tb_shade.cpp): diffuse and highlight sums
 * before, diff, spec, the light's colour; the sums after. */
void __real_rgs_add_light(uint32_t diffuse[3], uint32_t highlight[3], uint32_t diff, uint32_t spec,
                          const uint32_t colour[3]);
void __wrap_rgs_add_light(uint32_t diffuse[3], uint32_t highlight[3], uint32_t diff, uint32_t spec,
                          const uint32_t colour[3]);

CAPTURE_PATH void captured_accum(uint32_t diffuse[3], uint32_t highlight[3], uint32_t diff, uint32_t spec,
                                 const uint32_t colour[3])
{
    const uint32_t in[11] = { diffuse[0], diffuse[1], diffuse[2], highlight[0], highlight[1], highlight[2], diff, spec,
                              colour[0], colour[1], colour[2] };
    __real_rgs_add_light(diffuse, highlight, diff, spec, colour);
    FILE *f = begin(CAP_ACCUM);
    if (!f)
        return;
    words(f, in, 11);
    fputc(' ', f);
    words(f, diffuse, 3);
    fputc(' ', f);
    words(f, highlight, 3);
    end(f);
}

void __wrap_rgs_add_light(uint32_t diffuse[3], uint32_t highlight[3], uint32_t diff, uint32_t spec,
                          const uint32_t colour[3])
{
    if (capturing())
        captured_accum(diffuse, highlight, diff, spec, colour);
    else
        __real_rgs_add_light(diffuse, highlight, diff, spec, colour);
}

/* Each component of a hit's interpolated vertex normal or texture coordinates (for
 * rtl/tb/tb_shade.cpp): a, b, c, u, v; u a + v b + (1 - u - v) c. */
f24_t __real_rgs_lerp(f24_t a, f24_t b, f24_t c, f24_t u, f24_t v);
f24_t __wrap_rgs_lerp(f24_t a, f24_t b, f24_t c, f24_t u, f24_t v);

CAPTURE_PATH f24_t captured_lerp(f24_t a, f24_t b, f24_t c, f24_t u, f24_t v)
{
    const f24_t r = __real_rgs_lerp(a, b, c, u, v);
    FILE *f = begin(CAP_LERP);
    if (!f)
        return r;
    const uint32_t w[6] = { a, b, c, u, v, r };
    words(f, w, 6);
    end(f);
    return r;
}

f24_t __wrap_rgs_lerp(f24_t a, f24_t b, f24_t c, f24_t u, f24_t v)
{
    return capturing() ? captured_lerp(a, b, c, u, v) : __real_rgs_lerp(a, b, c, u, v);
}

/* The interpolated vertex normal (rgs_lerp_normal): a lerp.hex line per component. */
f24_vec3 __real_rgs_lerp_normal(const f24_t n[3][F24Q_LANES], f24_t u, f24_t v);
f24_vec3 __wrap_rgs_lerp_normal(const f24_t n[3][F24Q_LANES], f24_t u, f24_t v);

CAPTURE_PATH f24_vec3 captured_lerp_normal(const f24_t n[3][F24Q_LANES], f24_t u, f24_t v)
{
    const f24_vec3 r = __real_rgs_lerp_normal(n, u, v);
    const f24_t rc[3] = { r.x, r.y, r.z };
    for (int c = 0; c < 3; c++) {
        FILE *f = begin(CAP_LERP);
        if (!f)
            return r;
        const uint32_t w[6] = { n[c][0], n[c][1], n[c][2], u, v, rc[c] };
        words(f, w, 6);
        end(f);
    }
    return r;
}

f24_vec3 __wrap_rgs_lerp_normal(const f24_t n[3][F24Q_LANES], f24_t u, f24_t v)
{
    return capturing() ? captured_lerp_normal(n, u, v) : __real_rgs_lerp_normal(n, u, v);
}

/* Each light's weights and shadow ray at each surface of a packet (for rtl/tb/tb_shade.cpp), a line
 * per ray: the light record's words 0..12, eps, the surface's valid, unlit, P, N^, D^, highlight
 * exponent; the shadow ray's o, d, tmin, tmax, its active bit, the diffuse and highlight weights. */
void __real_rgs_light_packet(const uint32_t *l, const surface sf[], f24_t eps, ray_packet *sh, uint32_t diff[],
                             uint32_t spec[], const uint32_t k_of[]);
void __wrap_rgs_light_packet(const uint32_t *l, const surface sf[], f24_t eps, ray_packet *sh, uint32_t diff[],
                             uint32_t spec[], const uint32_t k_of[]);

CAPTURE_PATH void captured_light(const uint32_t *l, const surface sf[], f24_t eps, ray_packet *sh, uint32_t diff[],
                                 uint32_t spec[], const uint32_t k_of[])
{
    __real_rgs_light_packet(l, sf, eps, sh, diff, spec, k_of);
    for (int i = 0; i < TRACE_PACKET; i++) {
        FILE *f = begin(CAP_LIGHT);
        if (!f)
            return;
        const surface *s = &sf[i];
        const uint32_t w[24] = { eps, (uint32_t)s->valid, (uint32_t)s->unlit, s->p.x, s->p.y, s->p.z, s->n.x, s->n.y, s->n.z,
                                 s->d.x, s->d.y, s->d.z, k_of[i], sh->o[i].x, sh->o[i].y, sh->o[i].z, sh->d[i].x,
                                 sh->d[i].y, sh->d[i].z, sh->tmin[i], sh->tmax[i], sh->active >> i & 1u, diff[i], spec[i] };
        words(f, l, 13);
        fputc(' ', f);
        words(f, w, 24);
        end(f);
    }
}

void __wrap_rgs_light_packet(const uint32_t *l, const surface sf[], f24_t eps, ray_packet *sh, uint32_t diff[],
                             uint32_t spec[], const uint32_t k_of[])
{
    if (capturing())
        captured_light(l, sf, eps, sh, diff, spec, k_of);
    else
        __real_rgs_light_packet(l, sf, eps, sh, diff, spec, k_of);
}

/* ---- traversal unit: its operations per trace_state and level (for rtl/tb/tb_trav.cpp) ---- */

uint32_t __real_trav_scene_clip(const uint32_t *bounds, const ray_packet *rays, f24_t tn[TRACE_PACKET],
                                f24_t tf[TRACE_PACKET]);
uint32_t __real_trav_object_clip(const uint32_t *bounds, const f24_vec3 o[], const f24_vec3 d[], const f24_t tmin[],
                                 const f24_t best_t[], uint32_t need, f24_t tn[TRACE_PACKET], f24_t tf[TRACE_PACKET]);
void __real_trav_start(trav_walker *w, const uint32_t *mem, uint32_t asked, uint32_t accel, uint32_t nodes,
                       uint32_t lists, uint32_t grid, uint32_t mask, const f24_t tn[], const f24_t tf[],
                       const f24_vec3 o[], const f24_vec3 d[], unit_op *op, trace_counters *c);
int __real_trav_walk(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[], const f24_t best_t[],
                     uint32_t alive, unit_op *op, trace_counters *c);
uint32_t __wrap_trav_scene_clip(const uint32_t *bounds, const ray_packet *rays, f24_t tn[TRACE_PACKET],
                                f24_t tf[TRACE_PACKET]);
uint32_t __wrap_trav_object_clip(const uint32_t *bounds, const f24_vec3 o[], const f24_vec3 d[], const f24_t tmin[],
                                 const f24_t best_t[], uint32_t need, f24_t tn[TRACE_PACKET], f24_t tf[TRACE_PACKET]);
void __wrap_trav_start(trav_walker *w, const uint32_t *mem, uint32_t asked, uint32_t accel, uint32_t nodes,
                       uint32_t lists, uint32_t grid, uint32_t mask, const f24_t tn[], const f24_t tf[],
                       const f24_vec3 o[], const f24_vec3 d[], unit_op *op, trace_counters *c);
int __wrap_trav_walk(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[], const f24_t best_t[],
                     uint32_t alive, unit_op *op, trace_counters *c);

/* One line of trav_unit.hex: kind (0 scene clip, 1 object clip, 2 start, 3 walk), thread, level;
 * box (6), o (12), d (12), tn (4), tf (4), best_t (4), mask, nodes, algorithm, the node read
 * (address, w0, w1; address ffffffff for none); the return value, and after the operation the
 * walker's have_cur, whether the step was at a leaf, leaf_first, leaf_count, leaf_mask, leaf_tn
 * (4), sp, the current entry (node, mask, tn (4), tf (4); for a clip its mask, tn, tf), lost, pass. */
typedef struct {
    uint32_t kind, box[6], o[12], d[12], tn[4], tf[4], best[4], mask, nodes, algo, read[3];
} trav_cap_in;

static void vec_words(uint32_t out[12], const f24_vec3 v[])
{
    for (int i = 0; i < TRACE_PACKET; i++)
        out[3 * i] = v[i].x, out[3 * i + 1] = v[i].y, out[3 * i + 2] = v[i].z;
}

static void record_trav(const char *base, uint32_t level, const trav_cap_in *in, uint32_t ret, const trav_walker *w,
                        uint32_t leaf, uint32_t node, uint32_t mask, const f24_t tn[4], const f24_t tf[4])
{
    FILE *f = begin(CAP_TRAV_UNIT);
    if (!f)
        return;
    fprintf(f, "%x %x %x ", in->kind, (unsigned)state_id(base, 1), level);
    words(f, in->box, 6);
    fputc(' ', f);
    words(f, in->o, 12);
    fputc(' ', f);
    words(f, in->d, 12);
    fputc(' ', f);
    words(f, in->tn, 4);
    fputc(' ', f);
    words(f, in->tf, 4);
    fputc(' ', f);
    words(f, in->best, 4);
    fprintf(f, " %x %x %x %x %x %x %x", in->mask, in->nodes, in->algo, in->read[0], in->read[1], in->read[2], ret);
    fprintf(f, " %x %x %x %x %x ", w->have_cur, leaf, w->leaf_first, w->leaf_count, w->leaf_mask);
    words(f, w->leaf_tn, 4);
    fprintf(f, " %x %x %x ", w->sp, node, mask);
    words(f, tn, 4);
    fputc(' ', f);
    words(f, tf, 4);
    fprintf(f, " %x %x", w->lost, w->pass);
    end(f);
}

CAPTURE_PATH uint32_t captured_scene_clip(const uint32_t *bounds, const ray_packet *rays, f24_t tn[TRACE_PACKET],
                                           f24_t tf[TRACE_PACKET])
{
    const uint32_t mask = __real_trav_scene_clip(bounds, rays, tn, tf);
    trav_cap_in in = { .kind = 0, .mask = rays->active, .read = { 0xFFFFFFFFu, 0, 0 } };
    memcpy(in.box, bounds, sizeof in.box);
    vec_words(in.o, rays->o);
    vec_words(in.d, rays->d);
    memcpy(in.tn, rays->tmin, sizeof in.tn);
    memcpy(in.tf, rays->tmax, sizeof in.tf);
    const trav_walker none = { 0 };
    record_trav((const char *)rays - offsetof(trace_state, rays), 0, &in, mask, &none, 0, 0, mask, tn, tf);
    return mask;
}

CAPTURE_PATH uint32_t captured_object_clip(const uint32_t *bounds, const f24_vec3 o[], const f24_vec3 d[],
                                            const f24_t tmin[], const f24_t best_t[], uint32_t need,
                                            f24_t tn[TRACE_PACKET], f24_t tf[TRACE_PACKET])
{
    const uint32_t mask = __real_trav_object_clip(bounds, o, d, tmin, best_t, need, tn, tf);
    trav_cap_in in = { .kind = 1, .mask = need, .read = { 0xFFFFFFFFu, 0, 0 } };
    memcpy(in.box, bounds, sizeof in.box);
    vec_words(in.o, o);
    vec_words(in.d, d);
    for (int i = 0; i < TRACE_PACKET; i++) /* the rays outside need: not read by the unit */
        in.tn[i] = need >> i & 1u ? tmin[i] : 0, in.tf[i] = need >> i & 1u ? best_t[i] : 0;
    const trav_walker none = { 0 };
    record_trav((const char *)o - offsetof(trace_state, o), 1, &in, mask, &none, 0, 0, mask, tn, tf);
    return mask;
}

/* record_trav after an operation of walker w, its current entry as the result */
static void record_walker(const char *base, uint32_t level, const trav_cap_in *in, uint32_t ret, const trav_walker *w,
                          uint32_t leaf)
{
    f24_t tn[TRACE_PACKET], tf[TRACE_PACKET];
    f24h_words(&w->cur.tn, tn);
    f24h_words(&w->cur.tf, tf);
    record_trav(base, level, in, ret, w, leaf, w->cur.node, w->cur.mask, tn, tf);
}

/* The trace_state and level of walker w: level 1 if that state is known, else level 0. */
static const char *walker_base(const trav_walker *w, uint32_t *level)
{
    const char *p = (const char *)w;
    pthread_mutex_lock(&cap.lock);
    *level = state_id(p - WALK_OFF(1), 0) >= 0;
    pthread_mutex_unlock(&cap.lock);
    return p - WALK_OFF(*level);
}

CAPTURE_PATH void captured_start(trav_walker *w, const uint32_t *mem, uint32_t asked, uint32_t accel, uint32_t nodes,
                                 uint32_t lists, uint32_t grid, uint32_t mask, const f24_t tn[], const f24_t tf[],
                                 const f24_vec3 o[], const f24_vec3 d[], unit_op *op, trace_counters *c)
{
    __real_trav_start(w, mem, asked, accel, nodes, lists, grid, mask, tn, tf, o, d, op, c);
    trav_cap_in in = { .kind = 2, .mask = mask, .nodes = nodes, .algo = w->algo, .read = { 0xFFFFFFFFu, 0, 0 } };
    vec_words(in.o, o);
    vec_words(in.d, d);
    memcpy(in.tn, tn, sizeof in.tn);
    memcpy(in.tf, tf, sizeof in.tf);
    uint32_t level;
    const char *base = walker_base(w, &level);
    record_walker(base, level, &in, 0, w, 0);
}

CAPTURE_PATH int captured_walk(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[],
                               const f24_t best_t[], uint32_t alive, unit_op *op, trace_counters *c)
{
    const uint64_t leaves = c->leaves;
    const int ret = __real_trav_walk(w, mem, o, d, best_t, alive, op, c);
    trav_cap_in in = { .kind = 3, .mask = alive, .nodes = w->nodes, .algo = w->algo, .read = { 0xFFFFFFFFu, 0, 0 } };
    vec_words(in.o, o);
    vec_words(in.d, d);
    memcpy(in.best, best_t, sizeof in.best);
    for (uint32_t r = 0; r < op->n_reads; r++)
        if (op->read[r].kind == MEM_NODES) {
            const uint32_t a = op->read[r].addr;
            in.read[0] = a, in.read[1] = mem[a], in.read[2] = mem[a + 1];
        }
    uint32_t level;
    const char *base = walker_base(w, &level);
    record_walker(base, level, &in, (uint32_t)ret, w, c->leaves != leaves);
    return ret;
}

uint32_t __wrap_trav_scene_clip(const uint32_t *bounds, const ray_packet *rays, f24_t tn[TRACE_PACKET],
                                f24_t tf[TRACE_PACKET])
{
    return capturing() ? captured_scene_clip(bounds, rays, tn, tf) : __real_trav_scene_clip(bounds, rays, tn, tf);
}

uint32_t __wrap_trav_object_clip(const uint32_t *bounds, const f24_vec3 o[], const f24_vec3 d[], const f24_t tmin[],
                                 const f24_t best_t[], uint32_t need, f24_t tn[TRACE_PACKET], f24_t tf[TRACE_PACKET])
{
    return capturing() ? captured_object_clip(bounds, o, d, tmin, best_t, need, tn, tf)
                       : __real_trav_object_clip(bounds, o, d, tmin, best_t, need, tn, tf);
}

void __wrap_trav_start(trav_walker *w, const uint32_t *mem, uint32_t asked, uint32_t accel, uint32_t nodes,
                       uint32_t lists, uint32_t grid, uint32_t mask, const f24_t tn[], const f24_t tf[],
                       const f24_vec3 o[], const f24_vec3 d[], unit_op *op, trace_counters *c)
{
    if (capturing())
        captured_start(w, mem, asked, accel, nodes, lists, grid, mask, tn, tf, o, d, op, c);
    else
        __real_trav_start(w, mem, asked, accel, nodes, lists, grid, mask, tn, tf, o, d, op, c);
}

int __wrap_trav_walk(trav_walker *w, const uint32_t *mem, const f24_vec3 o[], const f24_vec3 d[], const f24_t best_t[],
                     uint32_t alive, unit_op *op, trace_counters *c)
{
    return capturing() ? captured_walk(w, mem, o, d, best_t, alive, op, c)
                       : __real_trav_walk(w, mem, o, d, best_t, alive, op, c);
}

/* ---- the core: every packet from trace_begin to its hits (for rtl/tb/tb_core.cpp) ---- */

void __real_trace_begin(const ray_packet *rays, uint32_t flags, trace_state *s);
int __real_trace_step(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c);
void __wrap_trace_begin(const ray_packet *rays, uint32_t flags, trace_state *s);
int __wrap_trace_step(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c);

static int trace_slot(const trace_state *s)
{
    for (int i = 0; i < CAP_TRACES; i++)
        if (cap_trace[i].s == s)
            return i;
    return -1;
}

CAPTURE_PATH void captured_trace_begin(const ray_packet *rays, uint32_t flags, trace_state *s)
{
    __real_trace_begin(rays, flags, s);
    pthread_mutex_lock(&cap.lock);
    int i = trace_slot(s);
    if (i < 0)
        i = trace_slot(NULL); /* no slot free (more packets in flight than CAP_TRACES): not recorded */
    if (i >= 0) {
        cap_trace[i].s = s;
        cap_trace[i].id = (uint32_t)state_id((const char *)s, 1);
        cap_trace[i].flags = flags;
        cap_trace[i].rays = *rays;
        cap_trace[i].stepped = 0;
        memset(&cap_trace[i].c, 0, sizeof cap_trace[i].c);
    }
    pthread_mutex_unlock(&cap.lock);
}

/* The image a packet reads: written once per image address and frame word (animations update the
 * image in place), all its used words. */
static uint32_t trace_image(const uint32_t *mem)
{
    if (cap_images && mem == cap_image && mem[MI_H_FRAME] == cap_image_frame)
        return cap_images - 1;
    char path[1100];
    snprintf(path, sizeof path, "%s/image_%u.bin", cap_dir, cap_images);
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(mem, sizeof *mem, mem[MI_H_USED_WORDS], f);
        fclose(f);
    }
    cap_image = mem;
    cap_image_frame = mem[MI_H_FRAME];
    return cap_images++;
}

CAPTURE_PATH int captured_trace_step(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    const trace_counters before = *c;
    const int more = __real_trace_step(mem, s, op, c);
    pthread_mutex_lock(&cap.lock);
    const int i = trace_slot(s);
    if (i < 0) {
        pthread_mutex_unlock(&cap.lock);
        return more;
    }
    if (!cap_trace[i].stepped++)
        cap_trace[i].image = trace_image(mem);
    uint64_t *sum = &cap_trace[i].c.traversal_steps;
    const uint64_t *now = &c->traversal_steps, *was = &before.traversal_steps;
    for (uint32_t k = 0; k < sizeof *c / sizeof *now; k++) /* trace_counters: all uint64_t */
        sum[k] += now[k] - was[k];
    const uint32_t image = cap_trace[i].image, id = cap_trace[i].id, flags = cap_trace[i].flags;
    const ray_packet rays = cap_trace[i].rays;
    const trace_counters pc = cap_trace[i].c;
    if (!more)
        cap_trace[i].s = NULL;
    pthread_mutex_unlock(&cap.lock);
    if (more)
        return more;
    FILE *f = begin(CAP_TRACE);
    if (!f)
        return more;
    /* one line of trace.hex: image, thread (trace_state number), flags, active, 4 x O, 4 x D, 4 x tmin,
     * 4 x tmax; per ray instance, triangle, t, u, v, cos; the packet's trace_counters (10) */
    fprintf(f, "%x %x %x %x", image, id, flags, rays.active);
    for (int r = 0; r < TRACE_PACKET; r++)
        fprintf(f, " %06x %06x %06x", rays.o[r].x, rays.o[r].y, rays.o[r].z);
    for (int r = 0; r < TRACE_PACKET; r++)
        fprintf(f, " %06x %06x %06x", rays.d[r].x, rays.d[r].y, rays.d[r].z);
    fputc(' ', f);
    words(f, rays.tmin, TRACE_PACKET);
    fputc(' ', f);
    words(f, rays.tmax, TRACE_PACKET);
    for (int r = 0; r < TRACE_PACKET; r++) {
        const hit_record *h = &s->hits[r];
        fprintf(f, " %x %x %06x %06x %06x %06x", h->instance, h->triangle, h->t, h->u, h->v, h->cos_n);
    }
    const uint64_t *pw = &pc.traversal_steps;
    for (uint32_t k = 0; k < sizeof pc / sizeof *pw; k++)
        fprintf(f, " %llx", (unsigned long long)pw[k]);
    end(f);
    return more;
}

void __wrap_trace_begin(const ray_packet *rays, uint32_t flags, trace_state *s)
{
    if (capturing())
        captured_trace_begin(rays, flags, s);
    else
        __real_trace_begin(rays, flags, s);
}

int __wrap_trace_step(const uint32_t *mem, trace_state *s, unit_op *op, trace_counters *c)
{
    return capturing() ? captured_trace_step(mem, s, op, c) : __real_trace_step(mem, s, op, c);
}

/* The surface of each hit the RGS shades (for rtl/tb/tb_shade.cpp): the memory image it reads
 * (image_N.bin, as trace.hex), the ray's active bit, o, d; the hit's instance, triangle, t, u, v,
 * cos_n; the reads noted (count, then address and words of each); the surface: valid, P, D^, N^,
 * t_hat, entering, material address, unlit, base, emission, tint (Q12). */
surface __real_rgs_surface_at(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h, unit_op *op,
                              trace_counters *c);
surface __wrap_rgs_surface_at(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h, unit_op *op,
                              trace_counters *c);

CAPTURE_PATH surface captured_surface(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h,
                                      unit_op *op, trace_counters *c)
{
    const uint32_t first = op->n_reads;
    const surface sf = __real_rgs_surface_at(mem, rp, i, h, op, c);
    FILE *f = begin(CAP_SURFACE);
    if (!f)
        return sf;
    fprintf(f, "%x %x %06x %06x %06x %06x %06x %06x %x %x %06x %06x %06x %06x %x", trace_image(mem),
            rp->active >> i & 1u, rp->o[i].x, rp->o[i].y, rp->o[i].z, rp->d[i].x, rp->d[i].y, rp->d[i].z,
            h->instance, h->triangle, h->t, h->u, h->v, h->cos_n, op->n_reads - first);
    for (uint32_t r = first; r < op->n_reads; r++)
        fprintf(f, " %x %x", op->read[r].addr, op->read[r].words);
    const uint32_t w[14] = { (uint32_t)sf.valid, sf.p.x, sf.p.y, sf.p.z, sf.d.x, sf.d.y, sf.d.z,
                             sf.n.x, sf.n.y, sf.n.z, sf.t_hat, (uint32_t)sf.entering, sf.mat, (uint32_t)sf.unlit };
    fputc(' ', f);
    words(f, w, 14);
    for (int k = 0; k < 3; k++)
        fprintf(f, " %x %x %x", sf.base[k], sf.emission[k], sf.tint[k]);
    end(f);
    return sf;
}

surface __wrap_rgs_surface_at(const uint32_t *mem, const ray_packet *rp, int i, const hit_record *h, unit_op *op,
                              trace_counters *c)
{
    return capturing() ? captured_surface(mem, rp, i, h, op, c) : __real_rgs_surface_at(mem, rp, i, h, op, c);
}

/* The packet's surfaces (op_surfaces): while capturing, ray by ray through the wrapper above (the
 * simulation build's frames side by side call no rgs_surface_frame, and the per-ray loop calls
 * rgs_surface_at in its own object file, which no wrapper sees). */
void __real_rgs_surfaces(const uint32_t *mem, const ray_packet *rp, const hit_record h[], surface sf[], unit_op *op,
                         trace_counters *c);
void __wrap_rgs_surfaces(const uint32_t *mem, const ray_packet *rp, const hit_record h[], surface sf[], unit_op *op,
                         trace_counters *c);

void __wrap_rgs_surfaces(const uint32_t *mem, const ray_packet *rp, const hit_record h[], surface sf[], unit_op *op,
                         trace_counters *c)
{
    if (!capturing()) {
        __real_rgs_surfaces(mem, rp, h, sf, op, c);
        return;
    }
    for (int i = 0; i < TRACE_PACKET; i++)
        sf[i] = __wrap_rgs_surface_at(mem, rp, i, &h[i], op, c);
}

/* Each active ray's share of op_accumulate (for rtl/tb/tb_accum.cpp): the material's words 13..15
 * (0 for an invalid surface), the surface's valid, T_R origin, D^, N^, t_hat, entering, base,
 * emission, tint; the ray i, its weight, diffuse and highlight sums, e, the spawn bits, the pixel's
 * sum before; the sum after, the reflection ray's o, d, weight, active bit, the transmission ray's
 * likewise, and whether its children take T_R steps. */
int __real_rgs_accumulate_ray(const uint32_t *m, const surface *sf, int i, const uint32_t weight[3],
                              const uint32_t diffuse[3], const uint32_t highlight[3], f24_t eps, uint32_t spawn,
                              uint32_t acc[3], rgs_task *refl, rgs_task *trans);
int __wrap_rgs_accumulate_ray(const uint32_t *m, const surface *sf, int i, const uint32_t weight[3],
                              const uint32_t diffuse[3], const uint32_t highlight[3], f24_t eps, uint32_t spawn,
                              uint32_t acc[3], rgs_task *refl, rgs_task *trans);

CAPTURE_PATH int captured_accumulate(const uint32_t *m, const surface *sf, int i, const uint32_t weight[3],
                                     const uint32_t diffuse[3], const uint32_t highlight[3], f24_t eps, uint32_t spawn,
                                     uint32_t acc[3], rgs_task *refl, rgs_task *trans)
{
    const uint32_t before[3] = { acc[0], acc[1], acc[2] };
    const int steps = __real_rgs_accumulate_ray(m, sf, i, weight, diffuse, highlight, eps, spawn, acc, refl, trans);
    FILE *f = begin(CAP_ACCUMULATE);
    if (!f)
        return steps;
    const uint32_t mw[3] = { sf->valid ? m[M_ETA] : 0u, sf->valid ? m[M_SHADER0] : 0u, sf->valid ? m[M_SHADER1] : 0u };
    const uint32_t geo[12] = { (uint32_t)sf->valid, sf->tr.m[0][3], sf->tr.m[1][3], sf->tr.m[2][3], sf->d.x, sf->d.y,
                               sf->d.z, sf->n.x, sf->n.y, sf->n.z, sf->t_hat, (uint32_t)sf->entering };
    fprintf(f, "%x %x %x ", mw[0], mw[1], mw[2]);
    words(f, geo, 12);
    const uint32_t *q[6] = { sf->base, sf->emission, sf->tint, weight, diffuse, highlight };
    for (int k = 0; k < 6; k++)
        fprintf(f, " %x %x %x", q[k][0], q[k][1], q[k][2]);
    fprintf(f, " %x %06x %x %x %x %x", (uint32_t)i, eps, spawn, before[0], before[1], before[2]);
    fprintf(f, " %x %x %x", acc[0], acc[1], acc[2]);
    const rgs_task *child[2] = { refl, trans };
    for (int k = 0; k < 2; k++) {
        const rgs_task *t = child[k];
        fprintf(f, " %06x %06x %06x %06x %06x %06x", t->rays.o[i].x, t->rays.o[i].y, t->rays.o[i].z, t->rays.d[i].x,
                t->rays.d[i].y, t->rays.d[i].z);
        fprintf(f, " %x %x %x %x", t->weight[i][0], t->weight[i][1], t->weight[i][2], t->rays.active >> i & 1u);
    }
    fprintf(f, " %x", (uint32_t)steps);
    end(f);
    return steps;
}

int __wrap_rgs_accumulate_ray(const uint32_t *m, const surface *sf, int i, const uint32_t weight[3],
                              const uint32_t diffuse[3], const uint32_t highlight[3], f24_t eps, uint32_t spawn,
                              uint32_t acc[3], rgs_task *refl, rgs_task *trans)
{
    return capturing() ? captured_accumulate(m, sf, i, weight, diffuse, highlight, eps, spawn, acc, refl, trans)
                       : __real_rgs_accumulate_ray(m, sf, i, weight, diffuse, highlight, eps, spawn, acc, refl, trans);
}

/* The packet's accumulation (op_accumulate): while capturing, ray by ray through the wrapper above,
 * as the per-ray datapath issues it (the simulation build's side-by-side version calls no unit,
 * and the per-ray loop calls rgs_accumulate_ray in its own object file, which no wrapper sees). */
uint32_t __real_rgs_accumulate_rays(const uint32_t *mem, const surface sf[], uint32_t active, const uint32_t weight[][3],
                                    const uint32_t diffuse[][3], const uint32_t highlight[][3], f24_t eps,
                                    uint32_t spawn, uint32_t acc[][3], rgs_task *refl, rgs_task *trans);
uint32_t __wrap_rgs_accumulate_rays(const uint32_t *mem, const surface sf[], uint32_t active, const uint32_t weight[][3],
                                    const uint32_t diffuse[][3], const uint32_t highlight[][3], f24_t eps,
                                    uint32_t spawn, uint32_t acc[][3], rgs_task *refl, rgs_task *trans);

uint32_t __wrap_rgs_accumulate_rays(const uint32_t *mem, const surface sf[], uint32_t active, const uint32_t weight[][3],
                                    const uint32_t diffuse[][3], const uint32_t highlight[][3], f24_t eps,
                                    uint32_t spawn, uint32_t acc[][3], rgs_task *refl, rgs_task *trans)
{
    if (!capturing())
        return __real_rgs_accumulate_rays(mem, sf, active, weight, diffuse, highlight, eps, spawn, acc, refl, trans);
    uint32_t children = 0;
    for (int i = 0; i < TRACE_PACKET; i++)
        if (active >> i & 1u)
            children += (uint32_t)__wrap_rgs_accumulate_ray(sf[i].valid ? &mem[sf[i].mat] : 0, &sf[i], i, weight[i],
                                                            diffuse[i], highlight[i], eps, spawn, acc[i], refl, trans);
    return children;
}
