// Co-simulation of rgs_accum (rtl/rgs_accum.sv), an active ray's share of the RGS's accumulation,
// against rgs_accumulate_ray (hls/units/rgs_accum.c): the pixel's Q12 sum after the ray's colour,
// the reflection and transmission rays (o, d, weight, active bit) and whether its children take T_R
// steps. Captured transactions (saarcor render --capture-unit-io DIR: DIR/accumulate.hex, every
// rgs_accumulate_ray call: the material's words 13..15, the surface's valid, T_R origin, D^, N^,
// t_hat, entering, base, emission, tint; the ray i, its weight, diffuse and highlight sums, e, the
// spawn bits, the sum before; the outputs) come first and are also checked against the recording;
// then random ones: valid and invalid surfaces, indices of refraction 1, 3/2, 2/3 or anything,
// random shader fields, unit-like or arbitrary vectors, weights, light sums and pixel sums of any
// 16-bit value (saturating), every combination of the spawn and live bits. In every other epoch of
// 1024 cycles the input has random gaps and the output random back pressure. Each transaction has
// a thread id (its number modulo 64) that must come out with it. A mismatch prints the unit, the
// transaction, the cycle, the thread, the field and both values; exit code 1 on any mismatch, or a
// result lost or invented.
// usage: tb_accum [-n N] [--seed S] [--capture DIR]
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vtb_accum.h"
#include "tb_common.h"

extern "C" {
#include "rgs_ops.h"
}

using namespace cosim;

namespace {

struct accum_tx {
    uint32_t m[3];                                      // material words 13..15
    uint32_t valid, o[3], d[3], n[3], t_hat, entering;  // the surface
    uint32_t base[3], emis[3], tint[3], weight[3], diffuse[3], highlight[3];
    uint32_t i, eps, spawn, acc_in[3];
    // outputs
    uint32_t acc[3], r_o[3], r_d[3], r_w[3], r_active, t_o[3], t_d[3], t_w[3], t_active, steps;
};
constexpr std::size_t IN_WORDS = offsetof(accum_tx, acc) / sizeof(uint32_t);
constexpr std::size_t OUT_WORDS = sizeof(accum_tx) / sizeof(uint32_t) - IN_WORDS;
const char *const OUT_NAME[OUT_WORDS] = { "acc.r", "acc.g", "acc.b", "refl.o.x", "refl.o.y", "refl.o.z", "refl.d.x",
                                          "refl.d.y", "refl.d.z", "refl.w.r", "refl.w.g", "refl.w.b", "refl.active",
                                          "trans.o.x", "trans.o.y", "trans.o.z", "trans.d.x", "trans.d.y", "trans.d.z",
                                          "trans.w.r", "trans.w.g", "trans.w.b", "trans.active", "steps" };

void model(accum_tx &x)
{
    uint32_t m[16] = {};
    m[M_ETA] = x.m[0], m[M_SHADER0] = x.m[1], m[M_SHADER1] = x.m[2];
    surface sf{};
    sf.valid = (int)x.valid;
    sf.d = { x.d[0], x.d[1], x.d[2] };
    sf.n = { x.n[0], x.n[1], x.n[2] };
    sf.tr = t_r({ x.o[0], x.o[1], x.o[2] }, sf.d, sf.n);
    sf.t_hat = x.t_hat;
    sf.entering = (int)x.entering;
    for (int k = 0; k < 3; k++)
        sf.base[k] = x.base[k], sf.emission[k] = x.emis[k], sf.tint[k] = x.tint[k], x.acc[k] = x.acc_in[k];
    static rgs_task refl, trans;
    std::memset(&refl, 0, sizeof refl);
    std::memset(&trans, 0, sizeof trans);
    const int i = (int)x.i;
    x.steps = (uint32_t)rgs_accumulate_ray(m, &sf, i, x.weight, x.diffuse, x.highlight, x.eps, x.spawn, x.acc, &refl, &trans);
    const f24_vec3 ro = refl.rays.o[i], rd = refl.rays.d[i], to = trans.rays.o[i], td = trans.rays.d[i];
    const uint32_t r[] = { ro.x, ro.y, ro.z, rd.x, rd.y, rd.z }, t[] = { to.x, to.y, to.z, td.x, td.y, td.z };
    for (int k = 0; k < 3; k++)
        x.r_o[k] = r[k], x.r_d[k] = r[3 + k], x.t_o[k] = t[k], x.t_d[k] = t[3 + k], x.r_w[k] = refl.weight[i][k],
        x.t_w[k] = trans.weight[i][k];
    x.r_active = refl.rays.active >> i & 1u;
    x.t_active = trans.rays.active >> i & 1u;
}

uint32_t rnd_q() { return rnd() % 3 ? rnd() % 8192 : rnd() % 65536; }

accum_tx random_accum()
{
    accum_tx x{};
    const uint32_t etas[] = { F24_ONE, f24_div(f24_from_i32(3), f24_from_i32(2)), f24_div(f24_from_i32(2), f24_from_i32(3)) };
    x.m[0] = rnd() % 4 ? etas[rnd() % 3] : rnd_f24();
    x.m[1] = rnd(), x.m[2] = rnd();
    x.valid = rnd() % 5 != 0;
    const bool w_small = rnd() % 4 == 0; // children below the spawn threshold
    for (int k = 0; k < 3; k++) {
        x.o[k] = rnd_f24(), x.d[k] = rnd_f24(), x.n[k] = rnd_f24();
        x.base[k] = rnd_q(), x.emis[k] = rnd() % 2 ? 0 : rnd_q(), x.tint[k] = rnd_q(), x.weight[k] = w_small ? rnd() % 40 : rnd_q();
        x.diffuse[k] = rnd_q(), x.highlight[k] = rnd_q(), x.acc_in[k] = rnd() % 4 ? rnd_q() : 65535 - rnd() % 64;
    }
    x.t_hat = rnd_f24(), x.entering = rnd() & 1u, x.i = rnd() % 4, x.eps = rnd_f24(), x.spawn = rnd() % 4;
    return x;
}

} // namespace

