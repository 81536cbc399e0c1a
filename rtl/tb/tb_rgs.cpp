// Co-simulation of the RGS's ray generation (rtl/rgs_raygen.sv) and the tile controller
// (rtl/tile_ctrl.sv) against the C model: every packet leaving rgs_raygen is compared with
// rgs_primary (hls/units/rgs.c, on a memory image holding the camera block) for its block and,
// for captured blocks (saarcor render --capture-unit-io DIR: DIR/rgs.hex, the primary packet of
// every block a thread took, with the camera words), with the packet recorded while rendering;
// the tile controller's block sequence is compared with the cycle model's order (a replica of
// tb/cycle/cycle_sim.c next_block for one pipe, itself checked against the recording).
//   --capture DIR            the recorded blocks in their order straight into rgs_raygen (any mode,
//                            any thread count); the camera is reloaded where it changes
//   --capture DIR --order T  the recording is a cycle-mode frame (or frames) of one pipe with tile
//                            edge T: per frame tile_ctrl drives rgs_raygen (tb_rgs chain_i) over
//                            the whole image, and its blocks must be the recording's, in order
//   -n N                     N random blocks on random camera words (kind 0, 1 or other, sizes
//                            up to 2^32 - 1, coordinates to 2^32 - 1, any fp24 encodings; a new
//                            camera is offered at once and must be held off while packets of the
//                            old one are in flight), with gaps at the input and back pressure at
//                            the output; and N / 200 random
//                            frames of tile_ctrl (regions, edges 2 .. 4096) against the replica
// A mismatch prints the unit, the packet or block number, the block, the cycle and both values;
// exit code 1. It reports the ray generation's latency (block taken to packet out) and its
// interval between packets under full load.
// usage: tb_rgs [-n N] [--seed S] [--capture DIR [--order TILE]]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vtb_rgs.h"
#include "tb_common.h"
#include "verilated.h"

extern "C" {
#include "f24.h"
#include "memimage.h"
#include "rgs.h"
}

using namespace cosim;

