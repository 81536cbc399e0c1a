// Co-simulation of the memory interface (rtl/cache_dm.sv x 4, rtl/mem_port.sv) against the cycle
// model's caches and port (tb/cycle/mem_iface.c) on the reads of a real frame: saarcor render
// SCENE --mode cycle --capture-unit-io DIR records every read of the memory interface (DIR/mem.hex:
// kind, word address, words, the cycle, the cycle its data is at the unit, lookups, hits). The
// bench replays pipe 0's reads: per read one request per line (as mem_iface_read loops over the
// lines) to the cache of its kind, in the cycle the cycle model made it (later if the cache is not
// ready), and is the memory behind the port with the cycle model's arithmetic (a transfer occupies
// the port bytes x 65536 clock / MB/s in 1/65536 cycles after the port is free, its data is back
// --mem-latency cycles after the transfer ends; words hold a hash of their address and of the
// number of the memory image, which changes where the recording empties the caches). Checked per
// line: the hit or miss the RTL reports against a replica of the C cache (itself checked against
// the recorded lookups, hits and data arrival cycle of every read), the id, and the line's data;
// reported: the cycles from the C model's arrival to the RTL's response, per kind of lookup.
// A mismatch prints the cache, the transaction, the cycle and both values; exit code 1.
// usage: tb_cache --capture DIR [-n MAX_READS]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "Vtb_cache.h"
#include "verilated.h"

namespace {

constexpr int KINDS = 4;
const char *const kind_name[KINDS] = { "kd nodes", "lists", "matrices", "shading" };
constexpr uint64_t FX = 65536;

uint32_t g_image = 0; // memory images so far: the contents change with each emptying of the caches

uint32_t word_of(uint32_t a) // the memory's contents: a hash of the word address and the image
{
    uint32_t x = (a + g_image * 0x7F4A7C15u) * 0x9E3779B1u;
    x ^= x >> 15;
    x *= 0x85EBCA77u;
    return x ^ (x >> 13);
}

struct line_req {
    uint64_t index;   // transaction number (line lookups of this kind)
    uint32_t line;    // line address
    uint64_t now;     // cycle the C model looked it up
    uint64_t c_at;    // cycle the C model's data is at the unit
    int c_hit, c_kind_of_hit; // 0 miss, 1 hit on a filled line, 2 hit on a line being filled
    uint64_t offered = 0;
};

// replica of mem_iface.c (one pipe)
struct c_model {
    uint32_t size[KINDS], line[KINDS], latency;
    uint64_t fxpb, port_free = 0;
    uint64_t answer_at[KINDS] = {}; // each cache's last answer: answers leave in request order (cache_read's ring)
    std::vector<uint64_t> tag[KINDS], valid_at[KINDS];
    uint64_t transfer(uint64_t bytes, uint64_t now)
    {
        const uint64_t start = std::max(port_free, (now + 1) * FX); // the cycle after: mem_port's queue
        port_free = start + bytes * fxpb;
        return (port_free + FX - 1) / FX + latency;
    }
};

template <typename T> uint32_t word(const T &v, int i) { return (uint32_t)((uint64_t)v >> (32 * i)); }
template <std::size_t N> uint32_t word(const VlWide<N> &v, int i) { return v[i]; }
template <std::size_t N> void set_word(VlWide<N> &v, int i, uint32_t x) { v[i] = x; }

uint64_t g_mismatches = 0;

} // namespace

