#!/usr/bin/env bash
# Command-line tests of build/saarcor: help, exit codes, one-line errors, f24gen/f24/f24verify
# output, and `saarcor compare` against OIIO's idiff on the same images. Prints cmocka-style
# "[ RUN      ]" / "[       OK ]" / "[  FAILED  ]" lines for tests/run.sh.
set -u
cd "$(dirname "$0")/.."
BIN=${SAARCOR_BIN:-build/saarcor}
T=$(mktemp -d /tmp/saarcor-test-cli-XXXXXX)
trap 'rm -rf "$T"' EXIT
# shellcheck source=case_lib.sh
source tests/case_lib.sh

# expect CODE CMD...: runs CMD, checks the exit code; stdout in $T/out, stderr in $T/err
expect() {
  local want=$1; shift
  local got=0
  "$@" >"$T/out" 2>"$T/err" || got=$?
  if [[ $got -ne $want ]]; then
    echo "expected exit $want, got $got: $*"; cat "$T/err"; return 1
  fi
}

has() { # regex, file
  grep -q "$1" "$2" || { echo "no line matches '$1' in $2:"; head -20 "$2"; return 1; }
}

every_line_matches() { # regex, file
  if grep -vqE "$1" "$2"; then echo "a line of $2 does not match $1:"; grep -vE "$1" "$2" | head -3; return 1; fi
}

one_line_error() { # stderr is exactly one line that says error
  [[ $(wc -l <"$T/err") -eq 1 ]] && has 'error' "$T/err" || { echo "stderr not one error line:"; cat "$T/err"; return 1; }
}

t_help() {
  expect 0 "$BIN" --help
  for c in version f24 f24gen f24verify compare render reference compare-hits; do grep -q "^  $c " "$T/out"; done
  for c in version f24 f24gen f24verify compare render reference compare-hits; do expect 0 "$BIN" "$c" --help; has usage "$T/out"; done
}

t_bad_usage() {
  expect 2 "$BIN"
  expect 2 "$BIN" frobnicate; one_line_error
  expect 2 "$BIN" version extra; one_line_error
  expect 2 "$BIN" f24gen add; one_line_error
  expect 2 "$BIN" f24gen nosuchop 5; one_line_error
  expect 2 "$BIN" f24gen add -5; one_line_error
  expect 2 "$BIN" f24gen add 10 --seed x; one_line_error
  expect 2 "$BIN" f24gen add 10 --bogus; one_line_error
  expect 2 "$BIN" f24 add 1; one_line_error
  expect 2 "$BIN" f24 add 1 zz; one_line_error
  expect 2 "$BIN" f24verify -n 1.5; one_line_error
  expect 2 "$BIN" compare a.png; one_line_error
  expect 2 "$BIN" compare a.png b.png --psnr-min nan; one_line_error
}

t_version() {
  expect 0 "$BIN" version
  grep -q 'E=7 M=16 (24 bits' "$T/out"
}

# the program loads the image library on demand (host/image/img.c): without it, commands that
# write no image run, those that do stop before their work with one line; SAARCOR_IMG_LIB names it
t_image_library() {
  local lib
  lib=$(dirname "$(readlink -f "$BIN")")/libsaarcor_img.so
  [[ -f $lib ]] || lib=$(dirname "$(readlink -f "$BIN")")/../libsaarcor_img.so
  mkdir -p "$T/alone"; cp "$BIN" "$T/alone/saarcor"
  expect 0 "$T/alone/saarcor" info cornell
  # PNG files (libpng) and written EXR files (the OpenEXR core library) need no library; another
  # format does, and says so before the render
  expect 0 "$T/alone/saarcor" render cornell --width 8 --height 8 -o "$T/alone.png" --aov "$T/alone.exr"
  expect 0 "$T/alone/saarcor" compare "$T/alone.png" "$T/alone.png"
  expect 0 "$T/alone/saarcor" reference cornell --width 8 --height 8 -o "$T/alone_ref.exr" --png "$T/alone_ref.png"
  expect 4 "$T/alone/saarcor" render cornell --width 8 --height 8 -o "$T/alone2.png" --aov "$T/alone.tif"; one_line_error
  has 'libsaarcor_img.so' "$T/err"
  [[ ! -e $T/alone2.png && ! -e $T/alone.tif ]]
  expect 4 "$T/alone/saarcor" reference cornell --width 8 --height 8 -o "$T/alone.tif"; one_line_error
  # reading an EXR file is OpenImageIO's
  expect 3 "$T/alone/saarcor" compare "$T/alone.exr" "$T/alone.exr"; one_line_error
  SAARCOR_IMG_LIB=$lib expect 0 "$T/alone/saarcor" render cornell --width 8 --height 8 -o "$T/alone2.png" --aov "$T/alone.tif"
  expect 0 "$BIN" compare "$T/alone.exr" "$T/alone.exr"
  expect 0 "$BIN" compare "$T/alone_ref.exr" "$T/alone_ref.exr"
}

