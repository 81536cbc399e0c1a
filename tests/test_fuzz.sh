#!/usr/bin/env bash
# Fuzzing regression suite of `make test`: every libFuzzer harness of build/fuzz/ (make fuzz-build)
# runs once over its seed corpus (build/fuzz/corpus/<target>/, the generated scenes, valid memory
# images, the seed command lines) and its regression inputs (tests/fuzz/regress/<target>/: every
# crash ever found). One case per harness and one per regression input; a crash, sanitizer report
# or leak fails the case. Prints cmocka-style lines for tests/run.sh.
set -u
cd "$(dirname "$0")/.."
F=${SAARCOR_FUZZ_DIR:-build/asan/fuzz-replay} # make fuzz-build: SAARCOR_FUZZ_DIR=build/fuzz
T=$(mktemp -d /tmp/saarcor-test-fuzz-XXXXXX)
trap 'rm -rf "$T"' EXIT
source tests/case_lib.sh
export ASAN_OPTIONS=detect_leaks=1:malloc_context_size=8:quarantine_size_mb=32 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

# run_inputs TARGET FILE...: each input once (libFuzzer's file mode); output silenced unless it fails
run_inputs() {
  local target=$1; shift
  if ! "$F/fuzz_$target" -timeout=30 -rss_limit_mb=2048 "$@" >"$T/$target.log" 2>&1; then
    grep -E 'ERROR|SUMMARY|runtime error|Running:' "$T/$target.log" | tail -8; return 1
  fi
  echo "fuzz_$target: $# input(s) ran clean"
}

corpus_case() { # target
  local files=("$F/corpus/$1"/*)
  [[ -e ${files[0]} ]] || { echo "no seed corpus in $F/corpus/$1 (BUILD=build/asan SAN=1 make fuzz-replay)"; return 1; }
  run_inputs "$1" "${files[@]}"
}

for bin in "$F"/fuzz_gltf "$F"/fuzz_memimage "$F"/fuzz_cli; do
  if [[ ! -x $bin ]]; then
    echo "[ RUN      ] $(basename "$bin")"; echo "[  SKIPPED ] $(basename "$bin"): not built (make test builds it: BUILD=build/asan SAN=1 fuzz-replay)"
    continue
  fi
  target=${bin##*/fuzz_}
  eval "case_$target() { corpus_case $target; }"
  run_case "corpus_$target" "case_$target"
  for input in tests/fuzz/regress/"$target"/*; do
    [[ -f $input ]] || continue
    eval "case_regress() { run_inputs $target '$input'; }"
    run_case "regress_${target}_$(basename "$input")" case_regress
  done
done
exit $((fails != 0))
