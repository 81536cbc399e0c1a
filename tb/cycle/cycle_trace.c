/* Waveforms of the cycle model: see cycle_trace.h. */
#define _GNU_SOURCE
#include "cycle_trace.h"
#include "vcd_format.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Signals of one pipe: SIG_PER_UNIT per unit, then SIG_PER_CACHE per memory kind, then two. */
enum { S_BUSY, S_ISSUE, S_QUEUE, S_TID, SIG_PER_UNIT };
enum { S_LOOKUPS, S_MISSES, S_FILLS, SIG_PER_CACHE };
#define SIG_CACHE0 (UNIT_KINDS * SIG_PER_UNIT)
#define SIG_OUTSTANDING (SIG_CACHE0 + MEM_KINDS * SIG_PER_CACHE)
#define SIG_THREADS (SIG_OUTSTANDING + 1)
#define SIGS (SIG_THREADS + 1)

#define NEVER UINT64_MAX
#define VAL_X VCD_X /* an undefined value: thread_id while the unit is idle */
#define DEAD UINT32_MAX  /* an event undone by a later change in the same cycle */
#define CLOCK_ID "!"      /* the clock's identifier: number 0 of sig_id */

typedef struct {
    uint64_t val;          /* the value from the last change on */
    uint64_t rest, fall_at; /* the value it returns to at cycle fall_at (NEVER: it holds) */
    uint64_t acc, acc_t;   /* per-cycle counts: acc so far in cycle acc_t */
    uint64_t start;        /* the value at the window's first cycle */
    uint64_t last_t, before; /* the cycle of its last event in the buffer and the value before it */
    size_t last_i;
    int has_last;
    uint64_t rise; /* busy signals: the cycle the current busy run began */
} tsig;

typedef struct {
    uint64_t t, v;
    uint32_t sig;
} tevent;

typedef struct {
    uint64_t at;
    uint32_t kind, cached;
} transfer;

struct trace_pipe {
    const cycle_trace *tr;
    tsig sig[SIGS];
    tevent *ev;
    size_t n, cap;
    transfer *fly; /* transfers in flight, in arrival order (the port is serial) */
    size_t fly_head, fly_n, fly_cap;
    uint64_t *busy[UNIT_KINDS]; /* busy cycles per epoch */
    size_t epochs;
    int oom;
};

typedef struct {
    uint64_t t;
    uint32_t pipe, seq;
    const tevent *e;
} merged;

struct cycle_trace {
    FILE *vcd;
    char *path, *tmp;
    uint64_t from, to, half_ps; /* window [from, to); a cycle is 2 half_ps picoseconds */
    uint64_t cur;               /* the cycle whose rising clock edge was written last */
    int started;                /* $dumpvars written */
    cycle_config cfg;
    trace_pipe *pipes;
    merged *m;
    size_t m_cap;
};

static const char *const unit_keys[UNIT_KINDS] = { "rgs", "xform", "trav", "list", "isect" };

/* ---- recording ------------------------------------------------------------------------------ */

static int unit_of_busy(uint32_t s) { return s < SIG_CACHE0 && s % SIG_PER_UNIT == S_BUSY ? (int)(s / SIG_PER_UNIT) : -1; }

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap)
        return 0;
    size_t c = *cap ? *cap : 256;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, c * size);
    if (!q)
        return -1;
    memset((char *)q + *cap * size, 0, (c - *cap) * size);
    *p = q;
    *cap = c;
    return 0;
}

/* Adds the busy run [a, b) of unit u to its epochs. */
static void add_busy(trace_pipe *tp, int u, uint64_t a, uint64_t b)
{
    const uint64_t len = tp->tr->cfg.epoch;
    if (b <= a)
        return;
    size_t cap = tp->epochs;
    for (int k = 0; k < UNIT_KINDS; k++) { /* all units keep the same number of epochs */
        size_t c = cap;
        if (grow((void **)&tp->busy[k], &c, (size_t)((b - 1) / len + 1), sizeof(uint64_t)) != 0) {
            tp->oom = 1;
            return;
        }
        tp->epochs = c;
    }
    for (uint64_t t = a; t < b;) {
        const uint64_t e = t / len, end = (e + 1) * len < b ? (e + 1) * len : b;
        tp->busy[u][e] += end - t;
        t = end;
    }
}

/* Signal s changes to v at cycle t (t never decreases per signal). Changes up to the window's
 * first cycle only set its start value; several changes in one cycle leave one event. */