# --capture-unit-io: the program holds no capture wrappers and runs its capture build (capture/saarcor
# beside it) with the same command line, which records what calling that build does and changes no
# bit of the image; without the build, one line naming it (exit 2) and nothing written
t_capture_build() {
  local cap
  cap=$(dirname "$(readlink -f "$BIN")")/capture/saarcor
  [[ -x $cap ]] || { echo "no capture build at $cap"; return 1; }
  if nm "$BIN" | grep -q ' __wrap_'; then echo "$BIN holds the capture wrappers"; return 1; fi
  nm "$cap" | grep -q ' T __wrap_trace_step$'
  local args=(render cornell --width 16 --height 12 --threads 1 --capture-limit 50)
  expect 0 "$BIN" "${args[@]}" -o "$T/cap_p.png" --capture-unit-io "$T/cap_p"
  has '^captured unit transactions in .*trace [1-9]' "$T/out"
  expect 0 "$cap" "${args[@]}" -o "$T/cap_c.png" --capture-unit-io "$T/cap_c"
  diff -r "$T/cap_p" "$T/cap_c"
  cmp "$T/cap_p.png" "$T/cap_c.png"
  expect 0 "$BIN" "${args[@]}" -o "$T/plain.png"
  cmp "$T/plain.png" "$T/cap_p.png"
  mkdir -p "$T/nocap"; cp "$BIN" "$T/nocap/saarcor"
  expect 2 "$T/nocap/saarcor" "${args[@]}" -o "$T/nocap.png" --capture-unit-io "$T/nocap_dir"; one_line_error
  has 'capture/saarcor' "$T/err"
  [[ ! -e $T/nocap_dir && ! -e $T/nocap.png ]]
}

t_f24_eval() {
  expect 0 "$BIN" f24 add 1 2;        grep -q '= 3  \[0x408000\]' "$T/out"
  expect 0 "$BIN" f24 div 1 3;        has '\[0x3D5555\]' "$T/out"
  expect 0 "$BIN" f24 sqrt 0x3F0000;  has '\[0x3F0000\]' "$T/out"
  expect 0 "$BIN" f24 lt nan 1;       grep -q '= 0  \[0x0\]' "$T/out"
  expect 0 "$BIN" f24 from_i32 -7;    grep -q '= -7 ' "$T/out"
}

t_f24gen_format() {
  expect 0 "$BIN" f24gen mul 100 --seed 5 --no-edges
  [[ $(wc -l <"$T/out") -eq 100 ]]
  every_line_matches '^[0-9A-F]{6} [0-9A-F]{6} [0-9A-F]{6}$' "$T/out"
  expect 0 "$BIN" f24gen sqrt 10 -o "$T/v.hex"
  every_line_matches '^[0-9A-F]{6} [0-9A-F]{6}$' "$T/v.hex"
  expect 0 "$BIN" f24gen lt 10 --no-edges
  every_line_matches '^[0-9A-F]{6} [0-9A-F]{6} [01]$' "$T/out"
  expect 0 "$BIN" f24gen from_f32 10 --no-edges
  every_line_matches '^[0-9A-F]{8} [0-9A-F]{6}$' "$T/out"
  # same seed, same vectors; different seed, different vectors
  "$BIN" f24gen add 50 --seed 9 --no-edges >"$T/a"; "$BIN" f24gen add 50 --seed 9 --no-edges >"$T/b"
  cmp -s "$T/a" "$T/b"
  "$BIN" f24gen add 50 --seed 10 --no-edges >"$T/b"
  if cmp -s "$T/a" "$T/b"; then echo "different seeds gave the same vectors"; return 1; fi
  expect 3 "$BIN" f24gen add 5 -o /nonexistent-dir/v.hex; one_line_error
}

t_f24verify() {
  expect 0 "$BIN" f24verify -n 2000 --json "$T/v.json"
  grep -q 'all results agree with MPFR' "$T/out"
  python3 -c "import json,sys; d=json.load(open('$T/v.json')); assert len(d['results'])==17; assert all(r['hw_mismatches']==0 and r['fast_mismatches']==0 for r in d['results'])"
}

make_images() {
  oiiotool --pattern constant:color=0.5,0.5,0.5 64x48 3 -o "$T/a.png"
  oiiotool --pattern constant:color=0.6,0.5,0.5 64x48 3 -o "$T/b.png"
  oiiotool --pattern constant:color=0.5,0.5,0.5 32x48 3 -o "$T/small.png"
}

t_compare() {
  make_images
  expect 0 "$BIN" compare "$T/a.png" "$T/a.png"; grep -q '^psnr_db inf' "$T/out"
  expect 0 "$BIN" compare "$T/a.png" "$T/b.png" --diff "$T/d.exr"
  grep -q '^differing_pixels 3072 of 3072' "$T/out"
  [[ -s "$T/d.exr" ]]
  local ours theirs
  ours=$(awk '/^psnr_db/ {print $2}' "$T/out")
  theirs=$(idiff -v -a -fail 0 "$T/a.png" "$T/b.png" 2>&1 | awk -F'= ' '/Peak SNR/ {print $2}')
  awk -v a="$ours" -v b="$theirs" 'BEGIN { d = a - b; exit !(d < 1e-3 && d > -1e-3) }' || { echo "psnr $ours vs idiff $theirs"; return 1; }
  expect 0 "$BIN" compare "$T/a.png" "$T/b.png" --psnr-min 20; has PASS "$T/out"
  expect 1 "$BIN" compare "$T/a.png" "$T/b.png" --psnr-min 30; has FAIL "$T/out"
  expect 3 "$BIN" compare "$T/a.png" "$T/missing.png"; one_line_error
  expect 3 "$BIN" compare "$T/a.png" "$T/small.png"; one_line_error
}

