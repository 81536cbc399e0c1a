#!/usr/bin/env bash
# Hard limits and the glTF directory sandbox of build/saarcor (docs/limits.md): every limit exceeded
# gives one line naming the limit, the value and how to raise it, and exit code 5; --limit raises
# it; a glTF whose buffer lies outside its own directory ("../", an absolute path, a symlink out)
# is refused with exit 3. Prints cmocka-style lines for tests/run.sh.
set -u
cd "$(dirname "$0")/.."
BIN=$(pwd)/${SAARCOR_BIN:-build/saarcor}
T=$(mktemp -d /tmp/saarcor-test-limits-XXXXXX)
trap 'rm -rf "$T"' EXIT
source tests/case_lib.sh
cd "$T"

# limit CODE NAME ARGS...: saarcor ARGS exits CODE with one line naming limit NAME and --limit NAME=N
limit() {
  local want=$1 name=$2; shift 2
  local got=0
  "$BIN" "$@" >out 2>err || got=$?
  [[ $got -eq $want ]] || { echo "expected exit $want, got $got: saarcor $*"; cat err; return 1; }
  [[ $(wc -l <err) -eq 1 ]] || { echo "not one line:"; cat err; return 1; }
  grep -q "limit $name exceeded: .* is [0-9]*, the limit is [0-9]* (" err || { echo "no limit line:"; cat err; return 1; }
  cat err
}

case_triangles() {
  limit 5 triangles info cornell --limit triangles=23 && grep -q -- '--limit triangles=N' err
  "$BIN" info cornell --limit triangles=24 >/dev/null
}
case_instances() { # counted before the scene is evaluated (its instances allocated), with the ground
  limit 5 instances info room --limit instances=14
  "$BIN" info room --limit instances=15 >/dev/null
  limit 5 instances info room --limit instances=15 --ground && grep -q 'count is 16,' err
}
case_kd_nodes() { limit 5 kd-nodes info room --limit kd-nodes=100; }
case_kd_depth() {
  limit 5 kd-depth info cornell --kd-max-depth 50       # over the default of 48
  "$BIN" info cornell --kd-max-depth 50 --limit kd-depth=50 >/dev/null
  limit 5 kd-depth info room --limit kd-depth=3          # the trees may get deeper: refused before the build
  grep -q 'the depth the kd-tree builder may reach .* is 20,' err
}
case_texture_size() {
  limit 5 texture-size info room --limit texture-size=63
  "$BIN" info room --limit texture-size=64 >/dev/null
}
# bomb.py IN.gltf OUT.gltf: OUT's first PNG announces 40000x40000 texels in its header
cat >bomb.py <<'PY'
import base64, json, struct, sys
doc = json.load(open(sys.argv[1]))
buf = doc["buffers"][0]
head, data = buf["uri"].split(",", 1)
raw = bytearray(base64.b64decode(data))
at = doc["bufferViews"][doc["images"][0]["bufferView"]].get("byteOffset", 0)
assert raw[at + 1:at + 4] == b"PNG"
raw[at + 16:at + 24] = struct.pack(">II", 40000, 40000)
buf["uri"] = head + "," + base64.b64encode(bytes(raw)).decode()
json.dump(doc, open(sys.argv[2], "w"))
PY
case_texture_bomb() { # refused from the PNG header, before decoding (exit 3)
  "$BIN" gen room -o room.gltf >/dev/null && python3 bomb.py room.gltf bomb.gltf
  local got=0
  "$BIN" info bomb.gltf >out 2>err || got=$?
  [[ $got -eq 3 && $(wc -l <err) -eq 1 ]] && grep -q '40000x40000 texels, more than 16384 a side (not decoded)' err \
    || { echo "exit $got:"; cat err; return 1; }
  cat err
}
case_ray_depth() {
  limit 5 ray-depth render cornell --max-depth 9 -o x.png && grep -q 'at most 8 in this build' err
  limit 5 ray-depth reference cornell --max-depth 9 -o x.exr
}
case_image_size() {
  limit 5 width render cornell --width 16385 -o x.png
  limit 5 height info cornell --height 20000
  "$BIN" info cornell --width 16385 --limit width=16385 >/dev/null
}
case_frames() {
  limit 5 frames render animated --frames 0:100000 -o x.png   # 100001 frames
  limit 5 frames info animated --frames 11 --limit frames=10
}
case_memory_image() { # the existing limit of the device memory: --mem-mb (info reports such a scene)
  local got=0
  "$BIN" render terrain --mem-mb 1 --width 8 --height 8 -o t.png >out 2>err || got=$?
  [[ $got -eq 3 && $(wc -l <err) -eq 1 ]] && grep -q 'does not fit.*(pass --mem-mb [0-9]*)$' err && cat err
  "$BIN" info terrain --mem-mb 1 >out && grep -q '^fits         no: .* render it with --mem-mb [0-9]' out
}
case_bad_limit() {
  local got=0
  "$BIN" info cornell --limit nodes=3 2>err || got=$?
  [[ $got -eq 2 ]] && grep -q 'names: triangles' err
  got=0; "$BIN" info cornell --limit width=70000 2>err || got=$?
  [[ $got -eq 2 ]] && grep -q 'width is 1..65536' err && cat err
}

# external.py IN.gltf OUT.gltf URI BIN: OUT.gltf's buffer 0 is the file BIN, referenced as URI
cat >external.py <<'PY'
import base64, json, sys
doc = json.load(open(sys.argv[1]))
data = base64.b64decode(doc["buffers"][0]["uri"].split(",", 1)[1])
open(sys.argv[4], "wb").write(data)
doc["buffers"][0]["uri"] = sys.argv[3]
json.dump(doc, open(sys.argv[2], "w"))
PY
refused() { # GLTF: refused with exit 3 and one line naming the reference
  local got=0
  "$BIN" info "$1" >out 2>err || got=$?
  [[ $got -eq 3 && $(wc -l <err) -eq 1 ]] && grep -q 'outside its directory (refused)' err || { echo "exit $got:"; cat err; return 1; }
  cat err
}
case_path_outside() {
  mkdir -p a b && "$BIN" gen cornell -o c.gltf >/dev/null
  python3 external.py c.gltf a/inside.gltf buf.bin a/buf.bin
  "$BIN" info a/inside.gltf >/dev/null                     # inside its directory: loads
  python3 external.py c.gltf a/up.gltf ../b/buf.bin b/buf.bin
  refused a/up.gltf
  python3 external.py c.gltf a/abs.gltf "$T/b/buf.bin" b/buf.bin
  refused a/abs.gltf
  (cd a && refused abs.gltf)                                 # from its own directory, too
  ln -sf ../b/buf.bin a/link.bin
  python3 external.py c.gltf a/link.gltf link.bin b/buf.bin
  refused a/link.gltf
}

for c in triangles instances kd_nodes kd_depth texture_size texture_bomb ray_depth image_size frames memory_image bad_limit path_outside; do
  run_case "limit_$c" "case_$c"
done
exit $((fails != 0))
