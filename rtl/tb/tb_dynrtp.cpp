// The harness of saarcor render --mode rtl: renders a frame through the Verilated DynRTP top
// (rtl/dynrtp.sv: tile_ctrl, RGS_BLOCKS rgs_ctrl, trace_core, the caches, mem_port). saarcor writes
// the memory image and the parameters to DIR; this program
//   * starts the frame (the image's region, --tile, --max-depth, shadows, min(--threads-per-pipe,
//     RGS_BLOCKS) blocks in flight) and collects each block's 4 pixels and 4 primary hits from the
//     top's pixel port;
//   * is the memory behind the port, with the cycle model's arithmetic (tb/cycle/mem_iface.c): a
//     transfer occupies the port bytes x 65536 clock / MB/s in 1/65536 cycles after the port is
//     free, its data is there --mem-latency cycles after the transfer ends, answers in order;
//   * checks: every packet the core takes (observed at its input) is also traced by the C core
//     (trace_begin + trace_step), and the RTL's hits and counters must equal it; every block's
//     pixels and primary hits must equal rgs_render_block's (linked C of hls/units/rgs.c); a
//     mismatch prints the unit (trace_core or rgs_ctrl), the packet or block, the cycle, the
//     thread, the ray or pixel and field and both values, exit 1;
//   * checks every transaction of the units inside the frame (tb_unit_check.h, the ports made
//     readable by tb_dynrtp.vlt): trace_core's rebase_unit, xform_wide, isect_rebased, its two
//     f24_add, trav_unit and list_unit (their C units' walkers and mailboxes kept per thread and
//     level), rgs_units' rgs_raygen, rgs_light, rgs_light_colour, rgs_add_light, rgs_accum and each
//     rgs_surface, the 4 caches: every result against the unit's C function on the operands the
//     unit took (and the memory image: rgs_raygen, rgs_surface, trav_unit, list_unit, the caches);
//     a mismatch prints the unit, its instance, the cycle, the thread, the operands and both
//     results, exit 1. With TB_DYNRTP_MUTATE=UNIT the C's results of that unit have bit 0 of their
//     first word flipped (the test that the check can fail).
// Writes DIR/pixels.bin (0xRRGGBB per pixel), DIR/hits.bin (instance, triangle, t, u, v, cos per
// pixel: the primary hits) and DIR/stats (key value lines: the RTL's cycles, issues per unit,
// packets and reads per cache, the memory port's transfers and bytes; the trace counters, the
// rays by kind and the dropped packets of the C reference blocks: the RTL core's counters summed
// over the frame must equal them, and the RTL's equal pixels and primary hits stand for its equal
// ray trees); per checked unit checked_UNIT, its transactions checked (the surfaces' summed).
// With TB_DYNRTP_LOG=FILE in the environment it also writes the frame's timing to FILE for the
// comparison with the cycle model (docs/cycle-model.md): per packet a line
// "P number thread cycle_in cycle_out" and per kind of operation (OP_*) of the C core's steps its
// count and issue slots; per block "B x0 y0 cycle_out" and the same counts of rgs_step's operations.
// With VCD (render --vcd) it writes the waveform of the frame's cycles vcd_from up to vcd_to
// (DIR/params) there (struct waves below; docs/cycle-model.md has the signals).
// usage: tb_dynrtp DIR [VCD]  (DIR/image.bin, DIR/params as saarcor writes them); exit 0, 1 (a
// mismatch or a hang), 2 (bad input), 3 (VCD cannot be written)
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
#include "Vtb_dynrtp___024root.h"
#include "tb_common.h"
#include "tb_rays.h"
#include "tb_unit_check.h"
#include "tb_vcd.h"
#include "verilated.h"

extern "C" {
#include "f24.h"
#include "rgs.h"
#include "trace.h"
}