t_gen() {
  expect 0 "$BIN" gen --list
  [[ $(grep -cE '^(cornell|room|plants|terrain|animated|emissive|vertex_colours|uv_transform|unlit) ' "$T/out") -eq 9 ]]
  expect 0 "$BIN" gen cornell -o "$T/c.glb"
  [[ -s "$T/c.glb" ]]
  expect 0 "$BIN" gen plants --detail 10 --seed 3 -o "$T/p.gltf"
  expect 2 "$BIN" gen nosuch -o "$T/x.glb"; one_line_error
  expect 2 "$BIN" gen cornell; one_line_error
  expect 3 "$BIN" gen cornell -o /nonexistent-dir/x.glb; one_line_error
}

t_info() {
  "$BIN" gen cornell -o "$T/c.glb"
  expect 0 "$BIN" info "$T/c.glb" --validate --json "$T/i.json"
  has '^validate     ok' "$T/out"
  has '^objects      3 (meshes), instances 4' "$T/out"
  python3 -c "import json; d=json.load(open('$T/i.json')); assert d['instances']==4 and d['triangles']==24"
  # bytes per triangle: all regions in the total, the record types add up to the geometry regions
  python3 -c "
import json; d=json.load(open('$T/i.json')); r=d['regions']; b=d['bytes_per_triangle']
assert abs(b['total'] - 4*sum(r.values())/d['triangles']) < 1e-3, b
geo = 4*(r['STATIC_GEOMETRY'] + r['DYNAMIC_GEOMETRY'])/d['triangles']
assert abs(sum(v for k, v in b.items() if k != 'total') - geo) < 1e-3, b
assert all(b[k] > 0 for k in ('kd_nodes', 'lists', 'triangle_transformations', 'shading_records')), b"
  has 'bytes per unique triangle (all regions)' "$T/out"
  has '^geometry by record type, bytes per unique triangle: kd_nodes [0-9.]*, lists' "$T/out"
  has '^merged       nothing' "$T/out"
  # --merge: the room's static axis-aligned instances in one world-space object, the turned chairs kept
  expect 0 "$BIN" info room --merge --json "$T/m.json"
  has '^merged       8 instances into 1 world-space object(s) .*7 turned' "$T/out"
  python3 -c "import json; m=json.load(open('$T/m.json'))['merged']; assert m['instances']==8 and m['kept_turned']==7, m"
  expect 0 "$BIN" render room --merge --width 64 --height 48 -o "$T/m.png"
  expect 0 "$BIN" info animated --frames 4
  has '^frames       4 at 30 fps' "$T/out"
  expect 0 "$BIN" info room --ct 2 --ci 1 --max-depth 12 --leaf-size 2
  expect 0 "$BIN" info room --top-ci 6 --json "$T/t6.json"
  expect 0 "$BIN" info room --json "$T/t3.json"
  python3 -c "import json; a, b = (json.load(open(f))['top']['nodes'] for f in ('$T/t6.json', '$T/t3.json')); assert a != b, (a, b)"
  expect 2 "$BIN" info room --top-ci 0; one_line_error
  # --kd-bins: other bottom-level trees (other leaf references), the same scene; 1 bin is refused
  expect 0 "$BIN" info plants --kd-bins 64 --json "$T/b64.json"
  expect 0 "$BIN" info plants --json "$T/b0.json"
  python3 -c "import json; a, b = (json.load(open(f))['bottom']['references'] for f in ('$T/b64.json', '$T/b0.json')); assert a != b, (a, b)"
  expect 2 "$BIN" info room --kd-bins 1; one_line_error
  expect 3 "$BIN" info "$T/missing.glb"; one_line_error
  mkdir -p "$T/dir.glb"
  expect 3 "$BIN" render "$T/dir.glb" -o "$T/d.png"; one_line_error; has 'is a directory' "$T/err"
  printf '{"asset":{"version":"2.0"},"meshes":[' >"$T/bad.gltf"
  expect 3 "$BIN" info "$T/bad.gltf"; one_line_error
  expect 3 "$BIN" render terrain --mem-mb 1 --width 8 --height 8 -o "$T/t.png"; one_line_error
  has 'does not fit' "$T/err"
  # the --mem-mb the message names (the size of the image built in the largest memory) fits at once
  local mb
  mb=$(sed -n 's/.*(pass --mem-mb \([0-9]*\))$/\1/p' "$T/err")
  [[ -n $mb ]] || { echo "no --mem-mb in: $(cat "$T/err")"; return 1; }
  "$BIN" render terrain --mem-mb "$mb" --width 8 --height 8 -o "$T/t.png" >/dev/null ||
    { echo "--mem-mb $mb, as the message said, does not fit"; return 1; }
  expect 2 "$BIN" info cornell --mem-mb 0; one_line_error
  expect 2 "$BIN" info cornell --empty-bonus 2; one_line_error
  expect 2 "$BIN" info; one_line_error
}