int main(int argc, char **argv)
{
    std::size_t n = 100000;
    std::string capture;
    if (!parse_args(argc, argv, "tb_accum", n, capture))
        return 2;
    std::vector<accum_tx> tx;
    std::size_t captured = 0;
    if (!capture.empty()) {
        bool present;
        if (!read_capture("tb_accum", capture + "/accumulate.hex", tx, present))
            return 2;
        if (!present || tx.empty()) {
            std::printf("tb_accum: %s/accumulate.hex is missing or empty: no ray accumulated?\n", capture.c_str());
            return 2;
        }
        captured = tx.size();
    }
    for (std::size_t k = 0; k < n; k++)
        tx.push_back(random_accum());

    VerilatedContext ctx;
    Vtb_accum top{ &ctx };
    top.rst_ni = 0, top.clk_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;
    std::deque<std::size_t> in_flight;
    std::size_t next = 0, checked = 0, spawned = 0, steps = 0;
    uint64_t mismatches = 0, idle = 0, latency = 0, first_in = 0;
    auto report = [&](std::size_t t, const char *what, const char *field, uint32_t got, uint32_t exp, uint32_t tid) {
        if (mismatches++ < 20)
            std::printf("MISMATCH rgs_accum transaction %zu cycle %llu thread %u %s: rtl %06x, expected %06x (%s)\n", t,
                        (unsigned long long)g_cycle, tid, field, got, exp, what);
    };
    for (; (next < tx.size() || !in_flight.empty()) && idle < 1000; g_cycle++) {
        const bool calm = (g_cycle / 1024) % 2 == 0;
        top.clk_i = 0;
        top.valid_i = next < tx.size() && (calm || rnd() % 3 == 0);
        if (top.valid_i) {
            const accum_tx &x = tx[next];
            top.tid_i = (uint8_t)(next % 64);
            top.eta_i = x.m[0];
            top.kd_i = x.m[1] & 0x1FFFu, top.kr_i = x.m[1] >> 13 & 0x1FFFu;
            top.kt_i = x.m[2] & 0x1FFFu, top.ks_i = x.m[2] >> 13 & 0x1FFFu;
            top.sf_valid_i = x.valid & 1u;
            for (int k = 0; k < 3; k++)
                put(top.o_i, k, x.o[k]), put(top.d_i, k, x.d[k]), put(top.n_i, k, x.n[k]);
            top.t_hat_i = x.t_hat, top.entering_i = x.entering & 1u, top.eps_i = x.eps;
            auto q3 = [](const uint32_t *q) { return (uint64_t)q[0] | (uint64_t)q[1] << 16 | (uint64_t)q[2] << 32; };
            top.base_i = q3(x.base), top.emission_i = q3(x.emis), top.tint_i = q3(x.tint), top.weight_i = q3(x.weight);
            top.diffuse_i = q3(x.diffuse), top.highlight_i = q3(x.highlight), top.acc_i = q3(x.acc_in);
            top.spawn_i = x.spawn & RGS_SPAWN_ON ? 1 : 0, top.live_i = x.spawn & RGS_SPAWN_LIVE ? 1 : 0;
        }
        top.ready_i = calm || rnd() % 4 != 0;
        top.eval();
        const bool in_fire = top.valid_i && top.ready_o, out_fire = top.valid_o && top.ready_i;
        if (out_fire) {
            if (in_flight.empty()) {
                if (mismatches++ < 20)
                    std::printf("MISMATCH rgs_accum cycle %llu: a result nobody asked for\n", (unsigned long long)g_cycle);
            } else {
                const std::size_t t = in_flight.front();
                in_flight.pop_front();
                if (!latency)
                    latency = g_cycle - first_in;
                accum_tx want = tx[t];
                model(want);
                uint32_t got[OUT_WORDS];
                auto q = [](uint64_t v, int k) { return (uint32_t)(v >> (16 * k) & 0xFFFFu); };
                for (int k = 0; k < 3; k++) {
                    got[k] = q(top.acc_o, k);
                    got[3 + k] = get(top.r_o_o, k), got[6 + k] = get(top.r_d_o, k), got[9 + k] = q(top.r_w_o, k);
                    got[13 + k] = get(top.t_o_o, k), got[16 + k] = get(top.t_d_o, k), got[19 + k] = q(top.t_w_o, k);
                }
                got[12] = top.r_active_o, got[22] = top.t_active_o, got[23] = top.steps_o;
                const uint32_t tid = top.tid_o;
                if (tid != t % 64)
                    report(t, "thread id", "tid", tid, (uint32_t)(t % 64), tid);
                const uint32_t *w = reinterpret_cast<const uint32_t *>(&want) + IN_WORDS;
                const uint32_t *c = reinterpret_cast<const uint32_t *>(&tx[t]) + IN_WORDS;
                for (std::size_t k = 0; k < OUT_WORDS; k++) {
                    if (got[k] != w[k])
                        report(t, "C model", OUT_NAME[k], got[k], w[k], tid);
                    if (t < captured && c[k] != w[k])
                        report(t, "capture vs C model", OUT_NAME[k], c[k], w[k], tid);
                }
                checked++;
                spawned += want.r_active | want.t_active;
                steps += want.steps;
            }
        }
        if (in_fire) {
            if (next == 0)
                first_in = g_cycle;
            in_flight.push_back(next++);
        }
        idle = (in_fire || out_fire) ? 0 : idle + 1;
        top.clk_i = 1;
        top.eval();
    }
    const bool lost = next < tx.size() || !in_flight.empty();
    if (lost)
        std::printf("MISMATCH rgs_accum: %zu results missing\n", tx.size() - checked);
    std::printf("rgs_accum %zu rays checked (%zu captured, %zu random; %zu with an active child, %zu with T_R steps), "
                "%llu mismatches, latency %llu cycles\n",
                checked, captured, tx.size() - captured, spawned, steps, (unsigned long long)mismatches,
                (unsigned long long)latency);
    return mismatches || lost ? 1 : 0;
}