static void emit(trace_pipe *tp, uint32_t s, uint64_t t, uint64_t v)
{
    tsig *g = &tp->sig[s];
    const uint64_t old = g->val;
    const int u = unit_of_busy(s);
    if (u >= 0 && !old && v)
        g->rise = t;
    else if (u >= 0 && old && !v)
        add_busy(tp, u, g->rise, t);
    g->val = v;
    if (t <= tp->tr->from) {
        g->start = v;
        return;
    }
    if (t >= tp->tr->to)
        return;
    if (g->has_last && g->last_t == t) {
        tp->ev[g->last_i].v = v;
        tp->ev[g->last_i].sig = v == g->before ? DEAD : s;
        return;
    }
    if (grow((void **)&tp->ev, &tp->cap, tp->n + 1, sizeof *tp->ev) != 0) {
        tp->oom = 1;
        return;
    }
    g->last_t = t;
    g->before = old;
    g->last_i = tp->n;
    g->has_last = 1;
    tp->ev[tp->n++] = (tevent){ t, v, s };
}

/* s is v from cycle t on, and returns to its rest value at cycle fall (NEVER: holds). */
static void set(trace_pipe *tp, uint32_t s, uint64_t t, uint64_t v, uint64_t fall)
{
    tsig *g = &tp->sig[s];
    if (g->fall_at <= t) {
        const uint64_t at = g->fall_at;
        g->fall_at = NEVER;
        emit(tp, s, at, g->rest);
    }
    if (v != g->val)
        emit(tp, s, t, v);
    g->fall_at = fall;
}

static void flush_count(trace_pipe *tp, uint32_t s)
{
    tsig *g = &tp->sig[s];
    if (!g->acc)
        return;
    const uint64_t n = g->acc;
    g->acc = 0;
    set(tp, s, g->acc_t, n, g->acc_t + 1);
}

/* One more of per-cycle count s in cycle t. */
static void count(trace_pipe *tp, uint32_t s, uint64_t t)
{
    if (tp->sig[s].acc_t != t)
        flush_count(tp, s);
    tp->sig[s].acc_t = t;
    tp->sig[s].acc++;
}

/* Transfers whose data arrived by cycle t leave the port's and their cache's counts. */
static void retire(trace_pipe *tp, uint64_t t)
{
    while (tp->fly_n && tp->fly[tp->fly_head].at <= t) {
        const transfer *x = &tp->fly[tp->fly_head];
        set(tp, SIG_OUTSTANDING, x->at, tp->sig[SIG_OUTSTANDING].val - 1, NEVER);
        if (x->cached) {
            const uint32_t f = SIG_CACHE0 + x->kind * SIG_PER_CACHE + S_FILLS;
            set(tp, f, x->at, tp->sig[f].val - 1, NEVER);
        }
        tp->fly_head = (tp->fly_head + 1) % tp->fly_cap;
        tp->fly_n--;
    }
}

/* Everything pending before cycle until becomes an event. */
static void settle(trace_pipe *tp, uint64_t until)
{
    retire(tp, until == NEVER ? NEVER - 1 : until - 1);
    for (uint32_t s = 0; s < SIGS; s++) {
        tsig *g = &tp->sig[s];
        if (g->acc && g->acc_t < until)
            flush_count(tp, s);
        if (g->fall_at < until) {
            const uint64_t at = g->fall_at;
            g->fall_at = NEVER;
            emit(tp, s, at, g->rest);
        }
    }
}

void trace_issue(trace_pipe *tp, int u, uint64_t t) { set(tp, (uint32_t)u * SIG_PER_UNIT + S_ISSUE, t, 1, t + 1); }

void trace_busy(trace_pipe *tp, int u, uint64_t t, uint32_t tid, uint32_t slots)
{
    const uint32_t s = (uint32_t)u * SIG_PER_UNIT;
    set(tp, s + S_BUSY, t, 1, t + slots);
    set(tp, s + S_TID, t, tid, t + slots);
}

void trace_queue(trace_pipe *tp, int u, uint64_t t, uint32_t depth)
{
    set(tp, (uint32_t)u * SIG_PER_UNIT + S_QUEUE, t, depth, NEVER);
}

void trace_threads(trace_pipe *tp, uint64_t t, uint32_t active) { set(tp, SIG_THREADS, t, active, NEVER); }

