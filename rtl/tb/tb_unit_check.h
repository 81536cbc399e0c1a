// tb_dynrtp's per-unit transaction checks inside the frame (issue 23, goal 2): each unit of the
// DynRTP is watched at its ports (made readable by rtl/tb/tb_dynrtp.vlt, found by name with
// VerilatedScope::varFind): in every cycle the unit takes an operand (its valid and ready), the
// operand's words and thread are recorded with the C unit function's result on them; when a
// result leaves (valid_o; every unit here gives its results in the order it took its operands,
// trace_core and rgs_units take every result at once; trav_unit's and list_unit's of different
// threads may overtake each other) it must equal the oldest recorded one (of its thread), and
// where the unit carries a thread id the result's must be the operand's. The stateful units
// (trav_unit's stacks, list_unit's mailboxes) have their C state kept per thread and level here,
// each operation applied in the order the unit takes it. A mismatch prints the
// unit, its instance, the cycle, the thread, the operands and both results.
// The C functions are those the unit benches use as models (tb_wide.cpp, tb_units.cpp, tb_sum.cpp,
// tb_rgs.cpp, tb_shade.cpp, tb_accum.cpp, tb_surface.cpp, tb_trav.cpp, tb_list.cpp), on the
// recorded operands alone, but those that read the frame's memory image as the RTL does (the
// frame does not write it): rgs_raygen (the camera block), rgs_surface (the instance, object,
// triangle, material and texture records), trav_unit (kd nodes), list_unit (list entries) and the
// caches (cache_read), whose answers are the image's words.
#ifndef SAARCOR_RTL_TB_UNIT_CHECK_H
#define SAARCOR_RTL_TB_UNIT_CHECK_H

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tb_common.h"
#include "verilated.h"
#include "verilated_syms.h"

extern "C" {
#include "isect_unit.h"
#include "list_unit.h"
#include "rebase_unit.h"
#include "rgs.h"
#include "rgs_ops.h"
#include "trav_unit.h"
#include "xform_unit.h"
}

namespace cosim {

using words = std::vector<uint32_t>;

// a public signal of the model (one element of it: the bytes Verilator keeps it in, bit 0 first)
struct signal {
    const uint8_t *p = nullptr;
    uint32_t bytes = 0;
    // bits [lsb, lsb + n) (n <= 32)
    uint32_t bits(uint32_t lsb, uint32_t n) const
    {
        uint64_t v = 0;
        const uint32_t b = lsb / 8, take = std::min<uint32_t>((lsb % 8 + n + 7) / 8, bytes - b);
        std::memcpy(&v, p + b, take);
        return (uint32_t)(v >> lsb % 8) & (n == 32 ? ~0u : (1u << n) - 1);
    }
    uint32_t word(uint32_t i) const { return bits(i * W, W); } // fp24 word i
    uint32_t q12(uint32_t i) const { return bits(i * 16, 16); } // Q12 half-word i
    bool on() const { return bits(0, 1) != 0; }
    signal element(uint32_t i) const { return signal{ p + i * bytes, bytes }; } // of an unpacked array
    void append(words &out, uint32_t n) const // fp24 words 0 .. n - 1
    {
        for (uint32_t i = 0; i < n; i++)
            out.push_back(word(i));
    }
    void append_q12(words &out) const
    {
        for (uint32_t i = 0; i < 3; i++)
            out.push_back(q12(i));
    }
};

// a unit instance's scope: its signals by name; a missing one ends the harness (exit 2: the
// model was built without tb_dynrtp.vlt or the RTL renamed a port)
struct scope {
    std::string path;
    const VerilatedScope *s;
    scope(const VerilatedContext &ctx, const std::string &p) : path(p), s(ctx.scopeFind(("TOP." + p).c_str())) {}
    bool has(const char *name) const { return s && s->varFind(name); }
    signal operator[](const char *name) const
    {
        const VerilatedVar *v = s ? s->varFind(name) : nullptr;
        if (!v) {
            std::printf("tb_dynrtp: the model has no public signal %s.%s (tb_dynrtp.vlt)\n", path.c_str(), name);
            std::exit(2);
        }
        return signal{ static_cast<const uint8_t *>(v->datap()), v->entSize() };
    }
};

// one unit's check: what it takes and gives, read from its ports, and its C function
struct unit_check {
    const char *name;               // in MISMATCH lines and the stats (checked_NAME)
    std::string where;              // the instance
    std::function<bool()> taken, given;  // an operand in, a result out in this cycle
    std::function<uint32_t()> thread_in, thread_out; // thread_out empty: the unit carries no id
    std::function<void(words &)> operands, results;
    // the C's results on the operands; returns how many leading words are defined (the others:
    // any), NONE for an operand without a result (list_unit's clear)
    std::function<std::size_t(const words &, words &)> model;
    static constexpr std::size_t NONE = ~std::size_t{ 0 };
    uint32_t ray_bits = 0;          // the thread id's low bits are the ray in the packet (rgs_units)
    bool by_thread = false;         // results of different threads may overtake each other: a result
                                    // is the oldest operand's of its thread (thread_out)
    bool mutate = false;            // TB_DYNRTP_MUTATE=NAME: flip bit 0 of the C's first result word
    uint64_t checked = 0, mismatches = 0;

