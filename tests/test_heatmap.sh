#!/usr/bin/env bash
# Tests of the per-pixel cost (tb/cycle/pixel_cost.c) and `render --heatmap` (tb/cli/heatmap.c):
# the cost channels of --aov, their sums against the --stats totals in both modes, the heatmap
# PNG's size and scale bar, bad options, and that -o is unchanged by --aov/--heatmap. Prints
# cmocka-style "[ RUN      ]" / "[       OK ]" / "[  FAILED  ]" lines for tests/run.sh.
set -u
cd "$(dirname "$0")/.."
BIN=${SAARCOR_BIN:-build/saarcor}
T=$(mktemp -d /tmp/saarcor-test-heatmap-XXXXXX)
trap 'rm -rf "$T"' EXIT
# shellcheck source=case_lib.sh
source tests/case_lib.sh
SIZE=(--width 64 --height 48 --threads 2)
COUNTS="traversal_steps list_entries intersections transformations"

one_line_error() { # CODE CMD...: exits with CODE and says so in one stderr line
  local want=$1 got=0; shift
  "$@" >/dev/null 2>"$T/err" || got=$?
  [[ $got -eq $want && $(wc -l <"$T/err") -eq 1 ]] && grep -q error "$T/err" ||
    { echo "expected exit $want and one error line, got $got: $*"; cat "$T/err"; return 1; }
}

# column EXR CHANNEL: the channel's value at every pixel, one per line (the file's values and
# channel names are read once per file: each OpenImageIO tool costs half a second of start-up)
column() {
  [[ -s $1.dump ]] || oiiotool --dumpdata "$1" >"$1.dump"
  [[ -s $1.names ]] || iinfo -v "$1" | sed -n 's/.*channel list: //p' | tr -d ' ' | tr ',' '\n' >"$1.names"
  local k; k=$(grep -nx "$2" "$1.names" | cut -d: -f1)
  [[ -n $k ]] || { echo "$1 has no channel $2" >&2; return 1; }
  awk -F': ' -v k="$k" '/Pixel/ { split($2, v, " "); print v[k] }' "$1.dump"
}

# twelfths EXR CHANNEL: the sum over pixels of the channel in twelfths (the channels are exact
# multiples of 1/12)
twelfths() {
  column "$1" "$2" | awk '{ s += int($1 * 12 + 0.5) } END { printf "%d\n", s }'
}

# render MODE NAME: room with shadows and secondary rays into $T/NAME.{png,exr,json} (once)
render() {
  [[ -s "$T/$2.json" ]] && return 0
  "$BIN" render room "${SIZE[@]}" --mode "$1" -o "$T/$2.png" --aov "$T/$2.exr" --stats "$T/$2.json" >/dev/null
}

check_sums() { # NAME: each count channel sums to its --stats total
  local ch want got
  for ch in $COUNTS; do
    want=$(python3 -c "import json; print(12 * json.load(open('$T/$1.json'))['$ch'])")
    got=$(twelfths "$T/$1.exr" "$ch")
    [[ $want -gt 0 || $ch == traversal_steps ]] || { echo "$ch: total 0, the test proves nothing"; return 1; }
    [[ $got -eq $want ]] || { echo "$1 $ch: pixels sum to $got/12, --stats says $want/12"; return 1; }
  done
}

t_aov_channels() {
  render functional f
  render cycle c
  iinfo -v "$T/f.exr" | grep 'channel list' >"$T/fl"
  iinfo -v "$T/c.exr" | grep 'channel list' >"$T/cl"
  for ch in $COUNTS t node; do grep -qw "$ch" "$T/fl"; grep -qw "$ch" "$T/cl"; done
  ! grep -qw cycles "$T/fl"
  grep -qw cycles "$T/cl"
}

t_sums_functional() {
  render functional f
  check_sums f
  [[ $(python3 -c "import json; print(json.load(open('$T/f.json'))['traversal_steps'])") -gt 0 ]]
}

