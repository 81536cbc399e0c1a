// The harness of saarcor render --mode rtl: renders a frame through the Verilated DynRTP top
// (rtl/dynrtp.sv: tile_ctrl, trace_core, the caches, mem_port). saarcor writes the memory image and
// the parameters to DIR; this program is
//   * the RGS, as the linked C of hls/units/rgs.c: each block the tile controller deals goes to a
//     free thread (one block per core thread, --threads-per-pipe of them, at most the model's
//     THREADS), rgs_block_begin, then rgs_step, except that every trace (rgs_trace_pending: the
//     packet or shadow packet trace_begin prepared) enters the RTL core on the block's thread, and
//     its hits come back with trace_end so that rgs_step goes on as if trace_step had finished;
//     the RGS's own operations take no cycles here (it has no RTL in the top yet);
//   * the memory behind the port, with the cycle model's arithmetic (tb/cycle/mem_iface.c): a
//     transfer occupies the port bytes x 65536 clock / MB/s in 1/65536 cycles after the port is
//     free, its data is there --mem-latency cycles after the transfer ends, answers in order;
//   * a check: every packet is also traced by the C core (trace_begin + trace_step on a copy of
//     its state), and the RTL's hits and counters must equal it; a mismatch prints the unit
//     (trace_core), the packet, the cycle, the thread, the ray and field and both values, exit 1.
// Writes DIR/pixels.bin (0xRRGGBB per pixel), DIR/hits.bin (instance, triangle, t, u, v, cos per
// pixel: the primary hits) and DIR/stats (key value lines: the RTL's cycles, issues per unit,
// packets and reads per port of the core, the memory port's transfers and bytes, the RGS's
// counters).
// usage: tb_dynrtp DIR   (DIR/image.bin, DIR/params as saarcor writes them); exit 0, 1 (a
// mismatch or a hang), 2 (bad input)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "Vtb_dynrtp.h"
#include "tb_common.h"
#include "verilated.h"

extern "C" {
#include "f24.h"
#include "rgs.h"
#include "trace.h"
}

namespace {

using cosim::get;
using cosim::put;

constexpr uint32_t THREADS = 32;        // tb_dynrtp.sv's
constexpr uint64_t FX = 65536;
constexpr uint64_t FLUSH = 1024;        // cycles after reset: the caches empty their tags (512 lines at most)
constexpr uint64_t TIMEOUT = 1u << 22;  // cycles without a packet out before the harness gives up
const char *const UNIT[8] = { "trav", "list", "rebase", "wide", "xform", "isect", "add", "sum" };
const char *const PORT[3] = { "nodes", "lists", "words" }; // the core's memory ports
const char *const HIT[6] = { "instance", "triangle", "t", "u", "v", "cos" };
const char *const COUNTER[10] = { "traversal_steps", "leaves", "list_entries", "mailbox_skips", "transformations",
                                  "intersections", "words_nodes", "words_lists", "words_matrices", "words_shading" };

struct slot {
    bool busy = false, pending = false, sent = false;
    uint32_t x0 = 0, y0 = 0;
    uint64_t packet = 0;  // number of the packet in flight
    rgs_block b;
    trace_state ref;      // the C core's run of the packet in flight
    trace_counters ref_c;
};

struct transfer {
    uint64_t due;
    uint32_t addr, bytes;
};

bool read_words(const std::string &path, std::vector<uint32_t> &mem)
{
    FILE *f = std::fopen(path.c_str(), "rb");
    if (!f)
        return false;
    uint32_t w;
    while (std::fread(&w, sizeof w, 1, f) == 1)
        mem.push_back(w);
    std::fclose(f);
    return !mem.empty();
}

uint64_t g_mismatches = 0;

} // namespace