namespace {

using cosim::get;

// the model's threads and block controllers (the blocks in flight at most): the Makefile gives the
// same values to Verilator (-GTHREADS, -GRGS_BLOCKS) and here
#if !defined(TB_THREADS) || !defined(TB_RGS_BLOCKS)
#error "tb_dynrtp: build it by the Makefile (make rtl), which defines TB_THREADS and TB_RGS_BLOCKS"
#endif
constexpr uint32_t THREADS = TB_THREADS;
constexpr uint32_t RGS_BLOCKS = TB_RGS_BLOCKS;
static_assert(RGS_BLOCKS <= 64, "the harness holds the block controllers' flags in 64 bits");
// the bits of a counter up to n
constexpr uint32_t bits(uint32_t n) { return n ? 1 + bits(n >> 1) : 0; }
constexpr uint64_t FX = 65536;
constexpr uint64_t FLUSH = 1024;        // cycles after reset: the caches empty their tags (512 lines at most)
constexpr uint64_t TIMEOUT = 1u << 22;  // cycles without a packet or a block out before the harness gives up
const char *const UNIT[6] = { "trav", "list", "rebase", "wide", "isect", "add" };
const char *const PORT[4] = { "nodes", "lists", "words", "shading" }; // the caches
const char *const CACHE[4] = { "u_nodes", "u_lists", "u_matrices", "u_shading" }; // their instances
const char *const CACHE_UNIT[4] = { "cache_nodes", "cache_lists", "cache_words", "cache_shading" }; // checked as
const char *const HIT[6] = { "instance", "triangle", "t", "u", "v", "cos" };
const char *const COUNTER[10] = { "traversal_steps", "leaves", "list_entries", "mailbox_skips", "transformations",
                                  "intersections", "words_nodes", "words_lists", "words_matrices", "words_shading" };

struct packet { // the packet a core thread traces and the C core's run of it
    bool busy = false;
    uint64_t number = 0, in = 0;
    uint32_t ops[OP_KINDS] = {}, slots[OP_KINDS] = {}; // the C core's operations by kind (TB_DYNRTP_LOG)
    trace_state ref;
    trace_counters ref_c;
};

struct transfer {
    uint64_t due;
    uint32_t addr, bytes;
};

// bits [24 i, 24 i + 24) of a wide port: pixel i's 0xRRGGBB
template <std::size_t N> uint32_t rgb_of(const VlWide<N> &v, int i)
{
    const int b = 24 * i, s = b % 32;
    uint32_t x = v[b / 32] >> s;
    if (s > 8)
        x |= v[b / 32 + 1] << (32 - s);
    return x & 0xFFFFFFu;
}

uint64_t g_mismatches = 0;

// the counts and issue slots of a run of operations by kind, as a log line's tail
void log_ops(FILE *f, const uint32_t *ops, const uint32_t *slots)
{
    for (int k = 0; k < OP_KINDS; k++)
        std::fprintf(f, " %u %u", ops[k], slots[k]);
    std::fputc('\n', f);
}

// a block's operations by kind (rgs_step's, the core's among them), for the log
void block_ops(const std::vector<uint32_t> &mem, const rgs_config *cfg, uint32_t x0, uint32_t y0, FILE *f)
{
    static rgs_block b;
    uint32_t ops[OP_KINDS] = {}, slots[OP_KINDS] = {};
    rgs_counters c;
    std::memset(&c, 0, sizeof c);
    unit_op op;
    rgs_block_begin(mem.data(), x0, y0, &b);
    while (rgs_step(mem.data(), cfg, &b, &op, &c))
        ops[op.kind]++, slots[op.kind] += op.slots;
    log_ops(f, ops, slots);
}

// The per-unit transaction checks (tb_unit_check.h) of the DynRTP's units: trace_core's, rgs_units'
// (each surface unit on its own) and the caches. With TB_DYNRTP_MUTATE=NAME in the environment the
// C's results of unit NAME have a bit flipped: the frame must fail there.
struct unit_checks {
    const std::string core = "tb_dynrtp.u_dynrtp.u_core", units = "tb_dynrtp.u_dynrtp.u_units";
    cosim::signal sel;         // trace_core's scheduler's picks (public_flat_rd)
    uint32_t sel_prev[6] = {}; // the picks of the cycle before: the threads of this cycle's unit steps
    std::vector<cosim::unit_check> all;
    std::vector<const char *> names; // in the order of the stats, each once

