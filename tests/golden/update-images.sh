#!/usr/bin/env bash
# Rewrites the golden images of tests/golden/images/ from the current build: for every case of
# cases.txt, NAME.fp24.png (saarcor render) and NAME.ref.png (saarcor reference), and prints
# fp24 against the reference so the thresholds in cases.txt can be reviewed. Run only for a
# deliberate change of the units' arithmetic, the shading model or the reference; commit the
# images with that change and say why in the commit message.
set -eu
cd "$(dirname "$0")/../.."
BIN=${SAARCOR_BIN:-build/saarcor}
G=tests/golden/images
field() { echo "$1" | cut -d'|' -f"$2" | sed 's/^ *//; s/ *$//'; }
while IFS= read -r line; do
  [[ -z $line || $line == \#* ]] && continue
  name=$(field "$line" 1) scene=$(field "$line" 2) opts=$(field "$line" 3)
  if [[ $scene == ../shared/* && ! -e $scene ]]; then echo "$name: skipped ($scene absent)"; continue; fi
  # shellcheck disable=SC2086
  "$BIN" render "$scene" $opts --threads 2 -o "$G/$name.fp24.png" >/dev/null
  # shellcheck disable=SC2086
  "$BIN" reference "$scene" $opts --threads 2 -o "/tmp/$name.ref.exr" --png "$G/$name.ref.png" >/dev/null
  echo "$name: $("$BIN" compare "$G/$name.fp24.png" "$G/$name.ref.png" --threshold 0.0157 | tr '\n' ' ')"
done <"$G/cases.txt"
