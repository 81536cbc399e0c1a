// Co-simulation of rgs_surface (rtl/rgs_surface.sv), the surface the RGS shades at a hit, against
// rgs_surface_at (hls/units/rgs_surface.c): every field of the surface (valid, P, D^, N^, t_hat,
// entering, the material's address, unlit, its exponent k, the Q12 base colour, emission and tint)
// and every line the unit reads (its port names a 4-word line by its first word's address and is
// answered the line; the reads rgs_surface_at notes in its unit_op, word by word: instance, object
// descriptor, shading record, geometric normal, material, texture entries and texels): the unit
// works on several surfaces at once (its front reads the next hit's records while its back shades
// one), so a line read must start a line and hold a word the C reads for a surface in flight, and
// by the time no surface is in flight every word the C reads must have been in lines read as often
// (a line's due words count as read once per line read).
// Captured transactions (saarcor render --capture-unit-io DIR: DIR/surface.hex, every
// rgs_surface_at call: the memory image (DIR/image_N.bin), the ray's active bit, o, d, the hit's
// instance, triangle, t, u, v, cos_n, the reads noted, the surface) come first and are checked
// against the recording too; then (-n N, with --capture) random ones: a recorded hit with other
// barycentrics (inside, on the edges, outside the triangle, huge or special: texture coordinates
// that wrap, vertex colour weights that saturate), another distance or cos_n, an inactive ray or a
// miss. The bench is the memory: it takes requests with random gaps in every other epoch of 1024
// cycles and answers in order after 1 cycle (1 to 4 in those epochs), and gives the output random
// back pressure; up to 8 surfaces are in flight. Each transaction has a thread id (its number modulo 64) that must come out with
// it. A mismatch prints the unit, the transaction, the cycle, the thread, the field and both
// values; exit code 1 on any mismatch, wrong read, or a surface lost or invented.
// usage: tb_surface [-n N] [--seed S] [--capture DIR]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "Vtb_surface.h"
#include "tb_common.h"

extern "C" {
#include "rgs_ops.h"
#include "shade_rec.h"
}

using namespace cosim;

