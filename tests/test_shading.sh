#!/usr/bin/env bash
# Tests of the optional shading features (docs/shading.md) through the command line: each
# feature scene written as glTF (saarcor gen) and loaded back renders the same image as the
# generated scene, without a warning (writer and loader agree on emissiveTexture,
# KHR_materials_emissive_strength, COLOR_0, TEXCOORD_1, KHR_texture_transform and
# KHR_materials_unlit); an unlit surface traces no shadow rays; and the emissive-textured
# WaterBottle (../shared; skipped with a message when absent) is no longer mostly pure white.
# Its agreement with the reference is the golden case waterbottle (tests/test_golden.sh), as
# are the feature scenes'. Prints cmocka-style lines for tests/run.sh.
set -u
cd "$(dirname "$0")/.."
BIN=${SAARCOR_BIN:-build/saarcor}
T=$(mktemp -d /tmp/saarcor-test-shading-XXXXXX)
trap 'rm -rf "$T"' EXIT
# shellcheck source=case_lib.sh
source tests/case_lib.sh
SIZE=(--width 64 --height 48 --threads 2)
WATERBOTTLE=../shared/scenes/WaterBottle/WaterBottle.gltf

differing() { awk '/^differing_pixels/ { print $2 }' "$1"; }

t_gltf_round_trip() {
  for s in emissive vertex_colours uv_transform unlit; do
    "$BIN" gen "$s" -o "$T/$s.glb" >/dev/null
    "$BIN" render "$s" "${SIZE[@]}" -o "$T/$s.png" >/dev/null
    "$BIN" render "$T/$s.glb" "${SIZE[@]}" -o "$T/$s.glb.png" >/dev/null 2>"$T/err"
    ! grep -q warning "$T/err" || { cat "$T/err"; return 1; }
    "$BIN" compare "$T/$s.png" "$T/$s.glb.png" >"$T/c"
    [[ $(differing "$T/c") == 0 ]] || { echo "$s: the glTF file renders differently"; cat "$T/c"; return 1; }
  done
  echo "4 feature scenes: glTF round trip renders the same images, no warnings"
}

# rays_by_kind.shadow of --stats FILE
shadow_rays() { python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["rays_by_kind"]["shadow"])' "$1"; }

t_unlit_takes_no_light() { # the unlit scene's lit floor and sphere trace shadow rays; unlit surfaces none
  "$BIN" render unlit "${SIZE[@]}" --max-depth 0 -o "$T/u.png" --stats "$T/u.json" >/dev/null
  local n; n=$(shadow_rays "$T/u.json")
  [[ $n -gt 0 ]] || { echo "no shadow rays at all"; return 1; }
  "$BIN" gen unlit -o "$T/u.gltf" >/dev/null
  # every material unlit: not one shadow ray
  python3 - "$T/u.gltf" "$T/all.gltf" <<'EOF'
import json, sys
g = json.load(open(sys.argv[1]))
for m in g["materials"]:
    m.setdefault("extensions", {})["KHR_materials_unlit"] = {}
g.setdefault("extensionsUsed", []).append("KHR_materials_unlit")
g["extensionsUsed"] = sorted(set(g["extensionsUsed"]))
json.dump(g, open(sys.argv[2], "w"))
EOF
  "$BIN" render "$T/all.gltf" "${SIZE[@]}" --max-depth 0 -o "$T/all.png" --stats "$T/all.json" >/dev/null
  [[ $(shadow_rays "$T/all.json") == 0 ]] || { echo "unlit materials traced shadow rays"; return 1; }
  echo "unlit: $n shadow rays from the lit floor and sphere, 0 with every material unlit"
}

t_waterbottle_not_white() {
  if [[ ! -e $WATERBOTTLE ]]; then echo "skipped: $WATERBOTTLE is absent (../shared not available)"; return 0; fi
  "$BIN" render "$WATERBOTTLE" --width 128 --height 96 --mem-mb 40 --threads 2 -o "$T/wb.png" >/dev/null
  oiiotool --pattern constant:color=1,1,1 128x96 3 -d uint8 -o "$T/white.png"
  "$BIN" compare "$T/wb.png" "$T/white.png" --threshold 0.02 >"$T/c"
  local white=$((128 * 96 - $(differing "$T/c")))
  [[ $white -le 123 ]] || { echo "WaterBottle: $white of 12288 pixels are (nearly) pure white"; return 1; }
  echo "WaterBottle: $white of 12288 pixels nearly pure white (at most 1%; 2665 before emissive textures)"
}

run_case shading_gltf_round_trip t_gltf_round_trip
run_case shading_unlit_takes_no_light t_unlit_takes_no_light
run_case shading_waterbottle_not_white t_waterbottle_not_white
exit $((fails != 0))
