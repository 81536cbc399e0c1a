// Co-simulation of rgs_ctrl (rtl/rgs_ctrl.sv), the RGS's per-block control, against the C model:
// for every 2x2 block of a frame (in row-major order, or the first --blocks N), its pixels and
// primary hits against rgs_render_block (hls/units/rgs.c), and every packet it sends to be traced
// (active bits, o, d, tmin, tmax of the 4 rays, the TRACE_* flags) against the packets the C's
// rgs_step begins for the block (the primary and secondary packets as next_packet takes them, the
// shadow packets of op_shadow_gen), in order. The bench is the memory (the image of a capture,
// DIR/image_0.bin of saarcor render --capture-unit-io DIR; requests of a 4-word line's first
// word address with random gaps in every other epoch of 1024 cycles, the line answered in order
// after 1 to 4 cycles) and the ray tracing core: each
// packet is traced by the C (trace_begin, trace_step to the end on the image) and its hits come
// back after 1 to 40 cycles, so the RGS is checked alone. The pixel output gets random back
// pressure. A mismatch prints the block, the packet, the field and both values; exit code 1 on any
// mismatch, a packet too many or too few, or a block that does not finish. It prints the tasks
// written into and popped from rgs_ctrl's stack memory (the other tasks bypass it), the cycles a
// block spends in each rgs_ctrl state, rgs_surface's states in SURF, and SURF's cycles per packet
// by its hits (what the cycle model's surface, surface_hit and surface_miss are fitted on).
// usage: tb_rgs_ctrl --capture DIR [--max-depth D] [--no-shadows] [--blocks N] [--seed S]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vtb_rgs_ctrl.h"
#include "tb_common.h"
#include "tb_rays.h"

extern "C" {
#include "rgs.h"
#include "rgs_ops.h"
}

using namespace cosim;

namespace {

struct traced {
    ray_packet rays;
    uint32_t flags;
};

struct block_ref {
    uint32_t rgb[4];
    hit_record hits[4];
    std::vector<traced> packets;
};

// the C: the block's packets as rgs_step begins them, then its pixels and primary hits
block_ref reference(const std::vector<uint32_t> &mem, const rgs_config &cfg, uint32_t x0, uint32_t y0)
{
    block_ref r;
    static rgs_block b;
    unit_op op;
    rgs_counters c{};
    rgs_block_begin(mem.data(), x0, y0, &b);
    uint32_t packets = 0, phase = b.phase;
    for (uint32_t n = 0; n < RGS_STEP_LIMIT; n++) {
        const uint32_t was = phase;
        const int more = rgs_step(mem.data(), &cfg, &b, &op, &c);
        phase = b.phase;
        if (b.packets != packets) // next_packet began cur
            r.packets.push_back({ b.cur.rays, b.trace.flags });
        else if (was == RB_SHADOW_GEN && phase == RB_SHADOW_TRACE)
            r.packets.push_back({ b.shadow, b.trace.flags });
        packets = b.packets;
        if (!more)
            break;
    }
    rgs_block_finish(&b, r.rgb);
    rgs_config cfg2 = cfg;
    rgs_counters c2{};
    uint32_t rgb2[4];
    rgs_render_block(mem.data(), &cfg2, x0, y0, rgb2, r.hits, &c2);
    for (int i = 0; i < 4; i++)
        if (rgb2[i] != r.rgb[i])
            std::printf("tb_rgs_ctrl: the stepped block differs from rgs_render_block (pixel %d)\n", i);
    return r;
}

} // namespace