    unit_checks(const VerilatedContext &ctx, const std::vector<uint32_t> &mem)
    {
        using namespace cosim;
        sel = scope(ctx, core)["sel"];
        all = { rebase_check(ctx, core, sel_prev[2]), wide_check(ctx, core, sel_prev[3]),
                isect_check(ctx, core, sel_prev[4]),  add_check(ctx, core, sel_prev[5]),
                trav_check(ctx, core, mem),           list_check(ctx, core, mem),
                raygen_check(ctx, units, mem),        light_check(ctx, units),
                colour_check(ctx, units),             add_light_check(ctx, units),
                accum_check(ctx, units) };
        for (int k = 0; ctx.scopeFind(("TOP." + surface_path(k)).c_str()); k++)
            all.push_back(surface_check(ctx, surface_path(k), mem));
        for (int k = 0; k < 4; k++)
            all.push_back(cache_check(ctx, std::string("tb_dynrtp.u_dynrtp.") + CACHE[k], CACHE_UNIT[k], mem));
        for (const unit_check &u : all)
            if (names.empty() || std::strcmp(names.back(), u.name))
                names.push_back(u.name);
        if (const char *m = std::getenv("TB_DYNRTP_MUTATE")) {
            bool found = false;
            for (unit_check &u : all)
                found |= u.mutate = !std::strcmp(u.name, m);
            if (!found) {
                std::printf("tb_dynrtp: TB_DYNRTP_MUTATE=%s: no such unit\n", m);
                std::exit(2);
            }
        }
    }
    std::string surface_path(int k) const { return units + ".g_sf[" + std::to_string(k) + "].u_surface"; }
    void sample(uint64_t cycle)
    {
        for (cosim::unit_check &u : all)
            u.sample(cycle, g_mismatches);
        for (uint32_t u = 0; u < 6; u++)
            sel_prev[u] = sel.element(u).bits(0, 8);
    }
    void finish(uint64_t cycle)
    {
        for (cosim::unit_check &u : all)
            u.finish(cycle, g_mismatches);
    }
    // the transactions checked of the units called name (the surfaces: all of them)
    uint64_t checked(const char *name) const
    {
        uint64_t n = 0;
        for (const cosim::unit_check &u : all)
            n += std::strcmp(u.name, name) ? 0 : u.checked;
        return n;
    }
};

// The waveform of --vcd (tb_vcd.h) in cycle mode's names where the RTL has the same thing
// (docs/cycle-model.md has the mapping), RTL-only signals under their own: read from the harness's
// memory queue and the signals of dynrtp, trace_core and thread_sched marked
// /*verilator public_flat_rd*/.
struct waves {
    enum { BUSY, ISSUE, QUEUE, TID };
    enum { LOOKUPS, MISSES, FILLS };
    cosim::vcd_writer vcd;
    int unit[6][4] = {}, rgs[4] = {}, cache[4][3] = {}, outstanding = 0, in_flight = 0;
    uint32_t fills[4] = {}; // per cache: line requests the memory port took and has not answered
    uint64_t computing_q = 0;

    // the signals, in the scopes of cycle mode's file; the rgs scope has no queue_depth (every block
    // controller has its own units: no thread waits for them) and counts its busy controllers
    bool open(const char *path, uint64_t from, uint64_t to, double mhz, uint32_t blocks)
    {
        static const char *const unit_sig[4] = { "busy", "issue", "queue_depth", "thread_id" };
        static const char *const cache_sig[3] = { "lookups", "misses", "fills" };
        static const char *const cache_name[4] = { "kd_nodes", "lists", "matrices", "shading" }; // mem_kind_names
        const std::string pipe = "dynrtc.pipe0";
        const uint32_t widths[4] = { 1, 1, bits(THREADS), bits(THREADS - 1) }; // a depth up to THREADS, ids
        rgs[BUSY] = vcd.add(pipe + ".rgs", "busy", 1);
        rgs[ISSUE] = vcd.add(pipe + ".rgs", "issue", bits(RGS_BLOCKS));
        rgs[TID] = vcd.add(pipe + ".rgs", "thread_id", bits(RGS_BLOCKS - 1));
        rgs[QUEUE] = vcd.add(pipe + ".rgs", "controllers_busy", bits(RGS_BLOCKS)); // RTL only
        for (int u = 0; u < 6; u++)
            for (int k = 0; k < 4; k++)
                unit[u][k] = vcd.add(pipe + "." + UNIT[u], unit_sig[k], widths[k]);
        for (int c = 0; c < 4; c++)
            for (int k = 0; k < 3; k++)
                cache[c][k] = vcd.add(pipe + ".cache_" + cache_name[c], cache_sig[k], 32);
        outstanding = vcd.add(pipe + ".mem_port", "outstanding", 32);
        in_flight = vcd.add(pipe, "threads_in_flight", bits(RGS_BLOCKS));
        char comment[160];
        std::snprintf(comment, sizeof comment, "the RTL DynRTP (rtl/dynrtp.sv): 1 pipe x %u threads, %u blocks in "
                      "flight at %g MHz", THREADS, blocks, mhz);
        return vcd.open(path, from, to, mhz, comment);
    }

