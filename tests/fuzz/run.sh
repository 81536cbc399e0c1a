#!/usr/bin/env bash
# make fuzz: runs every libFuzzer harness of FUZZ_DIR for SECONDS, starting from the seed corpus
# (FUZZ_DIR/corpus/<target>/) and the regression inputs (tests/fuzz/regress/<target>/). New
# interesting inputs go to FUZZ_DIR/found/<target>/, crashes, leaks and timeouts to
# FUZZ_DIR/crashes/<target>-*; logs to FUZZ_DIR/logs/. Prints one line per harness (executions,
# coverage, crashes) and a summary in FUZZ_DIR/fuzz-report.txt. Exit 1 if anything crashed.
# Usage: tests/fuzz/run.sh FUZZ_DIR SECONDS
set -u
mkdir -p "$1"
dir=$(cd "$1" && pwd) secs=$2 # absolute: fuzz_cli runs each input in its own directory
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$dir/crashes" "$dir/logs"
report=$dir/fuzz-report.txt
: >"$report"
status=0
for bin in "$dir"/fuzz_*; do
  [[ -x $bin && -f $bin ]] || continue
  name=$(basename "$bin") target=${name#fuzz_}
  mkdir -p "$dir/found/$target" "$here/regress/$target"
  log=$dir/logs/$name.log
  before=$(ls "$dir/crashes" | grep -c "^$target-" || true)
  # -close_fd_mask=3: the command-line harness prints usage text; -rss_limit_mb: glTF bombs
  "$bin" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -close_fd_mask=3 \
    -artifact_prefix="$dir/crashes/$target-" "$dir/found/$target" "$dir/corpus/$target" "$here/regress/$target" \
    >"$log" 2>&1
  rc=$?
  after=$(ls "$dir/crashes" | grep -c "^$target-" || true)
  stats=$(grep -E '^#[0-9]+' "$log" | tail -1 | sed -E 's/^#([0-9]+).*cov: ([0-9]+).*/\1 executions, coverage \2 edges/')
  line="$name: ${secs}s, ${stats:-no statistics}, exit $rc, $((after - before)) new crash(es)"
  echo "$line" | tee -a "$report"
  if [[ $rc -ne 0 || $after -ne $before ]]; then
    status=1
    grep -m3 -E 'ERROR: |SUMMARY: |runtime error' "$log" | sed 's/^/    /' | tee -a "$report"
  fi
done
echo "reproduce a crash: $dir/fuzz_TARGET FILE; keep it as tests/fuzz/regress/TARGET/NAME (tests/test_fuzz.sh)" | tee -a "$report"
exit $status
