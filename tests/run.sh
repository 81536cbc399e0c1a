#!/usr/bin/env bash
# Test runner: runs test programs (cmocka binaries, or shell tests that print the same
# "[ RUN      ]" / "[       OK ]" lines), shows each program's counts as it finishes and the
# failures' output, and ends with the line "N passed, N failed, N skipped". Exit 0 only if nothing
# failed. A program that exits non-zero or crashes outside a test case counts as one failure. The
# report file holds every program's full output, in the order given.
# Usage:
#   tests/run.sh [--report FILE] [--jobs N] PROGRAM...   runs them, JOBS at a time (default: the
#                                                        number of cores; most use one core)
#   tests/run.sh --one DIR PROGRAM                       runs one, keeps its result in DIR, prints
#                                                        its line; exit 0 whatever the result
#   tests/run.sh --collect DIR [--report FILE] PROGRAM... the totals of results kept in DIR
# make test uses the last two: each program runs as a make target as soon as the builds it needs
# are done, beside the other builds (Makefile, TEST_RUNS), and the totals come at the end.
set -u
report=/dev/null
jobs=$(nproc)
mode=run
dir=
while [[ $# -gt 0 && $1 == --* ]]; do
  case $1 in
    --report) report=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --one | --collect) mode=${1#--}; dir=$2; shift 2 ;;
    *) echo "run.sh: unknown option $1" >&2; exit 2 ;;
  esac
done

# ASan records 8 frames of each allocation's stack (default 30) and keeps 32 MB of freed memory in
# quarantine (default 256 MB): every check stays on and reports keep the callers that matter, and
# the malloc-heavy tests (the kd-tree builds) run in half the time (build/asan/test_kdtree 8.7 ->
# 4.7 s; the 26 ASan unit tests one after another 106 -> 77 s)
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:exitcode=99:malloc_context_size=8:quarantine_size_mb=32}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export CMOCKA_MESSAGE_OUTPUT=STDOUT
# a program run from a make recipe behaves as when run alone (its own makes, their -j)
unset MAKEFLAGS MFLAGS MAKELEVEL MAKEOVERRIDES

tmp=$(mktemp -d /tmp/saarcor-run-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
[[ $mode == run ]] && dir=$tmp
mkdir -p "$dir"

# python3 behind a version manager's shim (pyenv's is a bash script that starts pyenv for every
# call: 0.5 s of CPU a call on the 2-core machine, against 0.05 s for the interpreter) costs the
# tests, which call it hundreds of times, minutes: the interpreter itself goes first on PATH
if py=$(python3 -c 'import sys; print(sys.executable)' 2>/dev/null) && [[ -x $py ]]; then
  mkdir "$tmp/bin" && ln -s "$py" "$tmp/bin/python3" && export PATH="$tmp/bin:$PATH"
fi

# key PROGRAM: the name of its result files in $dir
key() { local k=${1//\//__}; echo "$dir/$k"; }

# run_one PROGRAM: its output, exit code and seconds into $(key PROGRAM).{log,rc,sec}
run_one() {
  local k t0 t1 rc=0
  k=$(key "$1")
  rm -f "$k.rc"
  t0=$(date +%s.%N)
  timeout 900 "$1" >"$k.log" 2>&1 || rc=$?
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }' >"$k.sec"
  echo $rc >"$k.rc" # written last: the program is done
}

# summarize PROGRAM: prints the program's line (and its failures' output), adds the counts
passed=0 failed=0 skipped=0
summarize() {
  local k log rc runs oks skips fails status
  k=$(key "$1")
  log=$k.log
  if [[ ! -e $k.rc ]]; then
    printf '%-44s did not run\n' "$1"
    failed=$((failed + 1))
    return
  fi
  rc=$(cat "$k.rc")
  runs=$(grep -c '^\[ RUN      \]' "$log")
  oks=$(grep -c '^\[       OK \]' "$log")
  # cmocka repeats skipped names in its closing list: count distinct names
  skips=$(grep '^\[  SKIPPED \]' "$log" | grep -v 'test(s)' | sort -u | wc -l)
  fails=$((runs - oks - skips))
  [[ $rc -ne 0 && $fails -eq 0 ]] && fails=1
  passed=$((passed + oks))
  failed=$((failed + fails))
  skipped=$((skipped + skips))
  status=ok
  [[ $fails -ne 0 ]] && status=FAILED
  printf '%-44s %4d passed %3d failed %3d skipped  %6.1fs  %s\n' "$1" "$oks" "$fails" "$skips" \
    "$(cat "$k.sec")" "$status"
  if [[ $fails -ne 0 ]]; then
    echo "---- output of $1 (exit $rc) ----"
    grep -v '^\[ RUN      \]\|^\[       OK \]' "$log" | tail -40
    echo "----"
  fi
}

# collect PROGRAM...: the report in the order given, the failed programs again, the totals line
collect() {
  local p totals
  passed=0 failed=0 skipped=0
  : >"$report"
  for p in "$@"; do
    summarize "$p" >>"$report" 2>&1
    [[ -e $(key "$p").log ]] && cat "$(key "$p").log" >>"$report"
  done
  totals="$passed passed, $failed failed, $skipped skipped"
  grep -E '^[^ ]+ +([0-9]+ passed .*FAILED|did not run)$' "$report"
  echo "$totals"
  [[ $totals == *" 0 failed,"* ]]
}

case $mode in
  one)
    run_one "$1"
    summarize "$1"
    exit 0 ;;
  collect)
    collect "$@"
    exit ;;
esac

progs=("$@")
next=0 reported=0
declare -A running=()
while [[ $reported -lt ${#progs[@]} ]]; do
  while [[ ${#running[@]} -lt $jobs && $next -lt ${#progs[@]} ]]; do
    run_one "${progs[$next]}" &
    running[$next]=1
    next=$((next + 1))
  done
  for i in "${!running[@]}"; do
    if [[ -e $(key "${progs[$i]}").rc ]]; then
      summarize "${progs[$i]}"
      unset "running[$i]"
      reported=$((reported + 1))
    fi
  done
  sleep 0.1
done
wait
collect "${progs[@]}" >"$tmp/totals"
rc=$?
tail -1 "$tmp/totals"
exit $rc