int main(int argc, char **argv)
{
    std::string capture;
    rgs_config cfg = { 2, 1, 0 };
    std::size_t max_blocks = SIZE_MAX;
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "--capture") && i + 1 < argc) capture = argv[++i];
        else if (!std::strcmp(argv[i], "--max-depth") && i + 1 < argc) cfg.max_depth = (uint32_t)std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--no-shadows")) cfg.shadows = 0;
        else if (!std::strcmp(argv[i], "--blocks") && i + 1 < argc) max_blocks = std::strtoull(argv[++i], nullptr, 0);
        else if (!std::strcmp(argv[i], "--seed") && i + 1 < argc) g_rng = std::strtoull(argv[++i], nullptr, 0) | 1u;
        else {
            std::printf("usage: tb_rgs_ctrl --capture DIR [--max-depth D] [--no-shadows] [--blocks N] [--seed S]\n");
            return 2;
        }
    }
    std::vector<uint32_t> mem;
    if (capture.empty() || !load_image("tb_rgs_ctrl", capture, 0, mem))
        return 2;
    uint32_t width, height;
    rgs_image_size(mem.data(), &width, &height);
    struct blk { uint32_t x, y; };
    std::vector<blk> blocks;
    for (uint32_t y = 0; y < height; y += 2)
        for (uint32_t x = 0; x < width; x += 2)
            if (blocks.size() < max_blocks)
                blocks.push_back({ x, y });

    VerilatedContext ctx;
    Vtb_rgs_ctrl top{ &ctx };
    top.rst_ni = 0, top.clk_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;
    top.max_depth_i = cfg.max_depth;
    top.shadows_i = cfg.shadows;

    struct response { uint64_t due; uint32_t line[4]; };  // the port answers a line of 4 words
    std::deque<response> rsp;
    std::size_t next = 0, done = 0, packet = 0, packets = 0;
    uint64_t mismatches = 0, idle = 0, hits_due = 0, block_start = 0, block_cycles = 0;
    bool in_block = false, hits_pending = false;
    uint64_t state_cycles[32] = {};  // a block's cycles by rgs_ctrl state (its state_t order)
    uint64_t stack_writes = 0, stack_pops = 0;  // tasks through the stack memory (the rest bypass it)
    bool popping = false;
    const uint32_t S_SURF = 5;       // rgs_ctrl's S_SURF
    const uint32_t S_TRACE = 3;
    uint64_t surf_cycles[32] = {};   // SURF's cycles by rgs_surface state
    // SURF's cycles per packet by its hits (0..4): the cycle model's surface, surface_hit and
    // surface_miss are fitted on these (docs/cycle-model.md)
    uint64_t surf_by_hits[5] = {}, surf_packets[5] = {}, surf_now = 0;
    int last_hits = 0;
    bool in_surf = false;
    block_ref want;
    trace_state ts;
    hit_record hits[4];
    auto miss = [&](const char *what, uint32_t got, uint32_t exp) {
        if (mismatches++ < 20)
            std::printf("MISMATCH rgs_ctrl block %zu (%u, %u) packet %zu cycle %llu %s: rtl %06x, expected %06x\n", done,
                        blocks[done].x, blocks[done].y, packet, (unsigned long long)g_cycle, what, got, exp);
    };
    for (; done < blocks.size() && idle < 200000; g_cycle++) {
        const bool calm = (g_cycle / 1024) % 2 == 0;
        top.clk_i = 0;
        top.blk_valid_i = 0;
        if (!in_block && next < blocks.size()) {
            top.blk_valid_i = 1;
            top.blk_tag_i = (uint8_t)(next % 64);
            top.blk_x_i = blocks[next].x, top.blk_y_i = blocks[next].y;
        }
        top.mem_req_ready_i = calm || rnd() % 3 != 0;
        top.mem_rsp_valid_i = 0;
        if (!rsp.empty() && rsp.front().due <= g_cycle) {
            top.mem_rsp_valid_i = 1;
            for (int j = 0; j < 4; j++)
                top.mem_rdata_i[j] = rsp.front().line[j];
            rsp.pop_front();
        }
        top.tr_ready_i = !hits_pending;
        top.hit_valid_i = hits_pending && g_cycle >= hits_due;
        if (top.hit_valid_i)
            for (int i = 0; i < 4; i++) {
                top.hit_inst_i[i] = hits[i].instance, top.hit_tri_i[i] = hits[i].triangle;
                put(top.hit_t_i, i, hits[i].t), put(top.hit_u_i, i, hits[i].u), put(top.hit_v_i, i, hits[i].v);
                put(top.hit_cos_i, i, hits[i].cos_n);
            }
        top.px_ready_i = calm || rnd() % 4 != 0;
        top.eval();
        bool fired = false;
        if (top.mem_req_valid_o && top.mem_req_ready_i) {
            const uint32_t a = top.mem_addr_o;
            if ((a >= mem.size() || a % 4) && mismatches++ < 20)
                std::printf("MISMATCH rgs_ctrl cycle %llu: read of %x beyond the image or not a line's start\n",
                            (unsigned long long)g_cycle, a);
            const uint64_t due = std::max<uint64_t>(g_cycle + (calm ? 1 : 1 + rnd() % 4), rsp.empty() ? 0 : rsp.back().due);
            response r{ due, {} };
            for (uint32_t j = 0; j < 4; j++)
                r.line[j] = a + j < mem.size() ? mem[a + j] : 0u;
            rsp.push_back(r);
            fired = true;
        }
        if (top.tr_valid_o && top.tr_ready_i) {
            fired = true;
            if (!in_block || packet >= want.packets.size()) {
                miss("a packet the C does not trace", 1, 0);
            } else {
                const traced &p = want.packets[packet];
                if (top.tr_tag_o != (next - 1) % 64)
                    miss("tag", top.tr_tag_o, (uint32_t)((next - 1) % 64));
                if (top.tr_flags_o != p.flags)
                    miss("flags", top.tr_flags_o, p.flags);
                if (top.tr_active_o != p.rays.active)
                    miss("active", top.tr_active_o, p.rays.active);
                static const char *const XYZ[] = { "x", "y", "z" };
                char what[64];
                for (int i = 0; i < 4; i++) {
                    const uint32_t o[3] = { p.rays.o[i].x, p.rays.o[i].y, p.rays.o[i].z };
                    const uint32_t d[3] = { p.rays.d[i].x, p.rays.d[i].y, p.rays.d[i].z };
                    for (int k = 0; k < 3; k++) {
                        std::snprintf(what, sizeof what, "ray %d o.%s", i, XYZ[k]);
                        if (get(top.tr_o_o, 3 * i + k) != o[k])
                            miss(what, get(top.tr_o_o, 3 * i + k), o[k]);
                        std::snprintf(what, sizeof what, "ray %d d.%s", i, XYZ[k]);
                        if (get(top.tr_d_o, 3 * i + k) != d[k])
                            miss(what, get(top.tr_d_o, 3 * i + k), d[k]);
                    }
                    std::snprintf(what, sizeof what, "ray %d tmin", i);
                    if (get(top.tr_tmin_o, i) != p.rays.tmin[i])
                        miss(what, get(top.tr_tmin_o, i), p.rays.tmin[i]);
                    std::snprintf(what, sizeof what, "ray %d tmax", i);
                    if (get(top.tr_tmax_o, i) != p.rays.tmax[i])
                        miss(what, get(top.tr_tmax_o, i), p.rays.tmax[i]);
                }
            }
            // the C traces what the RTL sent
            const ray_packet rays = cosim::rays_of(top.tr_active_o, top.tr_o_o, top.tr_d_o, top.tr_tmin_o, top.tr_tmax_o);
            trace_begin(&rays, top.tr_flags_o, &ts);
            unit_op op;
            trace_counters c{};
            for (uint32_t n = 0; n < (1u << 30) && trace_step(mem.data(), &ts, &op, &c); n++)
                ;
            last_hits = 0;
            for (int i = 0; i < 4; i++)
                hits[i] = ts.hits[i], last_hits += ts.hits[i].instance != TRACE_NO_HIT;
            hits_pending = true;
            hits_due = g_cycle + 1 + (calm ? 0 : rnd() % 40);
            packet++;
            packets++;
        }
        if (top.hit_valid_i && top.hit_ready_o)
            hits_pending = false, fired = true;
        if (top.px_valid_o && top.px_ready_i) {
            fired = true;
            if (!in_block) {
                miss("pixels nobody asked for", 1, 0);
            } else {
                if (packet != want.packets.size())
                    miss("packets traced", (uint32_t)packet, (uint32_t)want.packets.size());
                if (top.px_tag_o != (next - 1) % 64)
                    miss("pixel tag", top.px_tag_o, (uint32_t)((next - 1) % 64));
                char what[64];
                for (int i = 0; i < 4; i++) {
                    const uint32_t rgb = (uint32_t)(top.px_rgb_o[(24 * i) / 32] >> (24 * i % 32)) |
                                         (24 * i % 32 > 8 ? (uint32_t)top.px_rgb_o[(24 * i) / 32 + 1] << (32 - 24 * i % 32) : 0u);
                    std::snprintf(what, sizeof what, "pixel %d", i);
                    if ((rgb & 0xFFFFFFu) != want.rgb[i])
                        miss(what, rgb & 0xFFFFFFu, want.rgb[i]);
                    const hit_record &h = want.hits[i];
                    const uint32_t got[6] = { top.px_inst_o[i], top.px_tri_o[i], get(top.px_t_o, i), get(top.px_u_o, i),
                                              get(top.px_v_o, i), get(top.px_cos_o, i) };
                    const uint32_t exp[6] = { h.instance, h.triangle, h.t, h.u, h.v, h.cos_n };
                    static const char *const HIT[] = { "instance", "triangle", "t", "u", "v", "cos_n" };
                    for (int k = 0; k < 6; k++) {
                        std::snprintf(what, sizeof what, "primary hit %d %s", i, HIT[k]);
                        if (got[k] != exp[k])
                            miss(what, got[k], exp[k]);
                    }
                }
                block_cycles += g_cycle - block_start;
                in_block = false;
                done++;
            }
        }
        if (top.blk_valid_i && top.blk_ready_o) {
            want = reference(mem, cfg, blocks[next].x, blocks[next].y);
            packet = 0;
            in_block = true;
            block_start = g_cycle;
            next++;
            fired = true;
        }
        if (in_block)
            state_cycles[top.st_o & 31u]++;
        stack_writes += top.stk_wr_o;
        stack_pops += popping && top.st_o == S_TRACE;  // not the packet limit's end
        popping = top.stk_pop_o;
        if (in_block && top.st_o == S_SURF)
            surf_cycles[top.sst_o & 31u]++, surf_now++;
        if (in_surf && top.st_o != S_SURF)  // a packet's surfaces are done
            surf_by_hits[last_hits] += surf_now, surf_packets[last_hits]++, surf_now = 0;
        in_surf = in_block && top.st_o == S_SURF;
        idle = fired ? 0 : idle + 1;
        top.clk_i = 1;
        top.eval();
    }
    if (done < blocks.size() && mismatches++ < 20)
        std::printf("MISMATCH rgs_ctrl: block %zu did not finish (nothing moved for 200000 cycles)\n", done);
    std::printf("rgs_ctrl %zu blocks checked (%zu packets, %.1f cycles per block), %llu mismatches\n", done, packets,
                done ? (double)block_cycles / (double)done : 0.0, (unsigned long long)mismatches);
    std::printf("rgs_ctrl stack memory: %llu tasks written, %llu popped\n", (unsigned long long)stack_writes,
                (unsigned long long)stack_pops);
    static const char *const STATE[] = { "IDLE", "GEN", "NEXT", "TRACE", "HITS", "SURF", "LIGHT", "LREC", "LCALC",
                                         "STRACE", "SHITS", "ADD", "ACCUM", "DONE" };
    std::printf("rgs_ctrl cycles per block by state:");
    for (size_t s = 0; s < sizeof STATE / sizeof *STATE; s++)
        if (state_cycles[s] && done)
            std::printf(" %s %.1f", STATE[s], (double)state_cycles[s] / (double)done);
    std::printf("\n");
    static const char *const SSTATE[] = { "IDLE", "INST", "OBJ", "REC", "NORM", "LERPN", "DOT", "GN", "FRAME", "MAT",
                                          "Q", "TEX", "TLERP", "TENTRY", "TSAMPLE", "TINT" };
    std::printf("rgs_surface cycles per block in SURF by state:");
    for (int s = 0; s < 16; s++)
        if (surf_cycles[s] && done)
            std::printf(" %s %.1f", SSTATE[s], (double)surf_cycles[s] / (double)done);
    std::printf("\n");
    std::printf("rgs_ctrl SURF cycles per packet by its hits:");
    for (int h = 0; h < 5; h++)
        if (surf_packets[h])
            std::printf(" %d: %.1f (%llu)", h, (double)surf_by_hits[h] / (double)surf_packets[h],
                        (unsigned long long)surf_packets[h]);
    std::printf("\n");
    return mismatches ? 1 : 0;
}
