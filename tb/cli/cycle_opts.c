/* Options and report of the cycle mode: see cycle_opts.h. */
#define _GNU_SOURCE
#include "cycle_opts.h"

#include <stdlib.h>
#include <string.h>

#include "cli.h"

const char CYCLE_OPTIONS_HELP[] =
    "cycle mode options (--mode cycle; defaults: docs/cycle-model.md):\n"
    "  --pipes P             DynRTPs fed by the tile controller (default 1)\n"
    "  --threads-per-pipe T  threads (2x2 pixel blocks in flight) per pipe (default 32, up to 1024)\n"
    "  --clock-mhz F         core clock for fps, rays/s and bandwidth (default 90)\n"
    "  --cache-kb N,L,M[,S]  cache sizes for kd nodes, lists, matrices, shading in KB (default 4,2,6,4;\n"
    "                        0: uncached; without S the shading cache keeps its size)\n"
    "  --line-bytes N,L,M[,S] their line sizes (default 8,4, one triangle transformation, 16)\n"
    "  --mem-latency C       memory latency in cycles after a transfer (default 10)\n"
    "  --mem-mbps B          memory port bandwidth per pipe in MB/s (default 1000)\n"
    "  --unit-latency LIST   pipeline latency of each kind of operation, e.g. trav=21,isect=29; kinds raygen\n"
    "                        xform instance shadow children (transformation unit), trav objclip, list leaf,\n"
    "                        isect, surface light accum (RGS); surface_hit: a surface's cycles per further hit,\n"
    "                        surface_miss: a surface operation's without a hit\n"
    "  --tile N              tile edge in pixels handed out by the controller (even, default 16)\n";

static const char *const unit_keys[UNIT_KINDS] = { "rgs", "xform", "trav", "list", "isect" };

/* "a,b,c" or "a,b,c,d" -> the number of values (3 or 4) in [lo, hi], else 0. */
static int parse_kinds(const char *arg, double lo, double hi, double out[MEM_KINDS])
{
    char tail;
    const int n = sscanf(arg, "%lf,%lf,%lf,%lf%c", &out[0], &out[1], &out[2], &out[3], &tail);
    if (n != 3 && n != 4)
        return 0;
    for (int k = 0; k < n; k++)
        if (!(out[k] >= lo && out[k] <= hi))
            return 0;
    return n;
}

static int parse_latencies(cycle_config *cfg, const char *arg)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", arg);
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        char *eq = strchr(tok, '=');
        uint64_t v;
        if (!eq)
            return 0;
        *eq = 0;
        uint32_t *extra = strcmp(tok, "surface_hit") == 0  ? &cfg->surface_hit  /* not kinds: per further hit, */
                        : strcmp(tok, "surface_miss") == 0 ? &cfg->surface_miss /* a packet without hits */
                                                           : NULL;
        if (extra) {
            if (!cli_parse_u64(eq + 1, 0, 1000, &v))
                return 0;
            *extra = (uint32_t)v;
            continue;
        }
        int kind = -1;
        for (int k = 0; k < OP_KINDS; k++)
            if (strcmp(tok, op_kind_names[k]) == 0)
                kind = k;
        if (kind < 0 || !cli_parse_u64(eq + 1, 1, 1000, &v))
            return 0;
        cfg->latency[kind] = (uint32_t)v;
    }
    return 1;
}

