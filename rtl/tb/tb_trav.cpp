// Co-simulation of the traversal unit (rtl/trav_unit.sv) against the C unit (hls/units/trav_unit.c:
// trav_scene_clip, trav_object_clip, trav_start, trav_walk with the algorithm TRAV_STACK,
// trav_stack.c, trav_restart.c). The bench is the unit's kd-node memory (read requests answered
// in order, 1 to 4 cycles later, with the two words at the address) and keeps the C walkers per
// thread and level; every operation the RTL accepts is applied to the C unit in the same order
// (the captured ones offered in their order per thread: the oldest first whose thread has
// nothing in flight), and every result leaving the RTL (matched by thread and level: results of
// different threads may overtake each other) is compared field by field with the C unit's
// (clip: mask, tn, tf; start and walk: the walker state after: have_cur, sp, the current entry's
// node, mask, tn, tf, lost, restarted; walk: the node address read, leaf, list, and at a leaf its
// first entry, count, mask, tn) and, for captured operations (saarcor render --capture-unit-io
// DIR: DIR/trav_unit.hex), with the results recorded while rendering. Random operations follow:
// walks over random kd-trees (child links anywhere) and a chain of inner nodes whose every far
// child is pushed (the stacks of 64 overflow, drop their oldest entries and restart), random
// closest hits and alive masks, random clips, with random gaps at the input, back pressure at the
// output and memory latency.
// A mismatch prints the unit, the operation, its kind, the cycle, thread, level, the field and
// both values; exit code 1 (the bench stops after 20 mismatches).
// usage: tb_trav [-n N] [--seed S] [--capture DIR]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vtb_trav.h"
#include "verilated.h"

extern "C" {
#include "f24.h"
#include "trav_unit.h"
}

