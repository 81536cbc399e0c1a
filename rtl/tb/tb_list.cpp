// Co-simulation of the mailboxed list unit (rtl/list_unit.sv) against the C unit
// (hls/units/list_unit.c: list_unit_entry, list_mailboxes_clear). The bench is the unit's memory
// (each request taken, mem_req_o and mem_req_ready_i, is answered in request order, one answer a
// cycle, with the entry the operation read while rendering, at that address only, for the image
// may change between frames; a request for another address is a protocol error; the captured
// operations' answers come in the cycle after the request, the random ones' after 1 to 4 cycles or
// now and then 24, with random refusals of the request) and keeps the C unit's
// mailboxes per thread and level; every operation the RTL accepts is applied to the C unit in the
// same order, and every result leaving the RTL is compared with the C unit's (thread, level, key,
// need, skip mask, k after) and, for captured operations (saarcor render --capture-unit-io DIR:
// DIR/list.hex), with the results recorded while rendering (key, need, skips, k after). Random
// operations follow: random threads, levels, clears and lists over few keys (mailbox hits and
// round-robin replacement), with random gaps at the input and random back pressure at the output.
// A mismatch prints the unit, the transaction, the thread, the cycle and both values; exit code 1.
// usage: tb_list [-n N] [--seed S] [--capture DIR]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "Vtb_list.h"
#include "verilated.h"

extern "C" {
#include "list_unit.h"
}

namespace {

constexpr uint32_t THREADS = 64;

struct op {
    uint32_t thread, level, clear, lists, first, k, leaf_mask, alive, entry;
    uint32_t key, need, skips, k_out; // recorded (captured operations)
    bool captured;
};

struct answer {
    uint64_t due;
    uint32_t word;
};

struct expect {
    std::size_t index;
    uint32_t thread, level, key, need, skip, k_out;
};

uint64_t g_rng = 1;
uint32_t rnd() { g_rng ^= g_rng << 13, g_rng ^= g_rng >> 7, g_rng ^= g_rng << 17; return (uint32_t)(g_rng >> 11); }

std::vector<uint32_t> g_mem;
trace_mailbox g_box[THREADS][2][TRACE_PACKET];
uint64_t g_cycle = 0, g_mismatches = 0;

uint32_t mem_at(uint32_t a) { return a < g_mem.size() ? g_mem[a] : 0xDEADBEEFu; }

void put_mem(uint32_t a, uint32_t v)
{
    if (a >= g_mem.size())
        g_mem.resize((std::size_t)a + 1, 0xDEADBEEFu);
    g_mem[a] = v;
}

// the C unit on one accepted operation: the expected result (entries only)
bool model(const op &o, std::size_t index, expect &e)
{
    if (o.clear) {
        list_mailboxes_clear(g_box[o.thread][o.level]);
        return false;
    }
    put_mem(o.lists + o.first + o.k, o.entry); // the memory image as the operation saw it
    trav_walker w{};
    w.lists = o.lists, w.leaf_first = o.first, w.k = o.k, w.leaf_mask = o.leaf_mask;
    unit_op u{};
    trace_counters c{};
    uint32_t key = 0;
    const uint32_t need = list_unit_entry(g_mem.data(), &w, g_box[o.thread][o.level], o.alive, &key, &u, &c);
    e = expect{ index, o.thread, o.level, key, need, o.leaf_mask & o.alive & ~need, w.k };
    if (o.captured && (key != o.key || need != o.need || c.mailbox_skips != o.skips || w.k != o.k_out)) {
        // the C unit replayed here must agree with the recording (same state, same order)
        if (g_mismatches++ < 10)
            std::printf("MISMATCH list_unit (C replay against capture) transaction %zu thread %u level %u: "
                        "capture key %08x need %x skips %u k %x, C key %08x need %x skips %llu k %x\n",
                        index, o.thread, o.level, o.key, o.need, o.skips, o.k_out, key, need,
                        (unsigned long long)c.mailbox_skips, w.k);
    }
    return true;
}

bool read_capture(const std::string &path, std::vector<op> &out)
{
    FILE *f = std::fopen(path.c_str(), "r");
    if (!f) {
        std::printf("tb_list: cannot read %s\n", path.c_str());
        return false;
    }
    char line[512];
    std::size_t n = 0;
    while (std::fgets(line, sizeof line, f)) {
        op o{};
        unsigned v[13];
        if (std::sscanf(line, "%x %x %x %x %x %x %x %x %x %x %x %x %x", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6],
                        &v[7], &v[8], &v[9], &v[10], &v[11], &v[12]) != 13) {
            std::printf("tb_list: %s line %zu: malformed\n", path.c_str(), n + 1);
            std::fclose(f);
            return false;
        }
        o = op{ v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11], v[12], true };
        if (o.thread >= THREADS) {
            std::printf("tb_list: %s line %zu: thread %u, the RTL has %u (capture with --threads-per-pipe <= %u)\n",
                        path.c_str(), n + 1, o.thread, THREADS, THREADS);
            std::fclose(f);
            return false;
        }
        out.push_back(o);
        n++;
    }
    std::fclose(f);
    return true;
}