static void push_transfer(trace_pipe *tp, uint32_t kind, int cached, uint64_t t, uint64_t arrive)
{
    if (tp->fly_n == tp->fly_cap) { /* unroll the ring into a bigger one */
        transfer *q = malloc((tp->fly_cap ? 2 * tp->fly_cap : 256) * sizeof *q);
        if (!q) {
            tp->oom = 1;
            return;
        }
        for (size_t i = 0; i < tp->fly_n; i++)
            q[i] = tp->fly[(tp->fly_head + i) % tp->fly_cap];
        free(tp->fly);
        tp->fly = q;
        tp->fly_head = 0;
        tp->fly_cap = tp->fly_cap ? 2 * tp->fly_cap : 256;
    }
    tp->fly[(tp->fly_head + tp->fly_n++) % tp->fly_cap] = (transfer){ arrive, kind, (uint32_t)cached };
    set(tp, SIG_OUTSTANDING, t, tp->sig[SIG_OUTSTANDING].val + 1, NEVER);
    if (cached) {
        const uint32_t f = SIG_CACHE0 + kind * SIG_PER_CACHE + S_FILLS;
        set(tp, f, t, tp->sig[f].val + 1, NEVER);
    }
}

void trace_mem(void *arg, uint32_t kind, int what, uint64_t t, uint64_t arrive)
{
    trace_pipe *tp = arg;
    const uint32_t c = SIG_CACHE0 + kind * SIG_PER_CACHE;
    retire(tp, t);
    if (what != MI_UNCACHED)
        count(tp, c + S_LOOKUPS, t);
    if (what == MI_MISS)
        count(tp, c + S_MISSES, t);
    if (what != MI_HIT)
        push_transfer(tp, kind, what == MI_MISS, t, arrive);
}

/* ---- the file -------------------------------------------------------------------------------- */

static uint32_t bits_for(uint64_t max)
{
    uint32_t b = 1;
    while (b < 64 && max >> b)
        b++;
    return b;
}

/* The width of signal s of a pipe. */
static uint32_t sig_width(const cycle_trace *tr, uint32_t s)
{
    const uint32_t threads = tr->cfg.threads_per_pipe;
    if (s == SIG_THREADS)
        return bits_for(threads);
    if (s >= SIG_CACHE0)
        return 32;
    switch (s % SIG_PER_UNIT) {
    case S_QUEUE: return bits_for(threads);
    case S_TID: return bits_for(threads - 1);
    default: return 1;
    }
}

/* VCD identifier of signal s of pipe p (number 0 is the clock). */
static void sig_id(uint32_t p, uint32_t s, char id[VCD_ID_CHARS]) { vcd_id((uint64_t)p * SIGS + s + 1, id); }

static void var(FILE *f, uint32_t width, uint32_t p, uint32_t s, const char *name)
{
    char id[VCD_ID_CHARS];
    sig_id(p, s, id);
    fprintf(f, "$var wire %u %s %s $end\n", width, id, name);
}

static void write_header(cycle_trace *tr)
{
    static const char *const unit_sig[SIG_PER_UNIT] = { "busy", "issue", "queue_depth", "thread_id" };
    static const char *const cache_sig[SIG_PER_CACHE] = { "lookups", "misses", "fills" };
    FILE *f = tr->vcd;
    fprintf(f, "$version saarcor render --mode cycle $end\n");
    fprintf(f, "$comment %u pipe(s) x %u threads at %g MHz; one cycle = %llu ps (rising clock edge at its start); "
               "cycles %llu to %llu $end\n",
            tr->cfg.pipes, tr->cfg.threads_per_pipe, tr->cfg.mem.clock_mhz, (unsigned long long)(2 * tr->half_ps),
            (unsigned long long)tr->from, (unsigned long long)tr->to - 1);
    fprintf(f, "$timescale 1ps $end\n$scope module dynrtc $end\n$var wire 1 %s clk $end\n", CLOCK_ID);
    for (uint32_t p = 0; p < tr->cfg.pipes; p++) {
        fprintf(f, "$scope module pipe%u $end\n", p);
        for (uint32_t u = 0; u < UNIT_KINDS; u++) {
            fprintf(f, "$scope module %s $end\n", unit_keys[u]);
            for (uint32_t k = 0; k < SIG_PER_UNIT; k++)
                var(f, sig_width(tr, u * SIG_PER_UNIT + k), p, u * SIG_PER_UNIT + k, unit_sig[k]);
            fprintf(f, "$upscope $end\n");
        }
        for (uint32_t c = 0; c < MEM_KINDS; c++) {
            fprintf(f, "$scope module cache_%s $end\n", mem_kind_names[c]);
            for (uint32_t k = 0; k < SIG_PER_CACHE; k++)
                var(f, 32, p, SIG_CACHE0 + c * SIG_PER_CACHE + k, cache_sig[k]);
            fprintf(f, "$upscope $end\n");
        }
        fprintf(f, "$scope module mem_port $end\n");
        var(f, 32, p, SIG_OUTSTANDING, "outstanding");
        fprintf(f, "$upscope $end\n");
        var(f, sig_width(tr, SIG_THREADS), p, SIG_THREADS, "threads_in_flight");
        fprintf(f, "$upscope $end\n");
    }
    fprintf(f, "$upscope $end\n$enddefinitions $end\n");
}