namespace {

constexpr uint32_t THREADS = 64, W = 1 + F24_EXP_BITS + F24_MAN_BITS, NONE = 0xFFFFFFFFu;
const char *const KIND[4] = { "scene clip", "object clip", "start", "walk" };

struct op {
    uint32_t kind, thread, level, box[6], o[12], d[12], tn[4], tf[4], best[4], mask, nodes, algo, read[3];
    bool captured;
};

// a result: the RTL's outputs, the C unit's, the recording's
struct result {
    uint32_t ret, have_cur, leaf, leaf_first, leaf_count, leaf_mask, leaf_tn[4], sp, node, mask, tn[4], tf[4], lost,
        restarted, addr;
};

uint64_t g_rng = 1;
uint32_t rnd() { g_rng ^= g_rng << 13, g_rng ^= g_rng >> 7, g_rng ^= g_rng << 17; return (uint32_t)(g_rng >> 11); }

std::vector<uint32_t> g_mem;
trav_walker g_w[THREADS][2];
uint64_t g_cycle = 0, g_mismatches = 0;

void put_mem(uint32_t a, uint32_t v)
{
    if (a >= g_mem.size())
        g_mem.resize((std::size_t)a + 1, 0xDEADBEEFu);
    g_mem[a] = v;
}
uint32_t mem_at(uint32_t a) { return a < g_mem.size() ? g_mem[a] : 0xDEADBEEFu; }

void vecs(const uint32_t w[12], f24_vec3 v[TRACE_PACKET])
{
    for (int i = 0; i < TRACE_PACKET; i++)
        v[i] = f24_vec3{ w[3 * i], w[3 * i + 1], w[3 * i + 2] };
}

void walker_result(const trav_walker &w, result &r)
{
    r.have_cur = w.have_cur, r.sp = w.sp, r.node = w.cur.node, r.mask = w.cur.mask, r.lost = w.lost;
    r.restarted = w.pass != 0, r.leaf_first = w.leaf_first, r.leaf_count = w.leaf_count, r.leaf_mask = w.leaf_mask;
    std::memcpy(r.tn, w.cur.tn, sizeof r.tn);
    std::memcpy(r.tf, w.cur.tf, sizeof r.tf);
    std::memcpy(r.leaf_tn, w.leaf_tn, sizeof r.leaf_tn);
}

// the C unit on one accepted operation
result model(const op &o)
{
    result r{};
    r.addr = NONE;
    f24_vec3 ov[TRACE_PACKET], dv[TRACE_PACKET];
    vecs(o.o, ov);
    vecs(o.d, dv);
    unit_op u{};
    trace_counters c{};
    if (o.kind <= 1) {
        if (o.kind == 0) {
            ray_packet rp{};
            std::memcpy(rp.o, ov, sizeof rp.o);
            std::memcpy(rp.d, dv, sizeof rp.d);
            std::memcpy(rp.tmin, o.tn, sizeof rp.tmin);
            std::memcpy(rp.tmax, o.tf, sizeof rp.tmax);
            rp.active = o.mask;
            r.ret = trav_scene_clip(o.box, &rp, r.tn, r.tf);
        } else {
            r.ret = trav_object_clip(o.box, ov, dv, o.tn, o.tf, o.mask, r.tn, r.tf);
        }
        r.mask = r.ret;
        return r;
    }
    trav_walker &w = g_w[o.thread][o.level];
    if (o.kind == 2) {
        trav_start(&w, g_mem.data(), TRAV_STACK, 0, o.nodes, 0, TRACE_NO_HIT, o.mask, o.tn, o.tf, ov, dv, &u, &c);
    } else {
        if (o.read[0] != NONE) { // the node as the operation saw it (the image may change between frames)
            put_mem(o.read[0], o.read[1]);
            put_mem(o.read[0] + 1, o.read[2]);
        }
        r.ret = (uint32_t)trav_walk(&w, g_mem.data(), ov, dv, o.best, o.mask, &u, &c);
        r.leaf = c.leaves != 0;
        for (uint32_t k = 0; k < u.n_reads; k++)
            if (u.read[k].kind == MEM_NODES)
                r.addr = u.read[k].addr;
    }
    walker_result(w, r);
    return r;
}

// compares the fields an operation of this kind defines; prints the mismatches
bool compare(const char *what, std::size_t index, const op &o, const result &a, const result &b, const char *an,
             const char *bn)
{
    bool ok = true;
    auto field = [&](const char *name, uint32_t x, uint32_t y) {
        if (x == y)
            return;
        ok = false;
        if (g_mismatches++ < 20)
            std::printf("MISMATCH trav_unit (%s) operation %zu (%s, %s) cycle %llu thread %u level %u: %s %s %x, %s %x\n",
                        what, index, o.captured ? "captured" : "random", KIND[o.kind], (unsigned long long)g_cycle,
                        o.thread, o.level, name, an, x, bn, y);
    };
    char name[32];
    if (o.kind <= 1) {
        field("mask", a.mask, b.mask);
    } else {
        field("have_cur", a.have_cur, b.have_cur);
        field("sp", a.sp, b.sp);
        field("node", a.node, b.node);
        field("mask", a.mask, b.mask);
        field("lost", a.lost, b.lost);
        field("restarted", a.restarted, b.restarted);
    }
    for (int i = 0; i < 4; i++) {
        std::snprintf(name, sizeof name, "tn[%d]", i);
        field(name, a.tn[i], b.tn[i]);
        std::snprintf(name, sizeof name, "tf[%d]", i);
        field(name, a.tf[i], b.tf[i]);
    }
    if (o.kind == 3) {
        field("leaf", a.leaf, b.leaf);
        field("list (leaf with entries)", a.ret, b.ret);
        if (a.leaf && b.leaf) {
            field("leaf_first", a.leaf_first, b.leaf_first);
            field("leaf_count", a.leaf_count, b.leaf_count);
            field("leaf_mask", a.leaf_mask, b.leaf_mask);
            for (int i = 0; i < 4; i++) {
                std::snprintf(name, sizeof name, "leaf_tn[%d]", i);
                field(name, a.leaf_tn[i], b.leaf_tn[i]);
            }
        }
    }
    return ok;
}

bool read_capture(const std::string &path, std::vector<op> &out, std::vector<result> &rec)
{
    FILE *f = std::fopen(path.c_str(), "r");
    if (!f) {
        std::printf("tb_trav: cannot read %s\n", path.c_str());
        return false;
    }
    std::size_t n = 0;
    for (;;) {
        uint32_t v[74];
        int got = 0;
        for (; got < 74; got++)
            if (std::fscanf(f, "%x", &v[got]) != 1)
                break;
        if (got == 0 && std::feof(f))
            break;
        if (got != 74) {
            std::printf("tb_trav: %s operation %zu: malformed\n", path.c_str(), n + 1);
            std::fclose(f);
            return false;
        }
        op o{};
        result r{};
        const uint32_t *p = v;
        o.kind = *p++, o.thread = *p++, o.level = *p++;
        for (auto &x : o.box) x = *p++;
        for (auto &x : o.o) x = *p++;
        for (auto &x : o.d) x = *p++;
        for (auto &x : o.tn) x = *p++;
        for (auto &x : o.tf) x = *p++;
        for (auto &x : o.best) x = *p++;
        o.mask = *p++, o.nodes = *p++, o.algo = *p++;
        for (auto &x : o.read) x = *p++;
        r.ret = *p++, r.have_cur = *p++, r.leaf = *p++, r.leaf_first = *p++, r.leaf_count = *p++, r.leaf_mask = *p++;
        for (auto &x : r.leaf_tn) x = *p++;
        r.sp = *p++, r.node = *p++, r.mask = *p++;
        for (auto &x : r.tn) x = *p++;
        for (auto &x : r.tf) x = *p++;
        r.lost = *p++, r.restarted = *p++ != 0;
        r.addr = o.read[0];
        o.captured = true;
        n++;
        if (o.thread >= THREADS || o.level > 1 || o.kind > 3) {
            std::printf("tb_trav: %s operation %zu: thread %u level %u kind %u, the RTL has %u threads (capture with "
                        "--threads-per-pipe <= %u)\n", path.c_str(), n, o.thread, o.level, o.kind, THREADS, THREADS);
            std::fclose(f);
            return false;
        }
        if (o.kind >= 2 && o.algo != TRAV_STACK) {
            std::printf("tb_trav: %s operation %zu: algorithm %u; the RTL walks TRAV_STACK only (render with the "
                        "default --traversal)\n", path.c_str(), n, o.algo);
            std::fclose(f);
            return false;
        }
        out.push_back(o);
        rec.push_back(r);
    }
    std::fclose(f);
    return true;
}

// ---- random operations ---------------------------------------------------------------------

uint32_t small_f24(int lo, int hi, int den) // (lo .. hi) / den
{
    return f24_div(f24_from_i32(lo + (int32_t)(rnd() % (uint32_t)(hi - lo + 1))), f24_from_i32(den));
}

uint32_t rnd_f24() // a few specials and arbitrary encodings among moderate values
{
    const uint32_t k = rnd() % 24;
    if (k == 0) {
        const uint32_t sp[] = { 0, F24_SIGN_BIT, F24_POS_INF, F24_POS_INF | F24_SIGN_BIT, F24_DEFAULT_NAN, 1 };
        return sp[rnd() % 6];
    }
    if (k == 1)
        return rnd() & F24_MASK;
    return small_f24(-64, 64, 8);
}

// two random trees of NODES nodes, a deep one (few leaves) and a shallow one, and a chain of
// CHAIN inner nodes with decreasing splits on x whose right children are leaves: rays along +x
// push every right child, so that the stack overflows, drops its oldest entries, runs dry and
// restarts (and, as TRAV_STACK keeps t_exit where the walk began, overflows again)
constexpr uint32_t NODES = 512, CHAIN = 100;
uint32_t g_tree[3];

void random_trees()
{
    g_tree[2] = (uint32_t)g_mem.size() + 16;
    for (uint32_t k = 0; k <= CHAIN; k++) { // inner node k at 2k, children at 2k + 2 (inner) and 2k + 3 (leaf)
        const uint32_t a = g_tree[2] + 4 * k;
        put_mem(a, k == CHAIN ? 1u << 2 | 3u : (2 * k + 2) << 4);
        put_mem(a + 1, k == CHAIN ? rnd() : f24_div(f24_from_i32(1024), f24_from_i32((int32_t)k + 1)));
        put_mem(a + 2, (1 + rnd() % 3) << 2 | 3u);
        put_mem(a + 3, rnd());
    }
    for (uint32_t t = 0; t < 2; t++) {
        g_tree[t] = (uint32_t)g_mem.size() + 16;
        for (uint32_t i = 0; i < NODES; i++) {
            const uint32_t a = g_tree[t] + 2 * i;
            if (rnd() % 100 < (t ? 40u : 8u)) {
                put_mem(a, (rnd() % 6) << 2 | 3u);
                put_mem(a + 1, rnd());
            } else {
                const uint32_t empty = rnd() % 8 == 0 ? 1u + rnd() % 2 : 0u;
                put_mem(a, (rnd() % (NODES - 1)) << 4 | empty << 2 | rnd() % 3);
                put_mem(a + 1, rnd() % 16 ? small_f24(-64, 64, 8) : rnd_f24());
            }
        }
    }
}

struct walk_rays {
    uint32_t o[12], d[12], best[4], alive, steps;
    bool on;
};
walk_rays g_rays[THREADS][2];

op random_op()
{
    op o{};
    o.thread = rnd() % THREADS, o.level = rnd() & 1u;
    o.read[0] = NONE;
    walk_rays &wr = g_rays[o.thread][o.level];
    const trav_walker &w = g_w[o.thread][o.level];
    if (rnd() % 12 == 0) { // a clip
        o.kind = rnd() & 1u;
        for (int k = 0; k < 3; k++) {
            o.box[k] = rnd() % 16 ? small_f24(-64, 8, 8) : rnd_f24();
            o.box[3 + k] = rnd() % 16 ? small_f24(-8, 64, 8) : rnd_f24();
        }
        for (auto &x : o.o) x = rnd_f24();
        for (auto &x : o.d) x = rnd() % 12 ? rnd_f24() : (rnd() & 1u) * F24_SIGN_BIT;
        for (int i = 0; i < 4; i++) {
            o.tn[i] = rnd() % 4 ? 0u : rnd_f24();
            o.tf[i] = rnd() % 3 ? F24_POS_INF : rnd_f24();
        }
        o.mask = rnd() & 15u;
        return o;
    }
    if (!wr.on || !w.have_cur || wr.steps > 2000) { // a new walk
        o.kind = 2;
        for (auto &x : wr.o) x = rnd() % 16 ? small_f24(-64, 64, 8) : rnd_f24();
        for (auto &x : wr.d) x = rnd() % 10 ? small_f24(-16, 16, 8) : rnd() % 2 ? (rnd() & 1u) * F24_SIGN_BIT : rnd_f24();
        for (int i = 0; i < 4; i++) {
            wr.best[i] = F24_POS_INF;
            o.tn[i] = rnd() % 4 ? 0u : small_f24(0, 16, 8);
            o.tf[i] = rnd() % 3 ? F24_POS_INF : small_f24(8, 200, 2);
        }
        o.mask = rnd() % 4 ? 15u : rnd() & 15u;
        const uint32_t tree = rnd() % 4;
        o.nodes = g_tree[tree < 2 ? 0 : tree - 1];
        if (tree == 3) // the chain: along +x from x <= 0
            for (int i = 0; i < 4; i++) {
                wr.o[3 * i] = small_f24(-8, 0, 8);
                wr.d[3 * i] = small_f24(1, 16, 8);
                o.tn[i] = 0;
                o.tf[i] = F24_POS_INF;
            }
        std::memcpy(o.o, wr.o, sizeof o.o);
        std::memcpy(o.d, wr.d, sizeof o.d);
        wr.alive = 15u, wr.steps = 0, wr.on = true;
        return o;
    }
    o.kind = 3; // a step: now and then a ray finds a hit or leaves
    wr.steps++;
    if (rnd() % 256 == 0)
        wr.best[rnd() % 4] = small_f24(0, 200, 4);
    if (w.lost && rnd() % 8 == 0) // after an overflow, hits prune the stack until it runs dry: a restart
        for (auto &b : wr.best)
            b = small_f24(0, 16, 8);
    if (rnd() % 512 == 0)
        wr.alive &= ~(1u << (rnd() % 4));
    std::memcpy(o.o, wr.o, sizeof o.o);
    std::memcpy(o.d, wr.d, sizeof o.d);
    std::memcpy(o.best, wr.best, sizeof o.best);
    o.mask = wr.alive;
    return o;
}

// ---- the RTL's ports -------------------------------------------------------------------------

template <typename T> void put(T &v, unsigned at, uint32_t x)
{
    for (unsigned b = 0; b < W; b++) {
        const unsigned k = at + b;
        v[k / 32] = (v[k / 32] & ~(1u << (k % 32))) | ((x >> b & 1u) << (k % 32));
    }
}

template <typename T> uint32_t get(const T &v, unsigned at)
{
    uint32_t x = 0;
    for (unsigned b = 0; b < W; b++) {
        const unsigned k = at + b;
        x |= (v[k / 32] >> (k % 32) & 1u) << b;
    }
    return x;
}

void drive(Vtb_trav &top, const op &o)
{
    top.kind_i = o.kind, top.thread_i = o.thread, top.level_i = o.level, top.mask_i = o.mask, top.nodes_i = o.nodes;
    for (unsigned i = 0; i < 12; i++) {
        put(top.o_i, i * W, o.o[i]);
        put(top.d_i, i * W, o.d[i]);
    }
    for (unsigned i = 0; i < 4; i++) {
        put(top.tn_i, i * W, o.tn[i]);
        put(top.tf_i, i * W, o.tf[i]);
        put(top.best_i, i * W, o.best[i]);
    }
    for (unsigned i = 0; i < 6; i++)
        put(top.box_i, i * W, o.box[i]);
}

result sample(const Vtb_trav &top)
{
    result r{};
    r.ret = top.kind_o <= 1 ? top.mask_o : top.list_o;
    r.have_cur = top.have_cur_o, r.leaf = top.leaf_o, r.leaf_first = top.leaf_first_o, r.leaf_count = top.leaf_count_o;
    r.leaf_mask = top.leaf_mask_o, r.sp = top.sp_o, r.node = top.node_o, r.mask = top.mask_o, r.lost = top.lost_o;
    r.restarted = top.restarted_o;
    for (unsigned i = 0; i < 4; i++) {
        r.tn[i] = get(top.tn_o, i * W);
        r.tf[i] = get(top.tf_o, i * W);
        r.leaf_tn[i] = get(top.leaf_tn_o, i * W);
    }
    return r;
}

} // namespace

