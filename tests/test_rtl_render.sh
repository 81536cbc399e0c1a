#!/usr/bin/env bash
# saarcor render --mode rtl (the Verilated DynRTP of rtl/dynrtp.sv, make rtl): the cornell box at
# 32x24 with shadows and secondary rays gives the PNG, the primary hits (the AOV's t, normal, node,
# triangle, u, v) and the counters of --mode functional bit for bit, every packet of the frame
# checked against the C core by the harness and every datapath unit's transactions against its C
# function (each unit exercised; a flipped bit of a unit's C result fails the frame naming the
# unit), and --stats carries the RTL's cycles and unit usage;
# --vcd (an 8x8 frame) leaves the PNG and --stats as they are, has cycle mode's names, its issues,
# lookups and misses add up to --stats and a --vcd-cycles window holds the whole run's values;
# without the model one line says to run make rtl (exit 2); options the RTL has no hardware for get
# one-line errors (the frame only where make rtl has built the model). Prints cmocka-style lines.
set -u
cd "$(dirname "$0")/.."
B=${BUILD:-build}
BIN=$B/saarcor
T=$(mktemp -d /tmp/saarcor-test-rtl-render-XXXXXX)
trap 'rm -rf "$T"' EXIT

# shellcheck source=case_lib.sh
source tests/case_lib.sh

SIZE=(--width 32 --height 24 --max-depth 3)

# the model: make test builds it (test-build-rtl, about 2 CPU minutes), as make rtl does
model_built() {
  [[ -x $B/rtl/e7m16/tb_dynrtp ]] || { echo "$B/rtl/e7m16/tb_dynrtp is not built (make rtl)"; return 1; }
}

t_cornell_matches_functional() {
  model_built
  "$BIN" render cornell "${SIZE[@]}" --mode rtl -o "$T/r.png" --aov "$T/r.exr" --stats "$T/r.json" >"$T/r.log" 2>"$T/r.err"
  # the default 32 threads per pipe on the 8-block model (where no 32-block model is built beside
  # it): said on stderr, never silently fewer
  if [[ ! -x $B/rtl/e7m16/b32/tb_dynrtp ]]; then
    grep -q "^saarcor render: warning: --mode rtl: 8 of the 32 threads per pipe in flight" "$T/r.err" || { cat "$T/r.err"; return 1; }
  fi
  "$BIN" render cornell "${SIZE[@]}" -o "$T/f.png" --aov "$T/f.exr" --stats "$T/f.json" >/dev/null
  cmp "$T/r.png" "$T/f.png"
  oiiotool "$T/f.exr" --ch t,N.X,N.Y,N.Z,node,triangle,u,v -o "$T/f_hits.exr"
  idiff -fail 0 -warn 0 "$T/f_hits.exr" "$T/r.exr" >/dev/null
  local checked
  checked=$(python3 - "$T/f.json" "$T/r.json" <<'PY'
import json, sys
f, r = (json.load(open(p)) for p in sys.argv[1:])
assert r["mode"] == "rtl" and r["rays_by_kind"]["shadow"] > 0, r["rays_by_kind"]
for k in f:
    if k not in ("mode", "seconds", "host", "host_rss_kb", "host_peak_rss_kb"):
        assert f[k] == r[k], (k, f[k], r[k])
c = r["cycle"]
assert c["cycles"] > 0 and c["packets"] > 0 and c["issues"]["isect"] == r["intersections"], c
# records read whole: a triangle's 10 words (e7m16) in one response of the word port, an instance's
# and its object's 31 in four, the header once per frame
assert c["reads"]["lists"] == r["list_entries"] and 0 < 5 * c["reads"]["words"] < r["words_by_type"]["matrices"], c
assert all(0 < u < 1 for u in c["usage"].values()), c["usage"]
# the harness checked every unit's transactions against its C function: each step of trace_core's
# units but list_unit's (its clears give no result), each read of the core's caches (the shading
# cache's also before the frame: the RGS's set-up)
k = c["checked_units"]
assert len(k) == 16 and all(n > 0 for n in k.values()), k
assert all(k[u] == c["issues"][u] for u in ("trav", "rebase", "wide", "isect", "add")), (k, c["issues"])
assert k["list"] == r["list_entries"] and all(k["cache_" + p] == c["reads"][p] for p in ("nodes", "lists", "words")), k
print(" ".join("%s %d" % x for x in k.items()))
PY
)
  echo "cornell 32x24 --mode rtl: PNG, primary hits and counters as functional; $(grep '^rtl:' "$T/r.log" | cut -d';' -f1);" \
       "transactions checked per unit: $checked"
}