int cycle_opts_parse(cycle_config *cfg, const char *cmd, int c, const char *arg)
{
    uint64_t v;
    double d, t[MEM_KINDS];
    int n;
    switch (c - CYCLE_OPT_BASE) {
    case 0:
        if (!cli_parse_u64(arg, 1, 64, &v))
            return cli_usage_error(cmd, "bad --pipes '%s' (1..64)", arg), -1;
        cfg->pipes = (uint32_t)v;
        return 1;
    case 1:
        if (!cli_parse_u64(arg, 1, 1024, &v))
            return cli_usage_error(cmd, "bad --threads-per-pipe '%s' (1..1024)", arg), -1;
        cfg->threads_per_pipe = (uint32_t)v;
        return 1;
    case 2:
        if (!cli_parse_double(arg, &d) || !(d >= 1 && d <= 100000))
            return cli_usage_error(cmd, "bad --clock-mhz '%s' (1..100000)", arg), -1;
        cfg->mem.clock_mhz = d;
        return 1;
    case 3:
        if (!(n = parse_kinds(arg, 0, 65536, t)))
            return cli_usage_error(cmd, "bad --cache-kb '%s' (sizes N,L,M or N,L,M,S in KB, 0..65536)", arg), -1;
        for (int k = 0; k < n; k++)
            cfg->mem.cache[k].size_bytes = (uint32_t)(t[k] * 1024.0);
        return 1;
    case 4:
        if (!(n = parse_kinds(arg, 4, 4096, t)))
            return cli_usage_error(cmd, "bad --line-bytes '%s' (sizes N,L,M or N,L,M,S, multiples of 4 in 4..4096)",
                                   arg), -1;
        for (int k = 0; k < n; k++) {
            if ((uint32_t)t[k] % 4 || t[k] != (double)(uint32_t)t[k])
                return cli_usage_error(cmd, "bad --line-bytes '%s' (multiples of 4)", arg), -1;
            cfg->mem.cache[k].line_bytes = (uint32_t)t[k];
        }
        return 1;
    case 5:
        if (!cli_parse_u64(arg, 0, 100000, &v))
            return cli_usage_error(cmd, "bad --mem-latency '%s' (0..100000 cycles)", arg), -1;
        cfg->mem.latency = (uint32_t)v;
        return 1;
    case 6:
        if (!cli_parse_double(arg, &d) || !(d >= 1 && d <= 1e7))
            return cli_usage_error(cmd, "bad --mem-mbps '%s' (1..1e7)", arg), -1;
        cfg->mem.mbps = d;
        return 1;
    case 7:
        if (!parse_latencies(cfg, arg))
            return cli_usage_error(cmd, "bad --unit-latency '%s' (e.g. trav=12,isect=14; kinds raygen xform "
                                        "instance shadow children trav objclip list leaf isect surface light accum, "
                                        "1..1000 cycles; surface_hit, surface_miss 0..1000)", arg), -1;
        return 1;
    case 8:
        if (!cli_parse_u64(arg, 2, 4096, &v) || v % 2)
            return cli_usage_error(cmd, "bad --tile '%s' (even, 2..4096)", arg), -1;
        cfg->tile = (uint32_t)v;
        return 1;
    default: return 0;
    }
}

static double pct(uint64_t a, uint64_t b) { return b ? 100.0 * (double)a / (double)b : 0.0; }

typedef struct {
    double seconds, fps, mbps[MEM_KINDS], dynrtc_mbps, total_mbps;
} derived;

static derived derive(const cycle_config *cfg, const cycle_stats *st)
{
    derived d;
    d.seconds = (double)st->cycles / (cfg->mem.clock_mhz * 1e6);
    d.fps = d.seconds > 0 ? 1.0 / d.seconds : 0.0;
    d.dynrtc_mbps = d.total_mbps = 0;
    for (int k = 0; k < MEM_KINDS; k++) {
        d.mbps[k] = (double)st->mem.bytes[k] * d.fps / 1e6;
        d.total_mbps += d.mbps[k];
        if (k != MEM_SHADING)
            d.dynrtc_mbps += d.mbps[k];
    }
    return d;
}

/* Usage rate of a unit: issue slots used over the cycles of all pipes. */
static double usage(const cycle_config *cfg, const cycle_stats *st, int u)
{
    return pct(st->busy[u], st->cycles * cfg->pipes);
}

