// Shared by the co-simulation benches of the fp24 datapaths (tb_units.cpp, tb_rgs.cpp): the fp24
// words of Verilator ports (packed W bits a word, word 0 in the low bits; wide ports are VlWide,
// narrow ones integers), the xorshift generator (seed: g_rng) and random fp24 operands.
#ifndef SAARCOR_TB_FP24_H
#define SAARCOR_TB_FP24_H

#include <cstddef>
#include <cstdint>

#include "verilated.h"

extern "C" {
#include "f24.h"
}

namespace {

constexpr int W = F24_WIDTH;

template <std::size_t N> void put(VlWide<N> &w, int idx, uint32_t v)
{
    for (int b = 0; b < W; b++) {
        const int bit = idx * W + b;
        const uint32_t m = 1u << (bit % 32);
        w[bit / 32] = (v >> b & 1u) ? (w[bit / 32] | m) : (w[bit / 32] & ~m);
    }
}
template <typename T> void put(T &q, int idx, uint32_t v)
{
    const int sh = idx * W;
    q = (T)((q & ~((((T)1 << W) - 1) << sh)) | ((T)v << sh));
}
template <std::size_t N> uint32_t get(const VlWide<N> &w, int idx)
{
    uint32_t v = 0;
    for (int b = 0; b < W; b++) {
        const int bit = idx * W + b;
        v |= (w[bit / 32] >> (bit % 32) & 1u) << b;
    }
    return v;
}
template <typename T> uint32_t get(const T &q, int idx) { return (uint32_t)((q >> (idx * W)) & (((T)1 << W) - 1)); }

uint64_t g_rng = 1;
uint32_t rnd() { g_rng ^= g_rng << 13, g_rng ^= g_rng >> 7, g_rng ^= g_rng << 17; return (uint32_t)(g_rng >> 11); }

// random operands: mostly values of moderate magnitude, some specials, some arbitrary encodings
uint32_t rnd_f24()
{
    const uint32_t k = rnd() % 20;
    if (k == 0) {
        const uint32_t sp[] = { 0, F24_SIGN_BIT, F24_POS_INF, F24_POS_INF | F24_SIGN_BIT, F24_DEFAULT_NAN, F24_ONE,
                                F24_ONE | F24_SIGN_BIT, F24_MIN_NORMAL, F24_MAX_NORMAL, 1 };
        return sp[rnd() % 10];
    }
    if (k == 1)
        return rnd() & F24_MASK;
    const uint32_t e = (uint32_t)F24_BIAS - 6 + rnd() % 13;
    return ((rnd() & 1u) ? F24_SIGN_BIT : 0u) | e << F24_MAN_BITS | (rnd() & F24_FRAC_MASK);
}

} // namespace

#endif
