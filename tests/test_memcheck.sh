#!/usr/bin/env bash
# Valgrind memcheck pass of one small render: 64x48 of the generated room scene in functional
# and in cycle mode (two host threads each, so the thread start/stop paths are checked too),
# and a two-frame animation (the per-frame update path). Zero errors and zero leaks: valgrind's
# --error-exitcode fails the case on any memory error and on definite, indirect or possible
# leaks. "Still reachable" blocks (libraries' caches alive at exit) are not counted; nothing is
# suppressed (tests/valgrind/saarcor.supp is kept empty of our code, see there).
# On a CPU without RDTSCP, tests/valgrind/hwy_timer_shim.c is preloaded (why: see that file).
# Prints cmocka-style lines for tests/run.sh.
set -u
cd "$(dirname "$0")/.."
BIN=${SAARCOR_BIN:-build/saarcor}
SHIM=${SAARCOR_HWY_SHIM:-build/valgrind/hwy_timer_shim.so}
T=$(mktemp -d /tmp/saarcor-memcheck-XXXXXX)
trap 'rm -rf "$T"' EXIT
source tests/case_lib.sh

command -v valgrind >/dev/null || { echo "test_memcheck: valgrind is missing (scripts/install-deps.sh)"; exit 1; }
preload=
if ! grep -qw rdtscp /proc/cpuinfo; then
  [[ -f $SHIM ]] || { echo "test_memcheck: $SHIM is missing (make $SHIM)"; exit 1; }
  preload=$(realpath "$SHIM")
fi

memcheck() { # log, command...: valgrind memcheck, failing on any error or leak
  local log=$1; shift
  LD_PRELOAD=$preload valgrind --error-exitcode=99 --leak-check=full \
    --errors-for-leak-kinds=definite,indirect,possible --show-leak-kinds=definite,indirect,possible \
    --suppressions=tests/valgrind/saarcor.supp "$@" >"$log" 2>&1 ||
    { echo "memcheck failed (exit $?): $*"; grep -v '^==[0-9]*== *$' "$log" | tail -60; return 1; }
  grep -q 'ERROR SUMMARY: 0 errors' "$log" || { echo "memcheck reported errors: $*"; tail -30 "$log"; return 1; }
  echo "$(grep -o 'definitely lost: .*' "$log"), $(grep -o 'ERROR SUMMARY: [0-9]* errors' "$log")"
}

t_functional() {
  memcheck "$T/f.log" "$BIN" render room --width 64 --height 48 --threads 2 -o "$T/f.png"
  "$BIN" compare "$T/f.png" "$T/f.png" >/dev/null
}

t_cycle() {
  memcheck "$T/c.log" "$BIN" render room --width 64 --height 48 --threads 2 --mode cycle --pipes 2 \
    --stats "$T/c.json" -o "$T/c.png"
  grep -q '"cycles"' "$T/c.json"
}

t_animation() {
  memcheck "$T/a.log" "$BIN" render animated --width 32 --height 24 --threads 2 --frames 0:1 -o "$T/a.png"
  [[ -f $T/a_0000.png && -f $T/a_0001.png ]]
}

run_case memcheck_render_functional t_functional
run_case memcheck_render_cycle t_cycle
run_case memcheck_render_animation t_animation
exit $((fails != 0))