t_render() {
  expect 0 "$BIN" render cornell -o "$T/r1.png" --width 96 --height 72 --threads 1 --stats "$T/s.json"
  has 'rendered cornell: 96x72, [0-9]* rays (6912 primary, [0-9]* shadow' "$T/out"
  expect 0 "$BIN" render cornell -o "$T/r2.png" --width 96 --height 72 --threads 3
  cmp "$T/r1.png" "$T/r2.png"                      # bit-identical for any thread count
  python3 -c "import json; d=json.load(open('$T/s.json')); k=d['rays_by_kind']; assert k['primary']==6912 and d['rays']==sum(k.values()) and d['intersections']>0"
  "$BIN" compare "$T/r1.png" "$T/r2.png" --psnr-min 99 >/dev/null
  expect 0 "$BIN" render room -o "$T/odd.png" --width 33 --height 17 --threads 2   # odd sizes
  expect 0 "$BIN" render animated --frames 0:2 --fps 2 -o "$T/a.png" --width 64 --height 48
  [[ $(grep -c '^rendered animated' "$T/out") -eq 3 ]]
  [[ -s "$T/a_0000.png" && -s "$T/a_0002.png" ]]
  if cmp -s "$T/a_0000.png" "$T/a_0002.png"; then echo "animation frames are identical"; return 1; fi
  expect 2 "$BIN" render animated --frames 3:1; one_line_error
  expect 0 "$BIN" render cornell -o "$T/c.png" --aov "$T/c.exr" --width 64 --height 48
  iinfo -v "$T/c.exr" >"$T/iinfo"
  for ch in t N.X N.Y N.Z node triangle u v; do has "channel list:.*[ ,]$ch\(,\|\$\)" "$T/iinfo"; done
  oiiotool "$T/c.exr" --ch triangle --printstats >"$T/stats" 2>&1
  has 'Stats Min: -1.0' "$T/stats"                   # misses around the open box
  awk '/Stats Max/ { exit !($3 >= 0 && $3 < 36) }' "$T/stats"   # 36 triangles in the scene
  expect 0 "$BIN" render cornell -o "$T/v.png" --width 64 --height 48 --eye 0,1,3 --at 0,1,0 --fov 60
  if cmp -s "$T/v.png" "$T/c.png"; then echo "--eye/--at did not change the view"; return 1; fi
  expect 2 "$BIN" render cornell --eye 1,2; one_line_error
  expect 2 "$BIN" render cornell --fov 200; one_line_error
  expect 2 "$BIN" render cornell --threads 0; one_line_error
  expect 3 "$BIN" render "$T/missing.glb"; one_line_error
  expect 3 "$BIN" render cornell -o /nonexistent-dir/x.png; one_line_error
}

# ray depth, shadows, number format and the ground plane of render
t_render_rays() {
  kinds() { python3 -c "import json; k=json.load(open('$1'))['rays_by_kind']; print(k['shadow'], k['reflection'], k['transmission'])"; }
  expect 0 "$BIN" render room -o "$T/d3.png" --width 64 --height 48 --stats "$T/d3.json"
  read -r sh refl trans < <(kinds "$T/d3.json")
  [[ $sh -gt 0 && $refl -gt 0 && $trans -gt 0 ]]      # the room has glass, metal and lights
  expect 0 "$BIN" render room -o "$T/d0.png" --width 64 --height 48 --max-depth 0 --no-shadows --stats "$T/d0.json"
  [[ "$(kinds "$T/d0.json")" == "0 0 0" ]]
  if cmp -s "$T/d0.png" "$T/d3.png"; then echo "--max-depth 0 --no-shadows changed nothing"; return 1; fi
  expect 0 "$BIN" render room -o "$T/f32.png" --width 64 --height 48 --precision fp32
  "$BIN" compare "$T/f32.png" "$T/d3.png" --psnr-min 25 >/dev/null   # same picture, other arithmetic
  expect 0 "$BIN" render room -o "$T/e7.png" --width 64 --height 48 --precision e7m16
  cmp "$T/e7.png" "$T/d3.png"                        # the build's own format: the same program
  expect 0 "$BIN" render cornell -o "$T/g.png" --width 64 --height 48 --ground --stats "$T/g.json"
  read -r sh refl trans < <(kinds "$T/g.json")
  [[ $refl -gt 0 ]]                                   # the polished ground reflects
  expect 0 "$BIN" render animated -o "$T/f45.png" --width 32 --height 24 --frame 45
  expect 0 "$BIN" render animated -o "$T/t15.png" --width 32 --height 24 --time 1.5
  cmp "$T/f45.png" "$T/t15.png"                       # frame 45 at 30 fps is t = 1.5 s
  expect 2 "$BIN" render animated --frame 3 --frames 1:2; one_line_error
  expect 5 "$BIN" render room --max-depth 9; one_line_error; has "limit ray-depth exceeded" "$T/err" # docs/limits.md
  expect 2 "$BIN" render room --precision fp64; one_line_error
  expect 2 "$BIN" render room --precision e9m40; one_line_error
  expect 2 "$BIN" render room --ground=1; one_line_error
}

