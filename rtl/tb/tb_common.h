// Shared by the co-simulation benches of the datapath units (tb_units.cpp, tb_wide.cpp, tb_rgs.cpp): fp24
// words in and out of Verilator's ports, transactions read from saarcor render --capture-unit-io
// files, the comparison of a unit's outputs with a readable MISMATCH report, the random numbers.
// A transaction is a struct of uint32_t words, its inputs first: a captured line holds its words
// in that order (the outputs recorded while rendering after the inputs).
#ifndef SAARCOR_RTL_TB_COMMON_H
#define SAARCOR_RTL_TB_COMMON_H

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "verilated.h"

extern "C" {
#include "f24.h"
}

namespace cosim {

constexpr int W = F24_WIDTH;

// word idx (W bits at idx * W) of a port
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

inline uint64_t g_rng = 1;
inline uint32_t rnd() { g_rng ^= g_rng << 13, g_rng ^= g_rng >> 7, g_rng ^= g_rng << 17; return (uint32_t)(g_rng >> 11); }

// random operands: mostly values of moderate magnitude, some specials, some arbitrary encodings
inline uint32_t rnd_f24()
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

// the 32-bit words of a binary file (a memory image) into mem; false (with a message naming the
// bench) if it cannot be read or is empty
inline bool read_words(const char *bench, const std::string &path, std::vector<uint32_t> &mem)
{
    FILE *f = std::fopen(path.c_str(), "rb");
    if (!f) {
        std::printf("%s: cannot read %s\n", bench, path.c_str());
        return false;
    }
    mem.clear();
    uint32_t w;
    while (std::fread(&w, sizeof w, 1, f) == 1)
        mem.push_back(w);
    std::fclose(f);
    return !mem.empty();
}

// the memory image N of a capture (DIR/image_N.bin, written by --capture-unit-io)
inline bool load_image(const char *bench, const std::string &dir, uint32_t n, std::vector<uint32_t> &mem)
{
    return read_words(bench, dir + "/image_" + std::to_string(n) + ".bin", mem);
}

// captured files: hex words per line in the field order of the structs; present says whether the
// file exists; false (with a message naming the bench) on a malformed line
template <typename T>
bool read_capture(const char *bench, const std::string &path, std::vector<T> &out, bool &present)
{
    FILE *f = std::fopen(path.c_str(), "r");
    present = f != nullptr;
    if (!f)
        return true;
    char line[4096];
    const std::size_t words = sizeof(T) / sizeof(uint32_t);
    while (std::fgets(line, sizeof line, f)) {
        T x;
        uint32_t *w = reinterpret_cast<uint32_t *>(&x);
        char *p = line;
        std::size_t k = 0;
        for (; k < words; k++) {
            char *end;
            w[k] = (uint32_t)std::strtoul(p, &end, 16);
            if (end == p)
                break;
            p = end;
        }
        if (k != words) {
            std::fclose(f);
            std::printf("%s: %s: malformed line (%zu of %zu words)\n", bench, path.c_str(), k, words);
            return false;
        }
        out.push_back(x);
    }
    std::fclose(f);
    return true;
}

struct stream_stats { uint64_t sent = 0, checked = 0, mismatches = 0, vs_capture = 0; };
inline uint64_t g_cycle = 0;

inline void print_words(const char *label, const uint32_t *w, std::size_t n)
{
    std::printf("  %s:", label);
    for (std::size_t i = 0; i < n; i++)
        std::printf(" %06x", w[i]);
    std::printf("\n");
}

// the words after the first in_words of want and got must be equal; the first 10 mismatches of a
// stream print the unit, the cycle, what was compared against, the inputs and both outputs
template <typename T> void compare(const char *unit, stream_stats &s, const T &want, const T &got, std::size_t in_words,
                                   const char *what)
{
    s.checked++;
    const uint32_t *a = reinterpret_cast<const uint32_t *>(&want), *b = reinterpret_cast<const uint32_t *>(&got);
    const std::size_t words = sizeof(T) / sizeof(uint32_t);
    if (!std::memcmp(a + in_words, b + in_words, (words - in_words) * sizeof(uint32_t)))
        return;
    if (s.mismatches++ < 10) {
        std::printf("MISMATCH %s at cycle %llu (against %s):\n", unit, (unsigned long long)g_cycle, what);
        print_words("inputs", a, in_words);
        print_words("expected", a + in_words, words - in_words);
        print_words("rtl", b + in_words, words - in_words);
    }
}

// the benches' options: -n N (random transactions), --seed S (of rnd), --capture DIR; false, with
// the usage line, on anything else
inline bool parse_args(int argc, char **argv, const char *bench, std::size_t &n, std::string &capture)
{
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "-n") && i + 1 < argc) n = std::strtoull(argv[++i], nullptr, 0);
        else if (!std::strcmp(argv[i], "--seed") && i + 1 < argc) g_rng = std::strtoull(argv[++i], nullptr, 0) | 1u;
        else if (!std::strcmp(argv[i], "--capture") && i + 1 < argc) capture = argv[++i];
        else { std::printf("usage: %s [-n N] [--seed S] [--capture DIR]\n", bench); return false; }
    }
    return true;
}

} // namespace cosim

#endif
