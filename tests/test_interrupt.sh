#!/usr/bin/env bash
# Ctrl-C and SIGTERM during `saarcor render` (docs/cli.md, exit codes): a frame sequence stopped
# after its first frames keeps the frames done so far as complete images, says in one line how
# many were written, exits with 130 (SIGINT) or 143 (SIGTERM) and leaves no temporary file; a
# single long frame (functional with two threads, and the cycle model) stops at the next block
# row / epoch within seconds and writes nothing; reference, compare-hits, info --frames, f24verify,
# f24gen, profile, stress and jobs stop at their next safe point with 130 and one line. Prints cmocka-style lines
# for tests/run.sh.
set -u
cd "$(dirname "$0")/.."
BIN=${SAARCOR_BIN:-build/saarcor}
T=$(mktemp -d /tmp/saarcor-interrupt-XXXXXX)
trap 'rm -rf "$T"' EXIT
source tests/case_lib.sh

wait_for() { # file, seconds: true once file exists
  local i
  for ((i = 0; i < $2 * 20; i++)); do [[ -e $1 ]] && return 0; sleep 0.05; done
  echo "timed out after $2 s waiting for $1"; return 1
}

# stop_after SIGNAL FILE ARGS...: starts render ARGS in the background, sends SIGNAL once FILE
# exists, waits (at most 60 s) and leaves the exit code in $T/rc, stderr in $T/err
stop_after() {
  local sig=$1 file=$2; shift 2
  "$BIN" render "$@" >"$T/out" 2>"$T/err" &
  local pid=$! rc
  wait_for "$file" 60 || { kill -KILL $pid; return 1; }
  kill -"$sig" $pid
  local i
  for ((i = 0; i < 600 && $(kill -0 $pid 2>/dev/null && echo 1 || echo 0); i++)); do sleep 0.1; done
  kill -0 $pid 2>/dev/null && { kill -KILL $pid; echo "render did not stop within 60 s of SIG$sig"; return 1; }
  rc=0; wait $pid || rc=$?
  echo $rc >"$T/rc"
}

check_sequence() { # signal, expected exit code, output stem
  local sig=$1 want=$2 stem=$3
  stop_after "$sig" "$T/${stem}_0002.png" animated --width 160 --height 120 --threads 2 --frames 0:99999 \
    --stats "$T/$stem.json" -o "$T/$stem.png"
  [[ $(cat "$T/rc") == "$want" ]] || { echo "exit $(cat "$T/rc"), expected $want"; cat "$T/err"; return 1; }
  [[ $(wc -l <"$T/err") == 1 ]] || { echo "expected one line on stderr:"; cat "$T/err"; return 1; }
  local n
  n=$(sed -n "s/^saarcor render: interrupted by SIG$sig: \([0-9]*\) frames written (.*)$/\1/p" "$T/err")
  [[ -n $n ]] || { echo "unexpected message: $(cat "$T/err")"; return 1; }
  local files
  files=$(ls "$T" | grep -c "^${stem}_[0-9]*\.png$")
  [[ $files == "$n" ]] || { echo "message says $n frames, $files files on disk"; return 1; }
  [[ $(ls "$T" | grep -c "^${stem}_[0-9]*\.json$") == "$n" ]] || { echo "stats files differ from $n"; return 1; }
  if ls "$T" | grep -q '\.tmp$'; then echo "temporary files left: $(ls "$T" | grep '\.tmp$')"; return 1; fi
  local f
  for f in "$T/${stem}"_*.png; do # every frame is a whole image: compare reads it completely
    "$BIN" compare "$f" "$f" >/dev/null || { echo "$f is not a valid image"; return 1; }
  done
  echo "SIG$sig after $n frames: exit $want, $n complete PNG and stats files, no temporary files"
}

t_sigint_sequence() { check_sequence INT 130 seq; }
t_sigterm_sequence() { check_sequence TERM 143 term; }

