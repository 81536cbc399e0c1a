#!/usr/bin/env bash
# HLS readiness and scene specialization in make test: `make hls-check` is clean for the general
# design and every hls/config_*.h; each of its checks catches a mutant (malloc, recursion, float,
# VLA, unbounded loops, function pointers); the unit top functions (hls/top) replay captured
# transactions bit for bit (tb/vitis/tb_units.c, the csim testbench); dynrtc_top renders a
# scene pixel for pixel like the simulator, in the general design and in a reduced
# configuration, and the testbench fails when the configuration does not fit the render;
# render with the scene profile draws the same image as --general; saarcor profile errors.
# Prints cmocka-style lines.
set -u
cd "$(dirname "$0")/.."
B=${BUILD:-build}
BIN=$B/saarcor
T=$(mktemp -d /tmp/saarcor-test-hls-XXXXXX)
trap 'rm -rf "$T"' EXIT
HLS_CFLAGS=(-std=c11 -O2 -Wall -Wextra -Werror -Wno-unknown-pragmas -Wno-unused-label -Ihls -Ihls/fp24 -Ihls/units -Ihls/top)

# shellcheck source=case_lib.sh
source tests/case_lib.sh

t_hls_check() {
  make --no-print-directory hls-check
  local n; n=$(ls hls/config_*.h | wc -l)
  [[ $n -ge 2 ]] || { echo "expected at least two reduced configurations, found $n"; return 1; }
  echo "hls-check clean: general design and $n reduced configurations"
}

mutant() { # file, source, expected message
  printf '%s\n' "$2" >"$T/$1"
  if python3 scripts/hls_check.py --src "$T/$1" --out "$T/out" >"$T/$1.log"; then
    echo "hls-check passed the mutant $1"; return 1
  fi
  grep -q "$3" "$T/$1.log" || { cat "$T/$1.log"; echo "$1: expected '$3'"; return 1; }
}

t_hls_check_mutants() {
  mutant malloc.c '#include <stdlib.h>
int *f(unsigned n) { return malloc(n); }' "undefined external symbol malloc"
  mutant strlen.c '#include <string.h>
size_t f(const char *s) { return strlen(s); }' "undefined external symbol strlen"
  mutant recursion.c 'unsigned f(unsigned n);
static unsigned g(unsigned n) { return n ? f(n - 1) + 1 : 0; }
unsigned f(unsigned n) { return n ? g(n - 1) * 2 : 1; }' "call graph cycle"
  mutant float.c '#include <stdint.h>
uint32_t f(uint32_t x) { float y = (float)x * 0.5f; return (uint32_t)y; }' "SSE"
  mutant vla.c '#include <stdint.h>
uint32_t f(const uint32_t *m, uint32_t n) { uint32_t a[n]; for (uint32_t i = 0; i < 4; i++) a[i & (n - 1)] = m[i]; return a[0]; }' "variable length array"
  mutant chase.c '#include <stdint.h>
uint32_t f(const uint32_t *m) { uint32_t s = 0, i = 0; while (m[i]) { s += m[i]; i = m[i + 1]; } return s; }' "has no static bound"
  mutant counter.c '#include <stdint.h>
uint32_t g(const uint32_t *m, int n) { uint32_t s = 0; for (int i = 0; i < n; i++) s += m[i]; return s; }' "bounded only by its counter type"
  mutant fptr.c '#include <stdint.h>
uint32_t f(uint32_t (*op)(uint32_t), uint32_t x) { return op(x); }' "indirect call"
  echo "8 mutants caught"
}

