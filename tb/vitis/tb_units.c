/*
 * HOST-ONLY TESTBENCH, not part of the design: it uses libc (stdio, malloc) to read vectors and
 * is never synthesized; make hls-check covers hls/fp24, hls/units and hls/top only.
 *
 * Testbench of the datapath top functions xform_top, isect_top and trav_top (C simulation with GCC
 * in `make test`, csim and cosim in Vitis HLS, tb/vitis/run.tcl): replays the transactions that
 * `saarcor render --capture-unit-io DIR` recorded (the vectors rtl/tb replays against the RTL) in
 * batches of HLS_BATCH and diffs every result word against the recording. Returns 0 if all
 * match, 1 on a mismatch (printing the first ones), 2 on bad input.
 *   tb_units DIR
 */
#include <stdio.h>
#include <string.h>

#include "hls_top.h"

enum { MAX_WORDS = 64 };

static uint64_t mismatches;

/* Reads one line of hex words; returns the count (0 at the end). */
static int read_words(FILE *f, uint32_t w[MAX_WORDS])
{
    char line[2048];
    if (!fgets(line, sizeof line, f))
        return 0;
    int n = 0;
    for (char *p = strtok(line, " \n"); p && n < MAX_WORDS; p = strtok(NULL, " \n")) {
        unsigned v;
        if (sscanf(p, "%x", &v) == 1)
            w[n++] = v;
    }
    return n;
}

static void expect(const char *unit, uint64_t txn, const char *what, uint32_t got, uint32_t want)
{
    if (got != want && mismatches++ < 5)
        fprintf(stderr, "tb_units: %s transaction %llu, %s: top function 0x%06x, recorded 0x%06x\n", unit,
                (unsigned long long)txn, what, got, want);
}

static xform_txn xin[HLS_BATCH];
static f24_vec3 xout[HLS_BATCH];
static uint32_t xwant[HLS_BATCH][3];
static isect_txn iin[HLS_BATCH];
static isect_result iout[HLS_BATCH];
static uint32_t iwant[HLS_BATCH][5];
static trav_txn tin[HLS_BATCH];
static trav_result tout[HLS_BATCH];
static uint32_t twant[HLS_BATCH][19];

static uint64_t run_xform(FILE *f)
{
    uint64_t total = 0;
    uint32_t w[MAX_WORDS], n = 0;
    for (int k; (k = read_words(f, w)) != 0 || n;) {
        if (k == 19) {
            memcpy(&xin[n].m, w, 12 * sizeof *w);
            xin[n].v = (f24_vec3){ w[12], w[13], w[14] };
            xin[n].point = w[15];
            memcpy(xwant[n++], w + 16, 3 * sizeof *w);
        }
        if (n == HLS_BATCH || (k == 0 && n)) {
            xform_top(xin, xout, n);
            for (uint32_t i = 0; i < n; i++) {
                expect("xform", total + i, "x", xout[i].x, xwant[i][0]);
                expect("xform", total + i, "y", xout[i].y, xwant[i][1]);
                expect("xform", total + i, "z", xout[i].z, xwant[i][2]);
            }
            total += n;
            n = 0;
        }
        if (k == 0)
            break;
    }
    return total;
}

static uint64_t run_isect(FILE *f)
{
    uint64_t total = 0;
    uint32_t w[MAX_WORDS], n = 0;
    for (int k; (k = read_words(f, w)) != 0 || n;) {
        if (k == 15) {
            iin[n] = (isect_txn){ { w[0], w[1], w[2] }, { w[3], w[4], w[5] }, w[6], w[7], w[8], w[9] };
            memcpy(iwant[n++], w + 10, 5 * sizeof *w);
        }
        if (n == HLS_BATCH || (k == 0 && n)) {
            isect_top(iin, iout, n);
            for (uint32_t i = 0; i < n; i++) {
                expect("isect", total + i, "hit", (uint32_t)iout[i].hit, iwant[i][0]);
                expect("isect", total + i, "t", iout[i].t, iwant[i][1]);
                expect("isect", total + i, "u", iout[i].u, iwant[i][2]);
                expect("isect", total + i, "v", iout[i].v, iwant[i][3]);
                expect("isect", total + i, "cos", iout[i].cos_n, iwant[i][4]);
            }
            total += n;
            n = 0;
        }
        if (k == 0)
            break;
    }
    return total;
}

static uint64_t run_trav(FILE *f)
{
    uint64_t total = 0;
    uint32_t w[MAX_WORDS], n = 0;
    for (int k; (k = read_words(f, w)) != 0 || n;) {
        if (k == 54) {
            trav_txn *t = &tin[n];
            t->axis = w[0];
            t->split = w[1];
            t->e.mask = w[2];
            t->e.node = 0;
            for (int i = 0; i < TRACE_PACKET; i++) {
                t->o[i] = (f24_vec3){ w[3 + 3 * i], w[4 + 3 * i], w[5 + 3 * i] };
                t->d[i] = (f24_vec3){ w[15 + 3 * i], w[16 + 3 * i], w[17 + 3 * i] };
                t->e.tn[i] = w[27 + i];
                t->e.tf[i] = w[31 + i];
            }
            memcpy(twant[n++], w + 35, 19 * sizeof *w);
        }
        if (n == HLS_BATCH || (k == 0 && n)) {
            trav_top(tin, tout, n);
            for (uint32_t i = 0; i < n; i++) {
                const uint32_t *e = twant[i];
                expect("trav", total + i, "left mask", tout[i].l.mask, e[0]);
                expect("trav", total + i, "right mask", tout[i].r.mask, e[1]);
                expect("trav", total + i, "near-left", tout[i].near_left, e[2]);
                for (int r = 0; r < TRACE_PACKET; r++) {
                    expect("trav", total + i, "left tn", tout[i].l.tn[r], e[3 + r]);
                    expect("trav", total + i, "left tf", tout[i].l.tf[r], e[7 + r]);
                    expect("trav", total + i, "right tn", tout[i].r.tn[r], e[11 + r]);
                    expect("trav", total + i, "right tf", tout[i].r.tf[r], e[15 + r]);
                }
            }
            total += n;
            n = 0;
        }
        if (k == 0)
            break;
    }
    return total;
}

int main(int argc, char **argv)
{
    static const char *files[] = { "xform.hex", "isect.hex", "trav.hex" };
    uint64_t (*const run[])(FILE *) = { run_xform, run_isect, run_trav };
    if (argc != 2) {
        fprintf(stderr, "usage: tb_units CAPTURE_DIR\n");
        return 2;
    }
    for (int u = 0; u < 3; u++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", argv[1], files[u]);
        FILE *f = fopen(path, "r");
        if (!f) {
            fprintf(stderr, "tb_units: cannot read %s\n", path);
            return 2;
        }
        const uint64_t n = run[u](f);
        fclose(f);
        printf("tb_units: %s %llu transactions\n", files[u], (unsigned long long)n);
        if (n == 0)
            return 2;
    }
    printf("tb_units: %llu mismatches\n", (unsigned long long)mismatches);
    return mismatches ? 1 : 0;
}