# the cycle mode: the same image, a report like the paper's, timing in the stats, bad options
t_render_cycle() {
  expect 0 "$BIN" render room -o "$T/fn.png" --width 64 --height 48 --max-depth 1
  expect 0 "$BIN" render room -o "$T/cy.png" --width 64 --height 48 --max-depth 1 --mode cycle --pipes 2 \
    --threads-per-pipe 8 --cache-kb 1,1,1 --line-bytes 8,8,48 --unit-latency trav=5,isect=20,surface_hit=9,surface_miss=4 --stats "$T/cy.json"
  cmp "$T/fn.png" "$T/cy.png"
  has '^frame: [0-9]* cycles' "$T/out"; has 'usage rate' "$T/out"; has 'cache hit rate' "$T/out"
  python3 -c "import json; c=json.load(open('$T/cy.json'))['cycle']; assert c['pipes'] == 2 and c['cycles'] > 0 \
and c['units']['trav']['latencies']['trav'] == 5 and c['units']['rgs']['latencies']['surface'] == 221 \
and c['units']['rgs']['latencies']['surface_hit'] == 9 \
and c['units']['rgs']['latencies']['surface_miss'] == 4 and c['memory']['kd_nodes']['cache_bytes'] == 1024, c"
  expect 0 "$BIN" render room -o "$T/cy1.png" --width 64 --height 48 --max-depth 1 --mode cycle --pipes 2 \
    --threads-per-pipe 8 --cache-kb 1,1,1 --line-bytes 8,8,48 --unit-latency trav=5,isect=20 --threads 1
  cmp "$T/cy.png" "$T/cy1.png"
  for bad in "--mode fast" "--mode cycle --pipes 0" "--mode cycle --threads-per-pipe 5000" "--mode cycle --cache-kb 4,2" \
             "--mode cycle --line-bytes 6,16,48" "--mode cycle --unit-latency warp=3" "--mode cycle --tile 7" \
             "--mode cycle --unit-latency surface_hit=x" "--mode cycle --unit-latency surface_miss=1001"; do
    # shellcheck disable=SC2086
    expect 2 "$BIN" render room $bad; one_line_error
  done
}

# the traversal algorithms: ropes and grids add their structures to the image, find the same
# surfaces (functional and cycle mode, with an animated frame and its rebuilt top level)
t_render_traversal() {
  expect 0 "$BIN" render animated -o "$T/stk.png" --width 48 --height 36 --frame 20
  for a in short-stack restart push-down ropes grid grid2; do
    expect 0 "$BIN" render animated -o "$T/$a.png" --width 48 --height 36 --frame 20 --traversal $a --stats "$T/$a.json"
    cmp "$T/stk.png" "$T/$a.png"
  done
  python3 -c "import json; d=json.load(open('$T/grid2.json')); assert d['traversal_steps'] == 0 and d['leaves'] > 0, d"
  expect 0 "$BIN" render room -o "$T/ropes_cy.png" --width 32 --height 24 --traversal ropes --mode cycle --pipes 2
  expect 0 "$BIN" render room -o "$T/ropes_fn.png" --width 32 --height 24 --traversal ropes
  cmp "$T/ropes_cy.png" "$T/ropes_fn.png"
  expect 2 "$BIN" render room --traversal octree; one_line_error
  has 'ropes, grid or grid2' "$T/err"
}

# the double-precision reference and the per-ray hit comparison
t_reference() {
  expect 0 "$BIN" reference --help; has usage "$T/out"
  expect 0 "$BIN" reference room -o "$T/ref.exr" --png "$T/ref.png" --aov "$T/ref_aov.exr" --width 64 --height 48 --threads 1
  expect 0 "$BIN" reference room -o "$T/ref3.exr" --png "$T/ref3.png" --width 64 --height 48 --threads 3
  cmp "$T/ref.png" "$T/ref3.png"                      # independent of the thread count
  iinfo -v "$T/ref_aov.exr" >"$T/iinfo"
  for ch in t N.X N.Y N.Z node triangle u v; do has "channel list:.*[ ,]$ch\(,\|\$\)" "$T/iinfo"; done
  expect 0 "$BIN" render room -o "$T/dev.png" --width 64 --height 48
  "$BIN" compare "$T/dev.png" "$T/ref.png" --psnr-min 35 >/dev/null   # fp24 close to the truth
  expect 0 "$BIN" compare-hits room --width 64 --height 48 --json "$T/hits.json"
  has 'agreement (same triangle or both miss)' "$T/out"
  python3 -c "import json; d=json.load(open('$T/hits.json')); assert d['rays']==3072 and d['agreement']>0.99, d"
  expect 5 "$BIN" reference room --max-depth 99; one_line_error; has "limit ray-depth exceeded" "$T/err"
  expect 2 "$BIN" reference room --bogus; one_line_error
  expect 2 "$BIN" compare-hits; one_line_error
  expect 3 "$BIN" reference "$T/missing.glb"; one_line_error
  expect 3 "$BIN" compare-hits "$T/missing.glb"; one_line_error
  expect 3 "$BIN" reference room -o /nonexistent-dir/x.exr --width 8 --height 8; one_line_error
}

