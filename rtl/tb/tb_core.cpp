// Co-simulation of the ray tracing core (rtl/trace_core.sv: THREADS trace_thread, each a packet's
// state and the routing of hls/units/trace.c, sharing the units' RTL through thread_sched) against
// the C core: every packet that saarcor render --capture-unit-io DIR recorded in DIR/trace.hex (its
// rays and TRACE_* flags at trace_begin, its hits and trace_counters when trace_step ended it;
// primary, shadow and secondary packets) is traced by trace_begin + trace_step on the memory image
// it read (DIR/image_N.bin) and checked against the recording; the packets then enter the RTL in
// their order, each into the lowest free thread (--threads T of the model's 8: T packets in
// flight; packets of another image wait until the core is empty and enter with flush_i, so the core
// reads that image's header). The bench is the RTL's memory (the descriptor word port, RW words
// from the requested address per response, the kd-node port and the list unit's read port answer one cycle after
// the request). Every packet leaving a
// thread is compared with its C result: the hits (instance, triangle, t, u, v, cos per ray) and the
// counters. A free thread may refuse a packet for up to 4 cycles in a row (the core's queue of
// world rays, full after packets in consecutive cycles, takes one every 4); longer is a mismatch.
// A mismatch prints the packet, its thread, the ray, the field and both values; exit
// code 1 (the bench stops after 20 mismatches). It reports the cycles per packet, the packets'
// latency and the operations in flight (threads with an operation in a unit, per cycle).
// usage: tb_core --capture DIR [--packets N] [--threads T]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vtb_core.h"
#include "tb_common.h"
#include "verilated.h"

extern "C" {
#include "f24.h"
#include "f24_record.h"
#include "trace.h"
}

namespace {

using cosim::get;
using cosim::put;

constexpr uint32_t THREADS = 8; // tb_core.sv's
constexpr int RW = F24_TRIANGLE_RECORD_WORDS; // the word port's words per response
constexpr uint64_t timeout = 1u << 22; // cycles without a packet out before the bench gives up
const char *const COUNTER[10] = { "traversal_steps", "leaves", "list_entries", "mailbox_skips", "transformations",
                                  "intersections", "words[nodes]", "words[lists]", "words[matrices]", "words[shading]" };
const char *const HIT[6] = { "instance", "triangle", "t", "u", "v", "cos" };

// one line of trace.hex (tb/cli/capture.c captured_trace_step)
struct packet {
    uint32_t image, id, flags, active, o[12], d[12], tmin[4], tmax[4];
    uint32_t hit[4][6];
    uint32_t count[10];
};

struct outcome {
    uint32_t hit[4][6];
    uint32_t count[10];
};

uint64_t g_mismatches = 0;

bool compare(const char *what, std::size_t index, uint32_t thread, const outcome &want, const outcome &got)
{
    bool same = true;
    for (int r = 0; r < 4; r++)
        for (int f = 0; f < 6; f++)
            if (want.hit[r][f] != got.hit[r][f]) {
                same = false;
                if (g_mismatches++ < 20)
                    std::printf("MISMATCH trace_core packet %zu thread %u ray %d %s: %s %06x, expected %06x\n", index,
                                thread, r, HIT[f], what, got.hit[r][f], want.hit[r][f]);
            }
    for (int k = 0; k < 10; k++)
        if (want.count[k] != got.count[k]) {
            same = false;
            if (g_mismatches++ < 20)
                std::printf("MISMATCH trace_core packet %zu thread %u counter %s: %s %u, expected %u\n", index, thread,
                            COUNTER[k], what, got.count[k], want.count[k]);
        }
    return same;
}

// the C core on one packet: trace_begin, then trace_step until it ends the packet
outcome trace_c(const std::vector<uint32_t> &mem, const packet &p, uint64_t &ops)
{
    static trace_state s;
    ray_packet rays;
    for (int r = 0; r < 4; r++) {
        rays.o[r] = { p.o[3 * r], p.o[3 * r + 1], p.o[3 * r + 2] };
        rays.d[r] = { p.d[3 * r], p.d[3 * r + 1], p.d[3 * r + 2] };
        rays.tmin[r] = p.tmin[r];
        rays.tmax[r] = p.tmax[r];
    }
    rays.active = p.active;
    trace_begin(&rays, p.flags, &s);
    unit_op op;
    trace_counters c;
    std::memset(&c, 0, sizeof c);
    while (trace_step(mem.data(), &s, &op, &c))
        ops++;
    outcome o;
    for (int r = 0; r < 4; r++) {
        const hit_record &h = s.hits[r];
        const uint32_t v[6] = { h.instance, h.triangle, h.t, h.u, h.v, h.cos_n };
        std::memcpy(o.hit[r], v, sizeof v);
    }
    const uint64_t *cw = &c.traversal_steps;
    for (int k = 0; k < 10; k++)
        o.count[k] = (uint32_t)cw[k];
    return o;
}

} // namespace