int main(int argc, char **argv)
{
    std::size_t n = 200000;
    std::string capture;
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "-n") && i + 1 < argc) n = std::strtoull(argv[++i], nullptr, 0);
        else if (!std::strcmp(argv[i], "--seed") && i + 1 < argc) g_rng = std::strtoull(argv[++i], nullptr, 0) | 1u;
        else if (!std::strcmp(argv[i], "--capture") && i + 1 < argc) capture = argv[++i];
        else { std::printf("usage: tb_trav [-n N] [--seed S] [--capture DIR]\n"); return 2; }
    }
    std::vector<op> ops;
    std::vector<result> rec;
    if (!capture.empty() && !read_capture(capture + "/trav_unit.hex", ops, rec))
        return 2;
    const std::size_t captured = ops.size();
    if (!capture.empty() && !captured) {
        std::printf("tb_trav: %s/trav_unit.hex holds no operations\n", capture.c_str());
        return 2;
    }
    for (const op &o : ops) // the memory spans the captured addresses before the random trees
        if (o.read[0] != NONE)
            put_mem(o.read[0] + 1, o.read[2]);
    random_trees();

    VerilatedContext ctx;
    Vtb_trav top{ &ctx };
    top.rst_ni = 0, top.clk_i = 0, top.valid_i = 0, top.ready_i = 1, top.node_req_ready_i = 1, top.node_rsp_valid_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;

    // the operations in flight, one per thread and level at most (the unit holds back another)
    struct pending {
        bool on;
        std::size_t index;
        result expect;
        uint64_t started;
    };
    static pending pend[THREADS][2];
    struct response {
        uint32_t w0, w1;
        uint64_t due;
    };
    std::deque<response> rsp; // the node memory: in request order
    // the captured operations are offered in their order per thread, the oldest first whose thread
    // has nothing in flight (as the threads' queue in front of the unit would), within a window
    constexpr std::size_t WINDOW = 256;
    std::vector<char> issued(captured, 0);
    std::vector<uint64_t> seen(THREADS, 0);
    uint64_t scan = 0;
    const std::size_t total = captured + n;
    std::size_t oldest = 0, next = captured, done = 0, captured_done = 0;
    uint64_t kinds[4] = {}, kind_cycles[4] = {}, vs_capture = 0, overflows = 0, restarts = 0, leaves = 0;
    uint64_t lists = 0, reads = 0, step_n[3] = {}, step_cycles[3] = {}, step_max[3] = {}, captured_cycles = 0;
    uint64_t in_flight = 0, in_flight_max = 0;
    for (; done < total && g_mismatches < 20; g_cycle++) { // after 20 the walkers have parted anyway
        if (g_cycle > 400 * total + 1000) {
            std::printf("PROTOCOL: trav_unit stopped (%zu of %zu operations done)\n", done, total);
            return 1;
        }
        const bool random_phase = oldest >= captured;
        top.clk_i = 0;
        std::size_t pick = total;
        if (!random_phase) {
            scan++;
            for (std::size_t j = oldest; j < captured && j < oldest + WINDOW && pick == total; j++) {
                const uint32_t t = ops[j].thread;
                if (issued[j])
                    continue;
                if (seen[t] != scan && !pend[t][0].on && !pend[t][1].on)
                    pick = j;
                seen[t] = scan;
            }
        } else if (next < total && rnd() % 4 != 0) {
            if (next == ops.size())
                ops.push_back(random_op());
            pick = next;
        }
        const bool offer = pick < total;
        if (offer)
            drive(top, ops[pick]);
        top.valid_i = offer;
        top.ready_i = !random_phase || rnd() % 3 != 0;
        top.node_req_ready_i = !random_phase || rnd() % 3 != 0;
        top.node_rsp_valid_i = !rsp.empty() && rsp.front().due <= g_cycle;
        if (top.node_rsp_valid_i) {
            top.node_w0_i = rsp.front().w0;
            top.node_w1_i = rsp.front().w1;
            rsp.pop_front();
        }
        top.eval();
        // this edge's transfers: the result, the operation, the node read
        if (top.valid_o && top.ready_i) {
            pending &p = pend[top.thread_o][top.level_o];
            if (!p.on) {
                std::printf("PROTOCOL: trav_unit result at cycle %llu for thread %u level %u, which has no operation\n",
                            (unsigned long long)g_cycle, top.thread_o, top.level_o);
                return 1;
            }
            const op &o = ops[p.index];
            const result got = sample(top);
            if (top.kind_o != o.kind && g_mismatches++ < 20)
                std::printf("MISMATCH trav_unit operation %zu cycle %llu thread %u level %u: kind %u left as %u\n",
                            p.index, (unsigned long long)g_cycle, o.thread, o.level, o.kind, top.kind_o);
            compare("RTL against the C unit", p.index, o, p.expect, got, "C", "rtl");
            if (o.captured) {
                compare("RTL against the capture", p.index, o, rec[p.index], got, "capture", "rtl");
                vs_capture++;
            }
            kinds[o.kind]++;
            kind_cycles[o.kind] += g_cycle - p.started;
            if (o.captured && o.kind == 3) {
                const int at = p.expect.addr == NONE ? 0 : p.expect.leaf ? 1 : 2;
                step_n[at]++;
                step_cycles[at] += g_cycle - p.started;
                step_max[at] = std::max(step_max[at], g_cycle - p.started);
            }
            p.on = false;
            in_flight--;
            done++;
            if (o.captured && ++captured_done == captured)
                captured_cycles = g_cycle + 1;
        }
        if (offer && top.ready_o) {
            const op &o = ops[pick];
            pending &p = pend[o.thread][o.level];
            if (p.on) {
                std::printf("PROTOCOL: trav_unit took operation %zu at cycle %llu while thread %u level %u has "
                            "operation %zu in flight\n", pick, (unsigned long long)g_cycle, o.thread, o.level, p.index);
                return 1;
            }
            const trav_walker before = o.kind >= 2 ? g_w[o.thread][o.level] : trav_walker{};
            p = pending{ true, pick, model(o), g_cycle };
            if (o.captured && !compare("C replay against the capture", pick, o, rec[pick], p.expect, "capture", "C"))
                std::printf("  (the C unit replayed here must agree with the recording: same state, same order)\n");
            if (o.kind == 3) {
                overflows += p.expect.lost && !before.lost;
                restarts += g_w[o.thread][o.level].pass != before.pass;
                leaves += p.expect.leaf;
                lists += p.expect.ret;
            }
            in_flight_max = std::max(in_flight_max, ++in_flight);
            if (o.captured) {
                issued[pick] = 1;
                while (oldest < captured && issued[oldest])
                    oldest++;
            } else {
                next++;
            }
        }
        if (top.node_req_valid_o && top.node_req_ready_i) {
            reads++;
            const pending &p = pend[top.node_thread_o][top.node_level_o];
            const op *o = p.on ? &ops[p.index] : nullptr;
            if ((!o || o->kind != 3 || top.node_addr_o != p.expect.addr) && g_mismatches++ < 20)
                std::printf("MISMATCH trav_unit (RTL against the C unit) operation %zu (%s) cycle %llu thread %u level "
                            "%u: node read at %x, C %x\n", p.index, o ? KIND[o->kind] : "none",
                            (unsigned long long)g_cycle, top.node_thread_o, top.node_level_o, top.node_addr_o,
                            p.expect.addr);
            // the words the operation read while rendering (the image may change between frames)
            const bool rec_words = o && o->captured && top.node_addr_o == o->read[0];
            const uint64_t after = random_phase ? 1 + rnd() % 4 : 1;
            rsp.push_back(response{ rec_words ? o->read[1] : mem_at(top.node_addr_o),
                                    rec_words ? o->read[2] : mem_at(top.node_addr_o + 1),
                                    std::max(rsp.empty() ? 0 : rsp.back().due, g_cycle + after) });
        }
        top.clk_i = 1;
        top.eval();
    }
    top.final();
    std::printf("tb_trav: %zu of %zu operations (%zu captured) compared with the C unit (%llu also with the capture): "
                "scene clips %llu, object clips %llu, starts %llu, walk steps %llu (%llu node reads, %llu leaves, %llu "
                "with entries, %llu stack overflows, %llu restarts); cycles per operation %.1f, %.1f, %.1f, %.1f; "
                "at most %llu in flight; %llu cycles; %llu mismatches\n",
                done, total, captured, (unsigned long long)vs_capture, (unsigned long long)kinds[0],
                (unsigned long long)kinds[1], (unsigned long long)kinds[2], (unsigned long long)kinds[3],
                (unsigned long long)reads, (unsigned long long)leaves, (unsigned long long)lists,
                (unsigned long long)overflows, (unsigned long long)restarts,
                kinds[0] ? (double)kind_cycles[0] / (double)kinds[0] : 0.0,
                kinds[1] ? (double)kind_cycles[1] / (double)kinds[1] : 0.0,
                kinds[2] ? (double)kind_cycles[2] / (double)kinds[2] : 0.0,
                kinds[3] ? (double)kind_cycles[3] / (double)kinds[3] : 0.0, (unsigned long long)in_flight_max,
                (unsigned long long)g_cycle, (unsigned long long)g_mismatches);
    if (captured && captured_cycles) {
        std::printf("tb_trav: the captured operations in %llu cycles (%.2f cycles per operation, the memory answering "
                    "in the next cycle); walk steps from operation to result:", (unsigned long long)captured_cycles,
                    (double)captured_cycles / (double)captured);
        const char *const at[3] = { "no node read", "leaf", "inner node" };
        for (int k = 0; k < 3; k++)
            std::printf("%s %s %llu x %.1f (max %llu)", k ? ";" : "", at[k], (unsigned long long)step_n[k],
                        step_n[k] ? (double)step_cycles[k] / (double)step_n[k] : 0.0, (unsigned long long)step_max[k]);
        std::printf("\n");
    }
    return g_mismatches ? 1 : 0;
}
