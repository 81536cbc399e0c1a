// Co-simulation of the accuracy datapath's units (rtl/rebase_unit.sv, rtl/xform_wide.sv) against
// the C model (hls/units: rebase_origin and rebase_distance; xform_point_wide and
// xform_vector_wide). Each unit has its own stream: transactions captured while rendering
// (saarcor render --capture-unit-io DIR: DIR/rebase.hex, DIR/wide.hex) first, then random ones:
// double words as rays carry them (low words about 2^-(M+1) of the high ones), origins that cancel
// (o = -fl(t d), a translation = -fl(m p)), all-zero products of random signs (the sign of a zero
// sum), zeros, Inf, NaN, huge and tiny exponents, any encoding, t = Inf or NaN (no entry
// distance: te = 0); vectors with anything in the words the vector mode ignores (p lo, tlo, the
// matrix's column 3). The handshake is exercised: in every other epoch of 1024 cycles the inputs
// have random gaps and the outputs random back pressure (ready_i low), else both run at full rate.
// Every result a unit hands over is compared with the C model's for the transaction it accepted in
// that order and, for captured ones, with the outputs recorded while rendering. A mismatch prints
// the unit, the cycle, the inputs and both results; exit code 1 on any mismatch or a transaction
// lost or invented.
// usage: tb_wide [-n N] [--seed S] [--capture DIR]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vtb_wide.h"
#include "tb_common.h"

extern "C" {
#include "rebase_unit.h"
#include "xform_unit.h"
}

using namespace cosim;