# the general design's hls/ objects, compiled once for the testbenches of both cases below
hls_objects() {
  [[ -f $T/hls/done ]] && return
  mkdir -p "$T/hls"
  local f
  for f in hls/fp24/*.c hls/units/*.c hls/top/*.c; do
    gcc "${HLS_CFLAGS[@]}" -c "$f" -o "$T/hls/$(basename "$f" .c).o"
  done
  touch "$T/hls/done"
}

t_unit_tops_replay_capture() {
  hls_objects
  gcc "${HLS_CFLAGS[@]}" tb/vitis/tb_units.c "$T"/hls/*.o -o "$T/tb_units"
  "$BIN" render room --width 64 --height 48 --capture-unit-io "$T/cap" --capture-limit 20000 -o "$T/room.png" >/dev/null
  "$T/tb_units" "$T/cap"
}

t_dynrtc_top_general_and_reduced() {
  local size=(--width 64 --height 48)
  "$BIN" info cornell "${size[@]}" --image "$T/cornell.bin" >/dev/null
  "$BIN" render cornell "${size[@]}" -o "$T/full.ppm" >/dev/null
  "$BIN" render cornell "${size[@]}" --max-depth 0 --no-shadows -o "$T/primary.ppm" >/dev/null
  hls_objects
  gcc "${HLS_CFLAGS[@]}" tb/vitis/tb_dynrtc.c "$T"/hls/*.o -o "$T/tb_general"
  gcc -include hls/config_cornell_primary.h "${HLS_CFLAGS[@]}" hls/fp24/*.c hls/units/*.c hls/top/*.c \
    tb/vitis/tb_dynrtc.c -o "$T/tb_reduced"
  "$T/tb_general" "$T/cornell.bin" "$T/full.ppm" 3 1
  "$T/tb_general" "$T/cornell.bin" "$T/primary.ppm" 0 0
  "$T/tb_reduced" "$T/cornell.bin" "$T/primary.ppm" 0 0
  if "$T/tb_reduced" "$T/cornell.bin" "$T/full.ppm" 3 1 >"$T/neg.log" 2>&1; then
    echo "the reduced design drew reflections and shadows it does not have"; return 1
  fi
  echo "dynrtc_top: general and cornell_primary designs match the simulator; the reduced one fails the full render"
}

t_profile_same_image() {
  for s in room cornell; do
    "$BIN" render "$s" --width 96 --height 64 -o "$T/$s.png" --stats "$T/$s.json" >/dev/null
    "$BIN" render "$s" --width 96 --height 64 -o "$T/${s}_general.png" --general --stats "$T/${s}_general.json" >/dev/null
    "$BIN" compare "$T/$s.png" "$T/${s}_general.png" --psnr-min 1000 >/dev/null
  done
  python3 - "$T" <<'PY'
import json, sys
t = sys.argv[1]
a, b = json.load(open(t + "/room.json")), json.load(open(t + "/room_general.json"))
assert a["rays"] == b["rays"], (a["rays"], b["rays"])
assert a["intersections"] < b["intersections"], (a["intersections"], b["intersections"])
print(f"room: same image, intersections {b['intersections']} -> {a['intersections']} with the profile")
PY
}

t_profile_command() {
  "$BIN" profile cornell --max-depth 0 --no-shadows -o "$T/config_x.h" | grep -q "run-time skips"
  grep -q "#define SAARCOR_CFG_SECONDARY 0" "$T/config_x.h"
  grep -q "#define SAARCOR_CFG_SHADOWS 0" "$T/config_x.h"
  cmp <(grep '#define SAARCOR_CFG_' "$T/config_x.h" | grep -v CFG_NAME) \
    <(grep '#define SAARCOR_CFG_' hls/config_cornell_primary.h | grep -v CFG_NAME)
  local rc=0
  "$BIN" profile cornell -o "$T/bad-name.h" 2>"$T/err" || rc=$?
  [[ $rc -eq 2 ]] && grep -q "config_NAME.h" "$T/err"
  rc=0; "$BIN" profile cornell --max-depth 99 2>/dev/null || rc=$?
  [[ $rc -eq 2 ]]
  rc=0; "$BIN" profile /nonexistent.gltf 2>/dev/null || rc=$?
  [[ $rc -eq 3 ]]
  echo "profile: config written and equal to the committed one; bad name/depth/file give exit 2/2/3"
}

run_case hls_check_default_and_configs t_hls_check
run_case hls_check_catches_mutants t_hls_check_mutants
run_case hls_unit_tops_replay_capture t_unit_tops_replay_capture
run_case hls_dynrtc_top_general_and_reduced t_dynrtc_top_general_and_reduced
run_case profile_skips_same_image t_profile_same_image
run_case profile_command t_profile_command
exit $((fails != 0))
