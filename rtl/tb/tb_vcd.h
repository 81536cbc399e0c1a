// tb_vcd.h: the value change dump (IEEE 1364 VCD) that tb_dynrtp writes for saarcor render
// --mode rtl --vcd FILE --vcd-cycles A:B (docs/cycle-model.md, "Waveforms and the utilisation
// plot"): signals sampled once per cycle, written for the cycles [from, to) in the layout of cycle
// mode's file (tb/cycle/cycle_trace.c): timescale 1 ps, the clock dynrtc.clk rising at each cycle's
// start (a cycle is 10^6 / clock_mhz ps), the values at the window's first cycle in $dumpvars,
// then each value where it changes; the file ends at the rising edge of min(cycles, to).
// Why not cycle_trace's recorder: it is made for the cycle model, which skips idle cycles and so
// records each signal's changes ahead of time (a busy run's end, a transfer's arrival) per pipe
// and merges the pipes after each epoch; the harness sees every cycle of the RTL, so dumping
// the changes of its samples is all it needs.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "../../tb/cycle/vcd_format.h"

namespace cosim {

class vcd_writer {
  public:
    static constexpr uint64_t X = VCD_X; // an undefined value (a unit's thread_id while it is idle)

    ~vcd_writer() { abort(); }

    // Signal `name` of `width` bits in the dotted scope (e.g. "dynrtc.pipe0.trav"); all before
    // open(), a scope's signals one after another. Its index for set().
    int add(const std::string &scope, const char *name, uint32_t width)
    {
        sigs_.push_back({ scope, name, width });
        cur_.push_back(0);
        last_.push_back(X - 1);
        return (int)sigs_.size() - 1;
    }

    // Creates path.tmp (renamed to path by close) for the cycles [from, to); false if it cannot.
    bool open(const std::string &path, uint64_t from, uint64_t to, double clock_mhz, const std::string &comment)
    {
        path_ = path, tmp_ = path + ".tmp", from_ = from, to_ = to;
        half_ = (uint64_t)std::llround(5e5 / clock_mhz);
        half_ += !half_;
        if (!(f_ = std::fopen(tmp_.c_str(), "w")))
            return false;
        std::fprintf(f_, "$version saarcor render --mode rtl $end\n$comment %s; one cycle = %llu ps (rising clock "
                         "edge at its start); cycles %llu to %llu $end\n$timescale 1ps $end\n",
                     comment.c_str(), (unsigned long long)(2 * half_), (unsigned long long)from,
                     (unsigned long long)to - 1);
        header();
        return true;
    }

    void set(int s, uint64_t v) { cur_[(size_t)s] = v; }

    // The values set are those of cycle c (called for every cycle, in order).
    void sample(uint64_t c)
    {
        if (!f_ || c < from_ || c >= to_)
            return;
        if (!started_) {
            start(c);
            return;
        }
        edges_to(c);
        for (size_t s = 0; s < sigs_.size(); s++)
            if (cur_[s] != last_[s])
                value(s);
    }

    // The frame ended after `cycles` cycles: completes the file and renames it into place.
    bool close(uint64_t cycles)
    {
        if (!f_)
            return false;
        const uint64_t end = cycles < to_ ? (cycles > from_ ? cycles : from_) : to_;
        if (!started_)
            start(from_);
        edges_to(end);
        const bool ok = !std::ferror(f_) && std::fclose(f_) == 0;
        f_ = nullptr;
        return ok && std::rename(tmp_.c_str(), path_.c_str()) == 0;
    }

    // Drops an unfinished file.
    void abort()
    {
        if (f_) {
            std::fclose(f_);
            std::remove(tmp_.c_str());
            f_ = nullptr;
        }
    }

  private:
    struct sig {
        std::string scope;
        const char *name;
        uint32_t width;
    };
    std::vector<sig> sigs_;
    std::vector<uint64_t> cur_, last_;
    std::string path_, tmp_;
    FILE *f_ = nullptr;
    uint64_t from_ = 0, to_ = 0, half_ = 1, at_ = 0; // at_: the cycle whose rising edge was written last
    bool started_ = false;

    // identifier of signal s ("!" is the clock)
    static std::string id(size_t s)
    {
        char r[VCD_ID_CHARS];
        vcd_id(s, r);
        return r;
    }

    // the scopes opened and closed between consecutive signals' dotted scopes
    void header()
    {
        std::vector<std::string> open;
        auto enter = [&](const std::string &scope) {
            std::vector<std::string> want;
            for (size_t a = 0, b; a <= scope.size(); a = b + 1) {
                b = scope.find('.', a);
                b = b == std::string::npos ? scope.size() : b;
                want.push_back(scope.substr(a, b - a));
            }
            size_t common = 0;
            while (common < open.size() && common < want.size() && open[common] == want[common])
                common++;
            for (; open.size() > common; open.pop_back())
                std::fprintf(f_, "$upscope $end\n");
            for (; open.size() < want.size(); open.push_back(want[open.size()]))
                std::fprintf(f_, "$scope module %s $end\n", want[open.size()].c_str());
        };
        enter("dynrtc");
        std::fprintf(f_, "$var wire 1 ! clk $end\n");
        for (size_t s = 0; s < sigs_.size(); s++) {
            enter(sigs_[s].scope);
            std::fprintf(f_, "$var wire %u %s %s $end\n", sigs_[s].width, id(s + 1).c_str(), sigs_[s].name);
        }
        for (; !open.empty(); open.pop_back())
            std::fprintf(f_, "$upscope $end\n");
        std::fprintf(f_, "$enddefinitions $end\n");
    }

    void value(size_t s)
    {
        last_[s] = cur_[s];
        vcd_value(f_, sigs_[s].width, cur_[s], id(s + 1).c_str());
    }

    void start(uint64_t c)
    {
        std::fprintf(f_, "#%llu\n$dumpvars\n1!\n", (unsigned long long)(c * 2 * half_));
        for (size_t s = 0; s < sigs_.size(); s++)
            value(s);
        std::fprintf(f_, "$end\n");
        at_ = c;
        started_ = true;
    }

    // the clock's falling and rising edges up to the rising edge of cycle c
    void edges_to(uint64_t c)
    {
        for (; at_ < c; at_++)
            std::fprintf(f_, "#%llu\n0!\n#%llu\n1!\n", (unsigned long long)(at_ * 2 * half_ + half_),
                         (unsigned long long)((at_ + 1) * 2 * half_));
    }
};

} // namespace cosim