int main(int argc, char **argv)
{
    if (argc != 2) {
        std::printf("usage: tb_dynrtp DIR (DIR/image.bin, DIR/params from saarcor render --mode rtl)\n");
        return 2;
    }
    const std::string dir = argv[1];
    std::vector<uint32_t> mem;
    if (!read_words(dir + "/image.bin", mem)) {
        std::printf("tb_dynrtp: cannot read %s/image.bin\n", dir.c_str());
        return 2;
    }
    std::map<std::string, double> par;
    if (FILE *f = std::fopen((dir + "/params").c_str(), "r")) {
        char key[64];
        double v;
        while (std::fscanf(f, "%63s %lf", key, &v) == 2)
            par[key] = v;
        std::fclose(f);
    }
    for (const char *k : { "tile", "threads", "max_depth", "shadows", "traversal", "mem_latency", "mem_mbps", "clock_mhz" })
        if (!par.count(k)) {
            std::printf("tb_dynrtp: %s/params lacks %s\n", dir.c_str(), k);
            return 2;
        }
    const uint32_t threads = (uint32_t)par["threads"], tile = (uint32_t)par["tile"];
    if (threads < 1 || threads > THREADS) {
        std::printf("tb_dynrtp: --threads-per-pipe %u: the RTL model has %u threads (1 .. %u)\n", threads, THREADS, THREADS);
        return 2;
    }
    if ((uint32_t)par["traversal"] != TRAV_STACK) {
        std::printf("tb_dynrtp: the RTL core has the traversal algorithm stack only\n");
        return 2;
    }
    const rgs_config cfg = { (uint32_t)par["max_depth"], (uint32_t)par["shadows"], TRAV_STACK };
    const uint32_t latency = (uint32_t)par["mem_latency"];
    const uint64_t fxpb = (uint64_t)std::llround(par["clock_mhz"] / par["mem_mbps"] * (double)FX);
    uint32_t w, h;
    rgs_image_size(mem.data(), &w, &h);
    std::vector<uint32_t> pixels((std::size_t)w * h, 0), hits((std::size_t)w * h * 6, 0);

    VerilatedContext ctx;
    Vtb_dynrtp top{ &ctx };
    auto tick = [&]() {
        top.clk_i = 0;
        top.eval();
        top.clk_i = 1;
        top.eval();
    };
    top.rst_ni = 0, top.flush_i = 0, top.frame_valid_i = 0, top.frame_end_i = 0, top.blk_ready_i = 0;
    top.valid_i = 0, top.ready_i = 1, top.mem_req_ready_i = 1, top.mem_rsp_valid_i = 0;
    tick();
    top.rst_ni = 1;
    for (uint64_t i = 0; i < FLUSH; i++)
        tick();

    std::vector<slot> slots(threads);
    rgs_counters counters;
    std::memset(&counters, 0, sizeof counters);
    std::deque<transfer> port;
    uint64_t cycle = 0, port_free = 0, last_out = 0, packets = 0, transfers = 0, bytes = 0, checked = 0;
    uint32_t offer = 0;
    std::size_t busy = 0;
    bool frame_taken = false, blocks_done = false, ended = false;

    // the block's operations in zero time until it needs the core or is done
    auto advance = [&](uint32_t t) {
        slot &s = slots[t];
        unit_op op;
        for (;;) {
            if (rgs_trace_pending(&s.b)) {
                s.pending = true;
                s.sent = false;
                s.packet = packets++;
                s.ref = s.b.trace;
                std::memset(&s.ref_c, 0, sizeof s.ref_c);
                while (trace_step(mem.data(), &s.ref, &op, &s.ref_c))
                    ;
                return;
            }
            if (!rgs_step(mem.data(), &cfg, &s.b, &op, &counters)) {
                uint32_t rgb[4];
                rgs_block_finish(&s.b, rgb);
                for (uint32_t i = 0; i < 4; i++) {
                    const uint32_t x = s.x0 + (i & 1u), y = s.y0 + (i >> 1);
                    if (x >= w || y >= h)
                        continue;
                    const std::size_t p = (std::size_t)y * w + x;
                    pixels[p] = rgb[i];
                    const hit_record &r = s.b.primary_hits[i];
                    const uint32_t v[6] = { r.instance, r.triangle, r.t, r.u, r.v, r.cos_n };
                    std::memcpy(&hits[6 * p], v, sizeof v);
                }
                s.busy = false;
                busy--;
                return;
            }
        }
    };

    while (!ended) {
        if (cycle - last_out > TIMEOUT) {
            std::printf("MISMATCH dynrtp: no packet out for %llu cycles at cycle %llu (%zu blocks in flight)\n",
                        (unsigned long long)TIMEOUT, (unsigned long long)cycle, busy);
            return 1;
        }
        // ---- inputs ----
        top.frame_valid_i = !frame_taken;
        top.x0_i = 0, top.y0_i = 0, top.x1_i = w, top.y1_i = h, top.tile_i = tile;
        const bool finished = blocks_done && busy == 0;
        top.frame_end_i = finished;
        long free_t = -1;
        for (uint32_t t = 0; t < threads && free_t < 0; t++)
            if (!slots[t].busy)
                free_t = t;
        top.blk_ready_i = free_t >= 0;
        long send = -1; // the next waiting packet, round robin over the threads
        for (uint32_t k = 0; k < threads && send < 0; k++) {
            const uint32_t t = (offer + k) % threads;
            if (slots[t].busy && slots[t].pending && !slots[t].sent)
                send = t;
        }
        top.valid_i = send >= 0;
        if (send >= 0) {
            const trace_state &ts = slots[send].b.trace;
            top.thread_i = (uint32_t)send;
            top.flags_i = ts.flags & 7u;
            top.active_i = ts.rays.active;
            for (int r = 0; r < 4; r++) {
                const uint32_t o[3] = { ts.rays.o[r].x, ts.rays.o[r].y, ts.rays.o[r].z };
                const uint32_t d[3] = { ts.rays.d[r].x, ts.rays.d[r].y, ts.rays.d[r].z };
                for (int k = 0; k < 3; k++)
                    put(top.o_i, 3 * r + k, o[k]), put(top.d_i, 3 * r + k, d[k]);
                put(top.tmin_i, r, ts.rays.tmin[r]), put(top.tmax_i, r, ts.rays.tmax[r]);
            }
        }
        top.mem_rsp_valid_i = !port.empty() && port.front().due <= cycle;
        if (top.mem_rsp_valid_i) {
            const transfer &x = port.front();
            for (uint32_t k = 0; k < sizeof top.mem_rsp_data_i / 4; k++) {
                const uint32_t a = x.addr / 4 + k;
                top.mem_rsp_data_i[k] = 4 * k < x.bytes && a < mem.size() ? mem[a] : 0u;
            }
            port.pop_front();
        }
        top.clk_i = 0;
        top.eval();
        // ---- what the cycle did ----
        frame_taken = frame_taken || top.frame_ready_o;
        if (top.blk_done_o)
            blocks_done = true;
        if (top.valid_i && top.ready_o) {
            slots[send].sent = true;
            offer = (uint32_t)send + 1;
        }
        if (top.mem_req_valid_o) {
            const uint64_t start = std::max(port_free, cycle * FX);
            port_free = start + top.mem_req_bytes_o * fxpb;
            port.push_back({ (port_free + FX - 1) / FX + latency, top.mem_req_addr_o, top.mem_req_bytes_o });
            transfers++;
            bytes += top.mem_req_bytes_o;
        }
        if (top.valid_o) {
            const uint32_t t = top.thread_o;
            if (t >= threads || !slots[t].busy || !slots[t].sent) {
                std::printf("MISMATCH dynrtp: cycle %llu: hits out of thread %u, which traces no packet\n",
                            (unsigned long long)cycle, t);
                return 1;
            }
            slot &s = slots[t];
            hit_record got[4];
            for (int r = 0; r < 4; r++) {
                const uint32_t v[6] = { top.inst_o[r], top.tri_o[r], get(top.t_o, r), get(top.u_o, r), get(top.v_o, r),
                                        get(top.cos_o, r) };
                const hit_record &c = s.ref.hits[r];
                const uint32_t want[6] = { c.instance, c.triangle, c.t, c.u, c.v, c.cos_n };
                for (int f = 0; f < 6; f++)
                    if (v[f] != want[f] && g_mismatches++ < 20)
                        std::printf("MISMATCH trace_core packet %llu cycle %llu thread %u ray %d %s: rtl %06x, C %06x\n",
                                    (unsigned long long)s.packet, (unsigned long long)cycle, t, r, HIT[f], v[f], want[f]);
                got[r] = { v[0], v[1], v[2], v[3], v[4], v[5] };
            }
            uint64_t *cw = &counters.trace.traversal_steps;
            const uint64_t *rw = &s.ref_c.traversal_steps;
            for (int k = 0; k < 10; k++) {
                const uint32_t v = top.count_o[k];
                if (v != rw[k] && g_mismatches++ < 20)
                    std::printf("MISMATCH trace_core packet %llu cycle %llu thread %u counter %s: rtl %u, C %llu\n",
                                (unsigned long long)s.packet, (unsigned long long)cycle, t, COUNTER[k], v,
                                (unsigned long long)rw[k]);
                cw[k] += v;
            }
            checked++;
            trace_end(&s.b.trace, got);
            s.pending = false;
            unit_op op;
            rgs_step(mem.data(), &cfg, &s.b, &op, &counters); // finds the packet done and goes on
            advance(t);
            last_out = cycle;
        }
        if (top.blk_valid_o && top.blk_ready_i) {
            slot &s = slots[free_t];
            s.busy = true;
            s.x0 = top.blk_x_o;
            s.y0 = top.blk_y_o;
            busy++;
            rgs_block_begin(mem.data(), s.x0, s.y0, &s.b);
            advance((uint32_t)free_t);
        }
        top.clk_i = 1;
        top.eval();
        cycle++;
        ended = finished;
        if (g_mismatches >= 20)
            break;
    }

    auto write = [&](const char *name, const std::vector<uint32_t> &v) {
        const std::string path = dir + "/" + name;
        FILE *f = std::fopen(path.c_str(), "wb");
        const bool ok = f && std::fwrite(v.data(), 4, v.size(), f) == v.size();
        return (f && std::fclose(f) == 0) && ok;
    };
    FILE *st = std::fopen((dir + "/stats").c_str(), "w");
    if (!st || !write("pixels.bin", pixels) || !write("hits.bin", hits)) {
        std::printf("tb_dynrtp: cannot write the results to %s\n", dir.c_str());
        return 2;
    }
    std::fprintf(st, "cycles %llu\npackets %llu\nthreads %u\n", (unsigned long long)top.cycles_o,
                 (unsigned long long)top.packets_o, threads);
    for (int u = 0; u < 8; u++)
        std::fprintf(st, "issues_%s %llu\n", UNIT[u],
                     (unsigned long long)((uint64_t)top.issues_o[2 * u] | (uint64_t)top.issues_o[2 * u + 1] << 32));
    for (int k = 0; k < 3; k++)
        std::fprintf(st, "reads_%s %llu\n", PORT[k],
                     (unsigned long long)((uint64_t)top.reads_o[2 * k] | (uint64_t)top.reads_o[2 * k + 1] << 32));
    std::fprintf(st, "mem_transfers %llu\nmem_bytes %llu\n", (unsigned long long)transfers, (unsigned long long)bytes);
    for (int k = 0; k < RAY_KINDS; k++)
        std::fprintf(st, "rays_%d %llu\n", k, (unsigned long long)counters.rays[k]);
    const uint64_t *cw = &counters.trace.traversal_steps;
    for (int k = 0; k < 10; k++)
        std::fprintf(st, "%s %llu\n", COUNTER[k], (unsigned long long)cw[k]);
    std::fprintf(st, "dropped %llu\nchecked %llu\nmismatches %llu\n", (unsigned long long)counters.dropped,
                 (unsigned long long)checked, (unsigned long long)g_mismatches);
    std::fclose(st);
    std::printf("tb_dynrtp: %ux%u, %llu packets on %u threads in %llu cycles, %llu checked against the C core, "
                "%llu mismatches\n", w, h, (unsigned long long)top.packets_o, threads, (unsigned long long)top.cycles_o,
                (unsigned long long)checked, (unsigned long long)g_mismatches);
    return g_mismatches ? 1 : 0;
}