    // the cycle's values (every cycle: the fills run from reset on), written for frame cycle
    // `frame_cycle` when in_frame
    void sample(Vtb_dynrtp &top, uint32_t blocks, std::size_t port_queue, bool in_frame, uint64_t frame_cycle)
    {
        const auto *r = top.rootp;
        const uint32_t issue = r->tb_dynrtp__DOT__u_dynrtp__DOT__issue;
        const uint32_t valid = r->tb_dynrtp__DOT__u_dynrtp__DOT__u_core__DOT__unit_valid;
        for (int u = 0; u < 6; u++) {
            vcd.set(unit[u][BUSY], valid >> u & 1);
            vcd.set(unit[u][ISSUE], issue >> u & 1);
            vcd.set(unit[u][QUEUE], (uint64_t)__builtin_popcountll(
                                        r->tb_dynrtp__DOT__u_dynrtp__DOT__u_core__DOT__u_sched__DOT__ready_q[u]));
            vcd.set(unit[u][TID], valid >> u & 1 ? r->tb_dynrtp__DOT__u_dynrtp__DOT__u_core__DOT__sel[u]
                                                  : cosim::vcd_writer::X);
        }
        // a block controller computes while it holds a block, not waiting for the core to take its
        // packet or to give back its hits
        const uint64_t mask = ~0ull >> (64 - blocks);
        const uint64_t computing = ~r->tb_dynrtp__DOT__u_dynrtp__DOT__rb_ready & ~r->tb_dynrtp__DOT__u_dynrtp__DOT__tr_valid &
                                   ~r->tb_dynrtp__DOT__u_dynrtp__DOT__hit_ready & mask;
        vcd.set(rgs[BUSY], computing != 0);
        vcd.set(rgs[ISSUE], (uint64_t)__builtin_popcountll(computing & ~computing_q));
        vcd.set(rgs[TID], computing ? (uint64_t)__builtin_ctzll(computing) : cosim::vcd_writer::X);
        vcd.set(rgs[QUEUE], (uint64_t)__builtin_popcountll(computing));
        computing_q = computing;
        const bool look[4] = { r->tb_dynrtp__DOT__u_dynrtp__DOT__node_req && r->tb_dynrtp__DOT__u_dynrtp__DOT__node_ready,
                               r->tb_dynrtp__DOT__u_dynrtp__DOT__list_req && r->tb_dynrtp__DOT__u_dynrtp__DOT__list_ready,
                               r->tb_dynrtp__DOT__u_dynrtp__DOT__word_req && r->tb_dynrtp__DOT__u_dynrtp__DOT__word_ready,
                               r->tb_dynrtp__DOT__u_dynrtp__DOT__sh_req && r->tb_dynrtp__DOT__u_dynrtp__DOT__sh_ready };
        const uint32_t miss = r->tb_dynrtp__DOT__u_dynrtp__DOT__mreq_valid & r->tb_dynrtp__DOT__u_dynrtp__DOT__mreq_ready;
        for (int c = 0; c < 4; c++) {
            fills[c] += (miss >> c & 1) - (r->tb_dynrtp__DOT__u_dynrtp__DOT__mrsp_valid >> c & 1);
            vcd.set(cache[c][LOOKUPS], look[c]);
            vcd.set(cache[c][MISSES], miss >> c & 1);
            vcd.set(cache[c][FILLS], fills[c]);
        }
        vcd.set(outstanding, port_queue);
        vcd.set(in_flight, r->tb_dynrtp__DOT__u_dynrtp__DOT__busy_q);
        if (in_frame)
            vcd.sample(frame_cycle);
    }
};

} // namespace