int main(int argc, char **argv)
{
    std::string capture;
    std::size_t limit = ~(std::size_t)0;
    uint32_t threads = THREADS;
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "--capture") && i + 1 < argc) capture = argv[++i];
        else if (!std::strcmp(argv[i], "--packets") && i + 1 < argc) limit = std::strtoull(argv[++i], nullptr, 0);
        else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = (uint32_t)std::strtoul(argv[++i], nullptr, 0);
        else { std::printf("usage: tb_core --capture DIR [--packets N] [--threads T]\n"); return 2; }
    }
    if (threads < 1 || threads > THREADS) {
        std::printf("tb_core: --threads 1 .. %u (the model's THREADS)\n", THREADS);
        return 2;
    }
    std::vector<packet> packets;
    bool present = false;
    if (capture.empty() || !cosim::read_capture("tb_core", capture + "/trace.hex", packets, present))
        return 2;
    if (packets.empty()) {
        std::printf("tb_core: %s/trace.hex holds no packets\n", capture.c_str());
        return 2;
    }
    for (const packet &p : packets)
        if ((p.flags >> TRACE_TRAV_SHIFT & TRACE_TRAV_MASK) != TRAV_STACK) {
            std::printf("tb_core: the capture was traced with traversal algorithm %u; the RTL has TRAV_STACK only\n",
                        p.flags >> TRACE_TRAV_SHIFT & TRACE_TRAV_MASK);
            return 2;
        }

    // the C core first: every packet's hits and counters, checked against the recording
    std::vector<outcome> want(packets.size());
    std::vector<uint32_t> mem;
    uint32_t image = ~0u;
    uint64_t ops = 0, any_hit = 0, hits = 0, vs_capture = 0;
    const std::size_t total = std::min(packets.size(), limit);
    for (std::size_t i = 0; i < total; i++) {
        const packet &p = packets[i];
        if (p.image != image && !cosim::load_image("tb_core", capture, image = p.image, mem))
            return 2;
        outcome rec;
        std::memcpy(rec.hit, p.hit, sizeof p.hit);
        std::memcpy(rec.count, p.count, sizeof p.count);
        want[i] = trace_c(mem, p, ops);
        if (!compare("C", i, p.id % THREADS, rec, want[i]))
            vs_capture++;
        any_hit += (p.flags & TRACE_ANY_HIT) != 0;
        for (int r = 0; r < 4; r++)
            hits += want[i].hit[r][0] != TRACE_NO_HIT;
    }

    VerilatedContext ctx;
    Vtb_core top{ &ctx };
    top.rst_ni = 0, top.clk_i = 0, top.valid_i = 0, top.flush_i = 0, top.ready_i = 1;
    top.mem_req_ready_i = 1, top.mem_rsp_valid_i = 0, top.node_req_ready_i = 1, top.node_rsp_valid_i = 0;
    top.list_req_ready_i = 1;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;

    // packets go into free threads in their order; all packets in flight read one image (a packet of
    // the next image waits until the core is empty)
    std::deque<uint32_t> word_q, node_q, list_q; // addresses requested in the last cycle, answered in this one
    std::vector<long> in_thread(threads, -1);
    std::vector<uint64_t> started(threads, 0);
    uint64_t cycle = 0, last_out = 0, inflight_sum = 0, latency_sum = 0, latency_max = 0;
    uint64_t refused = 0; // cycles in a row a free thread refused the packet offered
    std::size_t next = 0, done = 0, busy = 0;
    image = ~0u;
    auto at = [&](uint32_t a) { return a < mem.size() ? mem[a] : 0u; };
    while (done < total && g_mismatches < 20) {
        if (cycle - last_out > timeout) {
            std::printf("MISMATCH trace_core: no packet out for %llu cycles (%zu in flight)\n",
                        (unsigned long long)timeout, busy);
            return 1;
        }
        // offer the next packet to the lowest free thread
        long free_t = -1;
        for (uint32_t t = 0; t < threads && free_t < 0; t++)
            if (in_thread[t] < 0)
                free_t = t;
        top.valid_i = 0;
        top.flush_i = 0;
        if (next < total && free_t >= 0 && (packets[next].image == image || busy == 0)) {
            const packet &p = packets[next];
            top.flush_i = p.image != image;
            if (p.image != image && !cosim::load_image("tb_core", capture, image = p.image, mem))
                return 2;
            top.valid_i = 1;
            top.thread_i = (uint32_t)free_t;
            top.flags_i = p.flags & 7u;
            top.active_i = p.active;
            for (int k = 0; k < 12; k++)
                put(top.o_i, k, p.o[k]), put(top.d_i, k, p.d[k]);
            for (int r = 0; r < 4; r++)
                put(top.tmin_i, r, p.tmin[r]), put(top.tmax_i, r, p.tmax[r]);
        }
        top.mem_rsp_valid_i = !word_q.empty();
        for (int j = 0; j < RW; j++)
            top.mem_rdata_i[j] = word_q.empty() ? 0 : at(word_q.front() + (uint32_t)j);
        top.node_rsp_valid_i = !node_q.empty();
        top.node_w0_i = node_q.empty() ? 0 : at(node_q.front());
        top.node_w1_i = node_q.empty() ? 0 : at(node_q.front() + 1);
        top.list_rsp_valid_i = !list_q.empty();
        top.list_rdata_i = list_q.empty() ? 0 : at(list_q.front());
        list_q.clear();
        if (!word_q.empty())
            word_q.pop_front();
        if (!node_q.empty())
            node_q.pop_front();
        top.clk_i = 0;
        top.eval();
        refused = top.valid_i && !top.ready_o ? refused + 1 : 0;
        if (top.valid_i && top.ready_o) {
            in_thread[free_t] = (long)next++;
            started[free_t] = cycle;
            busy++;
        } else if (refused > 4) {
            std::printf("MISMATCH trace_core: thread %ld, free since its packet left, refuses a packet for %llu cycles\n",
                        free_t, (unsigned long long)refused);
            return 1;
        }
        if (top.mem_req_valid_o)
            word_q.push_back(top.mem_addr_o);
        if (top.node_req_valid_o)
            node_q.push_back(top.node_addr_o);
        if (top.list_req_o)
            list_q.push_back(top.list_addr_o);
        inflight_sum += top.inflight_o;
        if (top.valid_o) {
            const uint32_t t = top.thread_o;
            if (t >= threads || in_thread[t] < 0) {
                std::printf("MISMATCH trace_core: a packet out of thread %u, which holds none\n", t);
                return 1;
            }
            outcome got;
            for (int r = 0; r < 4; r++) {
                got.hit[r][0] = top.inst_o[r];
                got.hit[r][1] = top.tri_o[r];
                got.hit[r][2] = get(top.t_o, r);
                got.hit[r][3] = get(top.u_o, r);
                got.hit[r][4] = get(top.v_o, r);
                got.hit[r][5] = get(top.cos_o, r);
            }
            for (int k = 0; k < 10; k++)
                got.count[k] = top.count_o[k];
            const std::size_t i = (std::size_t)in_thread[t];
            compare("rtl", i, t, want[i], got);
            latency_sum += cycle - started[t];
            latency_max = std::max(latency_max, cycle - started[t]);
            in_thread[t] = -1;
            busy--;
            done++;
            last_out = cycle;
        }
        top.clk_i = 1;
        top.eval();
        cycle++;
    }
    std::printf("tb_core: %zu packets (%llu any-hit) on %u threads, %llu rays hit, %llu unit operations (C trace_step), "
                "%llu cycles: %.1f cycles per packet, latency %.1f (max %llu), %.2f operations in flight, %.1f cycles "
                "per operation; %llu mismatches, %llu packets whose C result differs from the recording\n",
                done, (unsigned long long)any_hit, threads, (unsigned long long)hits, (unsigned long long)ops,
                (unsigned long long)cycle, done ? (double)cycle / (double)done : 0.0,
                done ? (double)latency_sum / (double)done : 0.0, (unsigned long long)latency_max,
                cycle ? (double)inflight_sum / (double)cycle : 0.0, ops ? (double)cycle / (double)ops : 0.0,
                (unsigned long long)g_mismatches, (unsigned long long)vs_capture);
    return g_mismatches ? 1 : 0;
}
