#!/usr/bin/env bash
# Golden-image testbench: for every case of tests/golden/images/cases.txt, renders the scene
# through the hardware units (fp24) and with the double-precision reference, and checks
#   1. the fp24 image equals the committed golden fp24 image pixel for pixel (the hardware's
#      bits did not change by accident),
#   2. the reference image is within 50 dB of the committed golden reference (the truth did not
#      move),
#   3. fp24 against the reference meets the case's thresholds (PSNR, share of differing pixels),
#   4. the program built with the integer hardware arithmetic (build/hw/saarcor, make
#      SIM_ARITH=hw) draws the same fp24 image bit for bit as the fast-path simulator.
# Cases on ../shared scenes are skipped with a message when ../shared is absent. Prints
# cmocka-style lines for tests/run.sh. To update the golden images on purpose:
# tests/golden/update-images.sh (see tests/golden/README.md).
# Environment: SAARCOR_BIN (the program under test), SAARCOR_HW_BIN (empty: no check 4),
# SAARCOR_GOLDEN_CASES (space-separated names: only those), SAARCOR_GOLDEN_PREFIX (case name
# prefix, default golden_); tests/test_golden_asan.sh uses them.
set -u
cd "$(dirname "$0")/.."
BIN=${SAARCOR_BIN:-build/saarcor}
HW_BIN=${SAARCOR_HW_BIN-build/hw/saarcor}
ONLY=${SAARCOR_GOLDEN_CASES:-}
P=${SAARCOR_GOLDEN_PREFIX:-golden_}
G=tests/golden/images
T=$(mktemp -d /tmp/saarcor-golden-XXXXXX)
trap 'rm -rf "$T"' EXIT
# shellcheck source=case_lib.sh
source tests/case_lib.sh
[[ -z $HW_BIN || -x $HW_BIN ]] || { echo "test_golden: $HW_BIN is missing (make BUILD=build/hw SIM_ARITH=hw build/hw/saarcor)"; exit 1; }

field() { echo "$1" | cut -d'|' -f"$2" | sed 's/^ *//; s/ *$//'; }
psnr() { awk '/^psnr_db/ { print $2 }' "$1"; }
share() { awk '/^differing_pixels/ { gsub(/[(%)]/, "", $5); print $5 }' "$1"; }

check_hw() { # name scene options: check 4
  local name=$1 scene=$2 opts=$3
  # shellcheck disable=SC2086
  "$HW_BIN" render "$scene" $opts --threads 2 -o "$T/$name.hw.png" >/dev/null || return 1
  "$BIN" compare "$T/$name.hw.png" "$G/$name.fp24.png" >"$T/c4" || return 1
  [[ $(awk '/^differing_pixels/ { print $2 }' "$T/c4") == 0 ]] ||
    { echo "$name: the integer-arithmetic program ($HW_BIN) draws a different image:"; cat "$T/c4"; return 1; }
}

check_case() { # name scene options psnr_min share_max
  local name=$1 scene=$2 opts=$3 pmin=$4 smax=$5
  # shellcheck disable=SC2086
  "$BIN" render "$scene" $opts --threads 2 -o "$T/$name.png" >/dev/null || return 1
  "$BIN" reference "$scene" $opts --threads 2 -o "$T/$name.ref.exr" --png "$T/$name.ref.png" >/dev/null || return 1
  "$BIN" compare "$T/$name.png" "$G/$name.fp24.png" >"$T/c1" || return 1
  [[ $(awk '/^differing_pixels/ { print $2 }' "$T/c1") == 0 ]] ||
    { echo "$name: fp24 image differs from $G/$name.fp24.png:"; cat "$T/c1"; return 1; }
  [[ -z $HW_BIN ]] || check_hw "$name" "$scene" "$opts" || return 1
  "$BIN" compare "$T/$name.ref.png" "$G/$name.ref.png" --psnr-min 50 >"$T/c2" ||
    { echo "$name: reference image moved from $G/$name.ref.png:"; cat "$T/c2"; return 1; }
  "$BIN" compare "$T/$name.png" "$T/$name.ref.png" --threshold 0.0157 --psnr-min "$pmin" >"$T/c3" ||
    { echo "$name: fp24 against the reference below $pmin dB:"; cat "$T/c3"; return 1; }
  awk -v s="$(share "$T/c3")" -v m="$smax" 'BEGIN { exit !(s <= m) }' ||
    { echo "$name: $(share "$T/c3")% of pixels differ from the reference (at most $smax%)"; cat "$T/c3"; return 1; }
  echo "$name: fp24 vs reference $(psnr "$T/c3") dB (min $pmin), $(share "$T/c3")% pixels differ (max $smax%)"
}

while IFS= read -r line; do
  [[ -z $line || $line == \#* ]] && continue
  name=$(field "$line" 1) scene=$(field "$line" 2) opts=$(field "$line" 3)
  [[ -z $ONLY || " $ONLY " == *" $name "* ]] || continue
  if [[ $scene == ../shared/* && ! -e $scene ]]; then
    skip_case "${P}$name" "$scene is absent (../shared not available)"
    continue
  fi
  echo "[ RUN      ] ${P}$name"
  if check_case "$name" "$scene" "$opts" "$(field "$line" 4)" "$(field "$line" 5)" >"$T/log" 2>&1; then
    cat "$T/log"
    echo "[       OK ] ${P}$name"
  else
    cat "$T/log"
    echo "[  FAILED  ] ${P}$name"
    fails=$((fails + 1))
  fi
done <"$G/cases.txt"
exit $((fails != 0))
