// Co-simulation of the fp24 operators (rtl/f24_*.sv) against the C model (hls/fp24): one operand
// pair enters every cycle; every result leaving an operator is compared with the C model's
// result for the pair that entered `latency` cycles earlier; the unary square root and integer
// conversion take the pair's first operand. The converter f24_from_i32 takes the pair's bits as an
// int32 i (the low 32 bits of {a, b}): f24_from_i32(i), and at SCALE = -1 f24_mul(f24_from_i32(i), 1/2)
// (the RGS's pixel centres), with integer edges (0, +-2^k, +-2^k +- 1, ties of the rounding). Vectors: the TestFloat-style edge set of each
// operation (tb/fp/f24_vec.c), every value at the integer conversion's boundaries (|a| near 1,
// 2^M and 2^31 = saturation), N random pairs per operation class, and optional hex vector files
// ("a b result" or, unary, "a result"; tests/golden/f24, saarcor f24gen); --unary-all adds every
// encoding of the format as a first operand (b = 0), which checks the square root and the integer
// conversion exhaustively. A mismatch prints the vector, the cycle and both results; the exit code
// is 1 on any mismatch.
// usage: tb_f24_ops [-n N] [--seed S] [--unary-all] [FILE.hex ...]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vtb_f24_ops.h"
#include "verilated.h"

extern "C" {
#include "f24.h"
#include "f24_ops.h"
#include "f24_vec.h"
}

namespace {

struct pending {
    uint32_t a, b;
    uint64_t cycle;
};

struct checker {
    const char *name;
    std::deque<pending> q;
    uint64_t checked = 0, mismatches = 0;
};

uint64_t g_cycle = 0;

void report(checker &c, const pending &p, uint32_t rtl, uint32_t model, uint64_t cycle)
{
    if (c.mismatches++ < 20)
        std::printf("MISMATCH %s: a=%06x b=%06x (entered cycle %llu, left cycle %llu): rtl %06x, C model %06x\n",
                    c.name, p.a, p.b, (unsigned long long)p.cycle, (unsigned long long)cycle, rtl, model);
}

void check(checker &c, bool valid, uint32_t rtl, uint32_t (*model)(uint32_t, uint32_t))
{
    if (!valid)
        return;
    if (c.q.empty()) {
        std::printf("PROTOCOL %s: result without a pending operation at cycle %llu\n", c.name, (unsigned long long)g_cycle);
        c.mismatches++;
        return;
    }
    const pending p = c.q.front();
    c.q.pop_front();
    const uint32_t want = model(p.a, p.b);
    c.checked++;
    if (rtl != want)
        report(c, p, rtl, want, g_cycle);
}

uint32_t m_add(uint32_t a, uint32_t b) { return f24_add(a, b); }
uint32_t m_sub(uint32_t a, uint32_t b) { return f24_sub(a, b); }
uint32_t m_mul(uint32_t a, uint32_t b) { return f24_mul(a, b); }
uint32_t m_div(uint32_t a, uint32_t b) { return f24_div(a, b); }
uint32_t m_flags(uint32_t a, uint32_t b)
{
    return (uint32_t)f24_lt(a, b) | (uint32_t)f24_le(a, b) << 1 | (uint32_t)f24_eq(a, b) << 2 |
           (uint32_t)f24_unordered(a, b) << 3;
}
// the converter's int32: the low 32 bits of {a, b}; and the pair that gives an int32
int32_t int_of(uint32_t a, uint32_t b) { return (int32_t)(uint32_t)((uint64_t)a << F24_WIDTH | b); }
f24_pair pair_of(uint32_t i) { return f24_pair{ F24_WIDTH >= 32 ? 0u : i >> F24_WIDTH, i & F24_MASK }; }
uint32_t m_cvt(uint32_t a, uint32_t b) { return f24_from_i32(int_of(a, b)); }
uint32_t m_half(uint32_t a, uint32_t b) { return f24_mul(f24_from_i32(int_of(a, b)), f24_div(F24_ONE, f24_from_i32(2))); }
uint32_t m_min(uint32_t a, uint32_t b) { return f24_min(a, b); }
uint32_t m_max(uint32_t a, uint32_t b) { return f24_max(a, b); }
uint32_t m_sqrt(uint32_t a, uint32_t) { return f24_sqrt(a); }
uint32_t m_to_i32(uint32_t a, uint32_t) { return (uint32_t)f24_to_i32(a); }

// f24_to_i32's boundaries: every exponent from |a| < 1 to past the saturation at 2^31 (the
// shifter's every distance, truncation and the shift direction's change at 2^M), both signs, the
// significand's extremes
void to_i32_edges(std::vector<f24_pair> &vec)
{
    const uint32_t ones = F24_FRAC_MASK, fracs[] = { 0, 1, 1u << (F24_MAN_BITS - 1), ones - 1, ones };
    for (int32_t e = F24_BIAS - 1; e <= F24_BIAS + 32 && e < F24_EXP_MAX; e++)
        for (uint32_t f : fracs)
            for (uint32_t sign = 0; sign < 2; sign++)
                vec.push_back(f24_pair{ f24_pack(sign, (uint32_t)e, f), 0 });
}

}  // namespace

