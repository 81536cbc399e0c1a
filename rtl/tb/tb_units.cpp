// Co-simulation of the datapath units (rtl/xform_unit.sv, isect_unit.sv, trav_node.sv) against
// the C model (hls/units: xform_point/xform_vector, isect_unit_triangle, trav_node_split). One
// transaction per unit enters every cycle; every result leaving a unit is compared with the C
// model's result for the inputs that entered `latency` cycles before, and, for captured vectors
// (saarcor render --capture-unit-io DIR: xform.hex, isect.hex, trav.hex), also with the outputs
// recorded while rendering. A mismatch prints the unit, the vector, the cycle and both results;
// exit code 1 on any mismatch.
// usage: tb_units [-n N] [--seed S] [--capture DIR]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vtb_units.h"
#include "tb_common.h"
#include "verilated.h"

extern "C" {
#include "isect_unit.h"
#include "trav_node.h"
#include "xform_unit.h"
}

using namespace cosim;

namespace {

// one transaction of each unit: inputs, and the outputs the C model (or the capture) gives
struct xform_tx { uint32_t m[12], v[3], point, r[3]; };
struct isect_tx { uint32_t o[3], d[3], te, tmin, tmax, shared, hit, t, u, v, cos; };
struct trav_tx { uint32_t axis, split, mask, o[12], d[12], tn[4], tf[4], lmask, rmask, nleft, ltn[4], ltf[4], rtn[4], rtf[4]; };

f24_vec3 v3(const uint32_t *w) { return f24_vec3{ w[0], w[1], w[2] }; }

void model(xform_tx &x)
{
    f24_affine a;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            a.m[r][c] = x.m[4 * r + c];
    const f24_vec3 r = x.point ? xform_point(&a, v3(x.v)) : xform_vector(&a, v3(x.v));
    x.r[0] = r.x, x.r[1] = r.y, x.r[2] = r.z;
}

void model(isect_tx &x)
{
    const isect_result r = isect_unit_triangle(v3(x.o), v3(x.d), x.te, x.tmin, x.tmax, x.shared);
    x.hit = (uint32_t)r.hit, x.t = r.t, x.u = r.u, x.v = r.v, x.cos = r.cos_n;
}

void model(trav_tx &x)
{
    trav_entry e{}, l{}, r{};
    f24_vec3 o[4], d[4];
    e.mask = x.mask;
    for (int i = 0; i < 4; i++) {
        o[i] = v3(&x.o[3 * i]);
        d[i] = v3(&x.d[3 * i]);
        e.tn[i] = x.tn[i];
        e.tf[i] = x.tf[i];
    }
    trav_node_split(&e, x.axis, x.split, o, d, &l, &r, &x.nleft);
    x.lmask = l.mask, x.rmask = r.mask;
    for (int i = 0; i < 4; i++)
        x.ltn[i] = l.tn[i], x.ltf[i] = l.tf[i], x.rtn[i] = r.tn[i], x.rtf[i] = r.tf[i];
}

template <typename T> std::vector<T> random_set(std::size_t n);

template <> std::vector<xform_tx> random_set(std::size_t n)
{
    std::vector<xform_tx> v(n);
    for (auto &x : v) {
        for (auto &w : x.m) w = rnd_f24();
        for (auto &w : x.v) w = rnd_f24();
        x.point = rnd() & 1u;
        model(x);
    }
    return v;
}
template <> std::vector<isect_tx> random_set(std::size_t n)
{
    std::vector<isect_tx> v(n);
    for (auto &x : v) {
        for (auto &w : x.o) w = rnd_f24();
        for (auto &w : x.d) w = rnd_f24();
        x.te = rnd() % 2 ? 0u : rnd_f24() & ~F24_SIGN_BIT;
        x.tmin = rnd() % 4 ? 0u : rnd_f24() & ~F24_SIGN_BIT;
        x.tmax = rnd() % 2 ? F24_POS_INF : rnd_f24() & ~F24_SIGN_BIT;
        x.shared = rnd() & 7u;
        model(x);
    }
    return v;
}
template <> std::vector<trav_tx> random_set(std::size_t n)
{
    std::vector<trav_tx> v(n);
    for (auto &x : v) {
        x.axis = rnd() % 3;
        x.split = rnd_f24();
        x.mask = rnd() & 15u;
        for (auto &w : x.o) w = rnd_f24();
        for (auto &w : x.d) w = rnd() % 16 ? rnd_f24() : (rnd() & 1u) * F24_SIGN_BIT; // zero components too
        for (int i = 0; i < 4; i++) {
            x.tn[i] = rnd() % 4 ? rnd_f24() & ~F24_SIGN_BIT : 0u;
            x.tf[i] = rnd() % 4 ? rnd_f24() & ~F24_SIGN_BIT : F24_POS_INF;
        }
        model(x);
    }
    return v;
}

} // namespace

