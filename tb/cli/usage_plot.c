/* Utilisation plot of the cycle model: see usage_plot.h. */
#include "usage_plot.h"

#include <stdio.h>
#include <stdlib.h>

enum { W = 800, H = 360, LEFT = 60, RIGHT = 150, TOP = 30, BOTTOM = 40, MAX_POINTS = 800 };

static const char *const colours[UNIT_KINDS] = { "#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e" };

/* The cycles of epoch e of a frame of `cycles` (the last one may be short). */
static uint64_t epoch_len(uint64_t e, uint64_t len, uint64_t cycles)
{
    return (e + 1) * len <= cycles ? len : cycles - e * len;
}

/* One unit's line: epochs grouped so that at most MAX_POINTS points are drawn (each the group's
 * utilisation); its mean utilisation in *mean. */
static void plot_unit(FILE *f, const uint64_t *busy, size_t n, const cycle_config *cfg, uint64_t cycles, int u,
                      double *mean)
{
    const uint64_t len = cfg->epoch, epochs = (cycles + len - 1) / len, group = (epochs + MAX_POINTS - 1) / MAX_POINTS;
    uint64_t total = 0;
    fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" points=\"", colours[u]);
    for (uint64_t e0 = 0; e0 < epochs; e0 += group) {
        uint64_t b = 0, c = 0;
        for (uint64_t e = e0; e < e0 + group && e < epochs; e++) {
            b += e < n ? busy[e] : 0;
            c += epoch_len(e, len, cycles) * cfg->pipes;
        }
        total += b;
        const double x = LEFT + (double)(W - LEFT - RIGHT) * ((double)e0 + 0.5 * (double)group) / (double)epochs;
        fprintf(f, "%.1f,%.1f ", x, TOP + (H - TOP - BOTTOM) * (1.0 - (double)b / (double)c));
    }
    fprintf(f, "\"/>\n");
    *mean = 100.0 * (double)total / ((double)cycles * cfg->pipes);
}

static void axes(FILE *f, const cycle_config *cfg, uint64_t cycles)
{
    const int x1 = W - RIGHT, y1 = H - BOTTOM;
    fprintf(f, "<rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\" fill=\"none\" stroke=\"black\"/>\n", LEFT, TOP,
            x1 - LEFT, y1 - TOP);
    for (int p = 0; p <= 100; p += 25) {
        const double y = TOP + (y1 - TOP) * (1.0 - p / 100.0);
        fprintf(f, "<line x1=\"%d\" y1=\"%.1f\" x2=\"%d\" y2=\"%.1f\" stroke=\"#ddd\"/>"
                   "<text x=\"%d\" y=\"%.1f\" text-anchor=\"end\">%d%%</text>\n", LEFT, y, x1, y, LEFT - 4, y + 4, p);
    }
    fprintf(f, "<text x=\"%d\" y=\"%d\">0</text><text x=\"%d\" y=\"%d\" text-anchor=\"end\">%llu</text>\n", LEFT,
            y1 + 16, x1, y1 + 16, (unsigned long long)cycles);
    fprintf(f, "<text x=\"%d\" y=\"%d\" text-anchor=\"middle\">cycle (one point per %u-cycle epoch or group of "
               "epochs)</text>\n", (LEFT + x1) / 2, H - 8, cfg->epoch);
    fprintf(f, "<text x=\"%d\" y=\"18\">unit utilisation: busy issue cycles per epoch, %u pipe%s x %u threads</text>\n",
            LEFT, cfg->pipes, cfg->pipes == 1 ? "" : "s", cfg->threads_per_pipe);
}

int usage_plot_write(const char *path, const cycle_trace *tr, const cycle_config *cfg, uint64_t cycles, char *err,
                     size_t errlen)
{
    static const char *const names[UNIT_KINDS] = { "RGS", "transformation", "traversal", "list", "intersection" };
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s.tmp", path); /* complete files only */
    FILE *f = fopen(tmp, "w");
    if (!f)
        return snprintf(err, errlen, "cannot write '%s'", path), -1;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" font-family=\"sans-serif\" "
               "font-size=\"12\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n", W, H);
    axes(f, cfg, cycles ? cycles : 1);
    int oom = 0;
    for (int u = 0; u < UNIT_KINDS; u++) {
        size_t n;
        uint64_t *busy = cycle_trace_usage(tr, u, &n);
        double mean = 0;
        if (!busy) {
            oom = 1;
            break;
        }
        plot_unit(f, busy, n, cfg, cycles ? cycles : 1, u, &mean);
        free(busy);
        fprintf(f, "<line x1=\"%d\" y1=\"%d\" x2=\"%d\" y2=\"%d\" stroke=\"%s\" stroke-width=\"3\"/>"
                   "<text x=\"%d\" y=\"%d\">%s %.1f%%</text>\n", W - RIGHT + 10, TOP + 10 + 20 * u, W - RIGHT + 30,
                TOP + 10 + 20 * u, colours[u], W - RIGHT + 34, TOP + 14 + 20 * u, names[u], mean);
    }
    fprintf(f, "</svg>\n");
    const int bad = ferror(f) | (fclose(f) != 0);
    if (oom || bad || rename(tmp, path) != 0) {
        remove(tmp);
        snprintf(err, errlen, oom ? "out of memory for '%s'" : "cannot write '%s'", path);
        return -1;
    }
    return 0;
}