void cycle_report(FILE *f, const cycle_config *cfg, const cycle_stats *st, uint64_t rays)
{
    const derived d = derive(cfg, st);
    uint64_t all = 0;
    for (int k = 0; k < ST_KINDS; k++)
        all += st->thread_cycles[k];
    fprintf(f, "cycle model: %u pipe%s x %u threads at %.0f MHz; caches %.1f/%.1f/%.1f/%.1f KB (kd nodes/lists/"
               "matrices/shading), memory %.0f MB/s per pipe, latency %u\n",
            cfg->pipes, cfg->pipes == 1 ? "" : "s", cfg->threads_per_pipe, cfg->mem.clock_mhz,
            cfg->mem.cache[0].size_bytes / 1024.0, cfg->mem.cache[1].size_bytes / 1024.0,
            cfg->mem.cache[2].size_bytes / 1024.0, cfg->mem.cache[3].size_bytes / 1024.0, cfg->mem.mbps,
            cfg->mem.latency);
    fprintf(f, "frame: %llu cycles = %.3f ms -> %.1f fps, %.2f M rays/s\n", (unsigned long long)st->cycles,
            1e3 * d.seconds, d.fps, (double)rays * d.fps / 1e6);
    fprintf(f, "%-10s | %-35s | %-29s | %s\n", "", "usage rate [%]", "cache hit rate [%]", "ext. bandwidth [MB/s]");
    fprintf(f, "%-10s | %6s %6s %6s %6s %6s | %6s %6s %6s %6s | %8s %8s %8s\n", "", "Trav", "List", "Transf", "Int",
            "RGS", "Trav", "List", "Transf", "Shade", "DynRTC", "Shading", "Total");
    fprintf(f, "%-10s | %6.0f %6.0f %6.0f %6.0f %6.0f | %6.1f %6.1f %6.1f %6.1f | %8.1f %8.1f %8.1f\n", "this frame",
            usage(cfg, st, UNIT_TRAV), usage(cfg, st, UNIT_LIST), usage(cfg, st, UNIT_XFORM), usage(cfg, st, UNIT_ISECT),
            usage(cfg, st, UNIT_RGS), pct(st->mem.hits[MEM_NODES], st->mem.lookups[MEM_NODES]),
            pct(st->mem.hits[MEM_LISTS], st->mem.lookups[MEM_LISTS]),
            pct(st->mem.hits[MEM_MATRICES], st->mem.lookups[MEM_MATRICES]),
            pct(st->mem.hits[MEM_SHADING], st->mem.lookups[MEM_SHADING]), d.dynrtc_mbps, d.mbps[MEM_SHADING],
            d.total_mbps);
    fprintf(f, "bandwidth by type [MB/s]: kd nodes %.1f, lists %.1f, matrices %.1f, shading %.1f\n", d.mbps[MEM_NODES],
            d.mbps[MEM_LISTS], d.mbps[MEM_MATRICES], d.mbps[MEM_SHADING]);
    fprintf(f, "threads in flight: %.1f of %u per pipe on average\n",
            st->cycles ? (double)(all - st->thread_cycles[ST_NO_WORK]) / (double)(st->cycles * cfg->pipes) : 0.0,
            cfg->threads_per_pipe);
    fprintf(f, "thread time [%%]: in a unit %.1f, queued for a unit %.1f (trav %.1f, list %.1f, transf %.1f, int %.1f, "
               "RGS %.1f), waiting for memory %.1f (kd nodes %.1f, lists %.1f, matrices %.1f, shading %.1f), no work %.1f\n",
            pct(st->thread_cycles[ST_UNIT_BUSY], all), pct(st->thread_cycles[ST_UNIT_QUEUE], all),
            pct(st->wait_unit[UNIT_TRAV], all), pct(st->wait_unit[UNIT_LIST], all), pct(st->wait_unit[UNIT_XFORM], all),
            pct(st->wait_unit[UNIT_ISECT], all), pct(st->wait_unit[UNIT_RGS], all), pct(st->thread_cycles[ST_MEMORY], all),
            pct(st->wait_mem[MEM_NODES], all), pct(st->wait_mem[MEM_LISTS], all), pct(st->wait_mem[MEM_MATRICES], all),
            pct(st->wait_mem[MEM_SHADING], all), pct(st->thread_cycles[ST_NO_WORK], all));
}