int main(int argc, char **argv)
{
    std::size_t n = 200000;
    std::string capture;
    if (!parse_args(argc, argv, "tb_units", n, capture))
        return 2;
    std::vector<xform_tx> xs = random_set<xform_tx>(n);
    std::vector<isect_tx> is = random_set<isect_tx>(n);
    std::vector<trav_tx> ts = random_set<trav_tx>(n);
    std::size_t cap_x = 0, cap_i = 0, cap_t = 0;
    if (!capture.empty()) {
        std::vector<xform_tx> cx;
        std::vector<isect_tx> ci;
        std::vector<trav_tx> ct;
        bool px, pi, pt;
        if (!read_capture("tb_units", capture + "/xform.hex", cx, px) || !read_capture("tb_units", capture + "/isect.hex", ci, pi) ||
            !read_capture("tb_units", capture + "/trav.hex", ct, pt))
            return 2;
        if (!px || !pi || !pt || cx.empty() || ci.empty() || ct.empty()) {
            std::printf("tb_units: %s lacks xform.hex, isect.hex or trav.hex vectors\n", capture.c_str());
            return 2;
        }
        cap_x = cx.size(), cap_i = ci.size(), cap_t = ct.size();
        xs.insert(xs.begin(), cx.begin(), cx.end()); // captured first: checked against the recording too
        is.insert(is.begin(), ci.begin(), ci.end());
        ts.insert(ts.begin(), ct.begin(), ct.end());
    }

    // the C model alone on the same transactions, for the speed comparison
    const auto c0 = std::chrono::steady_clock::now();
    uint32_t sink = 0;
    for (std::size_t k = 0; k < xs.size(); k++) {
        xform_tx x = xs[k];
        isect_tx y = is[k % is.size()];
        trav_tx z = ts[k % ts.size()];
        model(x), model(y), model(z);
        sink ^= x.r[0] ^ y.t ^ z.lmask;
    }
    const double c_secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();

    VerilatedContext ctx;
    Vtb_units top{ &ctx };
    std::deque<std::size_t> qx, qi, qt;
    stream_stats sx, si, st;
    top.rst_ni = 0, top.clk_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;
    const std::size_t total = std::max(xs.size(), std::max(is.size(), ts.size()));
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t c = 0; c < total + 128; c++, g_cycle++) {
        top.clk_i = 0;
        top.x_valid_i = c < xs.size();
        if (c < xs.size()) {
            for (int k = 0; k < 12; k++) put(top.x_m_i, k, xs[c].m[k]);
            for (int k = 0; k < 3; k++) put(top.x_v_i, k, xs[c].v[k]);
            top.x_point_i = xs[c].point;
        }
        top.i_valid_i = c < is.size();
        if (c < is.size()) {
            for (int k = 0; k < 3; k++) put(top.i_o_i, k, is[c].o[k]), put(top.i_d_i, k, is[c].d[k]);
            top.i_te_i = is[c].te;
            top.i_tmin_i = is[c].tmin;
            top.i_tmax_i = is[c].tmax;
            top.i_shared_i = is[c].shared;
        }
        top.t_valid_i = c < ts.size();
        if (c < ts.size()) {
            top.t_axis_i = ts[c].axis;
            top.t_split_i = ts[c].split;
            top.t_mask_i = ts[c].mask;
            for (int k = 0; k < 12; k++) put(top.t_o_i, k, ts[c].o[k]), put(top.t_d_i, k, ts[c].d[k]);
            for (int k = 0; k < 4; k++) put(top.t_tn_i, k, ts[c].tn[k]), put(top.t_tf_i, k, ts[c].tf[k]);
        }
        top.eval();
        top.clk_i = 1;
        top.eval();
        if (c < xs.size()) qx.push_back(c), sx.sent++;
        if (c < is.size()) qi.push_back(c), si.sent++;
        if (c < ts.size()) qt.push_back(c), st.sent++;
        if (top.x_valid_o && !qx.empty()) {
            xform_tx got = xs[qx.front()], want = got;
            for (int k = 0; k < 3; k++) got.r[k] = get(top.x_r_o, k);
            model(want);
            compare("xform_unit", sx, want, got, 16, "C model");
            if (qx.front() < cap_x) compare("xform_unit", sx, xs[qx.front()], got, 16, "capture"), sx.vs_capture++;
            qx.pop_front();
        }
        if (top.i_valid_o && !qi.empty()) {
            isect_tx got = is[qi.front()], want = got;
            got.hit = top.i_hit_o, got.t = top.i_t_o, got.u = top.i_u_o, got.v = top.i_v_o, got.cos = top.i_cos_o;
            model(want);
            compare("isect_unit", si, want, got, 10, "C model");
            if (qi.front() < cap_i) compare("isect_unit", si, is[qi.front()], got, 10, "capture"), si.vs_capture++;
            qi.pop_front();
        }
        if (top.t_valid_o && !qt.empty()) {
            trav_tx got = ts[qt.front()], want = got;
            got.lmask = top.t_l_mask_o, got.rmask = top.t_r_mask_o, got.nleft = top.t_near_left_o;
            for (int k = 0; k < 4; k++)
                got.ltn[k] = get(top.t_l_tn_o, k), got.ltf[k] = get(top.t_l_tf_o, k), got.rtn[k] = get(top.t_r_tn_o, k),
                got.rtf[k] = get(top.t_r_tf_o, k);
            model(want);
            compare("trav_node", st, want, got, 35, "C model");
            if (qt.front() < cap_t) compare("trav_node", st, ts[qt.front()], got, 35, "capture"), st.vs_capture++;
            qt.pop_front();
        }
    }
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    top.final();
    const uint64_t lost = qx.size() + qi.size() + qt.size();
    if (lost)
        std::printf("PROTOCOL: %llu transactions never left their unit\n", (unsigned long long)lost);
    std::printf("tb_units e%dm%d: xform %llu (%zu captured), isect %llu (%zu captured), trav %llu (%zu captured) "
                "transactions; %llu mismatches; %.2f s (RTL + check %.2f M transactions/s; C model alone %.2f M/s) [%x]\n",
                F24_EXP_BITS, F24_MAN_BITS, (unsigned long long)sx.sent, cap_x, (unsigned long long)si.sent, cap_i,
                (unsigned long long)st.sent, cap_t, (unsigned long long)(sx.mismatches + si.mismatches + st.mismatches),
                secs, (double)(sx.sent + si.sent + st.sent) / secs / 1e6, 3.0 * (double)xs.size() / c_secs / 1e6,
                sink & 0u);
    return (sx.mismatches + si.mismatches + st.mismatches + lost) ? 1 : 0;
}
