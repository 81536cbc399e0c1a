// Co-simulation of the thread scheduler (rtl/thread_sched.sv) against the cycle model's
// (tb/cycle/cycle_sim.c: per unit a ready set and a round-robin pointer). The bench plays the 64
// threads of a pipe: from the scheduler events a cycle-mode frame recorded (saarcor render --mode
// cycle --threads-per-pipe 64 --capture-unit-io DIR: DIR/sched.hex; "R pipe cycle unit thread
// slots": the thread is ready for the unit from that cycle on, "I ...": the unit issued it) it
// raises each ready bit one cycle before the recorded cycle and holds each thread's slots, clocks
// the RTL through every cycle of the frame and compares each cycle's issues (unit, thread,
// slots) with the recorded ones; then random ready sets and slots against a replica of the
// model's policy (itself checked against the recording first). A mismatch prints the unit, the
// cycle, both threads and slots; exit code 1.
// usage: tb_sched [-n CYCLES] [--seed S] [--capture DIR]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "Vtb_sched.h"
#include "verilated.h"

namespace {

constexpr uint32_t THREADS = 64, UNITS = 5, SLOT_BITS = 8, TW = 6;
const char *const unit_name[UNITS] = { "RGS", "transformation", "traversal", "list", "intersection" };

uint64_t g_rng = 1;
uint32_t rnd() { g_rng ^= g_rng << 13, g_rng ^= g_rng >> 7, g_rng ^= g_rng << 17; return (uint32_t)(g_rng >> 11); }

struct event {
    char what; // 'R' ready (from cycle on), 'I' issue (in cycle)
    uint64_t cycle;
    uint32_t unit, thread, slots;
};

// The model's policy (cycle_sim.c ready_set): the reference for the random phase.
struct replica {
    uint64_t ready[UNITS] = {};
    uint32_t ptr[UNITS] = {}, busy[UNITS] = {};
    // the issue of unit u this cycle (THREADS: none)
    uint32_t pick(uint32_t u) const
    {
        if (!ready[u] || busy[u])
            return THREADS;
        for (uint32_t k = 0; k < THREADS; k++)
            if (ready[u] >> ((ptr[u] + k) % THREADS) & 1u)
                return (ptr[u] + k) % THREADS;
        return THREADS;
    }
    void commit(const uint32_t issue[UNITS], const uint32_t slots[THREADS], const uint64_t set[UNITS])
    {
        for (uint32_t u = 0; u < UNITS; u++) {
            if (issue[u] < THREADS) {
                ready[u] &= ~(1ull << issue[u]);
                ptr[u] = (issue[u] + 1) % THREADS;
                busy[u] = slots[issue[u]] - 1;
            } else if (busy[u]) {
                busy[u]--;
            }
            ready[u] |= set[u];
        }
    }
};

Vtb_sched *g_top;
uint64_t g_mismatches = 0;

void drive(const uint64_t set[UNITS], const uint32_t slots[THREADS])
{
    for (uint32_t w = 0; w < UNITS * THREADS / 32; w++) {
        const uint32_t bit = w * 32, u = bit / THREADS, t = bit % THREADS;
        g_top->set_i[w] = (uint32_t)(set[u] >> t);
    }
    for (uint32_t w = 0; w < THREADS * SLOT_BITS / 32; w++) {
        uint32_t v = 0;
        for (uint32_t k = 0; k < 32 / SLOT_BITS; k++)
            v |= (slots[w * (32 / SLOT_BITS) + k] & ((1u << SLOT_BITS) - 1)) << (k * SLOT_BITS);
        g_top->slots_i[w] = v;
    }
}

// the RTL's issue of unit u in this cycle (THREADS: none) and its slots; issue_grant_o must be
// the same thread one-hot (trace_core's grants), else THREADS + 1
uint32_t rtl_issue(uint32_t u, uint32_t *slots)
{
    *slots = (uint32_t)(g_top->issue_slots_o >> (u * SLOT_BITS)) & ((1u << SLOT_BITS) - 1);
    const uint32_t got = g_top->issue_valid_o >> u & 1u ? (uint32_t)(g_top->issue_thread_o >> (u * TW)) & (THREADS - 1)
                                                        : THREADS;
    for (uint32_t t = 0; t < THREADS; t++) {
        const uint32_t bit = u * THREADS + t;
        if ((g_top->issue_grant_o[bit / 32] >> (bit % 32) & 1u) != (t == got))
            return THREADS + 1;
    }
    return got;
}

void check(const char *phase, uint64_t cycle, uint32_t u, uint32_t want, uint32_t want_slots)
{
    uint32_t slots;
    const uint32_t got = rtl_issue(u, &slots);
    if (got == want && (got == THREADS || slots == want_slots))
        return;
    if (g_mismatches++ < 10)
        std::printf("MISMATCH thread_sched (%s) unit %s at cycle %llu: expected %s%u (slots %u), rtl %s%u (slots %u)\n",
                    phase, unit_name[u], (unsigned long long)cycle, want == THREADS ? "no issue " : "thread ",
                    want == THREADS ? 0 : want, want_slots,
                    got == THREADS ? "no issue " : got > THREADS ? "issue_grant_o not issue_thread_o one-hot " : "thread ",
                    got >= THREADS ? 0 : got, slots);
}

void clock()
{
    g_top->clk_i = 1;
    g_top->eval();
    g_top->clk_i = 0;
    g_top->eval();
}

void reset()
{
    g_top->rst_ni = 0;
    g_top->eval();
    g_top->rst_ni = 1;
    g_top->eval();
}

// Reads DIR/sched.hex (pipe 0, every frame): frames of events; false with a message if unusable.
bool read_capture(const std::string &dir, std::vector<std::vector<event>> &frames)
{
    FILE *f = std::fopen((dir + "/sched.hex").c_str(), "r");
    if (!f) {
        std::printf("tb_sched: cannot read %s/sched.hex (record it with saarcor render --mode cycle ... "
                    "--capture-unit-io DIR)\n", dir.c_str());
        return false;
    }
    char line[256];
    bool ok = true;
    while (ok && std::fgets(line, sizeof line, f)) {
        event e{};
        unsigned pipe, threads;
        unsigned long long cycle;
        if (std::sscanf(line, "N %x %x", &pipe, &threads) == 2) {
            if (pipe == 0 && threads != THREADS) {
                std::printf("tb_sched: the capture has %u threads per pipe; this bench is built for %u\n", threads, THREADS);
                ok = false;
            }
            if (pipe == 0)
                frames.emplace_back();
        } else if (std::sscanf(line, "%c %x %llx %x %x %x", &e.what, &pipe, &cycle, &e.unit, &e.thread, &e.slots) == 6 &&
                   (e.what == 'R' || e.what == 'I')) {
            e.cycle = cycle;
            if (e.unit >= UNITS || e.thread >= THREADS || e.slots == 0 || e.slots >= 1u << SLOT_BITS || frames.empty()) {
                std::printf("tb_sched: bad event in sched.hex: %s", line);
                ok = false;
            } else if (pipe == 0) {
                frames.back().push_back(e);
            }
        } else {
            std::printf("tb_sched: bad line in sched.hex: %s", line);
            ok = false;
        }
    }
    std::fclose(f);
    return ok;
}

// One captured frame: the RTL and the replica against the recorded issues, cycle by cycle.
// Events are recorded in the order they matter (ready ones before the cycle they can issue in);
// the last cycle may be incomplete (the capture limit), so only cycles before it are compared.
uint64_t run_frame(const std::vector<event> &ev, uint64_t *issues)
{
    reset();
    replica rep;
    uint32_t slots[THREADS] = {};
    const uint64_t last = ev.empty() ? 0 : ev.back().cycle;
    std::size_t next_ready = 0, next_issue = 0;
    // ready events for cycle c are applied in cycle c - 1 (c = 0: before the frame's first cycle)
    for (uint64_t c = 0; c <= last; c++) {
        uint64_t set[UNITS] = {};
        uint32_t want[UNITS], want_slots[UNITS] = {};
        for (uint32_t u = 0; u < UNITS; u++)
            want[u] = THREADS;
        if (c == 0) { // the frame's first ready threads: set before cycle 0
            for (; next_ready < ev.size() && !(ev[next_ready].what == 'R' && ev[next_ready].cycle > 0); next_ready++)
                if (ev[next_ready].what == 'R') {
                    set[ev[next_ready].unit] |= 1ull << ev[next_ready].thread;
                    slots[ev[next_ready].thread] = ev[next_ready].slots;
                }
            drive(set, slots);
            g_top->eval();
            for (uint32_t u = 0; u < UNITS; u++)
                rep.ready[u] |= set[u];
            clock();
            std::memset(set, 0, sizeof set);
        }
        while (next_issue < ev.size() && (ev[next_issue].what != 'I' || ev[next_issue].cycle < c))
            next_issue++;
        for (; next_issue < ev.size() && ev[next_issue].cycle == c; next_issue++)
            if (ev[next_issue].what == 'I') {
                want[ev[next_issue].unit] = ev[next_issue].thread;
                want_slots[ev[next_issue].unit] = ev[next_issue].slots;
            }
        // threads ready from c + 1 on raise their bits in cycle c, with the slots of their operation
        // (a thread issued in c is not among them: its result comes back at least a latency later)
        for (; next_ready < ev.size() && ev[next_ready].cycle <= c + 1; next_ready++)
            if (ev[next_ready].what == 'R') {
                if (ev[next_ready].cycle != c + 1) {
                    std::printf("tb_sched: ready event out of order in sched.hex (cycle %llu after %llu)\n",
                                (unsigned long long)ev[next_ready].cycle, (unsigned long long)c);
                    return ++g_mismatches;
                }
                set[ev[next_ready].unit] |= 1ull << ev[next_ready].thread;
                slots[ev[next_ready].thread] = ev[next_ready].slots;
            }
        drive(set, slots);
        g_top->eval();
        uint32_t rep_issue[UNITS];
        for (uint32_t u = 0; u < UNITS; u++) {
            rep_issue[u] = rep.pick(u);
            if (c < last) {
                check("captured", c, u, want[u], want_slots[u]);
                if (rep_issue[u] != want[u] && g_mismatches++ < 10)
                    std::printf("MISMATCH replica of the model's policy, unit %s at cycle %llu: capture thread %u, "
                                "replica %u\n", unit_name[u], (unsigned long long)c, want[u], rep_issue[u]);
                *issues += want[u] < THREADS;
            }
        }
        rep.commit(rep_issue, slots, set);
        clock();
    }
    return last;
}

// Random ready sets (few threads per unit, so that the pointer's wrap matters) and slots 1..4.
uint64_t run_random(uint64_t cycles, uint64_t *issues)
{
    reset();
    replica rep;
    uint32_t slots[THREADS];
    for (uint32_t t = 0; t < THREADS; t++)
        slots[t] = 1;
    for (uint64_t c = 0; c < cycles; c++) {
        uint64_t set[UNITS] = {}, busy_threads = 0;
        for (uint32_t u = 0; u < UNITS; u++)
            busy_threads |= rep.ready[u]; // a thread is in one set at a time
        for (uint32_t k = rnd() % 4; k-- > 0;) {
            const uint32_t t = rnd() % THREADS, u = rnd() % UNITS;
            if (busy_threads >> t & 1u)
                continue;
            busy_threads |= 1ull << t;
            set[u] |= 1ull << t;
            slots[t] = 1 + rnd() % 4; // its operation's slots, held until its issue
        }
        drive(set, slots);
        g_top->eval();
        uint32_t rep_issue[UNITS];
        for (uint32_t u = 0; u < UNITS; u++) {
            rep_issue[u] = rep.pick(u);
            check("random", c, u, rep_issue[u], rep_issue[u] < THREADS ? slots[rep_issue[u]] : 0);
            *issues += rep_issue[u] < THREADS;
        }
        rep.commit(rep_issue, slots, set);
        clock();
    }
    return cycles;
}

} // namespace