# a scene larger than the device memory: info reports it all and the --mem-mb to pass, render
# names that value, the reference is not bound by it
t_mem_mb() {
  expect 0 "$BIN" info plants --mem-mb 3 --json "$T/p.json"
  has '^memory image' "$T/out"; has '^bottom level' "$T/out"
  has '^fits         no: the image needs 3\.[0-9][0-9] MB, more than the 3.00 MB device memory; render it with --mem-mb 4$' "$T/out"
  python3 -c "import json; j=json.load(open('$T/p.json')); assert not j['fits'] and j['mem_mb_needed'] == 4, j"
  expect 3 "$BIN" render plants --mem-mb 3 --width 32 --height 24 -o "$T/p.png"; one_line_error
  has 'the image needs 3\.[0-9][0-9] MB (pass --mem-mb 4)$' "$T/err"
  expect 3 "$BIN" render plants --mem-mb 1 --width 32 --height 24 -o "$T/p.png"; one_line_error
  has '(pass --mem-mb 4)$' "$T/err"
  expect 0 "$BIN" render plants --mem-mb 4 --width 32 --height 24 -o "$T/p.png"
  expect 0 "$BIN" reference plants --mem-mb 1 --width 32 --height 24 -o "$T/p.exr"
  expect 0 "$BIN" info plants --json "$T/f.json"
  python3 -c "import json; j=json.load(open('$T/f.json')); assert j['fits'], j"
}

# triangles the device cannot hold: one warning line with the count and the reasons
t_dropped_warning() {
  python3 - "$T/d.gltf" <<'PY'
import base64, json, struct, sys
# an ordinary triangle; a tiny one (its transformation overflows fp24); a sliver over the condition
# limit; one without area (skipped without a word)
tris = [[(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 0, 3), (1e-20, 0, 3), (0, 1e-20, 3)],
        [(0, 0, 1), (1, 0, 1), (0.5, 1e-9, 1)], [(0, 0, 2), (1, 0, 2), (2, 0, 2)]]
pos = [c for t in tris for v in t for c in v]
data = struct.pack('<%df' % len(pos), *pos)
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(pos) // 3, "type": "VEC3",
                    "min": [min(pos[i::3]) for i in range(3)], "max": [max(pos[i::3]) for i in range(3)]}],
     "bufferViews": [{"buffer": 0, "byteLength": len(data)}],
     "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}]}
json.dump(g, open(sys.argv[1], "w"))
PY
  expect 0 "$BIN" render "$T/d.gltf" --width 16 --height 16 -o "$T/d.png"
  [[ $(wc -l <"$T/err") -eq 1 ]]
  has 'warning: 2 triangles dropped, fp24 cannot hold them: 1 with a transformation beyond its range, 1 over the condition limit' "$T/err"
  expect 0 "$BIN" render "$T/d.gltf" --width 16 --height 16 -o "$T/d.png" --max-condition 1e30
  has 'warning: 1 triangles dropped, fp24 cannot hold them: 1 with a transformation beyond its range, 0 over' "$T/err"
  expect 0 "$BIN" render cornell --width 16 --height 16 -o "$T/c.png"
  [[ ! -s $T/err ]] || { echo "unexpected stderr:"; cat "$T/err"; return 1; }
}

# gen_gltf KIND OUT [N]: a unit plane at y = 0 (two triangles, no camera, no light) as
#   plane      nothing more
#   required   .glb whose extensionsRequired names Draco, with Draco-style indices (no bufferView)
#   ignored    two materials with normal, occlusion and metallic-roughness textures, clearcoat and
#              sheen, a points and a lines primitive
#   instanced  N rows of EXT_mesh_gpu_instancing, 3 apart along x, under a node raised by 1 in y
gen_gltf() {
  python3 - "$@" <<'PY'
import base64, json, struct, sys, zlib
kind, out = sys.argv[1], sys.argv[2]
n = int(sys.argv[3]) if len(sys.argv) > 3 else 0
pos = [-1, 0, -1, -1, 0, 1, 1, 0, 1, 1, 0, -1]
data = struct.pack('<12f', *pos) + struct.pack('<6H', 0, 1, 2, 0, 2, 3)
views = [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}]
acc = [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1]},
       {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]
prim = {"attributes": {"POSITION": 0}, "indices": 1}
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
     "meshes": [{"primitives": [prim]}]}
