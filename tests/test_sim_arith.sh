#!/usr/bin/env bash
# One truth per computation: the simulator with the host fast path of the fp24 arithmetic
# (build/saarcor: tb/fp/f24_fast.h, f24_fast_sum.c, the units' decoded working values) against the
# program built with the integer hardware arithmetic (build/hw/saarcor, make SIM_ARITH=hw): the
# image, the AOVs (EXR) and every counter of --stats (all but the host's time and memory) equal,
# bit for bit, on every golden scene in both modes, and with every traversal algorithm on the
# instanced room and the cornell box in both modes; and the build of the packet values' baseline
# version (no AVX2) on every golden scene. Cases on ../shared scenes are skipped with a
# message when ../shared is absent. Prints cmocka-style lines for tests/run.sh.
set -u
cd "$(dirname "$0")/.."
BIN=${SAARCOR_BIN:-build/saarcor}
HW_BIN=${SAARCOR_HW_BIN:-build/hw/saarcor}
# the packet values' functions in their baseline version only (make SIM_LANES=baseline: what
# machines without AVX2 run; build/saarcor picks the AVX2 one where the CPU has it)
BASE_BIN=${SAARCOR_BASELINE_BIN:-build/baseline/saarcor}
T=$(mktemp -d /tmp/saarcor-sim-arith-XXXXXX)
export SOURCE_DATE_EPOCH=0 # the AOVs' EXR files dated alike: equal pixels, equal bytes
trap 'rm -rf "$T"' EXIT
[[ -x $HW_BIN ]] || { echo "test_sim_arith: $HW_BIN is missing (make BUILD=build/hw SIM_ARITH=hw build/hw/saarcor)"; exit 1; }
[[ -x $BASE_BIN ]] ||
  { echo "test_sim_arith: $BASE_BIN is missing (make BUILD=build/baseline HOST_BUILD=build SIM_LANES=baseline build/baseline/saarcor)"; exit 1; }

# shellcheck source=case_lib.sh
source tests/case_lib.sh

# the --stats counters without the host's wall time and memory, one per line
counters() {
  python3 - "$1" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
for k in ("seconds", "host_rss_kb", "host_peak_rss_kb"):
    s.pop(k, None)
s.get("host", {}).pop("seconds", None)
print(json.dumps(s, indent=0, sort_keys=True))
PY
}

# name scene options...: both programs ($FAST_BIN or $BIN), same image, AOVs and counters; with
# HW_FROM=CASE the integer arithmetic's files of that earlier case with the same scene and options
# (the baseline cases reuse the functional ones': the same hw render, 8 renders fewer)
same() {
  local name=$1 scene=$2
  shift 2
  local b
  for b in fast hw; do
    local bin=${FAST_BIN:-$BIN}
    [[ $b == hw ]] && bin=$HW_BIN
    if [[ $b == hw && -n ${HW_FROM:-} && -f $T/$HW_FROM.hw.txt ]]; then
      local f
      for f in png exr txt; do cp "$T/$HW_FROM.hw.$f" "$T/$name.hw.$f"; done
      continue
    fi
    "$bin" render "$scene" --width 48 --height 36 --threads 2 "$@" -o "$T/$name.$b.png" --aov "$T/$name.$b.exr" \
      --stats "$T/$name.$b.json" >/dev/null || { echo "$name: $bin render failed"; return 1; }
    counters "$T/$name.$b.json" >"$T/$name.$b.txt"
  done
  cmp -s "$T/$name.fast.png" "$T/$name.hw.png" || { echo "$name: the images differ"; return 1; }
  # every pixel of every AOV: the files' bytes (both dated SOURCE_DATE_EPOCH)
  cmp -s "$T/$name.fast.exr" "$T/$name.hw.exr" ||
    { echo "$name: the AOVs differ:"; idiff -fail 0 -warn 0 -a "$T/$name.fast.exr" "$T/$name.hw.exr" | tail -5; return 1; }
  diff "$T/$name.fast.txt" "$T/$name.hw.txt" >"$T/$name.diff" ||
    { echo "$name: the counters differ (< fast path, > integer arithmetic):"; head -20 "$T/$name.diff"; return 1; }
  echo "$name: image, AOVs and $(wc -l <"$T/$name.fast.txt") counter lines equal"
}

SCENES="cornell|cornell|
room|room|
plants|plants|
terrain|terrain|
animated|animated|--time 1.5
truck|../shared/scenes/CesiumMilkTruck.glb|--ground
bunny|../shared/scenes/bunny.glb|--ground
gallery|../shared/scenes/gallery_ccby_503k.glb|--mem-mb 128"

while IFS='|' read -r name scene opts; do
  for mode in functional cycle; do
    case_name="sim_arith_${name}_$mode"
    if [[ $scene == ../shared/* && ! -f $scene ]]; then
      skip_case "$case_name" "$scene is absent"
      continue
    fi
    eval "t_$case_name() { same $case_name $scene --mode $mode $opts; }"
    run_case "$case_name" "t_$case_name"
  done
  [[ $scene == ../shared/* && ! -f $scene ]] && continue
  case_name="sim_arith_${name}_baseline"
  eval "t_$case_name() { FAST_BIN=$BASE_BIN HW_FROM=sim_arith_${name}_functional same $case_name $scene --mode functional $opts; }"
  run_case "$case_name" "t_$case_name"
done <<<"$SCENES"

for scene in room cornell; do
  for algo in short-stack restart push-down ropes grid grid2; do
    for mode in functional cycle; do
      case_name="sim_arith_${scene}_${algo//-/_}_$mode"
      eval "t_$case_name() { same $case_name $scene --mode $mode --traversal $algo; }"
      run_case "$case_name" "t_$case_name"
    done
  done
done
exit $((fails != 0))
