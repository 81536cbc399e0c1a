#!/usr/bin/env bash
# RTL tests in make test (the short form of make rtl-test): verilator -Wall is clean for the
# DynRTP, under which every module in rtl/ is instantiated (its model's build), and Yosys parses
# them (make synth); make synth's totals and LUT6 levels of a hierarchical netlist (the whole
# DynRTP's method) equal Yosys's stat and the levels of the netlist flattened after mapping on a
# small hierarchy (cache_read); the fp24 operators (with the RGS's
# square root and integer conversion) match the C model bit for bit on the edge sets, 10^5 random
# vectors and the golden hex vectors; the datapath units match on random vectors and on
# transactions captured while rendering the room (saarcor render --capture-unit-io); the exact dot
# product (rtl/f24_sum_exact.sv) matches hls/fp24/f24_sum_exact.c on 10^5 sets; the list unit
# (rtl/list_unit.sv) matches hls/units/list_unit.c on the operations of a cycle-mode frame of the
# room at 64 threads and 5 x 10^4 random ones, the caches with the memory port (rtl/cache_dm.sv,
# mem_port.sv) the cycle model's caches on that frame's reads, and the thread scheduler
# (rtl/thread_sched.sv) its issues; the rebase unit and the transformation unit's wide mode
# (rtl/rebase_unit.sv, xform_wide.sv) match rebase_origin and xform_point_wide / xform_vector_wide
# on the room's captured transactions and 2 x 10^4 random ones; the traversal unit (rtl/trav_unit.sv)
# matches hls/units/trav_unit.c (TRAV_STACK) on the cycle-mode frame's operations and 2 x 10^4 random
# ones that overflow its stacks, and the queues between its stages (rtl/sync_fifo.sv) in block RAM
# give the LUT RAM form's and a deque's outputs every cycle (rtl/tb/tb_fifo.sv); the RGS's ray generation
# (rtl/rgs_raygen.sv) matches rgs_primary and the recorded packets of cycle-mode frames of the room
# (perspective) and an orthographic cornell box, whose block order the tile controller
# (rtl/tile_ctrl.sv) reproduces, and of a functional frame on 2 threads, and 2 x 10^4 random blocks
# on random cameras; the RGS's decoding of the shading record's vertex normals
# (rtl/shade_rec_decode.sv), its bilinear texture sample (rtl/tex_coords.sv on tex_axis.sv, then tex_fetch.sv, its
# texel reads served by the bench), the frame of a hit (rtl/rgs_frame.sv: unit direction and
# normal, t_hat, hit point), a light at a surface (rtl/rgs_light.sv: shadow ray, Q12 weights), its
# colour and accumulation (rtl/rgs_light_colour.sv, rgs_add_light.sv), the barycentric
# interpolation (rtl/rgs_lerp.sv) and the child rays (rtl/rgs_spawn.sv) match shade_rec_normal,
# rgs_sample_bilinear's parts, rgs_surface_frame, rgs_light_packet, rgs_light_colour, rgs_add_light,
# rgs_lerp and rgs_spawn_children and the transactions recorded while rendering the room
# (textured), the cornell box and (from ../shared/scenes, if present) subpass_scene_opaque and
# CesiumMilkTruck (textured) with shadows and reflections, and 2 x 10^4 random ones of each; the
# surface at a hit (rtl/rgs_surface.sv: its reads, normal, frame, colours, textures) matches
# rgs_surface_at on the surfaces of those frames, the built-in vertex-colour and emissive
# scenes and cornell without vertex normals and with zero ones (the geometric normal), up to 8
# surfaces in flight, its reads the C's words, and a ray's accumulation (rtl/rgs_accum.sv) matches
# rgs_accumulate_ray, and the per-block control (rtl/rgs_ctrl.sv) matches rgs_render_block's
# pixels and primary hits and rgs_step's packets on every block of cornell and part of the room
# (these three with SAARCOR_RTL_MUTANTS=all, as make rtl-test runs it; make test checks the blocks
# of cornell through the DynRTP's frame, tests/test_rtl_render.sh); the
# benches catch mutants (a rounder that never rounds ties to even; with SAARCOR_RTL_MUTANTS=all, as
# make rtl-test runs it, also a cache without its tag forwarding, a mailbox that never
# moves on, a scheduler whose pointer never moves on, a walk that pushes the near child, a
# square root without its sticky bit, a pixel centre without its + 1/2, a tile controller stepping
# past the region's edge, a vector mode whose unused terms are +0, a rebase that moves by t = Inf,
# a core thread that walks on before the rest of a leaf's entries, a triangle unit whose plane
# distance meets the ray before's origin, a normal decoder folding the
# lower hemisphere with the wrong sign, a bilinear blend that truncates, a shading normal turned
# away from the ray, a highlight squared once too often, a transmission ray leaving from behind
# the surface when eta = 1, a surface's vertex colours truncated instead of rounded and a ray
# whose spawned children take no T_R steps when none is active, a block control spawning children one
# level short); the ray tracing core (rtl/trace_core.sv: 8 threads of
# rtl/trace_thread.sv sharing the units) traces the packets of functional frames (primary, shadow,
# secondary) of cornell, subpass_scene_opaque.glb, the room and Fox.glb (TRACE_SKIP_TOP and
# TRACE_IDENTITY) to trace_step's hits and counters; the DynRTP top's harness (rtl/tb/tb_dynrtp.cpp,
# saarcor render --mode rtl, tests/test_rtl_render.sh) catches a list word taken before the list
# cache answered and a block's pixels under a wrong corner (with SAARCOR_RTL_MUTANTS=all). Prints
# cmocka-style lines.
set -u
cd "$(dirname "$0")/.."
B=${BUILD:-build}
BIN=$B/saarcor
T=$(mktemp -d /tmp/saarcor-test-rtl-XXXXXX)
trap 'rm -rf "$T"' EXIT

# shellcheck source=case_lib.sh
source tests/case_lib.sh

