#!/usr/bin/env bash
# Determinism: the same scene and options give the same image bits and the same counters and
# cycle counts across host thread counts (--threads 1, 2, 3), repeated runs and builds (-O2
# build/saarcor against -O0 build/O0/saarcor, which make test builds). For each case (room,
# cornell, a frame of the animated scene; functional mode, and cycle mode with two pipes so
# that the host threads share the pipes differently) every run's PNG must be byte-identical to
# the first run's, and its --stats JSON identical once the wall-clock and host-memory fields
# (seconds, host_rss_kb, host_peak_rss_kb, host.seconds) are removed: rays, unit work, memory words and, in
# cycle mode, cycles, unit usage, cache hits, stalls. Prints cmocka-style lines for tests/run.sh.
set -u
cd "$(dirname "$0")/.."
BIN=${SAARCOR_BIN:-build/saarcor}
O0_BIN=${SAARCOR_O0_BIN:-build/O0/saarcor}
T=$(mktemp -d /tmp/saarcor-determinism-XXXXXX)
trap 'rm -rf "$T"' EXIT
source tests/case_lib.sh
[[ -x $O0_BIN ]] || { echo "test_determinism: $O0_BIN is missing (make BUILD=build/O0 OPT='-O0 -g' build/O0/saarcor)"; exit 1; }

# the stats without what legitimately varies from run to run, keys sorted
stable_stats() {
  python3 -c 'import json, sys
d = json.load(open(sys.argv[1]))
for k in ("seconds", "host_rss_kb", "host_peak_rss_kb"):
    d.pop(k)
d["host"].pop("seconds")  # the host time of the frame; its upload bytes must agree
print(json.dumps(d, sort_keys=True, indent=1))' "$1"
}

# runs: label, program, threads
RUNS=("t1 $BIN 1" "t2 $BIN 2" "t3 $BIN 3" "t2-again $BIN 2" "O0-t2 $O0_BIN 2")

check() { # name, render arguments...
  local name=$1; shift
  local first= run label prog threads
  for run in "${RUNS[@]}"; do
    read -r label prog threads <<<"$run"
    # shellcheck disable=SC2068
    "$prog" render "$@" --width 64 --height 48 --threads "$threads" -o "$T/$name.$label.png" \
      --stats "$T/$name.$label.json" >/dev/null
    stable_stats "$T/$name.$label.json" >"$T/$name.$label.stats"
    if [[ -z $first ]]; then first=$label; continue; fi
    cmp -s "$T/$name.$first.png" "$T/$name.$label.png" ||
      { echo "$name: image of $label differs from $first:"; "$BIN" compare "$T/$name.$first.png" "$T/$name.$label.png"; return 1; }
    diff "$T/$name.$first.stats" "$T/$name.$label.stats" >"$T/diff" ||
      { echo "$name: counters of $label differ from $first:"; head -20 "$T/diff"; return 1; }
  done
  local cyc
  cyc=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1])).get("cycle", {}).get("cycles", "-"))' "$T/$name.$first.json")
  echo "$name: ${#RUNS[@]} runs (threads 1/2/3, again, -O0) give the same PNG bytes and counters; cycles $cyc"
}

t_room_functional() { check room room; }
t_room_cycle() { check room_cycle room --mode cycle --pipes 2; }
t_cornell_functional() { check cornell cornell; }
t_cornell_cycle() { check cornell_cycle cornell --mode cycle --pipes 2; }
t_animated_functional() { check animated animated --frame 45; }
t_animated_cycle() { check animated_cycle animated --frame 45 --mode cycle --pipes 2; }

run_case determinism_room_functional t_room_functional
run_case determinism_room_cycle t_room_cycle
run_case determinism_cornell_functional t_cornell_functional
run_case determinism_cornell_cycle t_cornell_cycle
run_case determinism_animated_frame_functional t_animated_functional
run_case determinism_animated_frame_cycle t_animated_cycle
exit $((fails != 0))
