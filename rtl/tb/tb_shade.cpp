// Co-simulation of the RGS's shading datapath (rtl/shade_rec_decode.sv) against the C model: each
// vertex normal decoded from a compact shading record is compared with shade_rec_normal
// (hls/units/shade_rec.c) and, for captured ones (saarcor render --capture-unit-io DIR:
// DIR/shade_rec.hex, every shade_rec_normal call while rendering: the record's 4 normal words, the
// vertex k, the unit normal), with the normal recorded while rendering. The bench slices the
// vertex's 42-bit code out of the record (shade_rec_bits, as the RGS's read of the record would) and
// gives every transaction a thread id (its number modulo 64), which must come out with its result.
// Random transactions: records of random words with one vertex's code set to an edge (the missing
// normal x = -2^20 with any y, the poles and axes +-(2^20 - 1), codes on and beside the fold
// |x| + |y| = 2^20 - 1, the smallest components) or anything. The handshake is exercised: in every
// other epoch of 1024 cycles the input has random gaps and the output random back pressure. A
// mismatch prints the unit, the transaction, the cycle, the thread, the field and both values (and
// the inputs); exit code 1 on any mismatch, a wrong thread, or a result lost or invented.
// usage: tb_shade [-n N] [--seed S] [--capture DIR]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vtb_shade.h"
#include "tb_common.h"

extern "C" {
#include "shade_rec.h"
}

using namespace cosim;

namespace {

// shade_rec.hex's word order: inputs (the record's normal words, the vertex), then the normal
struct normal_tx { uint32_t rec[SHADE_NORMAL_WORDS], k, n[3]; };
constexpr std::size_t NORMAL_IN = SHADE_NORMAL_WORDS + 1;
constexpr uint32_t OCT_MASK = (1u << SHADE_OCT_BITS) - 1u;

uint64_t code_of(const normal_tx &x)
{
    const uint32_t at = 2u * SHADE_OCT_BITS * x.k;
    return (uint64_t)shade_rec_bits(x.rec, at, SHADE_OCT_BITS) |
           (uint64_t)shade_rec_bits(x.rec, at + SHADE_OCT_BITS, SHADE_OCT_BITS) << SHADE_OCT_BITS;
}

void model(normal_tx &x)
{
    const f24_vec3 n = shade_rec_normal(x.rec, x.k);
    x.n[0] = n.x, x.n[1] = n.y, x.n[2] = n.z;
}

// an octahedral component: an edge or anything
int32_t rnd_oct()
{
    const int32_t one = SHADE_OCT_ONE;
    switch (rnd() % 8) {
    case 0: return (int32_t)(rnd() % 5) - 2;
    case 1: return one - (int32_t)(rnd() % 3);
    case 2: return -one + (int32_t)(rnd() % 3);
    case 3: return -one - 1; // -2^20: the missing normal's x
    default: return (int32_t)(rnd() & OCT_MASK) - (1 << (SHADE_OCT_BITS - 1));
    }
}

normal_tx random_normal()
{
    normal_tx x{};
    for (auto &w : x.rec)
        w = rnd() << 16 ^ rnd();
    x.k = rnd() % 3;
    int32_t cx = rnd_oct(), cy = rnd_oct();
    if (rnd() % 4 == 0) { // on or beside the fold |x| + |y| = 2^20 - 1
        const int32_t ax = (int32_t)(rnd() % (uint32_t)SHADE_OCT_ONE), ay = SHADE_OCT_ONE - ax + (int32_t)(rnd() % 3) - 1;
        cx = (rnd() & 1u) ? -ax : ax;
        cy = ay > SHADE_OCT_ONE ? SHADE_OCT_ONE : (rnd() & 1u) ? -ay : ay;
    }
    // the code into the record's bits 42k .. 42k + 41 (bits 126, 127 stay what they were: unread)
    const uint64_t code = ((uint64_t)((uint32_t)cy & OCT_MASK) << SHADE_OCT_BITS) | ((uint32_t)cx & OCT_MASK);
    for (uint32_t b = 0; b < 2u * SHADE_OCT_BITS; b++) {
        const uint32_t bit = 2u * SHADE_OCT_BITS * x.k + b;
        x.rec[bit / 32] = (x.rec[bit / 32] & ~(1u << bit % 32)) | (uint32_t)(code >> b & 1u) << bit % 32;
    }
    model(x);
    return x;
}

uint64_t g_mismatches = 0;

// the normal's words and the thread id against the expected ones; the first 10 mismatches print
void check(std::size_t t, const normal_tx &want, const uint32_t got[3], uint32_t tid, const char *against)
{
    const bool tid_ok = tid == t % 64;
    if (tid_ok && !std::memcmp(want.n, got, sizeof want.n))
        return;
    if (g_mismatches++ >= 10)
        return;
    std::printf("MISMATCH shade_rec_decode transaction %zu (vertex %u, code %011llx) at cycle %llu, thread %zu, against %s:\n",
                t, want.k, (unsigned long long)code_of(want), (unsigned long long)g_cycle, t % 64, against);
    if (!tid_ok)
        std::printf("  thread   expected %zu rtl %u\n", t % 64, tid);
    const char *field[3] = { "n.x", "n.y", "n.z" };
    for (int c = 0; c < 3; c++)
        if (want.n[c] != got[c])
            std::printf("  %-8s expected %06x rtl %06x\n", field[c], want.n[c], got[c]);
    print_words("inputs", want.rec, NORMAL_IN);
}

} // namespace