/* The values at the window's first cycle. */
static void write_start(cycle_trace *tr)
{
    fprintf(tr->vcd, "#%llu\n$dumpvars\n1%s\n", (unsigned long long)(tr->from * 2 * tr->half_ps), CLOCK_ID);
    for (uint32_t p = 0; p < tr->cfg.pipes; p++)
        for (uint32_t s = 0; s < SIGS; s++) {
            char id[VCD_ID_CHARS];
            sig_id(p, s, id);
            vcd_value(tr->vcd, sig_width(tr, s), tr->pipes[p].sig[s].start, id);
        }
    fprintf(tr->vcd, "$end\n");
    tr->cur = tr->from;
    tr->started = 1;
}

/* Moves the file's time to the rising clock edge of cycle c, with the clock of the cycles between. */
static void time_to(cycle_trace *tr, uint64_t c)
{
    const uint64_t cycle_ps = 2 * tr->half_ps;
    for (uint64_t k = tr->cur; k < c; k++) {
        if (k != tr->cur)
            fprintf(tr->vcd, "#%llu\n1%s\n", (unsigned long long)(k * cycle_ps), CLOCK_ID);
        fprintf(tr->vcd, "#%llu\n0%s\n", (unsigned long long)(k * cycle_ps + tr->half_ps), CLOCK_ID);
    }
    if (c != tr->cur)
        fprintf(tr->vcd, "#%llu\n1%s\n", (unsigned long long)(c * cycle_ps), CLOCK_ID);
    tr->cur = c;
}

static int cmp_merged(const void *a, const void *b)
{
    const merged *x = a, *y = b;
    if (x->t != y->t)
        return x->t < y->t ? -1 : 1;
    if (x->pipe != y->pipe)
        return x->pipe < y->pipe ? -1 : 1;
    return (x->seq > y->seq) - (x->seq < y->seq);
}

/* Writes the buffered events of all pipes in (cycle, pipe, order) and empties the buffers. */
static void write_events(cycle_trace *tr)
{
    size_t n = 0;
    for (uint32_t p = 0; p < tr->cfg.pipes; p++)
        n += tr->pipes[p].n;
    if (grow((void **)&tr->m, &tr->m_cap, n, sizeof *tr->m) != 0) {
        tr->pipes[0].oom = 1;
        return;
    }
    n = 0;
    for (uint32_t p = 0; p < tr->cfg.pipes; p++) {
        trace_pipe *tp = &tr->pipes[p];
        for (size_t i = 0; i < tp->n; i++)
            if (tp->ev[i].sig != DEAD)
                tr->m[n++] = (merged){ tp->ev[i].t, p, (uint32_t)i, &tp->ev[i] };
    }
    qsort(tr->m, n, sizeof *tr->m, cmp_merged);
    for (size_t i = 0; i < n; i++) {
        char id[VCD_ID_CHARS];
        time_to(tr, tr->m[i].t);
        sig_id(tr->m[i].pipe, tr->m[i].e->sig, id);
        vcd_value(tr->vcd, sig_width(tr, tr->m[i].e->sig), tr->m[i].e->v, id);
    }
    for (uint32_t p = 0; p < tr->cfg.pipes; p++) {
        tr->pipes[p].n = 0;
        for (uint32_t s = 0; s < SIGS; s++)
            tr->pipes[p].sig[s].has_last = 0;
    }
}

void cycle_trace_epoch(cycle_trace *tr, uint64_t until)
{
    for (uint32_t p = 0; p < tr->cfg.pipes; p++)
        settle(&tr->pipes[p], until);
    if (!tr->vcd || until <= tr->from)
        return;
    if (!tr->started)
        write_start(tr);
    write_events(tr);
}

trace_pipe *cycle_trace_pipe(cycle_trace *tr, uint32_t i) { return &tr->pipes[i]; }

