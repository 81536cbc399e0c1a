#!/usr/bin/env bash
# Short form of make bench-longrun: 100 frames of the generated animated scene must render at
# constant memory. Each frame's --stats holds the program's resident-set peak (VmHWM); the peak
# after frame 100 may exceed the peak after frame 10 by at most MARGIN_KB (allocator warm-up:
# about 0.3 MB measured). The image is large enough that losing one pixel buffer per frame
# (128x96x4 bytes = 48 KiB, 4.3 MB over 90 frames) would fail the functional case. The cycle
# case checks that the cycle model, kept across the frames, does not grow. Prints cmocka-style
# lines for tests/run.sh.
set -u
cd "$(dirname "$0")/.."
BIN=${SAARCOR_BIN:-build/saarcor}
MARGIN_KB=2048
T=$(mktemp -d /tmp/saarcor-longrun-XXXXXX)
trap 'rm -rf "$T"' EXIT
source tests/case_lib.sh

peak() { # stats file
  python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["host_peak_rss_kb"])' "$1"
}

check() { # name, render options...
  local name=$1; shift
  mkdir "$T/$name"
  "$BIN" render animated --frames 0:99 --threads 2 -o "$T/$name/f.png" --stats "$T/$name/s.json" "$@" >/dev/null
  local p10 p100
  p10=$(peak "$T/$name/s_0009.json") p100=$(peak "$T/$name/s_0099.json")
  ((p100 - p10 <= MARGIN_KB)) ||
    { echo "$name: peak RSS grew from $p10 KiB (frame 10) to $p100 KiB (frame 100), more than $MARGIN_KB KiB"; return 1; }
  echo "$name: peak RSS $p10 KiB at frame 10, $p100 KiB at frame 100 (+$((p100 - p10)) KiB, at most $MARGIN_KB)"
}

t_functional() { check functional --width 128 --height 96; }
t_cycle() { check cycle --mode cycle --width 32 --height 24; }

run_case longrun_100_frames_functional t_functional
run_case longrun_100_frames_cycle t_cycle
exit $((fails != 0))