int main(int argc, char **argv)
{
    uint64_t n = 1000000, seed = 1;
    bool unary_all = false;
    std::vector<std::string> files;
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "-n") && i + 1 < argc)
            n = std::strtoull(argv[++i], nullptr, 0);
        else if (!std::strcmp(argv[i], "--seed") && i + 1 < argc)
            seed = std::strtoull(argv[++i], nullptr, 0);
        else if (!std::strcmp(argv[i], "--unary-all"))
            unary_all = true;
        else
            files.push_back(argv[i]);
    }
    std::vector<f24_pair> vec;
    static f24_pair edges[F24_VEC_MAX_EDGES];
    const f24_op classes[] = { F24_OP_ADD, F24_OP_MUL, F24_OP_DIV, F24_OP_LT, F24_OP_MIN, F24_OP_SQRT, F24_OP_TO_I32 };
    const size_t n_classes = sizeof classes / sizeof classes[0];
    for (f24_op op : classes) {
        const size_t k = f24_vec_edges(op, edges, F24_VEC_MAX_EDGES);
        vec.insert(vec.end(), edges, edges + k);
    }
    for (int k = 0; k < 32; k++) // integers: powers of two and their neighbours, ties of the rounding
        for (int32_t d = -1; d <= 1; d++)
            for (uint32_t sign = 0; sign < 2; sign++) {
                const uint32_t i = (1u << k) + (uint32_t)d, tie = ((1u << (F24_MAN_BITS + 1)) + 1u + 2u * (uint32_t)(d + 1)) << (k % 8);
                vec.push_back(pair_of(sign ? 0u - i : i));
                vec.push_back(pair_of(sign ? 0u - tie : tie));
            }
    to_i32_edges(vec);
    f24_rng rng;
    f24_rng_seed(&rng, seed);
    for (uint64_t i = 0; i < n; i++)
        vec.push_back(f24_vec_random(classes[i % n_classes], &rng));
    if (unary_all)
        for (uint64_t a = 0; a <= F24_MASK; a++)
            vec.push_back(f24_pair{ (uint32_t)a, 0 });
    for (const std::string &f : files) {
        FILE *in = std::fopen(f.c_str(), "r");
        if (!in) {
            std::printf("tb_f24_ops: cannot read %s\n", f.c_str());
            return 2;
        }
        unsigned a, b, r;
        char line[128];
        while (std::fgets(line, sizeof line, in)) {
            const int fields = std::sscanf(line, "%x %x %x", &a, &b, &r);
            if (fields == 3)
                vec.push_back(f24_pair{ a, b });
            else if (fields == 2) // a unary operation's "a result"
                vec.push_back(f24_pair{ a, 0 });
        }
        std::fclose(in);
    }

    // the C model alone on the same vectors, for the speed comparison
    const auto c0 = std::chrono::steady_clock::now();
    uint32_t sink = 0;
    for (const f24_pair &v : vec)
        sink ^= m_add(v.a, v.b) ^ m_sub(v.a, v.b) ^ m_mul(v.a, v.b) ^ m_div(v.a, v.b) ^ m_flags(v.a, v.b) ^
                m_min(v.a, v.b) ^ m_max(v.a, v.b) ^ m_cvt(v.a, v.b) ^ m_half(v.a, v.b) ^ m_sqrt(v.a, v.b) ^
                m_to_i32(v.a, v.b);
    const double c_secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();

    VerilatedContext ctx;
    Vtb_f24_ops top{ &ctx };
    checker c_add{ "add" }, c_sub{ "sub" }, c_mul{ "mul" }, c_div{ "div" }, c_flags{ "lt/le/eq/unordered" },
        c_min{ "min" }, c_max{ "max" }, c_cvt{ "from_i32" }, c_half{ "from_i32 SCALE -1" }, c_sqrt{ "sqrt" },
        c_to_i32{ "to_i32" };
    checker *all[] = { &c_add, &c_sub, &c_mul, &c_div, &c_flags, &c_min, &c_max, &c_cvt, &c_half, &c_sqrt, &c_to_i32 };
    const size_t n_results = sizeof all / sizeof all[0];
    const uint32_t mask = F24_MASK;
    top.rst_ni = 0;
    top.clk_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t i = 0; i < vec.size() + 64; i++, g_cycle++) {
        const bool valid = i < vec.size();
        const uint32_t a = valid ? vec[i].a & mask : 0, b = valid ? vec[i].b & mask : 0;
        top.clk_i = 0;
        top.valid_i = valid;
        top.a_i = a;
        top.b_i = b;
        top.eval();
        top.clk_i = 1;
        top.eval(); // registers take the inputs; outputs show results of earlier cycles
        if (valid)
            for (checker *c : all)
                c->q.push_back(pending{ a, b, g_cycle });
        check(c_add, top.add_valid_o, top.add_o, m_add);
        check(c_sub, top.sub_valid_o, top.sub_o, m_sub);
        check(c_mul, top.mul_valid_o, top.mul_o, m_mul);
        check(c_div, top.div_valid_o, top.div_o, m_div);
        check(c_flags, top.cmp_valid_o, top.cmp_flags_o, m_flags);
        check(c_min, top.cmp_valid_o, top.min_o, m_min);
        check(c_max, top.cmp_valid_o, top.max_o, m_max);
        check(c_cvt, top.cvt_valid_o, top.cvt_o, m_cvt);
        check(c_half, top.half_valid_o, top.half_o, m_half);
        check(c_sqrt, top.sqrt_valid_o, top.sqrt_o, m_sqrt);
        check(c_to_i32, top.to_i32_valid_o, top.to_i32_o, m_to_i32);
    }
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    uint64_t bad = 0, checked = 0;
    for (checker *c : all) {
        bad += c->mismatches + c->q.size();
        checked += c->checked;
        if (!c->q.empty())
            std::printf("PROTOCOL %s: %zu operations never left the operator\n", c->name, c->q.size());
    }
    top.final();
    std::printf("tb_f24_ops e%dm%d: %zu vectors x %zu results, %llu checked, %llu mismatches, %.2f s (RTL + check %.2f M "
                "vectors/s; C model alone %.2f M vectors/s) [%x]\n",
                F24_EXP_BITS, F24_MAN_BITS, vec.size(), n_results, (unsigned long long)checked, (unsigned long long)bad, secs,
                vec.size() / secs / 1e6, vec.size() / c_secs / 1e6, sink & 0u);
    return bad ? 1 : 0;
}