# the per-unit checks can fail: a bit of one unit's C results flipped (TB_DYNRTP_MUTATE: a unit of
# the core, a stateful one, one of the RGS) fails the frame with a MISMATCH line naming the unit
t_unit_check_catches_mutant() {
  model_built
  local u rc seen=
  for u in isect trav surface; do
    rc=0
    TB_DYNRTP_MUTATE=$u "$BIN" render cornell --width 8 --height 8 --mode rtl -o "$T/m.png" 2>"$T/err" >/dev/null || rc=$?
    [[ $rc -ne 0 ]] && grep -q "MISMATCH $u (" "$T/err" || { echo "TB_DYNRTP_MUTATE=$u: exit $rc"; cat "$T/err"; return 1; }
    seen="$seen $(grep -o "MISMATCH $u ([^)]*) cycle [0-9]*" "$T/err"), exit $rc;"
  done
  echo "mutants caught:$seen"
}

# --vcd: a small frame at 100 MHz (a cycle is 10000 ps) with and without the waveform
VCD_FRAME=(cornell --width 8 --height 8 --max-depth 1 --mode rtl --clock-mhz 100)

t_vcd_matches_stats() {
  model_built
  "$BIN" render "${VCD_FRAME[@]}" -o "$T/n.png" --stats "$T/n.json" >/dev/null
  "$BIN" render "${VCD_FRAME[@]}" -o "$T/v.png" --stats "$T/v.json" --vcd "$T/all.vcd" --vcd-cycles 0:1000000000 >/dev/null
  "$BIN" render "${VCD_FRAME[@]}" -o "$T/w.png" --vcd "$T/w.vcd" --vcd-cycles 1000:1500 >/dev/null
  cmp "$T/n.png" "$T/v.png" && cmp "$T/n.png" "$T/w.png"
  local rc=0  # a file that cannot be written: one line, exit 3, as in cycle mode
  "$BIN" render "${VCD_FRAME[@]}" -o "$T/u.png" --vcd "$T/no/such/dir.vcd" 2>"$T/err" >/dev/null || rc=$?
  [[ $rc -eq 3 && $(wc -l <"$T/err") -eq 1 ]] || { echo "unwritable --vcd: exit $rc"; cat "$T/err"; return 1; }
  PYTHONPATH=tests python3 - "$T" <<'PY'
import json, sys, vcd_reader
T = sys.argv[1]
n, s = (json.load(open(T + f)) for f in ("/n.json", "/v.json"))
for k in n:  # --stats as without --vcd
    if k not in ("seconds", "host", "host_rss_kb", "host_peak_rss_kb"):
        assert n[k] == s[k], (k, n[k], s[k])
c, a, w = s["cycle"], vcd_reader.Vcd(T + "/all.vcd"), vcd_reader.Vcd(T + "/w.vcd")
P, end = 10000, c["cycles"] * 10000
assert a.timescale == "1ps" and "one cycle = 10000 ps" in a.comment, (a.timescale, a.comment)
assert a.times[0] == 0 and a.times[-1] == end, (a.times[0], a.times[-1], c["cycles"])
# cycle mode's names where the RTL has the same thing (no xform: rebase and wide are apart)
names = ["dynrtc.clk", "dynrtc.pipe0.threads_in_flight", "dynrtc.pipe0.mem_port.outstanding"]
names += ["dynrtc.pipe0.%s.%s" % (u, g) for u in ("rgs", "trav", "list", "isect") for g in ("busy", "issue", "thread_id")]
names += ["dynrtc.pipe0.%s.queue_depth" % u for u in ("trav", "list", "isect")]
names += ["dynrtc.pipe0.cache_%s.%s" % (k, g) for k in ("kd_nodes", "lists", "matrices", "shading")
          for g in ("lookups", "misses", "fills")]
for name in names:
    a.find(*name.rsplit(".", 1))
total = lambda scope, name: a.integral(a.find("dynrtc.pipe0." + scope, name), 0, end) // P
for u, k in c["issues"].items():  # every unit's steps, the RTL's counters
    assert total(u, "issue") == k, (u, total(u, "issue"), k)
for cache, port in (("kd_nodes", "nodes"), ("lists", "lists"), ("matrices", "words"), ("shading", "shading")):
    assert total("cache_" + cache, "lookups") == c["reads"][port], (cache, c["reads"][port])
# every transfer is a line fill; mem_transfers also has the controllers' set-up reads before cycle 0
misses = sum(total("cache_" + k, "misses") for k in ("kd_nodes", "lists", "matrices", "shading"))
assert 0 < misses <= c["mem_transfers"], (misses, c["mem_transfers"])
for scope, name in [("cache_" + k, "fills") for k in ("kd_nodes", "lists", "matrices", "shading")] + \
                   [("mem_port", "outstanding"), ("", "threads_in_flight")]:  # all arrived, all blocks done
    assert a.changes[a.find("dynrtc.pipe0" + (scope and "." + scope), name)][-1][1] == 0, (scope, name)
assert 0 < total("rgs", "busy") < c["cycles"] and total("rgs", "issue") > 0, total("rgs", "busy")
assert w.times[0] == 1000 * P and w.times[-1] == 1500 * P, (w.times[0], w.times[-1])
for ident, (scope, name, _) in w.vars.items():  # the window holds the whole run's values
    assert w.integral(ident, 1000 * P, 1500 * P) == a.integral(a.find(scope, name), 1000 * P, 1500 * P), (scope, name)
print("%d cycles: issues and lookups equal --stats, %d misses of %d transfers; window 1000:1500 as the whole run"
      % (c["cycles"], misses, c["mem_transfers"]))
PY
}