t_lint() {
  # Verilator -Wall over the DynRTP (the Makefile's VERILATOR_FLAGS): its model, built for make
  # test's frame (tests/test_rtl_render.sh), instantiates every module of rtl/ with the parameters
  # the design gives it (checked here), so its build log is the lint; a separate --lint-only run
  # took make test 27 s of CPU for the same passes. make rtl-lint (make rtl-test, make check-full)
  # lints every module as the top with its default parameters.
  local top log=$B/rtl/e7m16/build_dynrtp.log
  for top in $(basename -s .sv rtl/*.sv); do
    grep -q -E "^\s*$top\s+(#\s*\(|u_[a-z0-9_]*\s*\()" rtl/*.sv || [[ $top == dynrtp ]] ||
      { echo "rtl/$top.sv is instantiated by no module: lint it as a top here"; return 1; }
  done
  [[ -x $B/rtl/e7m16/tb_dynrtp && -f $log ]] || { echo "$B/rtl/e7m16/tb_dynrtp is not built (make rtl)"; return 1; }
  ! grep -E "^%(Warning|Error)" "$log" || { echo "verilator -Wall: the DynRTP's build has the warnings above"; return 1; }
  echo "verilator -Wall: the DynRTP and its $(ls rtl/*.sv | wc -l) modules clean ($log)"
  # make synth reads every module with Yosys, whose SystemVerilog subset is smaller than Verilator's
  yosys -q -p "$(for f in rtl/*.sv; do printf 'read_verilog -sv %s; ' "$f"; done)" >/dev/null 2>"$T/yosys.err" ||
    { grep ERROR "$T/yosys.err"; return 1; }
  echo "yosys read_verilog -sv: $(ls rtl/*.sv | wc -l) modules parse"
}

t_synth_levels() { # make synth's totals and LUT6 levels of a hierarchical netlist (the whole DynRTP's method)
  # against Yosys's own stat and the levels of the same netlist flattened after mapping, on a small
  # hierarchy whose paths cross module ports (cache_read: cache_dm and the combinational rr_pick)
  yosys -q -l "$T/h.log" -p "read_verilog -sv rtl/cache_read.sv rtl/cache_dm.sv rtl/rr_pick.sv rtl/read_ring.sv; chparam -set SIZE_BYTES 256 \
    -set OUTSTANDING 4 cache_read; synth_xilinx -top cache_read; stat; write_json $T/h.json" >/dev/null 2>&1 || return 1
  yosys -q -p "read_json $T/h.json; flatten; write_json $T/f.json" >/dev/null 2>&1 || return 1
  python3 - "$T" <<'PY' || return 1
import json, os, sys
sys.path.insert(0, "scripts")
import synth as S
t = sys.argv[1]
mods = json.load(open(f"{t}/h.json"))["modules"]
top = S.top_module(mods)
_, tot = S.hierarchy_totals(S.module_cells(mods), top)
flat = S.cells(open(f"{t}/h.log").read())
h, f = S.hier_lut_levels(mods, top)[top], S.lut_levels(f"{t}/f.json")
# the whole DynRTP's way (module_netlists): each module mapped by a Yosys run of its own, its
# submodules black boxes; against the same elaborated RTL mapped as one hierarchy with the same flow:
# every module there, the LUTs within 5% (ABC maps a module a little differently with its
# neighbours black boxes), the same levels; a second call maps nothing and gives the same netlists
os.environ["SYNTH_JOBS"] = "1"
files = ["rtl/cache_read.sv", "rtl/cache_dm.sv", "rtl/rr_pick.sv", "rtl/read_ring.sv"]
args = ("xilinx", "cache_read", {"SIZE_BYTES": 256, "OUTSTANDING": 4}, f"{t}/pm", files)
pm, pm_top, cpu = S.module_netlists(*args)
_, pm_tot = S.hierarchy_totals(S.module_cells(pm), pm_top)
S.yosys(f"read_rtlil {t}/pm/elab.il; {S.xilinx_flow('cache_read', flatten=False)}; write_json {t}/w.json", f"{t}/w.log")
whole = json.load(open(f"{t}/w.json"))["modules"]
_, w_tot = S.hierarchy_totals(S.module_cells(whole), "cache_read")
p, wl = S.hier_lut_levels(pm, pm_top)[pm_top], S.hier_lut_levels(whole, "cache_read")["cache_read"]
again = S.module_netlists(*args)
# --dynrtp-path's walk back: the deepest path has the levels counted, from a register to a register's input
lv, steps = S.deepest_path(mods, top)
S.print_path(mods, top, lv, steps)
walked = sum(S.LEVEL_CELLS.get(typ, 0) for _, typ, _ in steps)
print(f"cache_read: {S.luts_of(tot)} LUTs summed over the hierarchy, {S.luts_of(flat)} by stat; LUT6 levels {h} "
      f"across module ports, {f} flattened; module by module {S.luts_of(pm_tot)} LUTs and {p} levels, the same RTLIL "
      f"as one hierarchy {S.luts_of(w_tot)} and {wl}; modules {sorted(S.key_name(m) for m in cpu)}")
ok = (h, S.luts_of(tot)) == (f, S.luts_of(flat)) and set(pm) == set(k for k, m in whole.items() if not S.blackbox(m))
ok = ok and abs(S.luts_of(pm_tot) - S.luts_of(w_tot)) <= 0.05 * S.luts_of(w_tot) and p == wl and again[0] == pm
ok = ok and lv == walked == h and steps[0][1] not in S.LEVEL_CELLS and steps[-1][1] == "D"
sys.exit(0 if ok else 1)
PY
  # a LUT RAM's write ends a path as a flip-flop's D does: a product written into a LUT RAM has
  # the levels of the same product written into a register (counting on through the write to a
  # later read would add the read's level)
  cat > "$T/lr.sv" <<'SV'
module lr #(parameter bit MEM = 1) (input logic clk_i, input logic [4:0] wa_i, ra_i, input logic [15:0] a_i, b_i,
                                     output logic [15:0] q_o);
  logic [15:0] a, b, w;
  logic [15:0] m [32];
  always_ff @(posedge clk_i) begin
    a <= a_i;
    b <= b_i;
    if (MEM) m[wa_i] <= a * b; else w <= a * b;
    q_o <= MEM ? m[ra_i] : w;
  end
endmodule
SV
  for mem in 1 0; do
    yosys -q -l "$T/lr$mem.log" -p "read_verilog -sv $T/lr.sv; chparam -set MEM $mem lr; synth_xilinx -top lr -nodsp -flatten; stat; write_json $T/lr$mem.json" \
      >/dev/null 2>&1 || return 1
  done
  grep -q RAM32M "$T/lr1.log" || { echo "the memory is not LUT RAM"; return 1; }
  python3 - "$T" <<'PY' || return 1
import sys
sys.path.insert(0, "scripts")
import synth as S
t = sys.argv[1]
ram, reg = S.lut_levels(f"{t}/lr1.json"), S.lut_levels(f"{t}/lr0.json")
print(f"a product into LUT RAM: {ram} LUT6 levels, into a register: {reg}")
sys.exit(0 if ram == reg else 1)
PY
  # a DSP48E1 with a register on an input's way (xilinx_dsp packs the RTL's flip-flops into it) ends
  # that input's paths and starts its outputs' as a flip-flop does; without one it is passed through
  # at no level: LUT > DSP > LUT between two flip-flops is 1 level with its A register, 2 without
  python3 - <<'PY' || return 1
import json, os, sys, tempfile
sys.path.insert(0, "scripts")
import synth as S
def netlist(areg):
    io = {"I0": "input", "O": "output"}
    cells = {"f0": {"type": "FDRE", "port_directions": {"D": "input", "Q": "output"}, "connections": {"D": [2], "Q": [3]}},
             "l1": {"type": "LUT1", "port_directions": io, "connections": {"I0": [3], "O": [4]}},
             "d": {"type": "DSP48E1", "parameters": {k: format(areg if k == "AREG" else 0, "032b") for k in
                   ("AREG", "BREG", "CREG", "DREG", "ADREG", "MREG", "PREG", "OPMODEREG", "ALUMODEREG", "INMODEREG",
                    "CARRYINREG", "CARRYINSELREG")} | {"USE_MULT": "NONE"},
                   "port_directions": {"A": "input", "CEA2": "input", "P": "output"}, "connections": {"A": [4], "CEA2": [2], "P": [5]}},
             "l2": {"type": "LUT1", "port_directions": io, "connections": {"I0": [5], "O": [6]}},
             "f1": {"type": "FDRE", "port_directions": {"D": "input", "Q": "output"}, "connections": {"D": [6], "Q": [7]}}}
    return {"modules": {"t": {"attributes": {"top": "1"}, "ports": {"i": {"direction": "input", "bits": [2]},
                              "o": {"direction": "output", "bits": [7]}}, "cells": cells, "netnames": {}}}}
got = []
for areg in (1, 0):
    f = tempfile.NamedTemporaryFile("w", suffix=".json", delete=False)
    json.dump(netlist(areg), f)
    f.close()
    mods = json.load(open(f.name))["modules"]
    got.append((S.lut_levels(f.name), S.hier_lut_levels(mods, "t")["t"]))
    os.unlink(f.name)
print(f"LUT > DSP48E1 > LUT: {got[0][0]} level(s) with its A register, {got[1][0]} without (flat); hierarchical {got[0][1]}, {got[1][1]}")
sys.exit(0 if got == [(1, 1), (2, 2)] else 1)
PY
  # --ports: IBUF > LUT1 > FDRE > LUT1 > OBUF, the buffers as wires: i 1 level into a register, o 1
  # from one (0 and none if a buffer ended the path as a register does)
  python3 - <<'PY'
import sys
sys.path.insert(0, "scripts")
import synth as S
cell = lambda typ, i, o, ip="I0", op="O": {"type": typ, "port_directions": {ip: "input", op: "output"},
                                           "connections": {ip: [i], op: [o]}}
cells = {"ib": cell("IBUF", 2, 3, "I"), "l1": cell("LUT1", 3, 4), "f": cell("FDRE", 4, 5, "D", "Q"),
         "l2": cell("LUT1", 5, 6), "ob": cell("OBUF", 6, 7, "I")}
mods = {"t": {"attributes": {"top": "1"}, "ports": {"i": {"direction": "input", "bits": [2]},
                                                  "o": {"direction": "output", "bits": [7]}}, "cells": cells}}
got = S.port_levels(mods, ["i", "o"])
print(f"--ports through IBUF/OBUF: {got}")
sys.exit(0 if got == {"i": (None, None, 1), "o": (1, None, None)} else 1)
PY
}

t_operators() {
  "$B/rtl/e7m16/tb_f24_ops" -n 100000 tests/golden/f24/{add,sub,mul,div,lt,le,eq,min,max,sqrt,to_i32}.hex
}

t_units() {
  "$BIN" render room -o "$T/room.png" --width 48 --height 32 --capture-unit-io "$T/cap" --capture-limit 20000 >/dev/null
  "$B/rtl/e7m16/tb_units" -n 20000 --capture "$T/cap"
}

capture_room() { # the functional frame's capture of t_units, made here if that case did not run
  [[ -f "$T/cap/wide.hex" ]] || "$BIN" render room -o "$T/room.png" --width 48 --height 32 --capture-unit-io "$T/cap" \
    --capture-limit 20000 >/dev/null
}

t_wide() {
  capture_room
  "$B/rtl/e7m16/tb_wide" -n 20000 --capture "$T/cap"
}

t_exact_sum() {
  "$B/rtl/e7m16/tb_sum" -n 100000
}

t_list_and_cache() {
  "$BIN" render room -o "$T/room_cycle.png" --width 48 --height 32 --mode cycle --threads-per-pipe 64 \
    --capture-unit-io "$T/capc" --capture-limit 200000 >/dev/null
  "$B/rtl/e7m16/tb_list" -n 50000 --capture "$T/capc"
  "$B/rtl/e7m16/tb_cache" --capture "$T/capc"
  "$B/rtl/e7m16/tb_sched" -n 100000 --capture "$T/capc"
  # three frames of the animated scene: the caches emptied between frames (flush_i)
  mkdir -p "$T/anim"
  "$BIN" render animated -o "$T/anim/a.png" --width 32 --height 24 --mode cycle --threads-per-pipe 64 --frames 0:2 \
    --capture-unit-io "$T/capa" --capture-limit 200000 >/dev/null
  "$B/rtl/e7m16/tb_list" -n 0 --capture "$T/capa"
  "$B/rtl/e7m16/tb_cache" --capture "$T/capa" | tee "$T/capa.log"
  grep -q "(3 frames, 2 flushes)" "$T/capa.log"
}

# builds tb_NAME with rtl/FILE replaced by the sed expression EXPR in $T/mut_NAME; runs it with ARGS
# and expects it to fail
# Each mutant is a Verilator build (10-20 s, its C++ at -O0): make test runs the rounder's mutant
# (the bench machinery can fail); make rtl-test (SAARCOR_RTL_MUTANTS=all) also those of the cache,
# the list unit, the scheduler, the traversal unit, the square root, the ray generation, the tile controller,
# the wide transformation, the rebase unit and the core (its build takes about 2 minutes), and the
# caches with tables of 4 requests.
extra_mutants() { [[ ${SAARCOR_RTL_MUTANTS:-} == all ]]; }

mutant() {
  local name=$1 file=$2 expr=$3; shift 3
  local d="$T/mut_$name"
  mkdir -p "$d"
  sed "$expr" "rtl/$file" >"$d/$file"
  ! cmp -s "rtl/$file" "$d/$file" || { echo "the mutation of $file changed nothing"; return 1; }
  local srcs=()
  for f in rtl/*.sv; do [[ $f == "rtl/$file" ]] || srcs+=("$PWD/$f"); done
  model "$name" "$d" "" "${srcs[@]}" "$d/$file"
  local rc=0
  "$d/tb" "$@" >"$d/log" 2>&1 || rc=$?
  [[ $rc -ne 0 ]] || { echo "the mutant $file passed tb_$name"; return 1; }
  # caught only as the benches report a wrong result: exit 1 (2 is a usage or input error, above
  # 128 a signal); a crash of the bench is not the comparison catching the mutant
  [[ $rc -eq 1 ]] || { tail -5 "$d/log"; echo "the mutant $file made tb_$name exit $rc, not fail a comparison"; return 1; }
  echo "mutant $file caught by tb_$name: $(grep -c MISMATCH "$d/log") mismatch lines shown"
}

# builds DIR/tb, the model of tb_NAME from the given rtl/ sources with the Verilator options OPTS
# (e.g. other parameters of the bench's wrapper), its C++ at -O0, linked with the units in the
# hardware arithmetic as make's benches are (the fast build's objects hold other structures: a
# bench's trace_state overflowed, and the rgs_ctrl mutant "was caught" by a crash at main's return),
# its C++ as one translation unit as make's are (VM_PARALLEL_BUILDS=0, the Makefile's VERILATOR_FLAGS)
model() {
  local name=$1 d=$2 opts=$3; shift 3
  # shellcheck disable=SC2086 # OPTS are words
  verilator --cc --exe --build -j 2 -Wno-fatal -GE=7 -GM=16 $opts --top-module "tb_$name" -Mdir "$d/obj" \
    -MAKEFLAGS OPT_FAST=-O0 -MAKEFLAGS OPT_SLOW=-O0 -MAKEFLAGS OPT_GLOBAL=-O0 -MAKEFLAGS VM_GLOBAL_FAST= -MAKEFLAGS VM_PARALLEL_BUILDS=0 \
    -o "$d/tb" "$@" "$PWD/rtl/tb/tb_$name.sv" "$PWD/rtl/tb/tb_$name.cpp" \
    -CFLAGS "-DF24_EXP_BITS=7 -DF24_MAN_BITS=16 $(printf -- "-I$PWD/%s " hls hls/fp24 hls/units tb/fp host/memimage host/kdtree host/scene)" \
    -LDFLAGS "$(ls "$PWD/$B"/obj/e7m16/hls/fp24/*.o "$PWD/$B"/obj/hw/e7m16/hls/units/*.o "$PWD/$B"/obj/e7m16/tb/fp/*.o \
      "$PWD/$B"/rtl/verilated/*.o | tr '\n' ' ') -lmpfr -lgmp -lm" >/dev/null
}

# the caches with 4 outstanding requests each: their tables fill, so the room kept for the requests
# in the index stage and S1 (req_ready_o) is exercised
t_cache_small_table() {
  [[ -f "$T/capc/mem.hex" ]] || "$BIN" render room -o "$T/room_cycle.png" --width 48 --height 32 --mode cycle \
    --threads-per-pipe 64 --capture-unit-io "$T/capc" --capture-limit 200000 >/dev/null
  mkdir -p "$T/cache4"
  model cache "$T/cache4" -GOUTSTANDING=4 "$PWD"/rtl/*.sv
  "$T/cache4/tb" --capture "$T/capc" | tee "$T/cache4/log"
  grep -Eq "matrices cache .* [1-9][0-9]* cycles with its request table full" "$T/cache4/log"
}

t_fifo() { # sync_fifo's two storages (LUT RAM, block RAM) against a deque, every output every cycle
  local rc=0
  "$B/rtl/e7m16/tb_fifo" -n 200000 >"$T/fifo.log" || rc=$?
  cat "$T/fifo.log"
  return "$rc"
}

t_trav_unit() {
  [[ -f "$T/capc/trav_unit.hex" ]] || "$BIN" render room -o "$T/room_cycle.png" --width 48 --height 32 --mode cycle \
    --threads-per-pipe 64 --capture-unit-io "$T/capc" --capture-limit 200000 >/dev/null
  "$B/rtl/e7m16/tb_trav" -n 20000 --capture "$T/capc" | tee "$T/trav.log"
  # the random walks must have overflowed stacks and restarted, else the overflow path went unchecked
  grep -Eq ", [1-9][0-9]* stack overflows, [1-9][0-9]* restarts" "$T/trav.log"
  # pipelined: the captured frame's operations at under 2 cycles each (1.71; 10.28 with the
  # operation contexts it replaced, and a clip's 6 trav_node slots bound it at 1.50)
  awk '/captured operations in/ { for (i = 1; i <= NF; i++) if ($i == "cycles" && $(i+1) == "per") c = substr($(i-1), 2) }
       END { exit !(c != "" && c + 0 < 2.0) }' "$T/trav.log"
}

t_trav_mutant_caught() { # the near child pushed instead of the far one; at the end of a step that
  # popped already, the popped entry taken again instead of the one below it (the stack's other bank);
  # a clip's every axis narrowing the interval before the box instead of the chain's (trav_clip)
  [[ -f "$T/capc/trav_unit.hex" ]] || "$BIN" render room -o "$T/room_cycle.png" --width 48 --height 32 --mode cycle \
    --threads-per-pipe 64 --capture-unit-io "$T/capc" --capture-limit 200000 >/dev/null
  mutant trav trav_unit.sv "s/assign stk_wd = z3_first_near_left ?/assign stk_wd = !z3_first_near_left ?/" \
    -n 0 --capture "$T/capc"
  mutant trav trav_unit.sv "s/z4_cx\[O_POPPED\] ? z4_cx\[O_E2 +: ENW\]/z4_cx[O_POPPED] ? z4_cx[O_E1 +: ENW]/" \
    -n 20000 --capture "$T/capc" &&
    mutant trav trav_clip.sv "s/pass_i == 3'd1 ?/pass_i[0] ?/g" -n 0 --capture "$T/capc"
}

t_cache_mutant_caught() {
  [[ -f "$T/capc/mem.hex" ]] || "$BIN" render room -o "$T/room_cycle.png" --width 48 --height 32 --mode cycle \
    --threads-per-pipe 64 --capture-unit-io "$T/capc" --capture-limit 200000 >/dev/null
  mutant cache cache_dm.sv "s/tag_eff = (p_tag_we \&\& p_tag_idx == s1_idx) ? p_tag : tag_q;/tag_eff = tag_q;/" \
    --capture "$T/capc"
}

t_list_sched_mutants_caught() {
  [[ -f "$T/capc/list.hex" ]] || "$BIN" render room -o "$T/room_cycle.png" --width 48 --height 32 --mode cycle \
    --threads-per-pipe 64 --capture-unit-io "$T/capc" --capture-limit 200000 >/dev/null
  mutant list list_unit.sv "s/s2_next\[r\] + 3'd1/s2_next[r]/" -n 2000 --capture "$T/capc" &&
    mutant sched thread_sched.sv "s/after_q\[u\] <= after_next;/after_q[u] <= '1;/" -n 0 --capture "$T/capc"
}

t_rgs() {
  # orthographic: the cornell box's camera made orthographic; odd sizes, partial tiles of 8
  "$BIN" gen cornell -o "$T/cornell.gltf" >/dev/null
  python3 scripts/ortho_camera.py "$T/cornell.gltf" "$T/ortho.gltf"
  "$BIN" render "$T/ortho.gltf" -o "$T/ortho.png" --width 38 --height 27 --mode cycle --tile 8 --capture-unit-io "$T/rgso" \
    --capture-limit 1000 >/dev/null
  "$B/rtl/e7m16/tb_rgs" -n 0 --capture "$T/rgso" --order 8 >"$T/rgso.log" || { cat "$T/rgso.log"; false; }
  cat "$T/rgso.log"
  grep -q "(266 orthographic; 1 frames in tile_ctrl's order" "$T/rgso.log"
  # functional mode on 2 threads: the blocks in the order the threads took them
  "$BIN" render cornell -o "$T/rgs_cornell.png" --width 32 --height 24 --threads 2 --capture-unit-io "$T/rgsf" \
    --capture-limit 1000 >/dev/null
  "$B/rtl/e7m16/tb_rgs" -n 0 --capture "$T/rgsf"
  # perspective, the room in the cycle model's order, and random blocks on random cameras
  "$BIN" render room -o "$T/rgs_room.png" --width 48 --height 32 --mode cycle --capture-unit-io "$T/rgsr" \
    --capture-limit 1000 >/dev/null
  "$B/rtl/e7m16/tb_rgs" -n 20000 --capture "$T/rgsr" --order 16
}

t_rgs_mutants_caught() {
  mutant rgs rgs_raygen.sv "s/{x\[30:0\], 1'b1}/{x[30:0], 1'b0}/" -n 200 &&
    mutant rgs tile_ctrl.sv "s/33'(x_q) + 33'd2 < 33'(x1_q)/33'(x_q) + 33'd2 <= 33'(x1_q)/" -n 2000
}

# the RGS's shading datapath: the vertex normals decoded while rendering scenes with vertex normals
# (textured ones among them), then random codes, which must include missing and folded normals
t_shade() {
  local scenes=(room cornell) s
  for s in subpass_scene_opaque CesiumMilkTruck; do
    if [[ -f ../shared/scenes/$s.glb ]]; then scenes+=("../shared/scenes/$s.glb"); else echo "../shared/scenes/$s.glb is absent: skipped"; fi
  done
  for s in "${scenes[@]}"; do
    local d
    d="$T/shade_$(basename "$s" .glb)"
    "$BIN" render "$s" -o "$d.png" --width 32 --height 24 --max-depth 2 --capture-unit-io "$d" --capture-limit 20000 \
      >/dev/null 2>&1
    "$B/rtl/e7m16/tb_shade" -n 0 --capture "$d" >"$d.log" || { cat "$d.log"; false; }
    cat "$d.log"
  done
  # the room and the truck are textured: their samples were checked; every scene's frames were
  grep -Eq "shade_rec_decode [1-9][0-9]* normals checked" "$T/shade_room.log"
  for s in room CesiumMilkTruck; do
    [[ ! -f "$T/shade_$s.log" ]] || grep -Eq "tex_bilinear [1-9][0-9]* samples checked" "$T/shade_$s.log"
  done
  for s in "${scenes[@]}"; do
    grep -Eq "rgs_frame [1-9][0-9]* frames checked" "$T/shade_$(basename "$s" .glb).log"
    grep -Eq "rgs_light [1-9][0-9]* light-surface pairs checked" "$T/shade_$(basename "$s" .glb).log"
  done
  "$B/rtl/e7m16/tb_shade" -n 20000 >"$T/shade.log" || { cat "$T/shade.log"; false; }
  cat "$T/shade.log"
  grep -Eq "; [1-9][0-9]* missing, [1-9][0-9]* folded\), latency" "$T/shade.log"
  grep -Eq "; [1-9][0-9]* lit, [1-9][0-9]* by a spot\), latency" "$T/shade.log"
  grep -Eq "; [1-9][0-9]* refracted, [1-9][0-9]* totally reflected\), latency" "$T/shade.log"
}

# the RGS's surface at a hit (rgs_surface: its reads, the normal and its zero test, the frame, the
# material's colours, vertex colours, base and emissive textures, the tint) on every surface of
# frames with shadows and reflections: the room, cornell, the built-in vertex-colour and
# emissive-texture scenes and ../shared's subpass_scene_opaque and textured CesiumMilkTruck, then
# their hits with other barycentrics, distances, inactive rays and misses
t_surface() {
  local scenes=(room cornell vertex_colours emissive) s d
  for s in subpass_scene_opaque CesiumMilkTruck; do
    if [[ -f ../shared/scenes/$s.glb ]]; then scenes+=("../shared/scenes/$s.glb"); else echo "../shared/scenes/$s.glb is absent: skipped"; fi
  done
  for s in "${scenes[@]}"; do
    d="$T/surface_$(basename "$s" .glb)"
    "$BIN" render "$s" -o "$d.png" --width 32 --height 24 --max-depth 2 --capture-unit-io "$d" --capture-limit 400 \
      >/dev/null 2>&1
    "$B/rtl/e7m16/tb_surface" -n 200 --capture "$d" >"$d.log" || { cat "$d.log"; false; }
    cat "$d.log"
  done
  # the geometric normal: cornell without vertex normals (read by the front after the record) and
  # with its first mesh's normals zero (read by the back after the zero-length test)
  "$BIN" gen cornell -o "$T/surface_cornell.gltf" >/dev/null
  for s in drop zero; do
    d="$T/surface_normals_$s"
    python3 scripts/vertex_normals.py "$T/surface_cornell.gltf" "$d.gltf" "$s"
    "$BIN" render "$d.gltf" -o "$d.png" --width 32 --height 24 --max-depth 2 --capture-unit-io "$d" --capture-limit 400 \
      >/dev/null 2>&1
    "$B/rtl/e7m16/tb_surface" -n 200 --capture "$d" >"$d.log" || { cat "$d.log"; false; }
    cat "$d.log"
    grep -Eq " [1-9][0-9]* with the geometric normal" "$d.log" || return 1
  done
  grep -Eq "; [1-9][0-9]* valid, [1-9][0-9]* with vertex colours" "$T/surface_vertex_colours.log" &&
    grep -Eq " [1-9][0-9]* texture samples\), 0 mismatches, 0 wrong reads" "$T/surface_emissive.log"
}

# the vertex colours' weighted sum truncated instead of rounded (no + 2048 before the shift by 12);
# rgs_normal's barycentrics leaving their queue after a hit's first component instead of its last
# (the next hit's u, v for the other two); line_reader taking word k of a burst from the line's
# word k mod 4, without the burst's offset in its first line
t_surface_mutant_caught() {
  [[ -f "$T/surface_vertex_colours/surface.hex" ]] || "$BIN" render vertex_colours -o "$T/vc.png" --width 32 --height 24 \
    --max-depth 2 --capture-unit-io "$T/surface_vertex_colours" --capture-limit 400 >/dev/null 2>&1
  mutant surface rgs_surface.sv "s/((sum_q\[k\] + 32'd2048) >> 12)/(sum_q[k] >> 12)/" -n 0 --capture "$T/surface_vertex_colours" &&
    mutant surface rgs_normal.sv "s/assign uv_pop = lerp_on_q \&\& lk_q == 2'd2;/assign uv_pop = lerp_on_q \&\& lk_q == 2'd0;/" \
      -n 0 --capture "$T/surface_vertex_colours" &&
    mutant surface line_reader.sv "s/rsp_line_i\[32\*(pos % LW) +: 32\]/rsp_line_i[32*(k % LW) +: 32]/" \
      -n 0 --capture "$T/surface_vertex_colours"
}

# an active ray's share of the accumulation (rgs_accum: the pixel's colour, the child rays through
# rgs_spawn, the T_R steps rule) on the rays of the room's frame, then random ones
t_accum() {
  local d="$T/accum_room"
  "$BIN" render room -o "$d.png" --width 32 --height 24 --max-depth 2 --capture-unit-io "$d" --capture-limit 400 >/dev/null
  "$B/rtl/e7m16/tb_accum" -n 4000 --capture "$d" | tee "$d.log"
  grep -Eq "; [1-9][0-9]* with an active child, [1-9][0-9]* with T_R steps\), 0 mismatches" "$d.log"
}

# a ray whose children take T_R steps only if one is active, also without PROFILE_LIVE_CHILDREN
t_accum_mutant_caught() {
  mutant accum rgs_accum.sv "s/assign steps_o = spawn_q \&\& (!live_q || r_act || t_act);/assign steps_o = spawn_q \&\& (r_act || t_act);/" \
    -n 4000
}

# SCENE (a scene's name or a glTF file) rendered at 32x24 with its units' I/O captured in
# $T/ctrl_NAME (NAME: the file's without .gltf) for tb_rgs_ctrl, once
ctrl_capture() {
  local n
  n=$(basename "$1" .gltf)
  [[ -f "$T/ctrl_$n/image_0.bin" ]] || "$BIN" render "$1" -o "$T/ctrl_$n.png" --width 32 --height 24 \
    --capture-unit-io "$T/ctrl_$n" --capture-limit 10 >/dev/null
}

# $T/glass.gltf: cornell of glass (scripts/glass_materials.py: smooth dielectrics, half of them
# transmissive), whose packets push transmission tasks under reflection tasks: the one case that
# writes rgs_ctrl's stack memory and pops it later (the repository's scenes do it for a few blocks)
glass_scene() {
  [[ -f "$T/glass.gltf" ]] || { "$BIN" gen cornell -o "$T/cornell.gltf" >/dev/null &&
    python3 scripts/glass_materials.py "$T/cornell.gltf" "$T/glass.gltf"; }
}

# the RGS's per-block control (rgs_ctrl): every block of cornell at 32x24 and the first 64 of the
# room (reflections) with shadows and depth 2, the room without shadows, and cornell of glass at
# depth 3, its stack memory written and popped (109 tasks); the bench traces the packets with the
# C and compares them, the pixels and the primary hits with rgs_render_block
t_rgs_ctrl() {
  local s
  glass_scene
  for s in cornell room "$T/glass.gltf"; do ctrl_capture "$s"; done
  { "$B/rtl/e7m16/tb_rgs_ctrl" --capture "$T/ctrl_cornell" &&
    "$B/rtl/e7m16/tb_rgs_ctrl" --capture "$T/ctrl_room" --blocks 64 &&
    "$B/rtl/e7m16/tb_rgs_ctrl" --capture "$T/ctrl_room" --blocks 32 --no-shadows &&
    "$B/rtl/e7m16/tb_rgs_ctrl" --capture "$T/ctrl_glass" --max-depth 3; } | tee "$T/ctrl.log"
  [[ $(grep -c " 0 mismatches" "$T/ctrl.log") == 4 ]] && grep -q "^rgs_ctrl 192 blocks checked" "$T/ctrl.log" &&
    grep "^rgs_ctrl stack memory" "$T/ctrl.log" | tail -1 | grep -Eq ": [1-9][0-9]* tasks written, [1-9][0-9]* popped"
}

# children one level short (depth + 1 < max_depth instead of <=): the room without reflections;
# the stack's top fetched as its first word over and over (the read address without the word's
# index): cornell of glass, whose tasks popped from the stack memory come out wrong
t_rgs_ctrl_mutant_caught() {
  ctrl_capture room && glass_scene && ctrl_capture "$T/glass.gltf" &&
    mutant rgs_ctrl rgs_ctrl.sv "s/assign children_on = depth1 <= {1'b0, max_depth_i}/assign children_on = depth1 < {1'b0, max_depth_i}/" \
      --capture "$T/ctrl_room" --max-depth 1 &&
    mutant rgs_ctrl rgs_ctrl.sv "s/assign raddr = SAW'(top) \* SAW'(CH) + SAW'(pc_q);/assign raddr = SAW'(top) * SAW'(CH);/" \
      --capture "$T/ctrl_glass" --max-depth 3
}

# the normal decoder's fold of the lower hemisphere with the x component's sign the wrong way round;
# the bilinear blend truncating instead of rounding (no + 2^15 before the shift by 16); the frame's
# normal negated where it already faces the ray; the Phong power with one squaring too many; the
# transmission ray from the back origin for eta = 1 instead of on total internal reflection
t_shade_mutants_caught() {
  mutant shade shade_rec_decode.sv "s/fx = x < 0 ? ay - OCT_ONE : OCT_ONE - ay;/fx = x < 0 ? OCT_ONE - ay : ay - OCT_ONE;/" \
    -n 2000 &&
    mutant shade tex_fetch.sv "s/bottom \* 32'(hfy) + 32'd32768;/bottom * 32'(hfy);/" -n 2000 &&
    mutant shade rgs_frame.sv "s/\^ !facing\[W-1\]/^ facing[W-1]/" -n 2000 &&
    mutant shade rgs_light.sv "s/4'(j) < k_s\[j\]/4'(j) <= k_s[j]/" -n 2000 &&
    mutant shade rgs_spawn.sv "s/assign t_o_o = !one_l \&\& tir_l/assign t_o_o = one_l || tir_l/" -n 2000
}

# the rebase unit without the test for t = Inf (rebase_distance: 0), the wide mode's vector with its
# five unused terms +0 * +0 (the sum of three -0 products would come out +0)
t_wide_mutants_caught() {
  mutant wide xform_wide.sv "s/{5{NEG_ZERO}}/'0/" -n 4000 &&
    mutant wide rebase_unit.sv "s/assign te = t_i\[W-2:M\] == '1 ? '0 : t_i;/assign te = t_i;/" -n 4000
}

# the ray tracing core: functional frames' packets (tb_core) at 32x24 (the room at 16x12); scenes
# of ../shared skipped with a message when it is absent
core_scene() { # NAME SCENE W H [tb_core options]: capture a frame, trace its packets in the RTL
  local name=$1 scene=$2 w=$3 h=$4; shift 4
  if [[ $scene == ../shared/* && ! -e $scene ]]; then echo "$name: skipped, $scene is absent"; return 0; fi
  "$BIN" render "$scene" -o "$T/core_$name.png" --width "$w" --height "$h" --capture-unit-io "$T/core_$name" \
    --capture-limit 1000 >/dev/null
  "$B/rtl/e7m16/tb_core" --capture "$T/core_$name" "$@" | tee "$T/core_$name.log"
  grep -Eq "\(([1-9][0-9]*) any-hit\) on [0-9]+ threads, [1-9][0-9]* rays hit.* 0 mismatches" "$T/core_$name.log"
}

t_core() {
  core_scene cornell cornell 32 24 &&
    # 8 threads: packets in flight together, more than one operation at a time in the units
    grep -Eq "on 8 threads.* ([2-9]|[1-9][0-9])\.[0-9]+ operations in flight" "$T/core_cornell.log" &&
    core_scene subpass ../shared/scenes/subpass_scene_opaque.glb 32 24 &&
    core_scene room room 16 12 &&
    core_scene fox ../shared/scenes/Fox.glb 16 12 &&
    { [[ ! -e ../shared/scenes/Fox.glb ]] || awk '{ f[$3] = 1 } END { exit !(f[5] && f[7]) }' "$T/core_fox/trace.hex"; }
}

t_core_mutant_caught() { # route_after_list walking on before the rest of its leaf's entries; a record's responses;
  # the triangle unit's pipeline
  [[ -f "$T/core_cornell/trace.hex" ]] || "$BIN" render cornell -o "$T/core_cornell.png" --width 32 --height 24 \
    --capture-unit-io "$T/core_cornell" --capture-limit 1000 >/dev/null
  mutant core trace_thread.sv "s/else if (k\[level\] < leaf_count\[level\]) st <= S_LIST_GO;/else if (k[level] < leaf_count[level] \&\& !have_cur[level]) st <= S_LIST_GO;/" \
    --capture "$T/core_cornell" --packets 60 &&
    # an object record read in one response, not two (its bounds' last words stale)
    mutant core trace_thread.sv "s/OBJ_RSP = (OBJ_READ + RW - 1) \/ RW/OBJ_RSP = OBJ_READ \/ RW/" \
      --capture "$T/core_cornell" --packets 60 &&
    # the triangle unit's plane distance joining its origin's rows a cycle early (the ray before's)
    mutant core isect_rebased.sv "s/STAGES(T_JOIN - ADD_STAGES - SUM_STAGES)/STAGES(T_JOIN - ADD_STAGES - SUM_STAGES - 1)/" \
      --capture "$T/core_cornell" --packets 60
}

# the DynRTP top (rtl/dynrtp.sv) rendering the cornell box at 16x12 through its harness: $T/dyn
dyn_frame() {
  mkdir -p "$T/dyn"
  "$BIN" info cornell --width 16 --height 12 --image "$T/dyn/image.bin" >/dev/null
  printf 'tile 16\nthreads 32\nmax_depth 3\nshadows 1\ntraversal 0\nmem_latency 10\nmem_mbps 1000\nclock_mhz 90\n' >"$T/dyn/params"
}

# a list word taken as there before the list cache has answered (the stale word of the read
# before); a block's pixels sent out under the corner (x, x) instead of (x, y), caught by the check
# of every block against rgs_render_block
t_dynrtp_mutants_caught() {
  dyn_frame
  mutant dynrtp dynrtp.sv "s/if (list_re) list_valid <= 1'b0;/if (1'b0) list_valid <= 1'b0;/" "$T/dyn" &&
    mutant dynrtp dynrtp.sv "s/assign px_y_o = by_q\[/assign px_y_o = bx_q[/" "$T/dyn"
}

t_mutant_caught() { # the bench must fail on a wrong rounder
  mutant f24_ops f24_round_pack.sv "s/kept_even = tie ? {kept\[M+1:1\], 1'b0} : kept;/kept_even = kept;/" -n 20000
}

# a square root that drops the remainder's sticky bit takes inexact roots above a half ulp for ties
t_sqrt_mutant_caught() {
  mutant f24_ops f24_sqrt.sv "s/rootl\[0\] | (reml != 0)/rootl[0]/" -n 20000
}

run_case rtl_lint_clean t_lint
run_case rtl_operators_match_c_model t_operators
run_case rtl_units_match_c_model_and_capture t_units
run_case rtl_rebase_and_wide_xform_match_c_model_and_capture t_wide
run_case rtl_exact_sum_matches_c_model t_exact_sum
run_case rtl_list_unit_and_caches_match_c_model t_list_and_cache
run_case rtl_rgs_raygen_and_tile_ctrl_match_c_model t_rgs
run_case rtl_shade_datapath_matches_c_model_and_capture t_shade
if extra_mutants; then
  # the block controllers on more blocks than make test's DynRTP frame (tests/test_rtl_render.sh)
  run_case rtl_rgs_ctrl_matches_c_model t_rgs_ctrl
  # make synth's method for the whole DynRTP (make synth runs in make check-full, as this does)
  run_case synth_hierarchy_totals_and_levels t_synth_levels
  # the unit benches of rgs_ctrl's surface and accumulation (make test checks both inside whole
  # blocks through the DynRTP's frame; their models are built by make rtl-test)
  run_case rtl_surface_matches_c_model_and_capture t_surface
  run_case rtl_accum_matches_c_model_and_capture t_accum
  run_case rtl_sqrt_bench_catches_mutant t_sqrt_mutant_caught
  run_case rtl_rgs_bench_catches_mutants t_rgs_mutants_caught
  run_case rtl_wide_bench_catches_mutants t_wide_mutants_caught
  run_case rtl_caches_with_full_tables_match_c_model t_cache_small_table
  run_case rtl_shade_bench_catches_mutants t_shade_mutants_caught
  run_case rtl_surface_bench_catches_mutant t_surface_mutant_caught
  run_case rtl_accum_bench_catches_mutant t_accum_mutant_caught
  run_case rtl_rgs_ctrl_bench_catches_mutant t_rgs_ctrl_mutant_caught
  run_case rtl_list_sched_benches_catch_mutants t_list_sched_mutants_caught
  run_case rtl_cache_bench_catches_mutant t_cache_mutant_caught
fi
run_case rtl_fifo_block_ram_matches_lut_ram_and_deque t_fifo
run_case rtl_trav_unit_matches_c_model_and_capture t_trav_unit
extra_mutants && run_case rtl_trav_bench_catches_mutant t_trav_mutant_caught
run_case rtl_core_matches_c_model_and_capture t_core
extra_mutants && run_case rtl_core_bench_catches_mutant t_core_mutant_caught
extra_mutants && run_case rtl_dynrtp_harness_catches_mutants t_dynrtp_mutants_caught
run_case rtl_bench_catches_mutant t_mutant_caught
exit $((fails != 0))