namespace {

// one transaction of each unit, inputs first (the capture files' word order)
struct rebase_tx { uint32_t o_hi[3], o_lo[3], d_hi[3], d_lo[3], t, p_hi[3], p_lo[3], te; };
struct wide_tx { uint32_t m[12], tlo[3], p_hi[3], p_lo[3], point, r_hi[3], r_lo[3]; };
constexpr std::size_t REBASE_IN = 13, WIDE_IN = 22;

f24_vec3 v3(const uint32_t *w) { return f24_vec3{ w[0], w[1], w[2] }; }
f24_vec3x2 v6(const uint32_t *hi, const uint32_t *lo) { return f24_vec3x2{ v3(hi), v3(lo) }; }
void words3(f24_vec3 v, uint32_t *w) { w[0] = v.x, w[1] = v.y, w[2] = v.z; }

void model(rebase_tx &x)
{
    const f24_vec3x2 p = rebase_origin(v6(x.o_hi, x.o_lo), v6(x.d_hi, x.d_lo), x.t);
    words3(p.hi, x.p_hi), words3(p.lo, x.p_lo);
    x.te = rebase_distance(x.t);
}

void model(wide_tx &x)
{
    f24_affine a;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            a.m[r][c] = x.m[4 * r + c];
    const f24_vec3x2 r = x.point ? xform_point_wide(&a, v3(x.tlo), v6(x.p_hi, x.p_lo)) : xform_vector_wide(&a, v3(x.p_hi));
    words3(r.hi, x.r_hi), words3(r.lo, x.r_lo);
}

// ---- random operands
uint32_t sign() { return (rnd() & 1u) ? F24_SIGN_BIT : 0u; }
uint32_t with_exp(uint32_t e) { return sign() | e << F24_MAN_BITS | (rnd() & F24_FRAC_MASK); }
uint32_t moderate(uint32_t span) { return with_exp((uint32_t)F24_BIAS - span + rnd() % (2 * span + 1)); }
uint32_t zero() { return sign(); }
uint32_t extreme() // the exponents next to the subnormal and Inf encodings
{
    return with_exp((rnd() & 1u) ? 1u + rnd() % 8 : (uint32_t)F24_EXP_MAX - 1 - rnd() % 8);
}
uint32_t any_value()
{
    static const uint32_t sp[] = { 0, F24_SIGN_BIT, F24_POS_INF, F24_POS_INF | F24_SIGN_BIT, F24_DEFAULT_NAN,
                                   F24_DEFAULT_NAN | F24_SIGN_BIT | 1u, F24_ONE, F24_ONE | F24_SIGN_BIT, F24_MIN_NORMAL,
                                   F24_MAX_NORMAL, F24_MAX_NORMAL | F24_SIGN_BIT, 1, F24_SIGN_BIT | 1u };
    const uint32_t k = rnd() % 32;
    return k == 0 ? sp[rnd() % (sizeof sp / sizeof sp[0])] : k == 1 ? (rnd() & F24_MASK) : k < 4 ? extreme() : moderate(12);
}
// the low word of a double word whose high word is hi: 2^-(M+1) .. 2^-(M+8) of it, or a zero
uint32_t low_of(uint32_t hi)
{
    const int e = (int)f24_exp(hi) - (F24_MAN_BITS + 1) - (int)(rnd() % 8);
    return (rnd() % 4 == 0 || f24_exp(hi) == F24_EXP_MAX || e < 1) ? zero() : with_exp((uint32_t)e);
}
// an entry distance: mostly positive, or none (Inf, NaN), or 0
uint32_t distance()
{
    const uint32_t k = rnd() % 16;
    return k == 0 ? F24_POS_INF : k == 1 ? F24_DEFAULT_NAN : k == 2 ? zero() : k == 3 ? F24_POS_INF | F24_SIGN_BIT
                                                                                       : moderate(10) & ~F24_SIGN_BIT;
}

rebase_tx random_rebase(uint64_t i)
{
    rebase_tx x{};
    const uint32_t kind = i % 4;
    x.t = kind == 1 ? any_value() : distance();
    for (int k = 0; k < 3; k++) {
        if (kind == 1) { // anything
            x.o_hi[k] = any_value(), x.o_lo[k] = any_value(), x.d_hi[k] = any_value(), x.d_lo[k] = any_value();
            continue;
        }
        if (kind == 3) { // every product zero: the sign of the zero sum
            x.o_hi[k] = zero(), x.o_lo[k] = zero(), x.d_hi[k] = zero(), x.d_lo[k] = zero();
            continue;
        }
        x.d_hi[k] = moderate(4);
        x.o_hi[k] = kind == 0 ? f24_neg(f24_mul(x.t, x.d_hi[k])) : moderate(12); // 0: o + t d cancels
        x.o_lo[k] = low_of(x.o_hi[k]), x.d_lo[k] = low_of(x.d_hi[k]);
    }
    model(x);
    return x;
}

wide_tx random_wide(uint64_t i)
{
    wide_tx x{};
    const uint32_t kind = i % 4;
    x.point = rnd() & 1u;
    for (int k = 0; k < 3; k++) {
        x.p_hi[k] = kind == 1 ? any_value() : kind == 2 ? zero() : kind == 3 ? extreme() : moderate(10);
        x.p_lo[k] = kind == 1 ? any_value() : kind == 2 ? zero() : low_of(x.p_hi[k]);
    }
    for (int r = 0; r < 3; r++) {
        uint32_t *row = &x.m[4 * r];
        for (int c = 0; c < 3; c++)
            row[c] = kind == 1 ? any_value() : kind == 3 ? extreme() : moderate(3);
        if (kind == 0 && (rnd() & 1u)) // the translation cancels the row's products to their rounding
            row[3] = f24_neg(f24_add(f24_add(f24_mul(row[0], x.p_hi[0]), f24_mul(row[1], x.p_hi[1])),
                                     f24_mul(row[2], x.p_hi[2])));
        else
            row[3] = kind == 1 ? any_value() : kind == 2 ? zero() : kind == 3 ? extreme() : moderate(10);
        x.tlo[r] = kind == 1 ? any_value() : kind == 2 ? zero() : low_of(row[3]);
    }
    if (!x.point) // what the vector mode must ignore: anything
        for (int k = 0; k < 3; k++)
            x.p_lo[k] = any_value(), x.tlo[k] = any_value(), x.m[4 * k + 3] = any_value();
    model(x);
    return x;
}

template <typename T> bool load(const std::string &dir, const char *file, std::vector<T> &out)
{
    bool present;
    if (!read_capture("tb_wide", dir + "/" + file, out, present))
        return false;
    if (!present || out.empty()) {
        std::printf("tb_wide: %s lacks %s vectors\n", dir.c_str(), file);
        return false;
    }
    return true;
}

// one unit's stream: the transactions, those accepted and not yet handed over (in order)
template <typename T> struct stream {
    const char *unit;
    std::vector<T> tx;
    std::size_t captured = 0, next = 0;
    std::deque<std::size_t> in_flight;
    stream_stats stats;
    uint64_t invented = 0;

    bool offer(bool calm) const { return next < tx.size() && (calm || rnd() % 4 != 0); }
    // at the clock edge: valid_i && ready_o accepted tx[next]
    void accept() { in_flight.push_back(next++), stats.sent++; }
    // valid_o && ready_i: got holds the unit's outputs (inputs as the front transaction's)
    void hand_over(const T &rtl_out, std::size_t in_words)
    {
        if (in_flight.empty()) {
            invented++;
            return;
        }
        const std::size_t k = in_flight.front();
        in_flight.pop_front();
        T want = tx[k];
        model(want);
        compare(unit, stats, want, rtl_out, in_words, "C model");
        if (k < captured)
            compare(unit, stats, tx[k], rtl_out, in_words, "capture"), stats.vs_capture++;
    }
};

} // namespace