t_missing_model() { # a saarcor whose build folder has no rtl/ model
  mkdir -p "$T/bare"
  cp "$BIN" "$T/bare/saarcor"
  local rc=0
  "$T/bare/saarcor" render cornell --width 8 --height 8 --mode rtl -o "$T/x.png" 2>"$T/err" >/dev/null || rc=$?
  [[ $rc -eq 2 && $(wc -l <"$T/err") -eq 1 ]] && grep -q "run make rtl" "$T/err" && [[ ! -e "$T/x.png" ]]
  cat "$T/err"
}

t_bad_inputs() { # one line and exit 2 each: a traversal algorithm without RTL, several pipes, other caches, bad
  # --vcd-cycles, --usage-plot
  local rc a
  for a in "--traversal ropes" "--pipes 2" "--cache-kb 8,2,6" "--unit-latency list=4" "--vcd $T/x.vcd --vcd-cycles 5:5" \
           "--vcd $T/x.vcd --vcd-cycles 7" "--vcd $T/x.vcd --vcd-cycles a:9" "--usage-plot $T/x.svg"; do
    rc=0
    # shellcheck disable=SC2086 # the option and its value
    "$BIN" render cornell --width 8 --height 8 --mode rtl $a -o "$T/y.png" 2>"$T/err" >/dev/null || rc=$?
    [[ $rc -eq 2 && $(wc -l <"$T/err") -eq 1 ]] || { echo "$a: exit $rc"; cat "$T/err"; return 1; }
  done
  cat "$T/err"
}

run_case rtl_render_cornell_matches_functional t_cornell_matches_functional
run_case rtl_render_unit_check_catches_mutant t_unit_check_catches_mutant
run_case rtl_render_vcd_matches_stats t_vcd_matches_stats
run_case rtl_render_without_model_says_make_rtl t_missing_model
run_case rtl_render_rejects_what_has_no_rtl t_bad_inputs
exit $((fails != 0))