check_long_frame() { # mode
  # the output file of the previous frame-less run cannot exist: wait on the scene load instead
  "$BIN" render room --width 4000 --height 3000 --threads 2 --mode "$1" -o "$T/long.png" >"$T/out" 2>"$T/err" &
  local pid=$! i
  sleep 2
  local t0=$SECONDS
  kill -INT $pid
  for ((i = 0; i < 300 && $(kill -0 $pid 2>/dev/null && echo 1 || echo 0); i++)); do sleep 0.1; done
  kill -0 $pid 2>/dev/null && { kill -KILL $pid; echo "$1: a long frame did not stop within 30 s"; return 1; }
  local rc=0; wait $pid || rc=$?
  [[ $rc == 130 ]] || { echo "$1: exit $rc, expected 130"; cat "$T/err"; return 1; }
  grep -qx 'saarcor render: interrupted by SIGINT: 0 frames written' "$T/err" ||
    { echo "$1: unexpected message: $(cat "$T/err")"; return 1; }
  [[ ! -e $T/long.png && ! -e $T/long.png.tmp ]] || { echo "$1: an unfinished frame was written"; return 1; }
  echo "$1 mode: a 4000x3000 frame stopped $((SECONDS - t0)) s after SIGINT, nothing written"
}

t_long_frame_functional() { check_long_frame functional; }
t_long_frame_cycle() { check_long_frame cycle; }

# check_command MESSAGE OUTPUT ARGS...: saarcor ARGS started in its own process group (as a
# terminal's foreground job) gets SIGINT after $DELAY seconds (default 1: well past the start-up,
# which installs the handler, and inside the long work); it must stop within 30 s with exit 130,
# the one line "saarcor MESSAGE" on stderr and no OUTPUT file (- for none)
check_command() {
  local msg=$1 out=$2; shift 2
  setsid "$BIN" "$@" >"$T/out" 2>"$T/err" &
  local pid=$! i rc=0
  sleep "${DELAY:-1}"
  kill -INT -- -$pid
  for ((i = 0; i < 300 && $(kill -0 $pid 2>/dev/null && echo 1 || echo 0); i++)); do sleep 0.1; done
  kill -0 $pid 2>/dev/null && { kill -KILL -- -$pid; echo "$1: did not stop within 30 s"; return 1; }
  wait $pid || rc=$?
  [[ $rc == 130 ]] || { echo "$*: exit $rc, expected 130"; cat "$T/err"; return 1; }
  [[ $(cat "$T/err") == "saarcor $msg" ]] || { echo "$*: unexpected stderr: $(cat "$T/err")"; return 1; }
  [[ $out == - || ! -e $out ]] || { echo "$*: $out was written"; return 1; }
  echo "$1: stopped by SIGINT, exit 130"
}

t_other_commands() {
  check_command "reference: interrupted by SIGINT: nothing written" "$T/ref.exr" \
    reference room --width 3000 --height 2000 -o "$T/ref.exr"
  check_command "compare-hits: interrupted by SIGINT: nothing written" "$T/h.json" \
    compare-hits room --width 3000 --height 2000 --json "$T/h.json"
  check_command "info: interrupted by SIGINT: frames not reported" "$T/i.json" \
    info animated --frames 100000 --json "$T/i.json"
  check_command "f24verify: interrupted by SIGINT: the operations above were checked, --json not written" \
    "$T/v.json" f24verify -n 1e8 --json "$T/v.json"
  check_command "stress: interrupted by SIGINT: nothing written" "$T/s.json" stress --json "$T/s.json"
  check_command "f24gen: interrupted by SIGINT: the vectors written so far are kept" - \
    f24gen add 1000000000000 -o "$T/g.txt"
  # a scene whose load and kd-tree builds take several seconds: profile stops after them
  "$BIN" gen terrain --detail 1000 -o "$T/big.glb" >/dev/null || { echo "gen terrain failed"; return 1; }
  check_command "profile: interrupted by SIGINT: nothing written" "$T/p.h" \
    profile "$T/big.glb" --mem-mb 1024 -o "$T/p.h"
  printf 'sleep 0.5\nsleep 30\nsleep 30\n' >"$T/jobs.txt"
  DELAY=2 check_command "jobs: interrupted by SIGINT: 2 of 3 jobs run" - jobs "$T/jobs.txt" # the first job's 0.5 s done
}

run_case interrupt_sequence_sigint t_sigint_sequence
run_case interrupt_sequence_sigterm t_sigterm_sequence
run_case interrupt_long_frame_functional t_long_frame_functional
run_case interrupt_long_frame_cycle t_long_frame_cycle
run_case interrupt_other_commands t_other_commands
exit $((fails != 0))