int main(int argc, char **argv)
{
    std::size_t n = 100000;
    std::string capture;
    if (!parse_args(argc, argv, "tb_wide", n, capture))
        return 2;
    stream<rebase_tx> b{ "rebase_unit" };
    stream<wide_tx> w{ "xform_wide" };
    if (!capture.empty()) {
        if (!load(capture, "rebase.hex", b.tx) || !load(capture, "wide.hex", w.tx))
            return 2;
        b.captured = b.tx.size(), w.captured = w.tx.size();
    }
    for (std::size_t i = 0; i < n; i++)
        b.tx.push_back(random_rebase(i)), w.tx.push_back(random_wide(i));
    std::size_t points = 0;
    for (const auto &x : w.tx)
        points += x.point;

    VerilatedContext ctx;
    Vtb_wide top{ &ctx };
    top.rst_ni = 0, top.clk_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;
    uint64_t stalls = 0, idle = 0;
    const auto t0 = std::chrono::steady_clock::now();
    // until both streams are through, or nothing left a unit for 1000 cycles
    for (; (b.next < b.tx.size() || w.next < w.tx.size() || !b.in_flight.empty() || !w.in_flight.empty()) && idle < 1000;
         g_cycle++) {
        const bool calm = (g_cycle / 1024) % 2 == 0;
        top.clk_i = 0;
        top.b_valid_i = b.offer(calm);
        if (top.b_valid_i) {
            const rebase_tx &x = b.tx[b.next];
            for (int k = 0; k < 3; k++)
                put(top.b_o_hi_i, k, x.o_hi[k]), put(top.b_o_lo_i, k, x.o_lo[k]), put(top.b_d_hi_i, k, x.d_hi[k]),
                    put(top.b_d_lo_i, k, x.d_lo[k]);
            top.b_t_i = x.t;
        }
        top.b_ready_i = calm || rnd() % 4 != 0;
        top.w_valid_i = w.offer(calm);
        if (top.w_valid_i) {
            const wide_tx &x = w.tx[w.next];
            for (int k = 0; k < 12; k++)
                put(top.w_m_i, k, x.m[k]);
            for (int k = 0; k < 3; k++)
                put(top.w_tlo_i, k, x.tlo[k]), put(top.w_p_hi_i, k, x.p_hi[k]), put(top.w_p_lo_i, k, x.p_lo[k]);
            top.w_point_i = x.point;
        }
        top.w_ready_i = calm || rnd() % 4 != 0;
        top.eval();
        const bool b_acc = top.b_valid_i && top.b_ready_o, w_acc = top.w_valid_i && top.w_ready_o;
        stalls += (top.b_valid_i && !top.b_ready_o) + (top.w_valid_i && !top.w_ready_o);
        idle = (top.b_valid_o && top.b_ready_i) || (top.w_valid_o && top.w_ready_i) || b_acc || w_acc ? 0 : idle + 1;
        if (top.b_valid_o && top.b_ready_i) {
            rebase_tx got = b.in_flight.empty() ? rebase_tx{} : b.tx[b.in_flight.front()];
            for (int k = 0; k < 3; k++)
                got.p_hi[k] = get(top.b_p_hi_o, k), got.p_lo[k] = get(top.b_p_lo_o, k);
            got.te = top.b_te_o;
            b.hand_over(got, REBASE_IN);
        }
        if (top.w_valid_o && top.w_ready_i) {
            wide_tx got = w.in_flight.empty() ? wide_tx{} : w.tx[w.in_flight.front()];
            for (int k = 0; k < 3; k++)
                got.r_hi[k] = get(top.w_r_hi_o, k), got.r_lo[k] = get(top.w_r_lo_o, k);
            w.hand_over(got, WIDE_IN);
        }
        top.clk_i = 1;
        top.eval();
        if (b_acc)
            b.accept();
        if (w_acc)
            w.accept();
    }
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    top.final();
    const uint64_t lost = b.in_flight.size() + w.in_flight.size() + (b.tx.size() - b.next) + (w.tx.size() - w.next);
    if (lost || b.invented || w.invented)
        std::printf("PROTOCOL: %llu transactions never left their unit, %llu results without a transaction\n",
                    (unsigned long long)lost, (unsigned long long)(b.invented + w.invented));
    const uint64_t mismatches = b.stats.mismatches + w.stats.mismatches;
    std::printf("tb_wide e%dm%d: rebase %llu (%zu captured), wide %llu (%zu captured; %zu points, %zu vectors) "
                "transactions; %llu mismatches; %llu cycles, %llu input stalls; %.2f s\n",
                F24_EXP_BITS, F24_MAN_BITS, (unsigned long long)b.stats.checked - b.stats.vs_capture, b.captured,
                (unsigned long long)w.stats.checked - w.stats.vs_capture, w.captured, points, w.tx.size() - points,
                (unsigned long long)mismatches, (unsigned long long)g_cycle, (unsigned long long)stalls, secs);
    return (mismatches + lost + b.invented + w.invented) ? 1 : 0;
}