void cycle_report_json(FILE *f, const cycle_config *cfg, const cycle_stats *st, uint64_t rays)
{
    const derived d = derive(cfg, st);
    uint64_t all = 0;
    for (int k = 0; k < ST_KINDS; k++)
        all += st->thread_cycles[k];
    fprintf(f, "{\"pipes\": %u, \"threads_per_pipe\": %u, \"clock_mhz\": %g, \"cycles\": %llu, \"seconds\": %.9f, "
               "\"fps\": %.4f, \"rays_per_second\": %.1f, \"pipe_cycles_min\": %llu, \"blocks\": %llu, \"tiles\": %llu, ",
            cfg->pipes, cfg->threads_per_pipe, cfg->mem.clock_mhz, (unsigned long long)st->cycles, d.seconds, d.fps,
            (double)rays * d.fps, (unsigned long long)st->pipe_cycles_min, (unsigned long long)st->blocks,
            (unsigned long long)st->tiles);
    fprintf(f, "\"units\": {");
    for (int u = 0; u < UNIT_KINDS; u++) {
        fprintf(f, "%s\"%s\": {\"latencies\": {", u ? ", " : "", unit_keys[u]);
        for (int k = 0, n = 0; k < OP_KINDS; k++)
            if (op_kind_unit((uint32_t)k) == (uint32_t)u)
                fprintf(f, "%s\"%s\": %u", n++ ? ", " : "", op_kind_names[k], cfg->latency[k]);
        if (u == UNIT_RGS)
            fprintf(f, ", \"surface_hit\": %u, \"surface_miss\": %u", cfg->surface_hit, cfg->surface_miss);
        fprintf(f, "}, \"busy_cycles\": %llu, \"operations\": %llu, \"usage\": %.6f, \"queued_thread_cycles\": %llu",
                (unsigned long long)st->busy[u], (unsigned long long)st->ops[u], usage(cfg, st, u) / 100.0,
                (unsigned long long)st->wait_unit[u]);
        if (u == UNIT_RGS) /* its operations' waits for the block controllers' one word port to the shading cache */
            fprintf(f, ", \"shading_port_wait_cycles\": %llu", (unsigned long long)st->shade_port_wait);
        fputc('}', f);
    }
    fprintf(f, "}, \"memory\": {\"latency\": %u, \"mbps_per_pipe\": %g", cfg->mem.latency, cfg->mem.mbps);
    for (int k = 0; k < MEM_KINDS; k++) {
        fprintf(f, ", \"%s\": {", mem_kind_names[k]);
        if (k < MI_CACHED_KINDS)
            fprintf(f, "\"cache_bytes\": %u, \"line_bytes\": %u, \"lookups\": %llu, \"hits\": %llu, \"hit_rate\": %.6f, ",
                    cfg->mem.cache[k].size_bytes, cfg->mem.cache[k].line_bytes, (unsigned long long)st->mem.lookups[k],
                    (unsigned long long)st->mem.hits[k], pct(st->mem.hits[k], st->mem.lookups[k]) / 100.0);
        fprintf(f, "\"requests\": %llu, \"bytes\": %llu, \"mb_per_s\": %.3f, \"waiting_thread_cycles\": %llu}",
                (unsigned long long)st->mem.requests[k], (unsigned long long)st->mem.bytes[k], d.mbps[k],
                (unsigned long long)st->wait_mem[k]);
    }
    fprintf(f, ", \"dynrtc_mb_per_s\": %.3f, \"total_mb_per_s\": %.3f}, ", d.dynrtc_mbps, d.total_mbps);
    fprintf(f, "\"threads_in_flight\": %.4f, \"thread_cycles\": {\"in_unit\": %llu, \"queued\": %llu, \"memory\": %llu, "
               "\"no_work\": %llu}}",
            st->cycles ? (double)(all - st->thread_cycles[ST_NO_WORK]) / (double)(st->cycles * cfg->pipes) : 0.0,
            (unsigned long long)st->thread_cycles[ST_UNIT_BUSY], (unsigned long long)st->thread_cycles[ST_UNIT_QUEUE],
            (unsigned long long)st->thread_cycles[ST_MEMORY], (unsigned long long)st->thread_cycles[ST_NO_WORK]);
}