int main(int argc, char **argv)
{
    uint64_t n = 100000;
    const char *capture = nullptr;
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "-n") && i + 1 < argc) n = std::strtoull(argv[++i], nullptr, 0);
        else if (!std::strcmp(argv[i], "--seed") && i + 1 < argc) g_rng = std::strtoull(argv[++i], nullptr, 0) | 1u;
        else if (!std::strcmp(argv[i], "--capture") && i + 1 < argc) capture = argv[++i];
        else {
            std::printf("usage: tb_sched [-n CYCLES] [--seed S] [--capture DIR]\n");
            return 2;
        }
    }
    VerilatedContext ctx;
    Vtb_sched top{&ctx};
    g_top = &top;
    top.clk_i = 0;
    uint64_t cap_cycles = 0, cap_issues = 0, rnd_issues = 0;
    std::size_t frames_n = 0;
    if (capture) {
        std::vector<std::vector<event>> frames;
        if (!read_capture(capture, frames))
            return 1;
        for (const auto &fr : frames)
            cap_cycles += run_frame(fr, &cap_issues);
        frames_n = frames.size();
    }
    run_random(n, &rnd_issues);
    top.final();
    std::printf("tb_sched: %zu captured frames, %llu cycles, %llu issues compared with the cycle model; %llu random "
                "cycles, %llu issues compared with its policy; %llu mismatches\n",
                frames_n, (unsigned long long)cap_cycles, (unsigned long long)cap_issues, (unsigned long long)n,
                (unsigned long long)rnd_issues, (unsigned long long)g_mismatches);
    return g_mismatches ? 1 : 0;
}
