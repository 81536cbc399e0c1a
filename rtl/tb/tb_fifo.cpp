// Random test of sync_fifo (rtl/sync_fifo.sv) in both storage forms (tb_fifo.sv: depths 2, 4 and
// 64, LUT RAM and block RAM) against a deque, every cycle: valid_o and ready_o of both forms equal
// the deque's (not empty, not full), data_o its front while valid; the two forms' data_o equal
// each other every cycle once every address has been written (the block RAM form's bypass and
// read ahead give the LUT RAM's word even while the queue is empty). The push and pop rates change
// every 256 cycles (each from 1/8 to always) so that the queues run full, empty and in between; a
// push and a pop in one cycle on a one-word queue (the bypass of the new head) and a push into an
// empty queue must occur at every depth. Exit code 1 on any mismatch or a case never reached.
// usage: tb_fifo [-n CYCLES] [--seed S]
#include <cstdio>
#include <deque>
#include <string>

#include "Vtb_fifo.h"
#include "tb_common.h"

using namespace cosim;

namespace {

constexpr int DEPTHS = 3;
constexpr std::size_t DEPTH[DEPTHS] = { 2, 4, 64 };

struct queue_stats {
    uint64_t pushes = 0, full = 0, into_empty = 0, through_one = 0, written = 0;
};

uint32_t word(const VlWide<3> &w, int k) { return w[k]; }

} // namespace

int main(int argc, char **argv)
{
    std::size_t n = 1000000;
    std::string capture;
    if (!parse_args(argc, argv, "tb_fifo", n, capture))
        return 2;
    VerilatedContext ctx;
    Vtb_fifo top{ &ctx };
    top.rst_ni = 0, top.clk_i = 0, top.valid_i = 0, top.ready_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;
    std::deque<uint32_t> model[DEPTHS];
    queue_stats st[DEPTHS];
    uint64_t mismatches = 0;
    auto report = [&](int k, const char *field, uint32_t got, uint32_t exp, const char *form) {
        if (mismatches++ < 20)
            std::printf("MISMATCH sync_fifo depth %zu (%s) cycle %llu %s: rtl %08x, expected %08x\n", DEPTH[k], form,
                        (unsigned long long)g_cycle, field, got, exp);
    };
    uint32_t push_rate = 8, pop_rate = 8; // out of 8
    for (g_cycle = 0; g_cycle < n; g_cycle++) {
        if (g_cycle % 256 == 0)
            push_rate = 1 + rnd() % 8, pop_rate = 1 + rnd() % 8;
        top.clk_i = 0;
        top.valid_i = 0, top.ready_i = 0;
        for (int k = 0; k < DEPTHS; k++) {
            top.valid_i |= (rnd() % 8 < push_rate) << k;
            top.ready_i |= (rnd() % 8 < pop_rate) << k;
            top.data_i[k] = rnd() ^ rnd() << 16;
        }
        top.eval();
        for (int k = 0; k < DEPTHS; k++) {
            std::deque<uint32_t> &q = model[k];
            const uint32_t valid = !q.empty(), ready = q.size() != DEPTH[k];
            const uint32_t lut_data = word(top.lut_data_o, k), bram_data = word(top.bram_data_o, k);
            if ((top.lut_valid_o >> k & 1u) != valid) report(k, "valid_o", top.lut_valid_o >> k & 1u, valid, "LUT RAM");
            if ((top.bram_valid_o >> k & 1u) != valid) report(k, "valid_o", top.bram_valid_o >> k & 1u, valid, "block RAM");
            if ((top.lut_ready_o >> k & 1u) != ready) report(k, "ready_o", top.lut_ready_o >> k & 1u, ready, "LUT RAM");
            if ((top.bram_ready_o >> k & 1u) != ready) report(k, "ready_o", top.bram_ready_o >> k & 1u, ready, "block RAM");
            if (valid && lut_data != q.front()) report(k, "data_o", lut_data, q.front(), "LUT RAM");
            if (valid && bram_data != q.front()) report(k, "data_o", bram_data, q.front(), "block RAM");
            if (st[k].written >= DEPTH[k] && bram_data != lut_data) report(k, "data_o", bram_data, lut_data, "block RAM vs LUT RAM");
            const bool push = (top.valid_i >> k & 1u) && ready, pop = valid && (top.ready_i >> k & 1u);
            st[k].full += !ready;
            st[k].into_empty += push && q.empty();
            st[k].through_one += push && pop && q.size() == 1;
            if (pop)
                q.pop_front();
            if (push)
                q.push_back(top.data_i[k]), st[k].pushes++, st[k].written++;
        }
        top.clk_i = 1;
        top.eval();
    }
    bool reached = true;
    for (int k = 0; k < DEPTHS; k++) {
        std::printf("tb_fifo: depth %zu: %llu pushes, %llu cycles full, %llu pushes into an empty queue, %llu push and pop "
                    "on one word\n", DEPTH[k], (unsigned long long)st[k].pushes, (unsigned long long)st[k].full,
                    (unsigned long long)st[k].into_empty, (unsigned long long)st[k].through_one);
        reached = reached && st[k].full && st[k].into_empty && st[k].through_one;
    }
    if (!reached)
        std::printf("tb_fifo: FAIL: a queue never ran full, never took a push while empty or never a push and a pop on "
                    "one word\n");
    std::printf("tb_fifo: %llu cycles, %llu mismatches\n", (unsigned long long)n, (unsigned long long)mismatches);
    return mismatches || !reached ? 1 : 0;
}