int main(int argc, char **argv)
{
    std::size_t n = 100000;
    std::string capture;
    if (!parse_args(argc, argv, "tb_shade", n, capture))
        return 2;
    std::vector<normal_tx> tx;
    std::size_t captured = 0;
    if (!capture.empty()) {
        bool present;
        if (!read_capture("tb_shade", capture + "/shade_rec.hex", tx, present))
            return 2;
        if (!present || tx.empty()) {
            std::printf("tb_shade: %s lacks shade_rec.hex vectors (a scene with vertex normals?)\n", capture.c_str());
            return 2;
        }
        captured = tx.size();
    }
    for (std::size_t i = 0; i < n; i++)
        tx.push_back(random_normal());
    std::size_t missing = 0, folded = 0;
    for (const auto &x : tx) {
        const uint64_t c = code_of(x);
        const int32_t cx = (int32_t)((uint32_t)c << 11) >> 11, cy = (int32_t)((uint32_t)(c >> SHADE_OCT_BITS) << 11) >> 11;
        missing += cx < -SHADE_OCT_ONE;
        folded += cx >= -SHADE_OCT_ONE && std::abs(cx) + std::abs(cy) > SHADE_OCT_ONE;
    }

    VerilatedContext ctx;
    Vtb_shade top{ &ctx };
    top.rst_ni = 0, top.clk_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;
    std::deque<std::size_t> in_flight;
    std::size_t next = 0;
    uint64_t checked = 0, vs_capture = 0, invented = 0, idle = 0, latency = 0, first_in = 0;
    for (; (next < tx.size() || !in_flight.empty()) && idle < 1000; g_cycle++) {
        const bool calm = (g_cycle / 1024) % 2 == 0;
        top.clk_i = 0;
        top.n_valid_i = next < tx.size() && (calm || rnd() % 4 != 0);
        if (top.n_valid_i) {
            top.n_code_i = code_of(tx[next]);
            top.n_tid_i = next % 64;
        }
        top.n_ready_i = calm || rnd() % 4 != 0;
        top.eval();
        const bool take = top.n_valid_i && top.n_ready_o, give = top.n_valid_o && top.n_ready_i;
        if (give) {
            const uint32_t got[3] = { get(top.n_o, 0), get(top.n_o, 1), get(top.n_o, 2) };
            if (in_flight.empty()) {
                invented++;
            } else {
                const std::size_t t = in_flight.front();
                in_flight.pop_front();
                if (!latency)
                    latency = g_cycle - first_in;
                normal_tx want = tx[t];
                model(want);
                check(t, want, got, top.n_tid_o, "C model");
                if (t < captured)
                    check(t, tx[t], got, top.n_tid_o, "capture"), vs_capture++;
                checked++;
            }
            idle = 0;
        } else {
            idle++;
        }
        if (take) {
            if (next == 0)
                first_in = g_cycle;
            in_flight.push_back(next++);
        }
        top.clk_i = 1;
        top.eval();
    }
    const bool lost = next < tx.size() || !in_flight.empty();
    std::printf("tb_shade: shade_rec_decode %llu normals checked (%zu captured, %llu also against the capture; %zu missing, "
                "%zu folded), latency %llu cycles, %llu cycles, %llu mismatches%s%s\n",
                (unsigned long long)checked, captured, (unsigned long long)vs_capture, missing, folded,
                (unsigned long long)latency, (unsigned long long)g_cycle, (unsigned long long)g_mismatches,
                lost ? ", RESULTS LOST" : "", invented ? ", RESULTS INVENTED" : "");
    return g_mismatches || lost || invented ? 1 : 0;
}