namespace {

constexpr int CAM = MI_CAMERA_WORDS;

// a block and its packet, in the word order of rgs.hex
struct packet { uint32_t active, o[12], d[12], tmin[4], tmax[4]; };
struct block { uint32_t x0, y0, cam[CAM]; packet p; };
constexpr std::size_t PACKET_WORDS = sizeof(packet) / sizeof(uint32_t), BLOCK_WORDS = sizeof(block) / sizeof(uint32_t);

// rgs_primary on a memory image holding only the region table's camera entry and the camera
packet model(const block &b)
{
    std::vector<uint32_t> mem(MI_HEADER_WORDS + CAM, 0);
    mem[MI_H_REGION_TABLE + 2 * MI_R_CAMERA] = MI_HEADER_WORDS;
    std::copy(b.cam, b.cam + CAM, mem.begin() + MI_HEADER_WORDS);
    ray_packet rp;
    rgs_primary(mem.data(), b.x0, b.y0, &rp);
    packet p{};
    p.active = rp.active;
    for (int i = 0; i < TRACE_PACKET; i++) {
        const f24_vec3 o = rp.o[i], d = rp.d[i];
        p.o[3 * i] = o.x, p.o[3 * i + 1] = o.y, p.o[3 * i + 2] = o.z;
        p.d[3 * i] = d.x, p.d[3 * i + 1] = d.y, p.d[3 * i + 2] = d.z;
        p.tmin[i] = rp.tmin[i], p.tmax[i] = rp.tmax[i];
    }
    return p;
}

// the cycle model's block order for one pipe (tb/cycle/cycle_sim.c: controller_refill hands the
// pipe every tile in order, next_block walks a tile's blocks and skips those outside the region)
std::vector<std::pair<uint32_t, uint32_t>> c_order(uint32_t rx0, uint32_t ry0, uint32_t rx1, uint32_t ry1, uint32_t tile)
{
    std::vector<std::pair<uint32_t, uint32_t>> v;
    const uint32_t width = rx1 > rx0 ? rx1 - rx0 : 0, height = ry1 > ry0 ? ry1 - ry0 : 0;
    const uint32_t n_tiles = ((width + tile - 1) / tile) * ((height + tile - 1) / tile);
    const uint32_t per_row = tile / 2, tiles_x = (rx1 - rx0 + tile - 1) / tile;
    for (uint32_t t = 0; t < n_tiles; t++)
        for (uint32_t b = 0; b < per_row * per_row; b++) {
            const uint32_t x0 = rx0 + t % tiles_x * tile + 2 * (b % per_row), y0 = ry0 + t / tiles_x * tile + 2 * (b / per_row);
            if (x0 < rx1 && y0 < ry1)
                v.emplace_back(x0, y0);
        }
    return v;
}

uint32_t rnd32() { return rnd() << 16 ^ rnd(); }
// sizes and coordinates: small ones, the int32 sign boundary of 2x + 1, the top of uint32
uint32_t rnd_coord()
{
    switch (rnd() % 6) {
    case 0: return rnd32();
    case 1: return (1u << 30) - 4 + rnd() % 8;
    case 2: return (1u << 31) - 4 + rnd() % 8;
    case 3: return 0u - 1 - rnd() % 4;
    default: return rnd() % 1024;
    }
}

uint64_t g_cycle = 0, g_mismatches = 0;

const char *const FIELD[] = { "active", "o", "d", "tmin", "tmax" };
const int FIELD_AT[] = { 0, 1, 13, 25, 29, 33 };

void compare(std::size_t k, const block &b, const packet &want, const packet &got, const char *against)
{
    const uint32_t *a = reinterpret_cast<const uint32_t *>(&want), *g = reinterpret_cast<const uint32_t *>(&got);
    if (!std::memcmp(a, g, PACKET_WORDS * sizeof(uint32_t)))
        return;
    if (g_mismatches++ >= 10)
        return;
    std::printf("MISMATCH rgs_raygen packet %zu (block x0 %u y0 %u, camera kind %u %ux%u) at cycle %llu against %s:\n",
                k, b.x0, b.y0, b.cam[0], b.cam[1], b.cam[2], (unsigned long long)g_cycle, against);
    for (int f = 0; f < 5; f++) {
        if (!std::memcmp(a + FIELD_AT[f], g + FIELD_AT[f], (std::size_t)(FIELD_AT[f + 1] - FIELD_AT[f]) * sizeof(uint32_t)))
            continue;
        std::printf("  %-6s expected", FIELD[f]);
        for (int w = FIELD_AT[f]; w < FIELD_AT[f + 1]; w++) std::printf(" %06x", a[w]);
        std::printf("\n  %-6s rtl     ", FIELD[f]);
        for (int w = FIELD_AT[f]; w < FIELD_AT[f + 1]; w++) std::printf(" %06x", g[w]);
        std::printf("\n");
    }
}

// the model of tb_rgs with one call per clock cycle
struct bench {
    VerilatedContext ctx;
    Vtb_rgs top{ &ctx };
    // the first block taken and the first and last packet out since timing was reset
    uint64_t first_take = UINT64_MAX, first_out = UINT64_MAX, last_out = 0, packets_out = 0, timed_out = 0;
    bench()
    {
        top.rst_ni = 0, top.clk_i = 0;
        top.eval();
        top.clk_i = 1;
        top.eval();
        top.rst_ni = 1, top.clk_i = 0;
        top.eval();
    }
    void reset_timing() { first_take = first_out = UINT64_MAX, timed_out = 0; }
    packet read_packet()
    {
        packet p{};
        p.active = top.pkt_active_o;
        for (int k = 0; k < 12; k++) p.o[k] = get(top.pkt_o_o, k), p.d[k] = get(top.pkt_d_o, k);
        for (int k = 0; k < 4; k++) p.tmin[k] = get(top.pkt_tmin_o, k), p.tmax[k] = get(top.pkt_tmax_o, k);
        return p;
    }
    void edge()
    {
        top.clk_i = 1;
        top.eval();
        top.clk_i = 0;
        g_cycle++;
    }
    // the camera block's words in a random order (the port takes any)
    static std::vector<uint32_t> camera_order()
    {
        std::vector<uint32_t> order(CAM);
        for (int i = 0; i < CAM; i++) order[(std::size_t)i] = (uint32_t)i;
        for (int i = CAM - 1; i > 0; i--) std::swap(order[(std::size_t)i], order[rnd() % (uint32_t)(i + 1)]);
        return order;
    }
    // the camera block, word by word, into the idle unit
    void load_camera(const uint32_t *cam)
    {
        top.blk_valid_i = 0, top.frame_valid_i = 0, top.pkt_ready_i = 1;
        for (uint32_t w : camera_order()) {
            top.cam_valid_i = 1, top.cam_idx_i = w, top.cam_word_i = cam[w];
            top.eval();
            while (!top.cam_ready_o) edge(), top.eval();
            edge();
        }
        top.cam_valid_i = 0;
    }
};

// blocks straight into rgs_raygen; gap and stall in percent of the cycles; the packets are checked
// against the C model and, for recorded blocks, against the recording
void run_blocks(bench &s, const std::vector<block> &bl, bool recorded, unsigned gap, unsigned stall)
{
    std::deque<std::size_t> inflight;
    std::size_t next = 0, loaded = SIZE_MAX;
    std::vector<uint32_t> cam_words; // the new camera's words still to load
    auto &t = s.top;
    const auto check = [&](std::size_t k) {
        const packet got = s.read_packet();
        compare(k, bl[k], model(bl[k]), got, "C model");
        if (recorded) compare(k, bl[k], bl[k].p, got, "capture");
        s.packets_out++;
    };
    t.chain_i = 0;
    for (uint64_t idle = 0; (next < bl.size() || !inflight.empty()) && idle < 10000;) {
        // a new camera is offered at once: the port must hold it off while the old one's packets are in flight
        if (cam_words.empty() && next < bl.size() &&
            (loaded == SIZE_MAX || std::memcmp(bl[next].cam, bl[loaded].cam, sizeof bl[next].cam)))
            cam_words = bench::camera_order(), loaded = next;
        t.cam_valid_i = !cam_words.empty();
        if (t.cam_valid_i) t.cam_idx_i = cam_words.back(), t.cam_word_i = bl[loaded].cam[cam_words.back()];
        t.blk_valid_i = cam_words.empty() && next < bl.size() && rnd() % 100 >= gap;
        if (t.blk_valid_i) t.blk_x_i = bl[next].x0, t.blk_y_i = bl[next].y0;
        t.pkt_ready_i = rnd() % 100 >= stall;
        t.eval();
        idle++;
        if (t.cam_valid_i && t.cam_ready_o) {
            if (!inflight.empty() && g_mismatches++ < 10)
                std::printf("PROTOCOL rgs_raygen: camera word %u taken at cycle %llu with %zu packets in flight\n",
                            (unsigned)t.cam_idx_i, (unsigned long long)g_cycle, inflight.size());
            cam_words.pop_back(), idle = 0;
        }
        if (t.blk_valid_i && t.blk_ready_o) {
            if (s.first_take == UINT64_MAX) s.first_take = g_cycle;
            inflight.push_back(next++);
            idle = 0;
        }
        if (t.pkt_valid_o && t.pkt_ready_i) {
            if (inflight.empty()) {
                if (g_mismatches++ < 10)
                    std::printf("PROTOCOL rgs_raygen: a packet at cycle %llu without a block\n", (unsigned long long)g_cycle);
            } else {
                if (s.first_out == UINT64_MAX) s.first_out = g_cycle;
                s.last_out = g_cycle, s.timed_out++;
                check(inflight.front()), inflight.pop_front();
            }
            idle = 0;
        }
        s.edge();
    }
    t.cam_valid_i = 0;
    if (next < bl.size() || !inflight.empty()) {
        std::printf("PROTOCOL rgs_raygen: stuck at cycle %llu with %zu blocks left and %zu in flight\n",
                    (unsigned long long)g_cycle, bl.size() - next, inflight.size());
        g_mismatches++;
    }
}

// one frame of tile_ctrl: chained into rgs_raygen (blocks given: the recorded frame, in order) or
// alone with random back pressure; its blocks against the replica's order; returns the cycles
uint64_t run_frame(bench &s, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint32_t tile,
                   const block *rec, std::size_t n_rec, unsigned stall)
{
    const auto want = c_order(x0, y0, x1 < x0 ? x0 : x1, y1 < y0 ? y0 : y1, tile);
    auto &t = s.top;
    if (rec && want.size() != n_rec) {
        std::printf("MISMATCH tile order (replica against capture): %zu blocks for the %ux%u frame, the recording has %zu\n",
                    want.size(), x1, y1, n_rec);
        g_mismatches++;
        return 0;
    }
    for (std::size_t k = 0; rec && k < n_rec; k++)
        if (want[k].first != rec[k].x0 || want[k].second != rec[k].y0) {
            if (g_mismatches++ < 10)
                std::printf("MISMATCH tile order (replica against capture) block %zu: capture (%u, %u), replica (%u, %u)\n",
                            k, rec[k].x0, rec[k].y0, want[k].first, want[k].second);
            return 0;
        }
    t.chain_i = rec != nullptr;
    t.blk_valid_i = 0;
    t.frame_valid_i = 1, t.x0_i = x0, t.y0_i = y0, t.x1_i = x1, t.y1_i = y1, t.tile_i = tile;
    t.eval();
    while (!t.frame_ready_o) s.edge(), t.eval();
    s.edge();
    t.frame_valid_i = 0;
    const uint64_t start = g_cycle;
    std::size_t got = 0, out = 0, dones = 0;
    uint64_t done_at = 0, last_take = 0;
    // until the frame is done and 8 cycles more (nothing may follow), or 200 cycles without progress
    for (uint64_t idle = 0, after = 0; idle < 200 && after < 8; idle++) {
        after += dones && got == want.size() && (!rec || out == n_rec);
        t.tc_ready_i = rnd() % 100 >= stall;
        t.pkt_ready_i = 1;
        t.eval();
        if (t.done_o) dones++, done_at = g_cycle;
        if (t.tc_valid_o && (rec ? t.blk_ready_o : t.tc_ready_i)) {
            const uint32_t bx = t.tc_x_o, by = t.tc_y_o;
            if (got >= want.size() || want[got].first != bx || want[got].second != by) {
                if (g_mismatches++ < 10)
                    std::printf("MISMATCH tile_ctrl block %zu of frame [%u,%u)x[%u,%u) tile %u at cycle %llu: "
                                "expected (%u, %u), rtl (%u, %u)\n",
                                got, x0, x1, y0, y1, tile, (unsigned long long)g_cycle,
                                got < want.size() ? want[got].first : 0u, got < want.size() ? want[got].second : 0u, bx, by);
            }
            got++, last_take = g_cycle, idle = 0;
        }
        if (rec && t.pkt_valid_o) {
            const packet p = s.read_packet();
            if (out < n_rec) {
                compare(out, rec[out], model(rec[out]), p, "C model");
                compare(out, rec[out], rec[out].p, p, "capture");
            }
            out++, s.packets_out++, idle = 0;
        }
        s.edge();
    }
    const bool done_ok = dones == 1 && done_at == (want.empty() ? start : last_take + 1);
    if ((got != want.size() || (rec && out != n_rec) || !done_ok) && g_mismatches++ < 10)
        std::printf("MISMATCH tile_ctrl frame [%u,%u)x[%u,%u) tile %u: %zu of %zu blocks, %zu packets, done_o %zu times "
                    "(cycle %llu, last block %llu)\n",
                    x0, x1, y0, y1, tile, got, want.size(), out, dones, (unsigned long long)done_at,
                    (unsigned long long)last_take);
    return last_take - start + 1;
}

bool read_capture(const std::string &path, std::vector<block> &out)
{
    FILE *f = std::fopen(path.c_str(), "r");
    if (!f) {
        std::printf("tb_rgs: cannot read %s\n", path.c_str());
        return false;
    }
    char line[4096];
    while (std::fgets(line, sizeof line, f)) {
        block b;
        uint32_t *w = reinterpret_cast<uint32_t *>(&b);
        char *p = line;
        std::size_t k = 0;
        for (char *end; k < BLOCK_WORDS; k++, p = end) {
            w[k] = (uint32_t)std::strtoul(p, &end, 16);
            if (end == p)
                break;
        }
        if (k != BLOCK_WORDS) {
            std::fclose(f);
            std::printf("tb_rgs: %s: malformed line (%zu of %zu words)\n", path.c_str(), k, BLOCK_WORDS);
            return false;
        }
        out.push_back(b);
    }
    std::fclose(f);
    return !out.empty();
}

} // namespace