int main(int argc, char **argv)
{
    if (argc != 2 && argc != 3) {
        std::printf("usage: tb_dynrtp DIR [VCD] (DIR/image.bin, DIR/params from saarcor render --mode rtl; VCD: "
                    "the waveform of the frame's cycles vcd_from up to vcd_to of DIR/params)\n");
        return 2;
    }
    const std::string dir = argv[1];
    std::vector<uint32_t> mem;
    if (!cosim::read_words("tb_dynrtp", dir + "/image.bin", mem))
        return 2;
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
    if (par["threads"] < 1) {
        std::printf("tb_dynrtp: --threads-per-pipe %g: at least 1\n", par["threads"]);
        return 2;
    }
    if ((uint32_t)par["traversal"] != TRAV_STACK) {
        std::printf("tb_dynrtp: the RTL core has the traversal algorithm stack only\n");
        return 2;
    }
    // one block per core thread; the RTL has RGS_BLOCKS block controllers
    const uint32_t blocks = std::min((uint32_t)par["threads"], RGS_BLOCKS), tile = (uint32_t)par["tile"];
    const rgs_config cfg = { (uint32_t)par["max_depth"], (uint32_t)par["shadows"], TRAV_STACK };
    const uint32_t latency = (uint32_t)par["mem_latency"];
    const uint64_t fxpb = (uint64_t)std::llround(par["clock_mhz"] / par["mem_mbps"] * (double)FX);
    uint32_t w, h;
    rgs_image_size(mem.data(), &w, &h);
    std::vector<uint32_t> pixels((std::size_t)w * h, 0), hits((std::size_t)w * h * 6, 0);
    static waves wave; // static: its destructor drops an unfinished file at exit
    const bool vcd = argc == 3;
    if (vcd && !wave.open(argv[2], (uint64_t)par["vcd_from"], (uint64_t)par["vcd_to"], par["clock_mhz"], blocks)) {
        std::printf("tb_dynrtp: cannot write '%s'\n", argv[2]);
        return 3;
    }

    VerilatedContext ctx;
    Vtb_dynrtp top{ &ctx };
    auto tick = [&]() {
        top.clk_i = 0;
        top.eval();
        top.clk_i = 1;
        top.eval();
    };
    top.rst_ni = 0, top.flush_i = 0, top.frame_valid_i = 0, top.px_ready_i = 1;
    top.x0_i = 0, top.y0_i = 0, top.x1_i = w, top.y1_i = h, top.tile_i = tile;
    top.max_depth_i = cfg.max_depth, top.shadows_i = cfg.shadows, top.blocks_i = blocks;
    top.mem_req_ready_i = 1, top.mem_rsp_valid_i = 0;
    tick();
    top.rst_ni = 1;
    unit_checks checks(ctx, mem);

    std::vector<packet> core(std::size_t{1} << 8);
    const char *log_path = std::getenv("TB_DYNRTP_LOG");
    FILE *log = log_path ? std::fopen(log_path, "w") : nullptr;
    rgs_counters counters, ref; // the RTL core's counters; the C reference blocks' (rays, drops, core counters)
    std::memset(&counters, 0, sizeof counters);
    std::memset(&ref, 0, sizeof ref);
    std::deque<transfer> port;
    uint64_t cycle = 0, frame_at = 0, port_free = 0, last_out = 0, packets = 0, transfers = 0, bytes = 0, checked = 0, done = 0;
    bool frame_taken = false, ended = false;

    while (!ended) {
        if (cycle - last_out > TIMEOUT) {
            std::printf("MISMATCH dynrtp: no packet or block out for %llu cycles at cycle %llu (%llu blocks done)\n",
                        (unsigned long long)TIMEOUT, (unsigned long long)cycle, (unsigned long long)done);
            return 1;
        }
        // ---- inputs: the frame once the caches have emptied their tags, memory's answers ----
        top.frame_valid_i = !frame_taken && cycle >= FLUSH;
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
        if (top.frame_valid_i && top.frame_ready_o)
            frame_taken = true, last_out = frame_at = cycle;
        if (top.mem_req_valid_o) {
            const uint64_t start = std::max(port_free, cycle * FX);
            port_free = start + top.mem_req_bytes_o * fxpb;
            port.push_back({ (port_free + FX - 1) / FX + latency, top.mem_req_addr_o, top.mem_req_bytes_o });
            transfers++;
            bytes += top.mem_req_bytes_o;
        }
        if (top.valid_o) { // hits out: the controllers take them at once
            const uint32_t t = top.thread_o;
            if (!core[t].busy) {
                std::printf("MISMATCH dynrtp: cycle %llu: hits out of thread %u, which traces no packet\n",
                            (unsigned long long)cycle, t);
                return 1;
            }
            packet &s = core[t];
            for (int r = 0; r < 4; r++) {
                const uint32_t v[6] = { top.inst_o[r], top.tri_o[r], get(top.t_o, r), get(top.u_o, r), get(top.v_o, r),
                                        get(top.cos_o, r) };
                const hit_record &c = s.ref.hits[r];
                const uint32_t want[6] = { c.instance, c.triangle, c.t, c.u, c.v, c.cos_n };
                for (int f = 0; f < 6; f++)
                    if (v[f] != want[f] && g_mismatches++ < 20)
                        std::printf("MISMATCH trace_core packet %llu cycle %llu thread %u ray %d %s: rtl %06x, C %06x\n",
                                    (unsigned long long)s.number, (unsigned long long)cycle, t, r, HIT[f], v[f], want[f]);
            }
            uint64_t *cw = &counters.trace.traversal_steps;
            const uint64_t *rw = &s.ref_c.traversal_steps;
            for (int k = 0; k < 10; k++) {
                const uint32_t v = top.count_o[k];
                if (v != rw[k] && g_mismatches++ < 20)
                    std::printf("MISMATCH trace_core packet %llu cycle %llu thread %u counter %s: rtl %u, C %llu\n",
                                (unsigned long long)s.number, (unsigned long long)cycle, t, COUNTER[k], v,
                                (unsigned long long)rw[k]);
                cw[k] += v;
            }
            checked++;
            if (log) {
                std::fprintf(log, "P %llu %u %llu %llu", (unsigned long long)s.number, t, (unsigned long long)s.in,
                             (unsigned long long)cycle);
                log_ops(log, s.ops, s.slots);
            }
            s.busy = false;
            last_out = cycle;
        }
        if (top.tr_valid_o) { // a packet into the core: the C core traces it too
            const uint32_t t = top.tr_thread_o;
            packet &s = core[t];
            if (s.busy) {
                std::printf("MISMATCH dynrtp: cycle %llu: a packet into thread %u, which traces packet %llu\n",
                            (unsigned long long)cycle, t, (unsigned long long)s.number);
                return 1;
            }
            const ray_packet rays = cosim::rays_of(top.tr_active_o, top.tr_o_o, top.tr_d_o, top.tr_tmin_o, top.tr_tmax_o);
            trace_begin(&rays, top.tr_flags_o, &s.ref);
            std::memset(&s.ref_c, 0, sizeof s.ref_c);
            unit_op op;
            std::memset(s.ops, 0, sizeof s.ops);
            std::memset(s.slots, 0, sizeof s.slots);
            while (trace_step(mem.data(), &s.ref, &op, &s.ref_c))
                s.ops[op.kind]++, s.slots[op.kind] += op.slots;
            s.busy = true;
            s.in = cycle;
            s.number = packets++;
        }
        if (top.px_valid_o && top.px_ready_i) { // a block's pixels: as rgs_render_block's
            const uint32_t x0 = top.px_x_o, y0 = top.px_y_o;
            uint32_t rgb[4];
            hit_record want[4];
            rgs_render_block(mem.data(), &cfg, x0, y0, rgb, want, &ref);
            for (int i = 0; i < 4; i++) {
                const uint32_t x = x0 + (i & 1u), y = y0 + (i >> 1);
                if (x >= w || y >= h)
                    continue;
                const std::size_t p = (std::size_t)y * w + x;
                const uint32_t v[6] = { top.px_inst_o[i], top.px_tri_o[i], get(top.px_t_o, i), get(top.px_u_o, i),
                                        get(top.px_v_o, i), get(top.px_cos_o, i) };
                const uint32_t c[6] = { want[i].instance, want[i].triangle, want[i].t, want[i].u, want[i].v,
                                        want[i].cos_n };
                pixels[p] = rgb_of(top.px_rgb_o, i);
                if (pixels[p] != rgb[i] && g_mismatches++ < 20)
                    std::printf("MISMATCH rgs_ctrl block (%u, %u) cycle %llu pixel %d: rtl %06x, C %06x\n", x0, y0,
                                (unsigned long long)cycle, i, pixels[p], rgb[i]);
                for (int f = 0; f < 6; f++)
                    if (v[f] != c[f] && g_mismatches++ < 20)
                        std::printf("MISMATCH rgs_ctrl block (%u, %u) cycle %llu primary hit %d %s: rtl %06x, C %06x\n",
                                    x0, y0, (unsigned long long)cycle, i, HIT[f], v[f], c[f]);
                std::memcpy(&hits[6 * p], v, sizeof v);
            }
            if (log) {
                std::fprintf(log, "B %u %u %llu", x0, y0, (unsigned long long)cycle);
                block_ops(mem, &cfg, x0, y0, log);
            }
            done++;
            last_out = cycle;
        }
        checks.sample(cycle);
        if (vcd) // frame cycle 0 is the first that cycles_o counts, the one after the frame was taken
            wave.sample(top, blocks, port.size(), frame_taken && cycle > frame_at, cycle - frame_at - 1);
        ended = top.frame_done_o;
        top.clk_i = 1;
        top.eval();
        cycle++;
        if (g_mismatches >= 20)
            break;
    }

    if (log)
        std::fclose(log);
    if (ended)
        checks.finish(cycle);
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
                 (unsigned long long)top.packets_o, blocks);
    for (int u = 0; u < 6; u++)
        std::fprintf(st, "issues_%s %llu\n", UNIT[u],
                     (unsigned long long)((uint64_t)top.issues_o[2 * u] | (uint64_t)top.issues_o[2 * u + 1] << 32));
    for (int k = 0; k < 4; k++)
        std::fprintf(st, "reads_%s %llu\n", PORT[k],
                     (unsigned long long)((uint64_t)top.reads_o[2 * k] | (uint64_t)top.reads_o[2 * k + 1] << 32));
    std::fprintf(st, "mem_transfers %llu\nmem_bytes %llu\n", (unsigned long long)transfers, (unsigned long long)bytes);
    for (int k = 0; k < RAY_KINDS; k++)
        std::fprintf(st, "rays_%d %llu\n", k, (unsigned long long)ref.rays[k]);
    // the core's counters summed over the frame are the reference blocks' (their packets are the
    // frame's); words_shading counts the RGS's reads (the core's stays 0): the C's, as functional mode's
    const uint64_t *cw = &counters.trace.traversal_steps, *rw = &ref.trace.traversal_steps;
    for (int k = 0; k < 10; k++) {
        std::fprintf(st, "%s %llu\n", COUNTER[k], (unsigned long long)rw[k]);
        if (k < 9 && cw[k] != rw[k] && g_mismatches++ < 20)
            std::printf("MISMATCH dynrtp: the frame's %s: rtl %llu, C blocks %llu\n", COUNTER[k],
                        (unsigned long long)cw[k], (unsigned long long)rw[k]);
    }
    for (const char *u : checks.names)
        std::fprintf(st, "checked_%s %llu\n", u, (unsigned long long)checks.checked(u));
    std::fprintf(st, "dropped %llu\nchecked %llu\nmismatches %llu\n", (unsigned long long)ref.dropped,
                 (unsigned long long)checked, (unsigned long long)g_mismatches);
    std::fclose(st);
    if (vcd && !g_mismatches && !wave.vcd.close(top.cycles_o)) { // with mismatches: dropped at exit
        std::printf("tb_dynrtp: cannot write '%s'\n", argv[2]);
        return 3;
    }
    std::printf("tb_dynrtp: transactions checked per unit against its C function:");
    for (const char *u : checks.names)
        std::printf(" %s %llu", u, (unsigned long long)checks.checked(u));
    std::printf("\n");
    std::printf("tb_dynrtp: %ux%u, %llu blocks (%u in flight) and %llu packets in %llu cycles, %llu packets checked "
                "against the C core and %llu blocks against rgs_render_block, %llu mismatches\n", w, h,
                (unsigned long long)done, blocks, (unsigned long long)top.packets_o, (unsigned long long)top.cycles_o,
                (unsigned long long)checked, (unsigned long long)done, (unsigned long long)g_mismatches);
    return g_mismatches ? 1 : 0;
}