namespace {

struct surface_tx {
    uint32_t image, active, o[3], d[3], inst, tri, t, u, v, cos_n;
    std::vector<uint32_t> reads;  // recorded: word addresses
    std::vector<uint32_t> out;    // recorded outputs (OUT_WORDS); empty for a random transaction
};

// the outputs compared, in this order
enum { O_VALID, O_P, O_D = O_P + 3, O_N = O_D + 3, O_THAT = O_N + 3, O_ENT, O_MAT, O_UNLIT, O_BASE, O_EMIS = O_BASE + 3,
       O_TINT = O_EMIS + 3, O_K = O_TINT + 3, O_ETA, O_KD, O_KR, O_KT, O_KS, OUT_WORDS };
const char *field_name(int k)
{
    static const char *const name[] = { "valid", "p.x", "p.y", "p.z", "d.x", "d.y", "d.z", "n.x", "n.y", "n.z", "t_hat",
                                        "entering", "mat", "unlit", "base.r", "base.g", "base.b", "emission.r",
                                        "emission.g", "emission.b", "tint.r", "tint.g", "tint.b", "k", "eta", "kd",
                                        "kr", "kt", "ks" };
    return name[k];
}

bool parse_line(const char *line, surface_tx &x)
{
    const char *p = line;
    auto next = [&](uint32_t &w) {
        char *end;
        w = (uint32_t)std::strtoul(p, &end, 16);
        if (end == p)
            return false;
        p = end;
        return true;
    };
    uint32_t *in[] = { &x.image, &x.active, &x.o[0], &x.o[1], &x.o[2], &x.d[0], &x.d[1], &x.d[2],
                       &x.inst, &x.tri, &x.t, &x.u, &x.v, &x.cos_n };
    for (uint32_t *w : in)
        if (!next(*w))
            return false;
    uint32_t n;
    if (!next(n))
        return false;
    for (uint32_t r = 0; r < n; r++) {
        uint32_t a, words;
        if (!next(a) || !next(words))
            return false;
        for (uint32_t k = 0; k < words; k++)
            x.reads.push_back(a + k);
    }
    // valid p d n t_hat entering mat unlit, then per channel base emission tint
    uint32_t w[14], c[9];
    for (uint32_t &v : w)
        if (!next(v))
            return false;
    for (uint32_t &v : c)
        if (!next(v))
            return false;
    x.out.assign(w, w + 14);
    for (int k = 0; k < 3; k++)
        x.out.push_back(c[3 * k]);
    for (int k = 0; k < 3; k++)
        x.out.push_back(c[3 * k + 1]);
    for (int k = 0; k < 3; k++)
        x.out.push_back(c[3 * k + 2]);
    x.out.resize(OUT_WORDS); // k and the material's fields: not recorded (compared with the C only)
    return true;
}

// the C model: the surface's outputs and the word addresses it reads
struct coverage { std::size_t valid = 0, colours = 0, samples = 0, geometric = 0; };

void model(const std::vector<uint32_t> &mem, const surface_tx &x, std::vector<uint32_t> &out, std::vector<uint32_t> &reads,
           coverage &cov)
{
    ray_packet rp{};
    rp.active = x.active & 1u;
    rp.o[0] = { x.o[0], x.o[1], x.o[2] };
    rp.d[0] = { x.d[0], x.d[1], x.d[2] };
    const hit_record h = { x.inst, x.tri, x.t, x.u, x.v, x.cos_n };
    unit_op op{};
    trace_counters c{};
    const surface sf = rgs_surface_at(mem.data(), &rp, 0, &h, &op, &c);
    out = { (uint32_t)sf.valid, sf.p.x, sf.p.y, sf.p.z, sf.d.x, sf.d.y, sf.d.z, sf.n.x, sf.n.y, sf.n.z, sf.t_hat,
            (uint32_t)sf.entering, sf.mat, (uint32_t)sf.unlit };
    for (const uint32_t *q : { sf.base, sf.emission, sf.tint })
        for (int k = 0; k < 3; k++)
            out.push_back(q[k]);
    const uint32_t *m = &mem[sf.mat];
    out.push_back(sf.valid ? m[M_SHADER0] >> 26 & 0xFu : 0u);
    out.push_back(sf.valid ? m[M_ETA] & F24_MASK : 0u);
    out.push_back(sf.valid ? m[M_SHADER0] & 0x1FFFu : 0u);
    out.push_back(sf.valid ? m[M_SHADER0] >> 13 & 0x1FFFu : 0u);
    out.push_back(sf.valid ? m[M_SHADER1] & 0x1FFFu : 0u);
    out.push_back(sf.valid ? m[M_SHADER1] >> 13 & 0x1FFFu : 0u);
    reads.clear();
    for (uint32_t r = 0; r < op.n_reads; r++) {
        for (uint32_t k = 0; k < op.read[r].words; k++)
            reads.push_back(op.read[r].addr + k);
        cov.samples += op.read[r].words == 1; // a texel (a sample reads 4); every other read is longer
    }
    if (!sf.valid)
        return;
    cov.valid++;
    const uint32_t obj = region_start(mem.data(), R_OBJECTS) +
                         OBJ_WORDS * mem[region_start(mem.data(), R_INSTANCES) + INST_WORDS * x.inst + 12];
    cov.colours += (mem[obj + O_FLAGS] & SHADE_HAS_COLOURS) != 0;
    cov.geometric += op.n_reads > 3 && op.read[3].addr != sf.mat; // the read after the record: the normal's
}

uint32_t rnd_bary()
{
    switch (rnd() % 6) {
    case 0: return rnd() % 2 ? 0u : F24_ONE;
    case 1: return rnd_f24();
    case 2: return f24_from_i32((int32_t)(rnd() % 9) - 4);
    default: return f24_div(f24_from_i32((int32_t)(rnd() % 4097)), f24_from_i32(4096));
    }
}

} // namespace