int main(int argc, char **argv)
{
    std::size_t n = 20000;
    std::string capture;
    uint32_t order = 0;
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "-n") && i + 1 < argc) n = std::strtoull(argv[++i], nullptr, 0);
        else if (!std::strcmp(argv[i], "--seed") && i + 1 < argc) g_rng = std::strtoull(argv[++i], nullptr, 0) | 1u;
        else if (!std::strcmp(argv[i], "--capture") && i + 1 < argc) capture = argv[++i];
        else if (!std::strcmp(argv[i], "--order") && i + 1 < argc) order = (uint32_t)std::strtoul(argv[++i], nullptr, 0);
        else { std::printf("usage: tb_rgs [-n N] [--seed S] [--capture DIR [--order TILE]]\n"); return 2; }
    }
    if (order && (order % 2 || order > 4096)) {
        std::printf("tb_rgs: --order wants the even tile edge 2 .. 4096\n");
        return 2;
    }
    bench s;
    std::size_t cap_blocks = 0, cap_frames = 0, ortho = 0;
    uint64_t frame_cycles = 0;
    if (!capture.empty()) {
        std::vector<block> rec;
        if (!read_capture(capture + "/rgs.hex", rec))
            return 2;
        cap_blocks = rec.size();
        for (const block &b : rec) ortho += b.cam[0] == 1;
        if (order) { // frames of the cycle model's controller, one after the other
            for (std::size_t k = 0; k < rec.size() && g_mismatches == 0; cap_frames++) {
                const block &b = rec[k];
                const std::size_t blocks = c_order(0, 0, b.cam[1], b.cam[2], order).size();
                if (!blocks)
                    break;
                s.load_camera(b.cam);
                frame_cycles += run_frame(s, 0, 0, b.cam[1], b.cam[2], order, &rec[k], std::min(blocks, rec.size() - k), 0);
                k += blocks;
            }
        } else {
            run_blocks(s, rec, true, 0, 0);
        }
    }

    // random blocks on random cameras, a new camera every 64 blocks: first at full load (latency
    // and interval), then with gaps and back pressure
    std::vector<block> bl(n);
    uint32_t cam[CAM] = {};
    for (std::size_t k = 0; k < n; k++) {
        if (k % 64 == 0) {
            const uint32_t kinds[] = { 0, 1, 1, 2, rnd32() };
            cam[0] = kinds[rnd() % 5];
            cam[1] = rnd() % 2 ? rnd() % 600 : rnd_coord();
            cam[2] = rnd() % 2 ? rnd() % 600 : rnd_coord();
            cam[3] = rnd32();
            for (int w = 4; w < CAM; w++) cam[w] = rnd_f24();
        }
        block &b = bl[k];
        std::copy(cam, cam + CAM, b.cam);
        b.x0 = rnd() % 2 ? 2 * (rnd() % 320) : rnd_coord();
        b.y0 = rnd() % 2 ? 2 * (rnd() % 320) : rnd_coord();
    }
    const std::size_t full = std::min<std::size_t>(n, 64);
    s.reset_timing();
    run_blocks(s, std::vector<block>(bl.begin(), bl.begin() + (long)full), false, 0, 0);
    const uint64_t latency = s.first_out - s.first_take;
    const double interval = s.timed_out > 1 ? (double)(s.last_out - s.first_out) / (double)(s.timed_out - 1) : 0.0;
    run_blocks(s, std::vector<block>(bl.begin() + (long)full, bl.end()), false, 20, 20);

    // random frames of tile_ctrl alone, with back pressure
    const std::size_t frames = n / 200;
    uint64_t tc_blocks = 0;
    for (std::size_t f = 0; f < frames; f++) {
        const uint32_t tile = rnd() % 64 == 0 ? 2u << rnd() % 12 : 2 + 2 * (rnd() % 32);
        const uint32_t x0 = rnd() % 4 ? 0u : rnd() % 100, y0 = rnd() % 4 ? 0u : rnd() % 100;
        const uint32_t x1 = rnd() % 16 ? x0 + rnd() % (tile > 64 ? 40 : 200) : rnd() % 100, y1 = rnd() % 16 ? y0 + rnd() % 150 : rnd() % 100;
        tc_blocks += c_order(x0, y0, std::max(x0, x1), std::max(y0, y1), tile).size();
        run_frame(s, x0, y0, x1, y1, tile, nullptr, 0, 25);
    }
    s.top.final();
    std::printf("tb_rgs e%dm%d: %zu captured blocks (%zu orthographic; %s), %zu random blocks; %llu packets checked; "
                "tile_ctrl %zu random frames (%llu blocks); %llu mismatches",
                F24_EXP_BITS, F24_MAN_BITS, cap_blocks, ortho,
                capture.empty() ? "no capture"
                : order ? (std::to_string(cap_frames) + " frames in tile_ctrl's order, tile " + std::to_string(order) + ", " +
                         std::to_string(frame_cycles) + " cycles").c_str()
                      : "in the recorded order",
                n, (unsigned long long)s.packets_out, frames, (unsigned long long)tc_blocks,
                (unsigned long long)g_mismatches);
    if (s.timed_out)
        std::printf("; latency %llu cycles block to packet, %.2f cycles between packets at full load",
                    (unsigned long long)latency, interval);
    std::printf("\n");
    return g_mismatches ? 1 : 0;
}