// random operations after the captured ones: a memory region of list entries over few keys
void random_ops(std::size_t n, std::vector<op> &out)
{
    const uint32_t base = (uint32_t)g_mem.size() + 16;
    for (uint32_t a = 0; a < 4096; a++)
        put_mem(base + a, rnd() % 5 == 0 ? 0xFFFFFFFFu : rnd() % 24); // NO_HIT too: it is in an empty mailbox
    for (uint32_t t = 0; t < THREADS; t++) // every mailbox starts empty
        for (uint32_t l = 0; l < 2; l++)
            out.push_back(op{ t, l, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, false });
    for (std::size_t i = 0; i < n; i++) {
        op o{};
        o.thread = rnd() % 8 == 0 ? out.back().thread : rnd() % THREADS; // back to back on one thread too
        o.level = rnd() & 1u;
        o.clear = rnd() % 40 == 0;
        if (!o.clear) {
            o.lists = base + rnd() % 1024;
            o.first = rnd() % 1024;
            o.k = rnd() % 2048;
            o.leaf_mask = rnd() & 15u;
            o.alive = rnd() % 4 ? 15u : rnd() & 15u;
            o.entry = mem_at(o.lists + o.first + o.k);
        }
        out.push_back(o);
    }
}

void print_result(const char *label, uint32_t thread, uint32_t level, uint32_t key, uint32_t need, uint32_t skip,
                  uint32_t k)
{
    std::printf("  %-9s thread %u level %u key %08x need %x skip %x k %08x\n", label, thread, level, key, need, skip, k);
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
        else { std::printf("usage: tb_list [-n N] [--seed S] [--capture DIR]\n"); return 2; }
    }
    std::vector<op> ops;
    if (!capture.empty() && !read_capture(capture + "/list.hex", ops))
        return 2;
    const std::size_t captured = ops.size();
    if (!capture.empty() && !captured) {
        std::printf("tb_list: %s/list.hex holds no operations\n", capture.c_str());
        return 2;
    }
    random_ops(n, ops);

    VerilatedContext ctx;
    Vtb_list top{ &ctx };
    top.rst_ni = 0, top.clk_i = 0, top.valid_i = 0, top.ready_i = 1;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;
    std::deque<expect> q;
    std::deque<const op *> reads; // the entries taken whose read request has not been taken
    std::deque<answer> answers;   // the requests taken, in order
    std::size_t next = 0;
    uint64_t results = 0, vs_capture = 0, entries = 0, clears = 0, need_rays = 0, skip_rays = 0, stalls = 0;
    for (; next < ops.size() || !q.empty(); g_cycle++) {
        if (g_cycle > 8 * ops.size() + 1000) {
            std::printf("PROTOCOL: list_unit stopped (%zu of %zu operations in, %zu results outstanding)\n", next,
                        ops.size(), q.size());
            return 1;
        }
        const bool random_phase = next >= captured;
        top.clk_i = 0;
        const bool offer = next < ops.size() && (!random_phase || rnd() % 8 != 0);
        top.valid_i = offer;
        if (offer) {
            const op &o = ops[next];
            top.thread_i = o.thread, top.level_i = o.level, top.clear_i = o.clear, top.lists_i = o.lists;
            top.first_i = o.first, top.k_i = o.k, top.leaf_mask_i = o.leaf_mask, top.alive_i = o.alive;
        }
        top.ready_i = !random_phase || rnd() % 6 != 0;
        top.mem_req_ready_i = !random_phase || rnd() % 5 != 0;
        top.mem_rsp_valid_i = !answers.empty() && answers.front().due <= g_cycle;
        top.mem_rdata_i = top.mem_rsp_valid_i ? answers.front().word : 0xDEADBEEFu;
        top.eval();
        // this edge's transfers: the result at the output, the operation at the input, the memory read
        if (top.valid_o && top.ready_i) {
            if (q.empty()) {
                std::printf("PROTOCOL: list_unit result at cycle %llu without an operation\n",
                            (unsigned long long)g_cycle);
                return 1;
            }
            const expect e = q.front();
            q.pop_front();
            results++;
            const bool ok = top.thread_o == e.thread && top.level_o == e.level && top.key_o == e.key &&
                            top.need_o == e.need && top.skip_o == e.skip && top.k_o == e.k_out;
            if (!ok && g_mismatches++ < 10) {
                std::printf("MISMATCH list_unit transaction %zu (%s) thread %u at cycle %llu:\n", e.index,
                            e.index < captured ? "captured" : "random", e.thread, (unsigned long long)g_cycle);
                print_result("expected", e.thread, e.level, e.key, e.need, e.skip, e.k_out);
                print_result("rtl", top.thread_o, top.level_o, top.key_o, top.need_o, top.skip_o, top.k_o);
            }
            if (e.index < captured) {
                const op &o = ops[e.index];
                vs_capture++;
                if ((top.key_o != o.key || top.need_o != o.need || (uint32_t)__builtin_popcount(top.skip_o) != o.skips ||
                     top.k_o != o.k_out) && g_mismatches++ < 10)
                    std::printf("MISMATCH list_unit transaction %zu (against capture) thread %u: capture key %08x "
                                "need %x skips %u k %x, rtl key %08x need %x skip %x k %x\n",
                                e.index, o.thread, o.key, o.need, o.skips, o.k_out, top.key_o, top.need_o, top.skip_o,
                                top.k_o);
            }
        }
        if (offer && top.ready_o) {
            expect e;
            const op &o = ops[next];
            if (model(o, next, e)) {
                q.push_back(e);
                reads.push_back(&o);
                entries++;
                need_rays += (uint32_t)__builtin_popcount(e.need);
                skip_rays += (uint32_t)__builtin_popcount(e.skip);
            } else {
                clears++;
            }
            next++;
        } else if (offer) {
            stalls++;
        }
        if (top.mem_rsp_valid_i)
            answers.pop_front();
        if (top.mem_req_o && top.mem_req_ready_i) { // the read of the oldest entry taken and not yet read
            if (reads.empty() || top.mem_addr_o != reads.front()->lists + reads.front()->first + reads.front()->k) {
                std::printf("PROTOCOL: list_unit read of %08x at cycle %llu, not the next entry's\n", top.mem_addr_o,
                            (unsigned long long)g_cycle);
                return 1;
            }
            const uint64_t lat = !random_phase ? 1 : rnd() % 16 == 0 ? 24 : 1 + rnd() % 4;
            const uint64_t after = answers.empty() ? 0 : answers.back().due + 1;
            answers.push_back({ std::max(g_cycle + lat, after), reads.front()->entry });
            reads.pop_front();
        }
        top.clk_i = 1;
        top.eval();
    }
    top.final();
    std::printf("tb_list: %zu operations (%zu captured) -> %llu entries, %llu clears, %llu results compared with the "
                "C unit (%llu also with the capture): rays needing %llu, skipping %llu; %llu input stalls; %llu cycles; "
                "%llu mismatches\n",
                ops.size(), captured, (unsigned long long)entries, (unsigned long long)clears,
                (unsigned long long)results, (unsigned long long)vs_capture, (unsigned long long)need_rays,
                (unsigned long long)skip_rays, (unsigned long long)stalls, (unsigned long long)g_cycle,
                (unsigned long long)g_mismatches);
    return g_mismatches ? 1 : 0;
}