int main(int argc, char **argv)
{
    std::size_t n = 0;
    std::string capture;
    if (!parse_args(argc, argv, "tb_surface", n, capture))
        return 2;
    std::vector<surface_tx> tx;
    if (capture.empty()) {
        std::printf("tb_surface: the surfaces read a memory image: give --capture DIR\n");
        return 2;
    }
    {
        const std::string path = capture + "/surface.hex";
        FILE *f = std::fopen(path.c_str(), "r");
        if (!f) {
            std::printf("tb_surface: cannot read %s\n", path.c_str());
            return 2;
        }
        char line[8192];
        while (std::fgets(line, sizeof line, f)) {
            surface_tx x;
            if (!parse_line(line, x)) {
                std::printf("tb_surface: %s: malformed line %zu\n", path.c_str(), tx.size() + 1);
                std::fclose(f);
                return 2;
            }
            tx.push_back(x);
        }
        std::fclose(f);
    }
    const std::size_t captured = tx.size();
    if (!captured) {
        std::printf("tb_surface: %s/surface.hex is empty: no surface shaded?\n", capture.c_str());
        return 2;
    }
    for (std::size_t i = 0; i < n; i++) {
        surface_tx x = tx[rnd() % captured];
        x.reads.clear(), x.out.clear();
        const uint32_t k = rnd() % 16;
        x.u = rnd_bary(), x.v = rnd_bary();
        if (k == 0)
            x.active = 0;
        else if (k == 1)
            x.inst = TRACE_NO_HIT;
        else if (k == 2)
            x.t = rnd_f24(), x.cos_n = rnd_f24();
        tx.push_back(x);
    }

    VerilatedContext ctx;
    Vtb_surface top{ &ctx };
    top.rst_ni = 0, top.clk_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;

    std::vector<uint32_t> mem;
    uint32_t image = UINT32_MAX;
    std::size_t next = 0, checked = 0, vs_capture = 0;
    coverage cov;
    uint64_t mismatches = 0, bad_reads = 0, idle = 0, cycles_busy = 0, latency_max = 0;
    struct flight { std::size_t t; uint64_t started; std::vector<uint32_t> want, reads; };
    std::deque<flight> in_flight;      // surfaces taken, in order
    std::map<uint32_t, long> due_reads; // the words the C reads for them, not yet in a line the RTL read
    std::map<uint32_t, long> live;      // the words the C reads for them (a line may be read again:
                                        // two texels in one line, an instance's two bursts)
    const std::size_t MAX_IN_FLIGHT = 8;
    struct response { uint64_t due; uint32_t line[4]; };  // the port answers a line of 4 words
    std::deque<response> rsp;
    auto report = [&](std::size_t t, const char *what, const char *field, uint32_t got, uint32_t exp, uint32_t tid) {
        if (mismatches++ < 20)
            std::printf("MISMATCH rgs_surface transaction %zu cycle %llu thread %u %s: %s %06x, expected %06x (%s)\n", t,
                        (unsigned long long)g_cycle, tid, field, "rtl", got, exp, what);
    };
    for (; (next < tx.size() || !in_flight.empty()) && idle < 20000; g_cycle++) {
        const bool calm = (g_cycle / 1024) % 2 == 0;
        top.clk_i = 0;
        // inputs (a new memory image only with nothing in flight)
        top.valid_i = 0;
        if (next < tx.size() && in_flight.size() < MAX_IN_FLIGHT && (calm || rnd() % 3 == 0) &&
            (tx[next].image == image || in_flight.empty())) {
            const surface_tx &x = tx[next];
            if (x.image != image) {
                if (!load_image("tb_surface", capture, x.image, mem))
                    return 2;
                image = x.image;
            }
            top.inst_base_i = region_start(mem.data(), R_INSTANCES);
            top.obj_base_i = region_start(mem.data(), R_OBJECTS);
            top.mat_base_i = region_start(mem.data(), R_MATERIALS);
            top.tex_base_i = region_start(mem.data(), R_TEXTURES);
            top.n_tex_i = mem[H_TEXTURES];
            top.valid_i = 1;
            top.tid_i = (uint8_t)(next % 64);
            top.active_i = x.active & 1u;
            for (int k = 0; k < 3; k++)
                put(top.o_i, k, x.o[k]), put(top.d_i, k, x.d[k]);
            top.inst_i = x.inst, top.tri_i = x.tri, top.t_i = x.t, top.u_i = x.u, top.v_i = x.v, top.cos_n_i = x.cos_n;
        }
        top.ready_i = calm || rnd() % 4 != 0;
        top.mem_req_ready_i = calm || rnd() % 3 != 0;
        top.mem_rsp_valid_i = 0;
        if (!rsp.empty() && rsp.front().due <= g_cycle) {
            top.mem_rsp_valid_i = 1;
            for (int j = 0; j < 4; j++)
                top.mem_rdata_i[j] = rsp.front().line[j];
            rsp.pop_front();
        }
        top.eval();
        // what fires at this edge
        const bool in_fire = top.valid_i && top.ready_o;
        const bool out_fire = top.valid_o && top.ready_i;
        if (top.mem_req_valid_o && top.mem_req_ready_i) {
            // a line: it must hold a word the C reads for a surface in flight; the words it holds
            // that are still due are read (once each)
            const uint32_t a = top.mem_addr_o;
            bool wanted = false;
            for (uint32_t j = 0; j < 4; j++) {
                wanted = wanted || live.count(a + j);
                auto w = due_reads.find(a + j);
                if (w != due_reads.end() && --w->second == 0)
                    due_reads.erase(w);
            }
            if ((!wanted || a % 4) && bad_reads++ < 20)
                std::printf("MISMATCH rgs_surface cycle %llu: read of the line at %x, which holds no word the C reads for "
                            "the %zu surfaces in flight (transactions up to %zu), or is not a line's start\n",
                            (unsigned long long)g_cycle, a, in_flight.size(), next);
            if (!wanted && getenv("TB_SURFACE_DEBUG")) { // which words the C reads for the surfaces in flight
                for (const flight &g : in_flight) {
                    std::printf("  tx %zu:", g.t);
                    for (uint32_t w : g.reads) std::printf(" %x", w);
                    std::printf("\n");
                }
            }
            const uint64_t lat = calm ? 1 : 1 + rnd() % 4;
            const uint64_t due = std::max<uint64_t>(g_cycle + lat, rsp.empty() ? 0 : rsp.back().due);
            response r{ due, {} };
            for (uint32_t j = 0; j < 4; j++)
                r.line[j] = a + j < mem.size() ? mem[a + j] : 0u;
            rsp.push_back(r);
        }
        if (out_fire) {
            if (in_flight.empty()) {
                if (mismatches++ < 20)
                    std::printf("MISMATCH rgs_surface cycle %llu: a surface nobody asked for\n", (unsigned long long)g_cycle);
            } else {
                const flight &f = in_flight.front();
                const std::size_t t = f.t;
                const uint32_t tid = top.tid_o;
                uint32_t got[OUT_WORDS];
                got[O_VALID] = top.sf_valid_o;
                for (int k = 0; k < 3; k++)
                    got[O_P + k] = get(top.p_o, k), got[O_D + k] = get(top.d_o, k), got[O_N + k] = get(top.n_o, k),
                              got[O_BASE + k] = (uint32_t)(top.base_o >> (16 * k) & 0xFFFFu),
                              got[O_EMIS + k] = (uint32_t)(top.emission_o >> (16 * k) & 0xFFFFu),
                              got[O_TINT + k] = (uint32_t)(top.tint_o >> (16 * k) & 0xFFFFu);
                got[O_THAT] = top.t_hat_o, got[O_ENT] = top.entering_o, got[O_MAT] = top.mat_o;
                got[O_UNLIT] = top.unlit_o, got[O_K] = top.k_o, got[O_ETA] = top.eta_o, got[O_KD] = top.kd_o;
                got[O_KR] = top.kr_o, got[O_KT] = top.kt_o, got[O_KS] = top.ks_o;
                if (tid != t % 64)
                    report(t, "thread id", "tid", tid, (uint32_t)(t % 64), tid);
                for (int k = 0; k < OUT_WORDS; k++)
                    if (got[k] != f.want[k])
                        report(t, "C model", field_name(k), got[k], f.want[k], tid);
                if (t < captured) {
                    vs_capture++;
                    for (int k = 0; k < O_K; k++)
                        if (tx[t].out[k] != f.want[k])
                            report(t, "capture vs C model", field_name(k), tx[t].out[k], f.want[k], tid);
                    if (tx[t].reads != f.reads && mismatches++ < 20)
                        std::printf("MISMATCH rgs_surface transaction %zu: the recorded reads differ from the C's\n", t);
                }
                checked++;
                latency_max = std::max<uint64_t>(latency_max, g_cycle - f.started);
                for (uint32_t w : f.reads) {
                    auto l = live.find(w);
                    if (--l->second == 0)
                        live.erase(l);
                }
                in_flight.pop_front();
                // the oldest surface is out: every word the C reads for it has been read (the words
                // still due belong to the surfaces after it, if any)
                if (in_flight.empty() && !due_reads.empty()) {
                    if (bad_reads++ < 20)
                        std::printf("MISMATCH rgs_surface transaction %zu: %zu addresses the C reads were not read (%x first)\n",
                                    t, due_reads.size(), due_reads.begin()->first);
                    due_reads.clear();
                }
            }
        }
        if (in_fire) {
            flight f{ next, g_cycle, {}, {} };
            model(mem, tx[next], f.want, f.reads, cov);
            for (uint32_t a : f.reads)
                due_reads[a]++, live[a]++;
            in_flight.push_back(std::move(f));
            next++;
        }
        cycles_busy += !in_flight.empty();
        idle = (in_fire || out_fire) ? 0 : idle + 1;
        top.clk_i = 1;
        top.eval();
    }
    const bool lost = next < tx.size() || !in_flight.empty();
    if (lost)
        std::printf("MISMATCH rgs_surface: stuck at transaction %zu (no result in 20000 cycles)\n", next);
    std::printf("rgs_surface %zu surfaces checked (%zu captured, %zu vs capture, %zu random; %zu valid, %zu with vertex "
                "colours, %zu with the geometric normal, %zu texture samples), %llu mismatches, %llu wrong reads, %.1f cycles "
                "per surface (up to 8 in flight), at most %llu from input to output\n",
                checked, captured, vs_capture, tx.size() - captured, cov.valid, cov.colours, cov.geometric, cov.samples / 4, (unsigned long long)mismatches,
                (unsigned long long)bad_reads, checked ? (double)cycles_busy / (double)checked : 0.0,
                (unsigned long long)latency_max);
    return mismatches || bad_reads || lost ? 1 : 0;
}