static void trace_free(cycle_trace *tr)
{
    for (uint32_t p = 0; tr->pipes && p < tr->cfg.pipes; p++) {
        free(tr->pipes[p].ev);
        free(tr->pipes[p].fly);
        for (int u = 0; u < UNIT_KINDS; u++)
            free(tr->pipes[p].busy[u]);
    }
    free(tr->pipes);
    free(tr->m);
    free(tr->path);
    free(tr->tmp);
    free(tr);
}

static void pipe_init(cycle_trace *tr, trace_pipe *tp)
{
    tp->tr = tr;
    for (uint32_t s = 0; s < SIGS; s++)
        tp->sig[s] = (tsig){ .fall_at = NEVER, .acc_t = NEVER };
    for (int u = 0; u < UNIT_KINDS; u++) /* idle units have no thread */
        tp->sig[u * SIG_PER_UNIT + S_TID].val = tp->sig[u * SIG_PER_UNIT + S_TID].rest =
            tp->sig[u * SIG_PER_UNIT + S_TID].start = VAL_X;
}

cycle_trace *cycle_trace_open(const char *vcd_path, uint64_t from, uint64_t to, const cycle_config *cfg, char *err,
                              size_t errlen)
{
    cycle_trace *tr = calloc(1, sizeof *tr);
    if (!tr || !(tr->pipes = calloc(cfg->pipes, sizeof *tr->pipes))) {
        free(tr);
        snprintf(err, errlen, "out of memory for the trace");
        return NULL;
    }
    tr->cfg = *cfg;
    tr->from = vcd_path ? from : NEVER;
    tr->to = vcd_path ? to : NEVER;
    tr->half_ps = (uint64_t)llround(5e5 / cfg->mem.clock_mhz);
    tr->half_ps += !tr->half_ps;
    for (uint32_t p = 0; p < cfg->pipes; p++)
        pipe_init(tr, &tr->pipes[p]);
    if (!vcd_path)
        return tr;
    const size_t n = strlen(vcd_path) + 5;
    tr->path = strdup(vcd_path);
    tr->tmp = malloc(n);
    if (!tr->path || !tr->tmp) {
        trace_free(tr);
        snprintf(err, errlen, "out of memory for the trace");
        return NULL;
    }
    snprintf(tr->tmp, n, "%s.tmp", vcd_path); /* complete files only: renamed when closed */
    if (!(tr->vcd = fopen(tr->tmp, "w"))) {
        snprintf(err, errlen, "cannot write '%s'", vcd_path);
        trace_free(tr);
        return NULL;
    }
    write_header(tr);
    return tr;
}

int cycle_trace_close(cycle_trace *tr, uint64_t cycles, char *err, size_t errlen)
{
    int oom = 0, rc = 0;
    for (uint32_t p = 0; p < tr->cfg.pipes; p++)
        oom |= tr->pipes[p].oom;
    if (tr->vcd) {
        if (!tr->started)
            write_start(tr);
        time_to(tr, cycles < tr->to ? (cycles > tr->from ? cycles : tr->from) : tr->to);
        const int bad = ferror(tr->vcd) | (fclose(tr->vcd) != 0);
        tr->vcd = NULL;
        if (oom || bad || rename(tr->tmp, tr->path) != 0) {
            remove(tr->tmp);
            snprintf(err, errlen, oom ? "out of memory for the trace '%s'" : "cannot write '%s'", tr->path);
            rc = -1;
        }
    } else if (oom) {
        snprintf(err, errlen, "out of memory for the usage plot");
        rc = -1;
    }
    trace_free(tr);
    return rc;
}

void cycle_trace_abort(cycle_trace *tr)
{
    if (tr && tr->vcd) {
        fclose(tr->vcd);
        remove(tr->tmp);
    }
    if (tr)
        trace_free(tr);
}

uint64_t *cycle_trace_usage(const cycle_trace *tr, int u, size_t *n)
{
    *n = 0;
    for (uint32_t p = 0; p < tr->cfg.pipes; p++)
        *n = tr->pipes[p].epochs > *n ? tr->pipes[p].epochs : *n;
    uint64_t *sum = calloc(*n ? *n : 1, sizeof *sum);
    for (uint32_t p = 0; sum && p < tr->cfg.pipes; p++)
        for (size_t e = 0; e < tr->pipes[p].epochs; e++)
            sum[e] += tr->pipes[p].busy[u][e];
    return sum;
}