if kind == "required":
    g["extensionsUsed"] = g["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    del acc[1]["bufferView"]
    prim["extensions"] = {"KHR_draco_mesh_compression": {"bufferView": 1, "attributes": {"POSITION": 0}}}
elif kind == "ignored":
    def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
    png = (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', 1, 1, 8, 2, 0, 0, 0))
           + chunk(b'IDAT', zlib.compress(b'\x00\x80\x80\xff')) + chunk(b'IEND', b''))
    g["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode()}]
    g["textures"] = [{"source": 0}]
    mat = {"normalTexture": {"index": 0}, "occlusionTexture": {"index": 0},
           "pbrMetallicRoughness": {"metallicRoughnessTexture": {"index": 0}},
           "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1}, "KHR_materials_sheen": {}}}
    g["materials"] = [mat, mat]
    g["extensionsUsed"] = ["KHR_materials_clearcoat", "KHR_materials_sheen"]
    prim["material"] = 0
    g["meshes"][0]["primitives"] += [dict(prim, mode=0, material=1), dict(prim, mode=1), dict(prim, mode=3)]
elif kind == "instanced":
    data += struct.pack('<%df' % (3 * n), *[c for i in range(n) for c in (3 * i, 0, 0)])
    views.append({"buffer": 0, "byteOffset": 60, "byteLength": 12 * n})
    acc.append({"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC3"})
    g["extensionsUsed"] = g["extensionsRequired"] = ["EXT_mesh_gpu_instancing"]
    g["nodes"] = [{"mesh": 0, "translation": [0, 1, 0],
                   "extensions": {"EXT_mesh_gpu_instancing": {"attributes": {"TRANSLATION": 2}}}}]
g["accessors"], g["bufferViews"] = acc, views
if kind == "required":  # binary: the JSON chunk, then the buffer
    g["buffers"] = [{"byteLength": len(data)}]
    j = json.dumps(g).encode(); j += b' ' * (-len(j) % 4); data += b'\0' * (-len(data) % 4)
    body = struct.pack('<II', len(j), 0x4E4F534A) + j + struct.pack('<II', len(data), 0x004E4942) + data
    open(out, "wb").write(struct.pack('<4sII', b'glTF', 2, 12 + len(body)) + body)
else:
    g["buffers"] = [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}]
    json.dump(g, open(out, "w"))
PY
}

# hit_share EXR: the share of pixels whose primary ray hit something (AOV triangle >= 0)
hit_share() {
  oiiotool "$1" --ch triangle --addc 1 --clamp:min=0:max=1 --printstats 2>&1 | awk '/Stats Avg/ { print $3 }'
}

# a file that requires an extension we lack is refused by every command, naming it, before
# tinygltf trips over the compressed data; one that requires what we implement loads
t_required_extension() {
  gen_gltf required "$T/req.glb"
  for cmd in render info reference compare-hits; do
    expect 3 "$BIN" $cmd "$T/req.glb" --width 16 --height 16; one_line_error
    has "req.glb: requires extension KHR_draco_mesh_compression, which saarcor does not implement$" "$T/err"
  done
  gen_gltf instanced "$T/inst.gltf" 2
  expect 0 "$BIN" info "$T/inst.gltf"
}

# features that change the appearance and are not implemented: one warning each (however many
# materials or primitives use them), in info and render, listed by info --json
t_ignored_features() {
  gen_gltf ignored "$T/ign.gltf"
  local want="KHR_materials_clearcoat KHR_materials_sheen normalTexture occlusionTexture metallicRoughnessTexture points lines"
  once_each() {
    [[ $(grep -c 'is not supported and is ignored$' "$T/err") -eq 7 ]] || { echo "not 7 warnings:"; cat "$T/err"; return 1; }
    for f in $want; do
      [[ $(grep -c ": $f is not supported and is ignored$" "$T/err") -eq 1 ]] || { echo "$f not warned once"; return 1; }
    done
  }
  expect 0 "$BIN" render "$T/ign.gltf" --width 16 --height 16 -o "$T/ign.png"
  once_each
  expect 0 "$BIN" info "$T/ign.gltf" --json "$T/ign.json"
  once_each
  has "^content .* 7 warnings" "$T/out"
  python3 -c "import json; f=json.load(open('$T/ign.json'))['ignored_features']; assert f == '$want'.split(), f"
  expect 0 "$BIN" info room --json "$T/room.json"
  python3 -c "import json; assert json.load(open('$T/room.json'))['ignored_features'] == []"
}

# without a camera the default view is raised: a plane at y = 0 is seen, not edge-on
t_default_camera() {
  gen_gltf plane "$T/plane.gltf"
  expect 0 "$BIN" render "$T/plane.gltf" --width 32 --height 24 -o "$T/plane.png" --aov "$T/plane.exr"
  awk -v s="$(hit_share "$T/plane.exr")" 'BEGIN { exit !(s > 0.1) }' || { echo "plane hit share $(hit_share "$T/plane.exr")"; return 1; }
}

# EXT_mesh_gpu_instancing: N rows are N instances (info), and all of them are drawn: from above,
# 4 rows cover 4 times the pixels of 1
t_gpu_instancing() {
  gen_gltf instanced "$T/i1.gltf" 1
  gen_gltf instanced "$T/i4.gltf" 4
  expect 0 "$BIN" info "$T/i4.gltf" --json "$T/i4.json"
  has '^objects      1 (meshes), instances 4,' "$T/out"
  python3 -c "import json; assert json.load(open('$T/i4.json'))['instances'] == 4"
  for n in 1 4; do
    expect 0 "$BIN" render "$T/i$n.gltf" --width 64 --height 32 --eye 4.5,12,0.01 --at 4.5,0,0 -o "$T/i$n.png" --aov "$T/i$n.exr"
  done
  awk -v a="$(hit_share "$T/i1.exr")" -v b="$(hit_share "$T/i4.exr")" 'BEGIN { r = b / a; exit !(a > 0 && r > 3.8 && r < 4.2) }' \
    || { echo "hit shares $(hit_share "$T/i1.exr") / $(hit_share "$T/i4.exr")"; return 1; }
  expect 0 "$BIN" reference "$T/i4.gltf" --width 64 --height 32 --eye 4.5,12,0.01 --at 4.5,0,0 -o "$T/i4r.exr" --png "$T/i4r.png"
  "$BIN" compare "$T/i4.png" "$T/i4r.png" --psnr-min 35 >/dev/null
  if [[ -f ../shared/scenes/SimpleInstancing.glb ]]; then
    expect 0 "$BIN" info ../shared/scenes/SimpleInstancing.glb
    has '^objects      1 (meshes), instances 125,' "$T/out"
  else
    echo "../shared/scenes is absent: SimpleInstancing.glb skipped"
  fi
}

# skinned animation on the shared Fox.glb: the pose changes, only the skinned object's geometry
# (and the per-frame regions) is uploaded after the first frame, the reference draws the same pose
t_render_skinned() {
  local fox=../shared/scenes/Fox.glb view="--eye 250,80,0 --at 0,50,0 --width 96 --height 72"
  expect 0 "$BIN" render $fox --frames 0:3 -o "$T/fox.png" --stats "$T/fox.json" $view
  [[ ! -s $T/err ]] || { echo "unexpected stderr (a skin warning?):"; cat "$T/err"; return 1; }
  has '^rendered .*Fox.glb: .*host [0-9.]* ms, rebuilt 1 (geometry [0-9.]* KB), upload [0-9.]* KB -> ' "$T/out"
  if cmp -s "$T/fox_0000.png" "$T/fox_0003.png"; then echo "the fox does not move"; return 1; fi
  python3 - "$T" <<'PY'
import json, sys
first = json.load(open(f"{sys.argv[1]}/fox_0000.json"))
for f in (1, 2, 3):
    d = json.load(open(f"{sys.argv[1]}/fox_{f:04d}.json"))["host"]
    assert d["rebuilt_objects"] == 1 and d["geometry_upload_bytes"] > 0 and d["seconds"] > 0, d
    # the rest of a frame's upload is the camera, lights, instances and top level: a few hundred bytes
    assert 0 < d["upload_bytes"] - d["geometry_upload_bytes"] < 1024, d
    assert d["upload_bytes"] < first["host"]["upload_bytes"] / 10, (d, first["host"])
PY
  expect 0 "$BIN" render cornell --frames 0:1 -o "$T/c.png" --width 16 --height 16 --stats "$T/c.json"
  python3 -c "import json; d=json.load(open('$T/c_0001.json'))['host']; assert d['geometry_upload_bytes'] == 0 and d['rebuilt_objects'] == 0, d"
  expect 0 "$BIN" render $fox --animation Walk --frame 10 -o "$T/walk.png" $view
  expect 0 "$BIN" reference $fox --animation Walk --time 0.3333333333333333 -o "$T/walk_ref.png" $view
  "$BIN" compare "$T/walk.png" "$T/walk_ref.png" --psnr-min 35 >/dev/null
  expect 2 "$BIN" render $fox --animation Nope; one_line_error
}

run_skinned() {
  if [[ -e ../shared/scenes/Fox.glb ]]; then run_case cli_render_skinned t_render_skinned; return; fi
  skip_case cli_render_skinned "../shared/scenes/Fox.glb is absent"
}

run_case cli_help t_help
run_case cli_bad_usage_exit_2_one_line t_bad_usage
run_case cli_version t_version
run_case cli_image_library t_image_library
run_case cli_capture_build t_capture_build
run_case cli_f24_eval t_f24_eval
run_case cli_f24gen_format t_f24gen_format
run_case cli_f24verify t_f24verify
run_case cli_compare_vs_idiff t_compare
run_case cli_gen t_gen
run_case cli_info t_info
run_case cli_render t_render
run_case cli_render_rays t_render_rays
run_case cli_render_cycle t_render_cycle
run_case cli_render_traversal t_render_traversal
run_case cli_reference t_reference
run_case cli_mem_mb t_mem_mb
run_case cli_dropped_warning t_dropped_warning
run_case cli_required_extension t_required_extension
run_case cli_ignored_features t_ignored_features
run_case cli_default_camera t_default_camera
run_case cli_gpu_instancing t_gpu_instancing
run_skinned
exit $((fails != 0))
