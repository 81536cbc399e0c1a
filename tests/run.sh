#!/usr/bin/env bash
# Test runner of `make test`: runs test programs (cmocka binaries, or shell tests that print the
# same "[ RUN      ]" / "[       OK ]" lines), JOBS of them at a time (--jobs, default the number
# of cores: most test programs use one core), shows each program's counts as it finishes and the
# failures' output, and ends with the line "N passed, N failed". Exit 0 only if nothing failed.
# A program that exits non-zero or crashes outside a test case counts as one failure. The report
# file holds every program's full output, in the order given.
# Usage: tests/run.sh [--report FILE] [--jobs N] PROGRAM...
set -u
report=/dev/null
jobs=$(nproc)
while [[ $# -gt 0 && $1 == --* ]]; do
  case $1 in
    --report) report=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
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

work=$(mktemp -d /tmp/saarcor-run-XXXXXX)
trap 'rm -rf "$work"' EXIT

# python3 behind a version manager's shim (pyenv's is a bash script that starts pyenv for every
# call: 0.5 s of CPU a call on the 2-core machine, against 0.05 s for the interpreter) costs the
# tests, which call it hundreds of times, minutes: the interpreter itself goes first on PATH
if py=$(python3 -c 'import sys; print(sys.executable)' 2>/dev/null) && [[ -x $py ]]; then
  mkdir "$work/bin" && ln -s "$py" "$work/bin/python3" && export PATH="$work/bin:$PATH"
fi

# run_one INDEX PROGRAM: its output, exit code and seconds into $work/INDEX.{log,rc,sec}
run_one() {
  local t0 t1 rc=0
  t0=$(date +%s.%N)
  timeout 900 "$2" >"$work/$1.log" 2>&1 || rc=$?
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }' >"$work/$1.sec"
  echo $rc >"$work/$1.rc" # written last: the program is done
}

# summarize INDEX PROGRAM: prints the program's line (and its failures' output), adds the counts
passed=0 failed=0 skipped=0
summarize() {
  local log=$work/$1.log rc runs oks skips fails status
  rc=$(cat "$work/$1.rc")
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
  printf '%-44s %4d passed %3d failed %3d skipped  %6.1fs  %s\n' "$2" "$oks" "$fails" "$skips" \
    "$(cat "$work/$1.sec")" "$status"
  if [[ $fails -ne 0 ]]; then
    echo "---- output of $2 (exit $rc) ----"
    grep -v '^\[ RUN      \]\|^\[       OK \]' "$log" | tail -40
    echo "----"
  fi
}

progs=("$@")
next=0 reported=0
declare -A running=()
while [[ $reported -lt ${#progs[@]} ]]; do
  while [[ ${#running[@]} -lt $jobs && $next -lt ${#progs[@]} ]]; do
    run_one "$next" "${progs[$next]}" &
    running[$next]=1
    next=$((next + 1))
  done
  for i in "${!running[@]}"; do
    if [[ -e $work/$i.rc ]]; then
      summarize "$i" "${progs[$i]}"
      unset "running[$i]"
      reported=$((reported + 1))
    fi
  done
  sleep 0.1
done
wait

totals="$passed passed, $failed failed, $skipped skipped"
: >"$report"
for i in "${!progs[@]}"; do
  summarize "$i" "${progs[$i]}" >>"$report" 2>&1
  cat "$work/$i.log" >>"$report"
done
echo "$totals"
[[ $totals == *" 0 failed,"* ]]
