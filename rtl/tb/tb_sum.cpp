// Co-simulation of the exact dot product (rtl/f24_sum_exact.sv) against the C model
// (hls/fp24/f24_sum_exact.c): one set of N = 9 operand pairs enters every cycle; every result
// leaving the unit is compared, hi and lo, with the C model's for the set that entered `latency`
// cycles earlier. Sets: random terms of moderate exponents (single terms as x * 1), terms built to
// cancel (o + t d with o = -fl(t d), the rebase of a ray origin), zeros and specials. A mismatch
// prints the set and both results; the exit code is 1 on any mismatch.
// usage: tb_sum [-n N] [--seed S]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vtb_sum.h"
#include "verilated.h"

extern "C" {
#include "f24.h"
}

namespace {

constexpr int N = 9;
constexpr int W = F24_WIDTH;

struct set { uint32_t a[N], b[N]; };

uint64_t g_rng = 1;
uint32_t rnd() { g_rng ^= g_rng << 13, g_rng ^= g_rng >> 7, g_rng ^= g_rng << 17; return (uint32_t)(g_rng >> 11); }

uint32_t moderate(int span)
{
    const uint32_t e = (uint32_t)(F24_BIAS - span + (int)(rnd() % (2 * span + 1)));
    return ((rnd() & 1u) ? F24_SIGN_BIT : 0u) | e << F24_MAN_BITS | (rnd() & F24_FRAC_MASK);
}

uint32_t any_value()
{
    static const uint32_t sp[] = { 0, F24_SIGN_BIT, F24_POS_INF, F24_POS_INF | F24_SIGN_BIT, F24_DEFAULT_NAN, F24_ONE,
                                   F24_MIN_NORMAL, F24_MAX_NORMAL, 1 };
    const uint32_t k = rnd() % 40;
    return k == 0 ? sp[rnd() % 9] : k == 1 ? (rnd() & F24_MASK) : moderate(k < 8 ? 60 : 12);
}

set make_set(uint64_t i)
{
    set s;
    for (int k = 0; k < N; k++) {
        s.a[k] = any_value();
        s.b[k] = rnd() % 3 ? any_value() : F24_ONE;
    }
    if (i % 3 == 0) { // a rebase: o + t d cancelling down to its rounding error, plus a nudge
        const uint32_t t = moderate(8), d = moderate(8);
        s.a[0] = f24_neg(f24_mul(t, d)), s.b[0] = F24_ONE;
        s.a[1] = t, s.b[1] = d;
        for (int k = 2; k < N; k++)
            s.a[k] = k == 2 ? moderate(30) : 0, s.b[k] = F24_ONE;
    }
    if (i % 7 == 1) // every product zero: the sign of the zero sum
        for (int k = 0; k < N; k++)
            s.a[k] &= F24_SIGN_BIT;
    return s;
}

// packs N W-bit values into Verilator's 32-bit words, value k at bits [k W, (k + 1) W)
template <typename T> void pack(T &port, const uint32_t *v)
{
    uint32_t words[(N * W + 31) / 32] = { 0 };
    for (int k = 0; k < N; k++)
        for (int j = 0; j < W; j++)
            if (v[k] >> j & 1u)
                words[(k * W + j) / 32] |= 1u << ((k * W + j) % 32);
    for (int w = 0; w < (N * W + 31) / 32; w++)
        port[w] = words[w];
}

} // namespace

int main(int argc, char **argv)
{
    uint64_t n = 100000;
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "-n") && i + 1 < argc)
            n = std::strtoull(argv[++i], nullptr, 10);
        else if (!std::strcmp(argv[i], "--seed") && i + 1 < argc)
            g_rng = std::strtoull(argv[++i], nullptr, 10) | 1u;
    }
    VerilatedContext ctx;
    Vtb_sum top(&ctx);
    std::deque<set> q;
    uint64_t checked = 0, mismatches = 0;
    top.clk_i = 0;
    top.rst_ni = 0;
    top.valid_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;
    for (uint64_t cycle = 0; checked < n; cycle++) {
        const bool feed = cycle < n;
        set s{};
        if (feed) {
            s = make_set(cycle);
            pack(top.a_i, s.a);
            pack(top.b_i, s.b);
            q.push_back(s);
        }
        top.valid_i = feed;
        top.clk_i = 0;
        top.eval();
        top.clk_i = 1;
        top.eval();
        if (!top.valid_o)
            continue;
        const set p = q.front();
        q.pop_front();
        const f24x2 want = f24_sum_exact(p.a, p.b, N);
        checked++;
        if (top.hi_o != want.hi || top.lo_o != want.lo) {
            if (mismatches++ < 10) {
                std::printf("MISMATCH f24_sum_exact:");
                for (int k = 0; k < N; k++)
                    std::printf(" %06x*%06x", p.a[k], p.b[k]);
                std::printf(": rtl %06x %06x, C model %06x %06x\n", top.hi_o, top.lo_o, want.hi, want.lo);
            }
        }
    }
    std::printf("tb_sum e%dm%d: %llu sets of %d products, %llu mismatches\n", F24_EXP_BITS, F24_MAN_BITS,
                (unsigned long long)checked, N, (unsigned long long)mismatches);
    return mismatches != 0;
}