    struct pending { uint64_t cycle; uint32_t thread; words ops, want; std::size_t defined; };
    std::deque<pending> q;
    words got;

    // the cycle's transactions (after the cycle's evaluation with the clock low)
    void sample(uint64_t cycle, uint64_t &total_mismatches)
    {
        if (taken()) {
            pending x{ cycle, thread_in ? thread_in() : 0u, {}, {}, 0 };
            operands(x.ops);
            x.defined = model(x.ops, x.want);
            if (x.defined != NONE) {
                if (mutate)
                    x.want[0] ^= 1u;
                q.push_back(std::move(x));
            }
        }
        if (!given())
            return;
        auto x = q.begin();
        if (by_thread)
            for (const uint32_t t = thread_out(); x != q.end() && x->thread != t;)
                ++x;
        if (x == q.end()) {
            report(cycle, nullptr, "a result without an operand", total_mismatches);
            return;
        }
        got.clear();
        results(got);
        const bool same_thread = !thread_out || thread_out() == x->thread;
        checked++;
        if (!same_thread || std::memcmp(got.data(), x->want.data(), x->defined * sizeof(uint32_t)))
            report(cycle, &*x, same_thread ? "" : "the result of another thread", total_mismatches);
        q.erase(x);
    }
    // results still due at the frame's end
    void finish(uint64_t cycle, uint64_t &total_mismatches)
    {
        got.clear();
        for (const pending &x : q)
            report(cycle, &x, "no result by the frame's end", total_mismatches);
        q.clear();
    }
    void report(uint64_t cycle, const pending *x, const char *what, uint64_t &total_mismatches)
    {
        mismatches++;
        if (total_mismatches++ >= 20)
            return;
        std::printf("MISMATCH %s (%s) cycle %llu", name, where.c_str(), (unsigned long long)cycle);
        if (x && thread_in)
            ray_bits ? std::printf(" thread %u ray %u", x->thread >> ray_bits, x->thread & ((1u << ray_bits) - 1))
                     : std::printf(" thread %u", x->thread);
        if (x)
            std::printf(" (operands taken at cycle %llu)", (unsigned long long)x->cycle);
        std::printf("%s%s:\n", *what ? ": " : "", what);
        if (!x)
            return;
        print_words("operands", x->ops.data(), x->ops.size());
        print_words("C", x->want.data(), x->defined);
        if (!got.empty())
            print_words("rtl", got.data(), std::min(got.size(), x->defined));
    }
};

inline f24_vec3 vec3_of(const uint32_t *w) { return f24_vec3{ w[0], w[1], w[2] }; }
inline f24_vec3x2 vec3x2_of(const uint32_t *hi, const uint32_t *lo) { return f24_vec3x2{ vec3_of(hi), vec3_of(lo) }; }
inline void push3(words &out, f24_vec3 v) { out.insert(out.end(), { v.x, v.y, v.z }); }
inline f24_affine affine_of(const uint32_t *m) // 12 words, row r column c at 4 r + c
{
    f24_affine a;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            a.m[r][c] = m[4 * r + c];
    return a;
}

// the handshake of a unit: valid_i and ready_o in, valid_o and ready_i out (those it has)
inline void handshake(unit_check &u, const scope &s)
{
    const signal v = s["valid_i"], o = s["valid_o"];
    const bool ri = s.has("ready_i"), ro = s.has("ready_o");
    const signal r_out = ro ? s["ready_o"] : v, r_in = ri ? s["ready_i"] : o; // without a ready: the valid
    u.taken = [v, r_out] { return v.on() && r_out.on(); };
    u.given = [o, r_in] { return o.on() && r_in.on(); };
}

// ---- trace_core's per-ray units (they carry the issued thread beside their pipelines in
// trace_core: the thread is the scheduler's pick of the cycle before the step, sel_prev) ----

inline unit_check rebase_check(const VerilatedContext &ctx, const std::string &core, const uint32_t &thread)
{
    const scope s(ctx, core + ".u_rebase");
    unit_check u{ "rebase", s.path };
    handshake(u, s);
    u.thread_in = [&thread] { return thread; };
    const signal oh = s["o_hi_i"], ol = s["o_lo_i"], dh = s["d_hi_i"], dl = s["d_lo_i"], t = s["t_i"];
    const signal ph = s["p_hi_o"], pl = s["p_lo_o"], te = s["te_o"];
    u.operands = [=](words &w) { oh.append(w, 3), ol.append(w, 3), dh.append(w, 3), dl.append(w, 3), t.append(w, 1); };
    u.results = [=](words &w) { ph.append(w, 3), pl.append(w, 3), te.append(w, 1); };
    u.model = [](const words &x, words &w) {
        const f24_vec3x2 p = rebase_origin(vec3x2_of(&x[0], &x[3]), vec3x2_of(&x[6], &x[9]), x[12]);
        push3(w, p.hi), push3(w, p.lo), w.push_back(rebase_distance(x[12]));
        return w.size();
    };
    return u;
}

inline unit_check wide_check(const VerilatedContext &ctx, const std::string &core, const uint32_t &thread)
{
    const scope s(ctx, core + ".u_wide");
    unit_check u{ "wide", s.path };
    handshake(u, s);
    u.thread_in = [&thread] { return thread; };
    const signal m = s["m_i"], tlo = s["tlo_i"], ph = s["p_hi_i"], pl = s["p_lo_i"], pt = s["point_i"];
    const signal rh = s["r_hi_o"], rl = s["r_lo_o"];
    u.operands = [=](words &w) { m.append(w, 12), tlo.append(w, 3), ph.append(w, 3), pl.append(w, 3), w.push_back(pt.on()); };
    u.results = [=](words &w) { rh.append(w, 3), rl.append(w, 3); };
    u.model = [](const words &x, words &w) {
        const f24_affine a = affine_of(&x[0]);
        const f24_vec3x2 r = x[21] ? xform_point_wide(&a, vec3_of(&x[12]), vec3x2_of(&x[15], &x[18]))
                                   : xform_vector_wide(&a, vec3_of(&x[15]));
        push3(w, r.hi), push3(w, r.lo);
        return w.size();
    };
    return u;
}

// the triangle test and t0 + t (trace.c's op_tri_isect); of a miss only the hit flag is defined
// (isect_unit_rebased computes a missing ray's z rows alone)
inline unit_check isect_check(const VerilatedContext &ctx, const std::string &core, const uint32_t &thread)
{
    const scope s(ctx, core + ".u_isect");
    unit_check u{ "isect", s.path };
    handshake(u, s);
    u.thread_in = [&thread] { return thread; };
    const signal m = s["m_i"], clo = s["c_lo_i"], sh = s["shared_i"], ph = s["p_hi_i"], pl = s["p_lo_i"], d = s["d_i"];
    const signal te = s["te_i"], tmin = s["tmin_i"], tmax = s["tmax_i"], t0 = s["t0_i"];
    const signal hit = s["hit_o"], t = s["t_o"], uu = s["u_o"], v = s["v_o"], cs = s["cos_o"], tw = s["t_world_o"];
    u.operands = [=](words &w) {
        m.append(w, 12), clo.append(w, 3), w.push_back(sh.bits(0, 3)), ph.append(w, 3), pl.append(w, 3), d.append(w, 3);
        te.append(w, 1), tmin.append(w, 1), tmax.append(w, 1), t0.append(w, 1);
    };
    u.results = [=](words &w) { w.insert(w.end(), { hit.on(), t.word(0), uu.word(0), v.word(0), cs.word(0), tw.word(0) }); };
    u.model = [](const words &x, words &w) {
        const f24_triangle tri = { affine_of(&x[0]), vec3_of(&x[12]), x[15] };
        const isect_result r = isect_unit_rebased(&tri, vec3x2_of(&x[16], &x[19]), x[25], vec3_of(&x[22]), x[26], x[27]);
        w.insert(w.end(), { (uint32_t)r.hit, r.t, r.u, r.v, r.cos_n, f24_add(x[28], r.t) });
        return r.hit ? w.size() : std::size_t{ 1 };
    };
    return u;
}

// the two adders of the relative distances (op_inst_xform's best_t - t0, tmin - t0), watched in
// trace_core's names: step_q (declared [UNITS-1:U_RB]: bit U_ADD - U_RB), add_a, add_t0, add_r
inline unit_check add_check(const VerilatedContext &ctx, const std::string &core, const uint32_t &thread)
{
    constexpr uint32_t U_RB = 2, U_ADD = 5;
    const scope s(ctx, core);
    unit_check u{ "add", s.path + ".g_add" };
    const signal step = s["step_q"], a = s["add_a"], t0 = s["add_t0"], valid = s["add_valid"], r = s["add_r"];
    u.taken = [step] { return step.bits(U_ADD - U_RB, 1) != 0; };
    u.given = [valid] { return valid.bits(0, 2) == 3u; };
    u.thread_in = [&thread] { return thread; };
    u.operands = [=](words &w) { a.append(w, 2), t0.append(w, 1); };
    u.results = [=](words &w) { r.append(w, 2); };
    u.model = [](const words &x, words &w) {
        w.insert(w.end(), { f24_sub(x[0], x[2]), f24_sub(x[1], x[2]) });
        return w.size();
    };
    return u;
}

// ---- rgs_units' shared datapaths (their thread id: {controller, ray}) ----

inline void rgs_ids(unit_check &u, const scope &s)
{
    const signal ti = s["tid_i"], to = s["tid_o"];
    u.thread_in = [ti] { return ti.bits(0, 32); };
    u.thread_out = [to] { return to.bits(0, 32); };
    u.ray_bits = 2;
}

// rgs_primary on the block's corner, from the memory image's camera block (rgs_raygen's camera:
// rgs_units loads it from the same words); the block's controller travels in rgs_units' FIFO
inline unit_check raygen_check(const VerilatedContext &ctx, const std::string &units, const std::vector<uint32_t> &mem)
{
    const scope s(ctx, units + ".u_gen");
    unit_check u{ "raygen", s.path };
    const signal bv = s["blk_valid_i"], br = s["blk_ready_o"], bx = s["blk_x_i"], by = s["blk_y_i"];
    const signal pv = s["pkt_valid_o"], pr = s["pkt_ready_i"], act = s["pkt_active_o"], o = s["pkt_o_o"], d = s["pkt_d_o"];
    const signal tmin = s["pkt_tmin_o"], tmax = s["pkt_tmax_o"];
    u.taken = [bv, br] { return bv.on() && br.on(); };
    u.given = [pv, pr] { return pv.on() && pr.on(); };
    u.operands = [=](words &w) { w.insert(w.end(), { bx.bits(0, 32), by.bits(0, 32) }); };
    u.results = [=](words &w) {
        w.push_back(act.bits(0, 4)), o.append(w, 12), d.append(w, 12), tmin.append(w, 4), tmax.append(w, 4);
    };
    u.model = [&mem](const words &x, words &w) {
        ray_packet rp;
        rgs_primary(mem.data(), x[0], x[1], &rp);
        w.push_back(rp.active);
        for (const f24_vec3 *v : { rp.o, rp.d })
            for (int i = 0; i < 4; i++)
                push3(w, v[i]);
        w.insert(w.end(), rp.tmin, rp.tmin + 4), w.insert(w.end(), rp.tmax, rp.tmax + 4);
        return w.size();
    };
    return u;
}

// rgs_surface_at on the ray and its hit, reading the memory image (tb_surface.cpp's model); the
// material's fields as the surface decodes them for the accumulation
inline unit_check surface_check(const VerilatedContext &ctx, const std::string &path, const std::vector<uint32_t> &mem)
{
    const scope s(ctx, path);
    unit_check u{ "surface", s.path };
    handshake(u, s);
    rgs_ids(u, s);
    const signal act = s["active_i"], o = s["o_i"], d = s["d_i"], inst = s["inst_i"], tri = s["tri_i"], t = s["t_i"];
    const signal uu = s["u_i"], v = s["v_i"], cs = s["cos_n_i"];
    const signal sv = s["sf_valid_o"], p = s["p_o"], dd = s["d_o"], n = s["n_o"], th = s["t_hat_o"], ent = s["entering_o"];
    const signal mat = s["mat_o"], unlit = s["unlit_o"], k = s["k_o"], eta = s["eta_o"], kd = s["kd_o"], kr = s["kr_o"];
    const signal kt = s["kt_o"], ks = s["ks_o"], base = s["base_o"], emis = s["emission_o"], tint = s["tint_o"];
    u.operands = [=](words &w) {
        w.push_back(act.on()), o.append(w, 3), d.append(w, 3), w.insert(w.end(), { inst.bits(0, 32), tri.bits(0, 32) });
        t.append(w, 1), uu.append(w, 1), v.append(w, 1), cs.append(w, 1);
    };
    u.results = [=](words &w) {
        w.push_back(sv.on()), p.append(w, 3), dd.append(w, 3), n.append(w, 3), th.append(w, 1);
        w.insert(w.end(), { ent.on(), mat.bits(0, 32), unlit.on() });
        base.append_q12(w), emis.append_q12(w), tint.append_q12(w);
        w.insert(w.end(), { k.bits(0, 4), eta.word(0), kd.bits(0, 13), kr.bits(0, 13), kt.bits(0, 13), ks.bits(0, 13) });
    };
    u.model = [&mem](const words &x, words &w) {
        ray_packet rp{};
        rp.active = x[0];
        rp.o[0] = vec3_of(&x[1]), rp.d[0] = vec3_of(&x[4]);
        const hit_record h = { x[7], x[8], x[9], x[10], x[11], x[12] };
        unit_op op{};
        trace_counters c{};
        const surface sf = rgs_surface_at(mem.data(), &rp, 0, &h, &op, &c);
        w.push_back((uint32_t)sf.valid), push3(w, sf.p), push3(w, sf.d), push3(w, sf.n), w.push_back(sf.t_hat);
        w.insert(w.end(), { (uint32_t)sf.entering, sf.mat, (uint32_t)sf.unlit });
        for (const uint32_t *q : { sf.base, sf.emission, sf.tint })
            w.insert(w.end(), q, q + 3);
        const uint32_t *m = &mem[sf.mat];
        w.insert(w.end(), { sf.valid ? rgs_mat_k(m) : 0u, sf.valid ? m[M_ETA] & F24_MASK : 0u,
                            sf.valid ? m[M_SHADER0] & 0x1FFFu : 0u, sf.valid ? m[M_SHADER0] >> 13 & 0x1FFFu : 0u,
                            sf.valid ? m[M_SHADER1] & 0x1FFFu : 0u, sf.valid ? m[M_SHADER1] >> 13 & 0x1FFFu : 0u });
        return w.size();
    };
    return u;
}

// rgs_light_packet on a packet of this surface (tb_shade.cpp's model): the light record's words the
// unit takes (0, 4..9, 11, 12), the others 0
inline unit_check light_check(const VerilatedContext &ctx, const std::string &units)
{
    const scope s(ctx, units + ".u_light");
    unit_check u{ "light", s.path };
    handshake(u, s);
    rgs_ids(u, s);
    const signal ty = s["type_i"], lp = s["lpos_i"], ld = s["ldir_i"], ci = s["cos_in_i"], co = s["cos_out_i"];
    const signal eps = s["eps_i"], sv = s["sf_valid_i"], ul = s["unlit_i"], p = s["p_i"], n = s["n_i"], d = s["d_i"];
    const signal k = s["k_i"];
    const signal o_o = s["o_o"], d_o = s["d_o"], tmin = s["tmin_o"], tmax = s["tmax_o"], act = s["active_o"];
    const signal diff = s["diff_o"], spec = s["spec_o"];
    u.operands = [=](words &w) {
        w.push_back(ty.bits(0, 32)), lp.append(w, 3), ld.append(w, 3), ci.append(w, 1), co.append(w, 1), eps.append(w, 1);
        w.insert(w.end(), { sv.on(), ul.on() }), p.append(w, 3), n.append(w, 3), d.append(w, 3), w.push_back(k.bits(0, 4));
    };
    u.results = [=](words &w) {
        o_o.append(w, 3), d_o.append(w, 3), tmin.append(w, 1), tmax.append(w, 1);
        w.insert(w.end(), { act.on(), diff.bits(0, 16), spec.bits(0, 16) });
    };
    u.model = [](const words &x, words &w) {
        uint32_t l[16] = {};
        l[0] = x[0];
        std::memcpy(&l[4], &x[1], 6 * sizeof(uint32_t));
        l[11] = x[7], l[12] = x[8];
        surface sf[TRACE_PACKET] = {};
        sf[0].valid = (int)x[10], sf[0].unlit = (int)x[11];
        sf[0].p = vec3_of(&x[12]), sf[0].n = vec3_of(&x[15]), sf[0].d = vec3_of(&x[18]);
        const uint32_t k_of[TRACE_PACKET] = { x[21], 0, 0, 0 };
        ray_packet sh;
        uint32_t diff[TRACE_PACKET], spec[TRACE_PACKET];
        rgs_light_packet(l, sf, x[9], &sh, diff, spec, k_of);
        push3(w, sh.o[0]), push3(w, sh.d[0]);
        w.insert(w.end(), { sh.tmin[0], sh.tmax[0], sh.active & 1u, diff[0], spec[0] });
        return w.size();
    };
    return u;
}

inline unit_check colour_check(const VerilatedContext &ctx, const std::string &units)
{
    const scope s(ctx, units + ".u_colour");
    unit_check u{ "colour", s.path };
    handshake(u, s);
    const signal ti = s["tid_i"], to = s["tid_o"], c = s["colour_i"], q = s["q_o"];
    u.thread_in = [ti] { return ti.bits(0, 32); }; // the controller alone
    u.thread_out = [to] { return to.bits(0, 32); };
    u.operands = [c](words &w) { c.append(w, 3); };
    u.results = [q](words &w) { q.append_q12(w); };
    u.model = [](const words &x, words &w) {
        const uint32_t l[4] = { 0, x[0], x[1], x[2] };
        w.resize(3);
        rgs_light_colour(l, w.data());
        return w.size();
    };
    return u;
}

inline unit_check add_light_check(const VerilatedContext &ctx, const std::string &units)
{
    const scope s(ctx, units + ".u_add");
    unit_check u{ "add_light", s.path };
    handshake(u, s);
    rgs_ids(u, s);
    const signal di = s["diffuse_i"], hi = s["highlight_i"], df = s["diff_i"], sp = s["spec_i"], c = s["colour_i"];
    const signal dout = s["diffuse_o"], hout = s["highlight_o"];
    u.operands = [=](words &w) {
        di.append_q12(w), hi.append_q12(w), w.insert(w.end(), { df.bits(0, 16), sp.bits(0, 16) }), c.append_q12(w);
    };
    u.results = [=](words &w) { dout.append_q12(w), hout.append_q12(w); };
    u.model = [](const words &x, words &w) {
        w.assign(x.begin(), x.begin() + 6);
        rgs_add_light(&w[0], &w[3], x[6], x[7], &x[8]);
        return w.size();
    };
    return u;
}

// rgs_accumulate_ray (tb_accum.cpp's model): the material's words 13..15 from the unit's fields,
// the ray's index in its packet from the thread id, spawn from spawn_i and live_i
inline unit_check accum_check(const VerilatedContext &ctx, const std::string &units)
{
    const scope s(ctx, units + ".u_accum");
    unit_check u{ "accum", s.path };
    handshake(u, s);
    rgs_ids(u, s);
    const signal ti = s["tid_i"], eta = s["eta_i"], kd = s["kd_i"], kr = s["kr_i"], kt = s["kt_i"], ks = s["ks_i"];
    const signal sv = s["sf_valid_i"], o = s["o_i"], d = s["d_i"], n = s["n_i"], th = s["t_hat_i"], ent = s["entering_i"];
    const signal q12s[7] = { s["base_i"], s["emission_i"], s["tint_i"], s["weight_i"], s["diffuse_i"], s["highlight_i"],
                             s["acc_i"] };
    const signal eps = s["eps_i"], spawn = s["spawn_i"], live = s["live_i"];
    const signal acc = s["acc_o"], ro = s["r_o_o"], rd = s["r_d_o"], rw = s["r_w_o"], ra = s["r_active_o"];
    const signal to = s["t_o_o"], td = s["t_d_o"], tw = s["t_w_o"], ta = s["t_active_o"], steps = s["steps_o"];
    // operand words: 0 eta, 1..4 kd kr kt ks, 5 sf_valid, 6 o, 9 d, 12 n, 15 t_hat, 16 entering,
    // 17 + 3 j the Q12 triples (base, emission, tint, weight, diffuse, highlight, acc), 38 eps,
    // 39 spawn (RGS_SPAWN_*), 40 the ray
    u.operands = [=](words &w) {
        eta.append(w, 1), w.insert(w.end(), { kd.bits(0, 13), kr.bits(0, 13), kt.bits(0, 13), ks.bits(0, 13), sv.on() });
        o.append(w, 3), d.append(w, 3), n.append(w, 3), th.append(w, 1), w.push_back(ent.on());
        for (const signal &q : q12s)
            q.append_q12(w);
        eps.append(w, 1);
        w.push_back((spawn.on() ? RGS_SPAWN_ON : 0u) | (live.on() ? RGS_SPAWN_LIVE : 0u));
        w.push_back(ti.bits(0, 2));
    };
    u.results = [=](words &w) {
        acc.append_q12(w), ro.append(w, 3), rd.append(w, 3), rw.append_q12(w), w.push_back(ra.on());
        to.append(w, 3), td.append(w, 3), tw.append_q12(w), w.push_back(ta.on()), w.push_back(steps.on());
    };
    u.model = [](const words &x, words &w) {
        uint32_t m[16] = {};
        m[M_ETA] = x[0], m[M_SHADER0] = x[1] | x[2] << 13, m[M_SHADER1] = x[3] | x[4] << 13;
        surface sf{};
        sf.valid = (int)x[5], sf.d = vec3_of(&x[9]), sf.n = vec3_of(&x[12]);
        sf.tr = t_r(vec3_of(&x[6]), sf.d, sf.n);
        sf.t_hat = x[15], sf.entering = (int)x[16];
        std::memcpy(sf.base, &x[17], sizeof sf.base), std::memcpy(sf.emission, &x[20], sizeof sf.emission);
        std::memcpy(sf.tint, &x[23], sizeof sf.tint);
        uint32_t acc[3] = { x[35], x[36], x[37] };
        static rgs_task refl, trans;
        std::memset(&refl, 0, sizeof refl), std::memset(&trans, 0, sizeof trans);
        const int i = (int)x[40];
        const int steps = rgs_accumulate_ray(m, &sf, i, &x[26], &x[29], &x[32], x[38], x[39], acc, &refl, &trans);
        w.insert(w.end(), acc, acc + 3), push3(w, refl.rays.o[i]), push3(w, refl.rays.d[i]);
        w.insert(w.end(), refl.weight[i], refl.weight[i] + 3), w.push_back(refl.rays.active >> i & 1u);
        push3(w, trans.rays.o[i]), push3(w, trans.rays.d[i]);
        w.insert(w.end(), trans.weight[i], trans.weight[i] + 3), w.push_back(trans.rays.active >> i & 1u);
        w.push_back((uint32_t)steps);
        return w.size();
    };
    return u;
}

// ---- list_unit: its mailboxes per thread and level are state, so the C unit's mailboxes are kept
// here per thread and level and each operation is applied to them in the order the unit takes it
// (tb_list.cpp's model; the mailboxes start empty, and a packet's thread clears them before its
// first list); a clear has no result. The entry is read from the memory image (the list cache's
// answer, checked as cache_lists). ----
inline unit_check list_check(const VerilatedContext &ctx, const std::string &core, const std::vector<uint32_t> &mem)
{
    const scope s(ctx, core + ".u_list");
    unit_check u{ "list", s.path };
    handshake(u, s);
    u.by_thread = true;
    const signal ti = s["thread_i"], lv = s["level_i"], clr = s["clear_i"], lists = s["lists_i"], first = s["first_i"];
    const signal k = s["k_i"], lm = s["leaf_mask_i"], alive = s["alive_i"];
    const signal to = s["thread_o"], lo = s["level_o"], key = s["key_o"], need = s["need_o"], skip = s["skip_o"];
    const signal ko = s["k_o"];
    u.thread_in = [ti] { return ti.bits(0, 32); };
    u.thread_out = [to] { return to.bits(0, 32); };
    u.operands = [=](words &w) {
        w.insert(w.end(), { ti.bits(0, 32), lv.bits(0, 1), clr.bits(0, 1), lists.bits(0, 32), first.bits(0, 32), k.bits(0, 32),
                            lm.bits(0, 4), alive.bits(0, 4) });
    };
    u.results = [=](words &w) {
        w.insert(w.end(), { to.bits(0, 32), lo.bits(0, 1), key.bits(0, 32), need.bits(0, 4), skip.bits(0, 4), ko.bits(0, 32) });
    };
    constexpr uint32_t THREADS = 256; // thread ids of at most 8 bits, as the harness's packets
    auto box = std::make_shared<std::vector<trace_mailbox>>(2 * THREADS * TRACE_PACKET);
    for (uint32_t b = 0; b < 2 * THREADS; b++)
        list_mailboxes_clear(&(*box)[b * TRACE_PACKET]);
    u.model = [&mem, box](const words &x, words &w) {
        trace_mailbox *b = &(*box)[(2 * x[0] + x[1]) * TRACE_PACKET];
        if (x[2]) {
            list_mailboxes_clear(b);
            return unit_check::NONE;
        }
        trav_walker tw{};
        tw.lists = x[3], tw.leaf_first = x[4], tw.k = x[5], tw.leaf_mask = x[6];
        unit_op op{};
        trace_counters c{};
        uint32_t key = 0;
        const uint32_t need = list_unit_entry(mem.data(), &tw, b, x[7], &key, &op, &c);
        w.insert(w.end(), { x[0], x[1], key, need, x[6] & x[7] & ~need, tw.k });
        return w.size();
    };
    return u;
}

// ---- trav_unit: its walkers (stacks) per thread and level are state, kept here as the C unit's
// per thread and level, each operation applied in the order the unit takes it (tb_trav.cpp's
// model, TRAV_STACK); the nodes are read from the memory image (the node cache's answers, checked
// as cache_nodes). A result's words: mask, tn, tf (the clips' alone), have_cur, sp, node, lost,
// restarted (start and walk), leaf, list (a walk), leaf_first, leaf_count, leaf_mask, leaf_tn (a
// walk that reached a leaf). ----
inline unit_check trav_check(const VerilatedContext &ctx, const std::string &core, const std::vector<uint32_t> &mem)
{
    const scope s(ctx, core + ".u_trav");
    unit_check u{ "trav", s.path };
    handshake(u, s);
    u.by_thread = true;
    const signal ti = s["thread_i"], lv = s["level_i"], kind = s["kind_i"], o = s["o_i"], d = s["d_i"], tn = s["tn_i"];
    const signal tf = s["tf_i"], best = s["best_i"], mask = s["mask_i"], box = s["box_i"], nodes = s["nodes_i"];
    const signal to = s["thread_o"], mo = s["mask_o"], tno = s["tn_o"], tfo = s["tf_o"], hc = s["have_cur_o"];
    const signal sp = s["sp_o"], node = s["node_o"], lost = s["lost_o"], rs = s["restarted_o"], leaf = s["leaf_o"];
    const signal list = s["list_o"], lf = s["leaf_first_o"], lc = s["leaf_count_o"], lm = s["leaf_mask_o"];
    const signal ltn = s["leaf_tn_o"];
    u.thread_in = [ti] { return ti.bits(0, 32); };
    u.thread_out = [to] { return to.bits(0, 32); };
    // operand words: 0 thread, 1 level, 2 kind, 3 o, 15 d, 27 tn, 31 tf, 35 best, 39 mask, 40 box, 46 nodes
    u.operands = [=](words &w) {
        w.insert(w.end(), { ti.bits(0, 32), lv.bits(0, 1), kind.bits(0, 2) });
        o.append(w, 12), d.append(w, 12), tn.append(w, 4), tf.append(w, 4), best.append(w, 4);
        w.push_back(mask.bits(0, 4)), box.append(w, 6), w.push_back(nodes.bits(0, 32));
    };
    u.results = [=](words &w) {
        w.push_back(mo.bits(0, 4)), tno.append(w, 4), tfo.append(w, 4);
        w.insert(w.end(), { hc.on(), sp.bits(0, 32), node.bits(0, 32), lost.on(), rs.on(), leaf.on(), list.on(),
                            lf.bits(0, 32), lc.bits(0, 32), lm.bits(0, 4) });
        ltn.append(w, 4);
    };
    constexpr uint32_t THREADS = 256; // thread ids of at most 8 bits, as the harness's packets
    auto walkers = std::make_shared<std::vector<trav_walker>>(2 * THREADS);
    u.model = [&mem, walkers](const words &x, words &w) {
        f24_vec3 ov[TRACE_PACKET], dv[TRACE_PACKET];
        for (int i = 0; i < TRACE_PACKET; i++)
            ov[i] = vec3_of(&x[3 + 3 * i]), dv[i] = vec3_of(&x[15 + 3 * i]);
        const uint32_t kind = x[2], msk = x[39], *box = &x[40];
        f24_t tn[TRACE_PACKET], tf[TRACE_PACKET];
        if (kind <= 1) {
            ray_packet rp{};
            std::memcpy(rp.o, ov, sizeof rp.o), std::memcpy(rp.d, dv, sizeof rp.d);
            std::memcpy(rp.tmin, &x[27], sizeof rp.tmin), std::memcpy(rp.tmax, &x[31], sizeof rp.tmax);
            rp.active = msk;
            w.push_back(kind == 0 ? trav_scene_clip(box, &rp, tn, tf) : trav_object_clip(box, ov, dv, &x[27], &x[31], msk, tn, tf));
            w.insert(w.end(), tn, tn + 4), w.insert(w.end(), tf, tf + 4);
            return w.size();
        }
        trav_walker &tw = (*walkers)[2 * x[0] + x[1]];
        unit_op op{};
        trace_counters c{};
        uint32_t list = 0;
        if (kind == 2)
            trav_start(&tw, mem.data(), TRAV_STACK, 0, x[46], 0, TRACE_NO_HIT, msk, &x[27], &x[31], ov, dv, &op, &c);
        else
            list = (uint32_t)trav_walk(&tw, mem.data(), ov, dv, &x[35], msk, &op, &c);
        uint32_t held[3][TRACE_PACKET]; // the held values' words (f24_held.h), as tb_trav.cpp reads them
        std::memcpy(held[0], &tw.cur.tn, sizeof held[0]), std::memcpy(held[1], &tw.cur.tf, sizeof held[1]);
        std::memcpy(held[2], &tw.leaf_tn, sizeof held[2]);
        w.push_back(tw.cur.mask), w.insert(w.end(), held[0], held[0] + 4), w.insert(w.end(), held[1], held[1] + 4);
        w.insert(w.end(), { tw.have_cur, tw.sp, tw.cur.node, tw.lost, tw.pass != 0 });
        if (kind == 2)
            return w.size();
        w.insert(w.end(), { c.leaves != 0, list, tw.leaf_first, tw.leaf_count, tw.leaf_mask });
        w.insert(w.end(), held[2], held[2] + 4);
        return c.leaves ? w.size() : w.size() - 8;
    };
    return u;
}

// ---- the caches (cache_read): a read's answer, in request order, is the WORDS memory words from
// its word address (tb/cycle/mem_iface.c's mem_iface_read; words beyond the image read as 0, as
// the harness's memory answers them): a function of the memory image, which the frame does not write ----
inline unit_check cache_check(const VerilatedContext &ctx, const std::string &path, const char *name,
                              const std::vector<uint32_t> &mem)
{
    const scope s(ctx, path);
    unit_check u{ name, s.path };
    const signal v = s["req_valid_i"], r = s["req_ready_o"], a = s["req_addr_i"], o = s["rsp_valid_o"];
    const signal d = s["rsp_data_o"];
    const uint32_t n = d.bytes / 4; // WORDS
    u.taken = [v, r] { return v.on() && r.on(); };
    u.given = [o] { return o.on(); };
    u.operands = [a](words &w) { w.push_back(a.bits(0, 32)); };
    u.results = [d, n](words &w) {
        for (uint32_t j = 0; j < n; j++)
            w.push_back(d.bits(32 * j, 32));
    };
    u.model = [&mem, n](const words &x, words &w) {
        for (uint32_t j = 0; j < n; j++)
            w.push_back((uint64_t)x[0] + j < mem.size() ? mem[x[0] + j] : 0u);
        return w.size();
    };
    return u;
}

} // namespace cosim

#endif
