#!/usr/bin/env bash
# Test runner of `make test`: runs test programs (cmocka binaries, or shell tests that print the
# same "[ RUN      ]" / "[       OK ]" lines), shows each program's counts and the failures'
# output, and ends with the line "N passed, N failed". Exit 0 only if nothing failed.
# A program that exits non-zero or crashes outside a test case counts as one failure.
# Usage: tests/run.sh [--report FILE] PROGRAM...
set -u
report=/dev/null
while [[ $# -gt 0 && $1 == --* ]]; do
  case $1 in
    --report) report=$2; shift 2 ;;
    *) echo "run.sh: unknown option $1" >&2; exit 2 ;;
  esac
done

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:exitcode=99}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export CMOCKA_MESSAGE_OUTPUT=STDOUT

passed=0 failed=0 skipped=0
: >"$report"
for prog in "$@"; do
  log=$(mktemp)
  t0=$(date +%s.%N)
  timeout 900 "$prog" >"$log" 2>&1
  rc=$?
  t1=$(date +%s.%N)
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
  printf '%-44s %4d passed %3d failed %3d skipped  %6.1fs  %s\n' "$prog" "$oks" "$fails" "$skips" \
    "$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')" "$status" | tee -a "$report"
  if [[ $fails -ne 0 ]]; then
    echo "---- output of $prog (exit $rc) ----"
    grep -v '^\[ RUN      \]\|^\[       OK \]' "$log" | tail -40
    echo "----"
  fi
  cat "$log" >>"$report"
  rm -f "$log"
done
echo "$passed passed, $failed failed, $skipped skipped"
[[ $failed -eq 0 ]]