int main(int argc, char **argv)
{
    std::string capture;
    uint64_t max_reads = ~0ull;
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "--capture") && i + 1 < argc) capture = argv[++i];
        else if (!std::strcmp(argv[i], "-n") && i + 1 < argc) max_reads = std::strtoull(argv[++i], nullptr, 0);
        else { std::printf("usage: tb_cache --capture DIR [-n MAX_READS]\n"); return 2; }
    }
    if (capture.empty()) {
        std::printf("usage: tb_cache --capture DIR [-n MAX_READS]\n");
        return 2;
    }
    const std::string path = capture + "/mem.hex";
    FILE *f = std::fopen(path.c_str(), "r");
    if (!f) {
        std::printf("tb_cache: cannot read %s (capture in --mode cycle)\n", path.c_str());
        return 2;
    }
    VerilatedContext ctx;
    Vtb_cache top{ &ctx };
    // the RTL's configuration (tb_cache.sv): must be the recording's
    const int W = 1 + F24_EXP_BITS + F24_MAN_BITS;
    const uint32_t rtl_line[KINDS] = { 8, 4, (uint32_t)(4 * ((12 * W + 27 + 31) / 32)), 16 },
                   rtl_size[KINDS] = { 4096, 2048, 6144, 4096 };

    c_model cm{};
    // the frames of the recording ("N"), each after an emptying of the caches or not ("F")
    struct segment { std::deque<line_req> q[KINDS]; bool flush = false; uint64_t lookups = 0; };
    std::vector<segment> segs(1);
    uint64_t frames = 0, flushes = 0;
    uint64_t reads = 0, lookups[KINDS] = {}, c_hits[KINDS] = {};
    char buf[512];
    bool have_cfg = false;
    while (std::fgets(buf, sizeof buf, f) && reads < max_reads) {
        if (buf[0] == 'C') {
            unsigned pipe, v[2 * KINDS + 1];
            unsigned long long fxpb;
            if (std::sscanf(buf + 1, "%x %x %x %x %x %x %x %x %x %x %llx", &pipe, &v[0], &v[1], &v[2], &v[3], &v[4],
                            &v[5], &v[6], &v[7], &v[8], &fxpb) != 11) {
                std::printf("tb_cache: %s: malformed configuration line\n", path.c_str());
                return 2;
            }
            if (pipe)
                continue;
            for (int k = 0; k < KINDS; k++) {
                cm.size[k] = v[2 * k], cm.line[k] = v[2 * k + 1];
                if (cm.size[k] != rtl_size[k] || cm.line[k] != rtl_line[k]) {
                    std::printf("tb_cache: the recording's %s cache is %u bytes of %u-byte lines, the RTL's %u of %u "
                                "(record with the default --cache-kb and --line-bytes)\n",
                                kind_name[k], cm.size[k], cm.line[k], rtl_size[k], rtl_line[k]);
                    return 2;
                }
                cm.tag[k].assign(cm.size[k] / cm.line[k], 0);
                cm.valid_at[k].assign(cm.size[k] / cm.line[k], 0);
            }
            cm.latency = v[8];
            cm.fxpb = fxpb;
            have_cfg = true;
            continue;
        }
        if (buf[0] == 'F' || buf[0] == 'N') {
            unsigned pipe;
            if (std::sscanf(buf + 1, "%x", &pipe) != 1 || !have_cfg) {
                std::printf("tb_cache: %s: malformed line\n", path.c_str());
                return 2;
            }
            if (pipe)
                continue;
            if (segs.back().lookups)
                segs.emplace_back();
            if (buf[0] == 'F') { // mem_iface_flush: the tags
                segs.back().flush = true;
                flushes++;
                for (int k = 0; k < KINDS; k++)
                    std::fill(cm.tag[k].begin(), cm.tag[k].end(), 0);
            } else { // mem_iface_new_frame: the port and the cycle count
                frames++;
                cm.port_free = 0;
                for (int k = 0; k < KINDS; k++) {
                    std::fill(cm.valid_at[k].begin(), cm.valid_at[k].end(), 0);
                    cm.answer_at[k] = 0;
                }
            }
            continue;
        }
        unsigned pipe, kind, addr, words;
        unsigned long long now, at, nl, nh;
        if (std::sscanf(buf, "%x %x %x %x %llx %llx %llx %llx", &pipe, &kind, &addr, &words, &now, &at, &nl, &nh) != 8 ||
            kind >= KINDS || !have_cfg) {
            std::printf("tb_cache: %s: malformed line\n", path.c_str());
            return 2;
        }
        if (pipe)
            continue;
        reads++;
        // the C cache, line by line (mem_iface_read)
        const uint32_t lb = cm.line[kind], lines = cm.size[kind] / lb;
        const uint64_t first = 4ull * addr / lb, last = (4ull * (addr + words) - 1) / lb;
        uint64_t ready = now, hits = 0; // now: unsigned long long
        for (uint64_t line = first; line <= last; line++) {
            const uint32_t i = (uint32_t)(line % lines);
            line_req r{};
            r.index = lookups[kind]++;
            r.line = (uint32_t)line;
            r.now = now;
            r.c_hit = cm.tag[kind][i] == line + 1;
            if (!r.c_hit) {
                cm.tag[kind][i] = line + 1;
                cm.valid_at[kind][i] = cm.transfer(lb, now);
            }
            r.c_at = std::max<uint64_t>(cm.valid_at[kind][i], now);
            r.c_kind_of_hit = !r.c_hit ? 0 : r.c_at > now ? 2 : 1;
            hits += (uint64_t)r.c_hit;
            ready = std::max<uint64_t>(ready, r.c_at);
            segs.back().q[kind].push_back(r);
            segs.back().lookups++;
        }
        ready = std::max(ready, cm.answer_at[kind]); // a read after a miss waits for the miss's line
        cm.answer_at[kind] = ready;
        c_hits[kind] += hits;
        if (nl != last - first + 1 || nh != hits || at != ready) {
            if (g_mismatches++ < 10)
                std::printf("MISMATCH C replica against the recording, read %llu (%s at %x, %u words, cycle %llu): "
                            "recorded %llu lookups %llu hits data at %llu, replica %llu %llu %llu\n",
                            (unsigned long long)reads, kind_name[kind], addr, words, now, nl, nh, at,
                            (unsigned long long)(last - first + 1), (unsigned long long)hits,
                            (unsigned long long)ready);
        }
    }
    std::fclose(f);
    if (!reads) {
        std::printf("tb_cache: %s holds no reads of pipe 0\n", path.c_str());
        return 2;
    }

    // reset, then wait for the caches' tag clearing
    top.rst_ni = 0, top.clk_i = 0, top.req_valid_i = 0, top.mem_rsp_valid_i = 0, top.flush_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.rst_ni = 1;
    uint64_t cyc = 0; // RTL cycles since reset
    auto wait_ready = [&]() {
        for (;; cyc++) {
            top.clk_i = 0;
            top.eval();
            if (top.req_ready_o == 0xF)
                break;
            top.clk_i = 1;
            top.eval();
            top.flush_i = 0;
        }
    };
    wait_ready();
    struct transfer { uint64_t at; uint32_t addr, bytes; };
    std::deque<transfer> mem_q;
    uint64_t mem_port_free = 0, transfers = 0, transfer_bytes = 0;
    std::map<uint32_t, line_req> inflight[KINDS]; // by id
    uint32_t next_id[KINDS] = {};
    uint64_t done[KINDS] = {}, rtl_hits[KINDS] = {}, delayed[KINDS] = {}, refused[KINDS] = {};
    // cycles from the C model's arrival to the RTL's response, per kind of lookup (0 miss, 1 hit, 2 pending)
    std::map<int64_t, uint64_t> offset[3];
    uint64_t total = 0;
    for (const segment &sg : segs)
        total += sg.lookups;
    for (segment &sg : segs) {
        if (sg.flush) { // empty the caches (all answered: nothing under way)
            top.clk_i = 0;
            top.flush_i = 1;
            top.eval();
            top.clk_i = 1;
            top.eval();
            top.flush_i = 0;
            cyc++;
            wait_ready();
            g_image++;
        }
        // the frame's cycle 0: the port and the C model's cycles start again
        const uint64_t base = cyc;
        mem_port_free = 0;
        std::deque<line_req> *q = sg.q;
        uint64_t finished = 0, last_now = 0;
        for (int k = 0; k < KINDS; k++)
            if (!q[k].empty())
                last_now = std::max<uint64_t>(last_now, q[k].back().now);
        const uint64_t limit = base + last_now + 1000000;
        for (; finished < sg.lookups; cyc++) {
            const uint64_t rel = cyc - base;
            if (cyc > limit) {
                std::printf("PROTOCOL: tb_cache: %llu of %llu lookups of a frame answered by cycle %llu\n",
                            (unsigned long long)finished, (unsigned long long)sg.lookups, (unsigned long long)rel);
                return 1;
            }
            top.clk_i = 0;
            // requests: each cache's next lookup once the C model made it
            uint32_t valid = 0;
            for (int k = 0; k < KINDS; k++) {
                if (q[k].empty() || q[k].front().now > rel || inflight[k].size() >= 256)
                    continue;
                valid |= 1u << k;
                top.req_id_i = (top.req_id_i & ~(0xFFu << (8 * k))) | (next_id[k] & 0xFFu) << (8 * k);
                set_word(top.req_line_i, k, q[k].front().line);
            }
            top.req_valid_i = valid;
            // memory: the oldest transfer whose data is back
            const bool rsp = !mem_q.empty() && mem_q.front().at <= rel;
            top.mem_rsp_valid_i = rsp;
            if (rsp) {
                const transfer &t = mem_q.front();
                for (uint32_t w = 0; w < t.bytes / 4; w++)
                    set_word(top.mem_rsp_data_i, (int)w, word_of(t.addr / 4 + w));
            }
            top.eval();
            // this edge's transfers
            for (int k = 0; k < KINDS; k++) {
                if (!(valid >> k & 1u))
                    continue;
                if (!(top.req_ready_o >> k & 1u))
                    refused[k]++;
                else {
                    line_req r = q[k].front();
                    q[k].pop_front();
                    r.offered = rel;
                    if (rel > r.now)
                        delayed[k]++;
                    inflight[k][next_id[k] & 0xFFu] = r;
                    next_id[k]++;
                }
            }
            if (rsp)
                mem_q.pop_front();
            if (top.mem_req_valid_o) { // the port's request: the cycle model's port arithmetic
                const uint64_t start = std::max(mem_port_free, rel * FX);
                mem_port_free = start + top.mem_req_bytes_o * cm.fxpb;
                mem_q.push_back(transfer{ (mem_port_free + FX - 1) / FX + cm.latency, top.mem_req_addr_o,
                                          top.mem_req_bytes_o });
                transfers++;
                transfer_bytes += top.mem_req_bytes_o;
            }
            for (int k = 0; k < KINDS; k++) {
                if (!(top.rsp_valid_o >> k & 1u))
                    continue;
                const uint32_t id = (top.rsp_id_o >> (8 * k)) & 0xFFu;
                const int hit = top.rsp_hit_o >> k & 1u;
                auto it = inflight[k].find(id);
                if (it == inflight[k].end()) {
                    std::printf("PROTOCOL: %s cache answered id %u at cycle %llu, not in flight\n", kind_name[k], id,
                                (unsigned long long)cyc);
                    return 1;
                }
                const line_req r = it->second;
                inflight[k].erase(it);
                done[k]++, finished++;
                rtl_hits[k] += (uint64_t)hit;
                bool data_ok = true;
                uint32_t got0 = 0, want0 = 0;
                for (uint32_t w = 0; w < cm.line[k] / 4; w++) {
                    const uint32_t want = word_of(r.line * (cm.line[k] / 4) + w);
                    const uint32_t got = k == 0 ? word(top.n_data_o, (int)w)
                                         : k == 1 ? word(top.l_data_o, (int)w)
                                         : k == 2 ? word(top.m_data_o, (int)w)
                                                  : word(top.s_data_o, (int)w);
                    if (got != want && data_ok)
                        data_ok = false, got0 = got, want0 = want;
                }
                if ((hit != r.c_hit || !data_ok) && g_mismatches++ < 10)
                    std::printf("MISMATCH %s cache lookup %llu (line %x, C cycle %llu) at cycle %llu: C %s, rtl %s; data %s "
                                "(first differing word: expected %08x, rtl %08x)\n",
                                kind_name[k], (unsigned long long)r.index, r.line, (unsigned long long)r.now,
                                (unsigned long long)cyc, r.c_hit ? "hit" : "miss", hit ? "hit" : "miss",
                                data_ok ? "equal" : "differs", want0, got0);
                offset[r.c_kind_of_hit][(int64_t)rel - (int64_t)r.c_at]++;
            }
            top.clk_i = 1;
            top.eval();
        }
    }
    top.final();
    std::printf("tb_cache e%dm%d: %llu reads of pipe 0 (%llu frames, %llu flushes), %llu line lookups; %llu transfers "
                "(%llu bytes); %llu mismatches\n",
                F24_EXP_BITS, F24_MAN_BITS, (unsigned long long)reads, (unsigned long long)frames,
                (unsigned long long)flushes, (unsigned long long)total,
                (unsigned long long)transfers, (unsigned long long)transfer_bytes, (unsigned long long)g_mismatches);
    for (int k = 0; k < KINDS; k++)
        std::printf("  %-8s cache (%u B, %u-byte lines): %llu lookups, hits C %llu rtl %llu; %llu requests taken "
                    "after the C model's cycle; %llu cycles with its request table full\n",
                    kind_name[k], cm.size[k], cm.line[k], (unsigned long long)done[k], (unsigned long long)c_hits[k],
                    (unsigned long long)rtl_hits[k], (unsigned long long)delayed[k], (unsigned long long)refused[k]);
    const char *const what[3] = { "misses", "hits on filled lines", "hits on lines being filled" };
    for (int w = 0; w < 3; w++) {
        uint64_t n = 0;
        for (const auto &[d, c] : offset[w])
            n += c;
        if (!n)
            continue;
        int64_t pct[4] = {}, lo = offset[w].begin()->first, hi = offset[w].rbegin()->first;
        const double at[4] = { 0.5, 0.9, 0.99, 1.0 };
        for (int p = 0; p < 4; p++) {
            uint64_t acc = 0;
            for (const auto &[d, c] : offset[w])
                if ((acc += c) >= (uint64_t)(at[p] * (double)n)) {
                    pct[p] = d;
                    break;
                }
        }
        std::printf("  RTL response cycle - C arrival cycle, %s (%llu): min %lld, median %lld, 90%% %lld, 99%% %lld, "
                    "max %lld\n",
                    what[w], (unsigned long long)n, (long long)lo, (long long)pct[0], (long long)pct[1],
                    (long long)pct[2], (long long)hi);
    }
    std::printf("  (the RTL caches take one lookup per cycle each; the cycle model any number: its lookups in one "
                "cycle queue here)\n");
    return g_mismatches ? 1 : 0;
}
