#!/usr/bin/env bash
# Seed corpus of the fuzzers (tests/fuzz/README.md), generated at build time into OUT:
#   OUT/gltf      the generated scenes as .glb, as .gltf with embedded (data: URI) buffers and
#                 images, and as .gltf bundles with external .bin/.png files (fuzz_gltf's format)
#   OUT/memimage  valid memory images of the generated scenes (saarcor info --image), and of
#                 cornell with rope and grid data (info --traversal ropes, grid, grid2)
#   OUT/cli       the command lines of tests/fuzz/cli_seeds.txt, one argument per line
# Usage: tests/fuzz/corpus.sh SAARCOR OUT
set -euo pipefail
saarcor=$1 out=$2
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out" && mkdir -p "$out"/{gltf,memimage,cli}
tmp=$(mktemp -d) && trap 'rm -rf "$tmp"' EXIT
for s in cornell room animated; do
  "$saarcor" gen "$s" -o "$out/gltf/$s.glb" >/dev/null
  "$saarcor" gen "$s" -o "$out/gltf/$s.gltf" >/dev/null
  python3 "$here/bundle.py" "$out/gltf/$s.gltf" "$out/gltf/$s.external"
  "$saarcor" info "$s" --width 64 --height 48 --image "$out/memimage/$s.bin" >/dev/null
done
for t in ropes grid grid2; do # the traversal structures beside the kd-trees (docs/traversal.md)
  "$saarcor" info cornell --width 64 --height 48 --traversal $t --image "$out/memimage/cornell-$t.bin" >/dev/null
done
n=0
grep -v '^#' "$here/cli_seeds.txt" | while read -r line; do
  n=$((n + 1))
  tr ' ' '\n' <<<"$line" | head -c -1 >"$out/cli/seed$n"
done
echo "corpus: $(ls "$out/gltf" | wc -l) glTF, $(ls "$out/memimage" | wc -l) images, $(ls "$out/cli" | wc -l) command lines in $out"
