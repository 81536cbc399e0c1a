#!/usr/bin/env bash
# saarcor render --mode rtl (the Verilated DynRTP of rtl/dynrtp.sv, make rtl): the cornell box at
# 32x24 with shadows and secondary rays gives the PNG, the primary hits (the AOV's t, normal, node,
# triangle, u, v) and the counters of --mode functional bit for bit, every packet of the frame
# checked against the C core by the harness, and --stats carries the RTL's cycles and unit usage;
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

t_cornell_matches_functional() {
  "$BIN" render cornell "${SIZE[@]}" --mode rtl -o "$T/r.png" --aov "$T/r.exr" --stats "$T/r.json" >"$T/r.log"
  "$BIN" render cornell "${SIZE[@]}" -o "$T/f.png" --aov "$T/f.exr" --stats "$T/f.json" >/dev/null
  cmp "$T/r.png" "$T/f.png"
  oiiotool "$T/f.exr" --ch t,N.X,N.Y,N.Z,node,triangle,u,v -o "$T/f_hits.exr"
  idiff -fail 0 -warn 0 "$T/f_hits.exr" "$T/r.exr" >/dev/null
  python3 - "$T/f.json" "$T/r.json" <<'PY'
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
PY
  echo "cornell 32x24 --mode rtl: PNG, primary hits and counters as functional; $(grep '^rtl:' "$T/r.log" | cut -d';' -f1)"
}

t_missing_model() { # a saarcor whose build folder has no rtl/ model
  mkdir -p "$T/bare"
  cp "$BIN" "$T/bare/saarcor"
  local rc=0
  "$T/bare/saarcor" render cornell --width 8 --height 8 --mode rtl -o "$T/x.png" 2>"$T/err" >/dev/null || rc=$?
  [[ $rc -eq 2 && $(wc -l <"$T/err") -eq 1 ]] && grep -q "run make rtl" "$T/err" && [[ ! -e "$T/x.png" ]]
  cat "$T/err"
}

t_bad_inputs() { # one line and exit 2 each: a traversal algorithm without RTL, several pipes, other caches
  local rc a
  for a in "--traversal ropes" "--pipes 2" "--cache-kb 8,2,6" "--unit-latency list=4"; do
    rc=0
    # shellcheck disable=SC2086 # the option and its value
    "$BIN" render cornell --width 8 --height 8 --mode rtl $a -o "$T/y.png" 2>"$T/err" >/dev/null || rc=$?
    [[ $rc -eq 2 && $(wc -l <"$T/err") -eq 1 ]] || { echo "$a: exit $rc"; cat "$T/err"; return 1; }
  done
  cat "$T/err"
}

# the model takes about 7 CPU minutes to build (127 MB of C++ for 8 block controllers and 32
# threads), more than make test's budget allows: make rtl builds it, make rtl-test runs this case
if [[ -x $B/rtl/e7m16/tb_dynrtp ]]; then
  run_case rtl_render_cornell_matches_functional t_cornell_matches_functional
else
  echo "[ RUN      ] rtl_render_cornell_matches_functional"
  echo "[  SKIPPED ] rtl_render_cornell_matches_functional: $B/rtl/e7m16/tb_dynrtp is not built (make rtl; make rtl-test runs it)"
fi
run_case rtl_render_without_model_says_make_rtl t_missing_model
run_case rtl_render_rejects_what_has_no_rtl t_bad_inputs
exit $((fails != 0))