t_sums_cycle() {
  render cycle c
  check_sums c
  local want got
  want=$(python3 -c "import json; c = json.load(open('$T/c.json'))['cycle']['thread_cycles']; print(12 * (c['in_unit'] + c['queued'] + c['memory']))")
  got=$(twelfths "$T/c.exr" cycles)
  [[ $want -gt 0 && $got -eq $want ]] || { echo "cycles: pixels sum to $got/12, thread cycles $want/12"; return 1; }
}

t_same_costs_both_modes() { # the same unit steps: the same per-pixel counts
  render functional f
  render cycle c
  local ch
  for ch in $COUNTS; do
    column "$T/f.exr" "$ch" >"$T/f1"
    column "$T/c.exr" "$ch" >"$T/c1"
    [[ -s $T/f1 ]] && cmp "$T/f1" "$T/c1"
  done
}

t_image_unchanged() {
  local m
  for m in functional cycle; do
    "$BIN" render room "${SIZE[@]}" --mode $m -o "$T/plain.png" >/dev/null
    "$BIN" render room "${SIZE[@]}" --mode $m -o "$T/with.png" --aov "$T/w.exr" --heatmap "$T/w_h.png" >/dev/null
    cmp "$T/plain.png" "$T/with.png"
  done
}

# pixel FILE X Y: the 8-bit values of a PNG pixel
pixel() { oiiotool --dumpdata "$1" | awk -v p="Pixel ($2, $3):" 'index($0, p) { print $4, $5, $6 }'; }

t_heatmap_png() {
  "$BIN" render room "${SIZE[@]}" -o "$T/r.png" --heatmap "$T/h.png" --heatmap-of intersections >/dev/null
  iinfo "$T/h.png" | grep -q '64 x   80, 3 channel, uint8 png'
  [[ $(pixel "$T/h.png" 4 56) == "68 1 84" ]]     # the bar: viridis from its start ...
  [[ $(pixel "$T/h.png" 59 56) == "253 231 37" ]] # ... to its end
  oiiotool "$T/h.png" --cut 64x10+0+66 -o "$T/labels.png"
  oiiotool --dumpdata "$T/labels.png" | grep -q ': 255 255 255' # the labels, in white
  "$BIN" render room "${SIZE[@]}" -o "$T/r.png" --heatmap "$T/h2.png" --heatmap-of list_entries >/dev/null
  ! cmp -s "$T/h.png" "$T/h2.png" # the channel matters
}

t_heatmap_cycle_frames() { # default channel in cycle mode: cycles; frames numbered like -o
  "$BIN" render room "${SIZE[@]}" --mode cycle --frames 0:1 -o "$T/s.png" --heatmap "$T/sh.png" >/dev/null
  iinfo "$T/sh_0000.png" | grep -q '64 x   80'
  iinfo "$T/sh_0001.png" | grep -q '64 x   80'
}

t_bad_options() {
  one_line_error 2 "$BIN" render room "${SIZE[@]}" -o "$T/x.png" --heatmap "$T/x_h.png" --heatmap-of frobs
  one_line_error 2 "$BIN" render room "${SIZE[@]}" -o "$T/x.png" --heatmap "$T/x_h.png" --heatmap-of cycles
  one_line_error 2 "$BIN" render room "${SIZE[@]}" -o "$T/x.png" --heatmap-of intersections
  one_line_error 3 "$BIN" render room "${SIZE[@]}" -o "$T/x.png" --heatmap "$T/no/such/dir/h.png"
}

run_case aov_channels t_aov_channels
run_case sums_functional t_sums_functional
run_case sums_cycle t_sums_cycle
run_case same_costs_both_modes t_same_costs_both_modes
run_case image_unchanged t_image_unchanged
run_case heatmap_png t_heatmap_png
run_case heatmap_cycle_frames t_heatmap_cycle_frames
run_case bad_options t_bad_options
[[ $fails -eq 0 ]]
