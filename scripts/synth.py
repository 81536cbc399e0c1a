#!/usr/bin/env python3
"""make synth: Yosys synthesis of every RTL module -> docs/synth.md (generated, do not edit).

1. Every operator (the datapaths' and the RGS's square root and integer conversion) and datapath
   unit at the default format (E=7, M=16) with synth_xilinx (7-series cells: LUTs, flip-flops,
   DSP48E1, block RAM, CARRY4), and the operators also with synth_ice40 followed by nextpnr-ice40
   (HX8K) for an Fmax estimate where a module fits.
2. A resource estimate for one DynRTP's floating-point datapaths (one transformation unit, one
   intersection unit, one traversal node decision for 4 rays) next to the paper's Table 2 and
   the prototype's Virtex-II 6000.
3. The operators (the RGS's too) and the intersection unit across mantissa widths M in {8, 10, ..., 20, 23}
   (E = 7), for hardware cost against image error (docs/synth.md, build/synth/synth.json, read
   by make bench-precision), and the intersection unit with the robust edge option
   (EDGE_EPS = 8, docs/stress.md) beside the exact one.
4. The memory interface and the list unit (no floating point): rtl/list_unit.sv at 64 threads,
   rtl/cache_dm.sv as the kd-node, list, matrix and shading caches of the cycle model's defaults,
   rtl/mem_port.sv for those four requesters, with synth_xilinx and synth_ice40 (LUTs, flip-flops,
   block RAM and its bits).
5. The accuracy datapath (docs/numerics.md): the exact dot product f24_sum_exact with the term
   counts its users need (4: rebase unit, 8: the transformation unit's wide mode, 9: the
   intersection unit's plane distance) at e7m16, and with 9 terms at M = 12 and 20; the units built
   from it (rtl/xform_wide.sv, rtl/rebase_unit.sv) with synth_xilinx at e7m16, and the area of the
   whole fix: those units as measured, the intersection unit's origin path composed from the exact
   sum and the operators.
6. The whole DynRTP (rtl/dynrtp.sv) at the paper's configuration, per module without flattening:
   7-series and iCE40 (`synth_ice40 -dsp`) totals, block RAM bits (and of them the bits the memories
   store, memory by memory: bram_memories), LUT6 levels across module ports,
   the LUT6 and LUT4 of each unit, beside the prototype (build/synth/synth.json "dynrtp"). Each
   distinct module is mapped by a Yosys run of its own (its submodules black boxes) and kept in
   build/synth/dynrtp/ by the hash of its RTL, so a second run maps only the modules that changed.
Runs two Yosys processes at a time (item 6: SYNTH_JOBS, default the CPUs); logs in build/synth/.
`scripts/synth.py --dynrtp [xilinx] [ice40]` (make synth-dynrtp) measures only item 6 and rewrites
docs/synth.md from build/synth/synth.json, or without one only its DynRTP section.
`scripts/synth.py --only-control` synthesizes only item 4 and merges it into an existing
build/synth/synth.json (the other modules' figures as they were) before writing docs/synth.md.
`python3 scripts/synth.py --redo i:f24_sum_exact:e7m16 [KEY ...]` measures only the given entries of
build/synth/synth.json again (keys as in that file, or new ones such as x:rebase_unit:e7m16) and
rewrites it and docs/synth.md.
`python3 scripts/synth.py --levels MODULE [PARAM=VALUE ...] [--hier]` prints one module's most LUT6
levels between registers and ports as the DynRTP's are counted (synth_xilinx per module,
hier_lut_levels), its deepest path flattened after mapping (cell type, a net it drives; not with
--hier, for modules too large to flatten), and per submodule its levels and its own cells' deepest
path (the named nets); it writes only build/synth/levels_*.
`python3 scripts/synth.py --dynrtp-path [UNIT ...]` prints the whole DynRTP's deepest path of LUT6 levels
as --dynrtp counts them (from the netlists it keeps; a module changed since is mapped again), and each
named unit's of the top (e.g. trace_core) as its own top: per module instance along it its levels
and its cells (type, a net it drives; a register at the start, D: the register input at the end).
`python3 scripts/synth.py --ice40 MODULE [PARAM=VALUE ...]` prints one module's synth_ice40 -dsp totals
(SB_LUT4, flip-flops, SB_RAM40_4K, SB_MAC16) mapped module by module as the DynRTP's are, per part
(its own cells, each kind of submodule) and per memory in block RAM its SB_RAM40_4K and the bits it
stores (width x depth); it writes only build/synth/ice40_*/.
`python3 scripts/synth.py --ports build/synth/levels_MODULE_hier.json PORT ...` prints, from a netlist
that --levels wrote, each port's LUT6 levels from the top's registers, from its inputs and into its
registers (the top's IBUF/OBUF as wires): the parts of a path composed across modules.
"""
import concurrent.futures as cf, hashlib, json, os, re, shlex, subprocess, sys, tempfile, time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RTL = sorted(os.path.join(ROOT, "rtl", f) for f in os.listdir(os.path.join(ROOT, "rtl")) if f.endswith(".sv"))


OUT = os.path.join(ROOT, "build", "synth")
OPERATORS = ["f24_add", "f24_mul", "f24_div", "f24_cmp"]
RGS_OPERATORS = ["f24_sqrt", "f24_to_i32"]  # the shading's (issue 23), unary; built pipelined from the start
UNITS = ["xform_unit", "isect_unit", "trav_node"]
ACCURACY_UNITS = ["xform_wide", "rebase_unit"]  # the accuracy datapath's units (docs/numerics.md)
# units with their control (beyond a datapath): the traversal unit (a pipeline around one
# trav_node, one operation per cycle, per-thread stacks), the RGS's primary rays (through its own xform_unit)
# and the core's triangle test (the origin path, two xform_unit, isect_unit, t0 + t)
PIPE_UNITS = ["trav_unit", "rgs_raygen", "isect_rebased"]
WIDTHS = [8, 10, 12, 14, 16, 18, 20, 23]
ROBUST_EDGE_EPS = 8
# the operators' default pipeline stages (rtl/f24_*.sv: STAGES) and the units' latencies built from them
STAGES = {"f24_add": 6, "f24_mul": 4, "f24_div": 11, "f24_cmp": 2, "f24_sum_exact": 25, "f24_sqrt": 9,
          "f24_to_i32": 2}
LATENCY = dict(STAGES, xform_unit=STAGES["f24_mul"] + 3 * STAGES["f24_add"],
               isect_unit=STAGES["f24_div"] + STAGES["f24_mul"] + 2 * STAGES["f24_add"] + STAGES["f24_cmp"],
               trav_node=STAGES["f24_add"] + STAGES["f24_div"] + 2 * STAGES["f24_cmp"],
               xform_wide=STAGES["f24_sum_exact"], rebase_unit=STAGES["f24_sum_exact"],
               rgs_raygen=1 + 2 + STAGES["f24_mul"] + 3 * STAGES["f24_add"] + 4,  # in, convert 2, xform, 4 rays
               trav_unit="38 (a walk step; start 2, clip 146)",
               isect_rebased=max(2 * STAGES["f24_add"] + STAGES["f24_mul"] + 3 * STAGES["f24_add"],
                                 STAGES["f24_add"] + STAGES["f24_sum_exact"])
               + STAGES["f24_div"] + STAGES["f24_mul"] + 3 * STAGES["f24_add"] + STAGES["f24_cmp"])
# before the operators were pipelined inside (a combinational core, then a delay line): make synth at
# commit 0abb082 (2026-11-24), iCE40 HX8K: latency, LUT4, FFs, Fmax MHz
BEFORE = {"f24_add": (3, 756, 72, 14.83), "f24_mul": (3, 896, 72, 32.89), "f24_div": (6, 1394, 144, 4.64),
          "f24_cmp": (1, 224, 24, 49.47), "f24_sum_exact": (4, 6133, 192, 3.69)}  # (sum: one term, measured alike)
FP_UNITS = {  # fp24 operators in each datapath: add/sub, mul, div, comparisons (min/max/compare)
    "xform_unit": (9, 9, 0, 0), "isect_unit": (4, 2, 1, 5), "trav_node": (4, 0, 4, 16)}
SUM_TERMS = [4, 8, 9]           # f24_sum_exact instances of the accuracy datapath at e7m16
SUM_WIDTHS = [12, 16, 20]       # ... and its 9-term form across widths
# the fix, per unit: (exact sums by term count, extra adders, extra multipliers, the module that builds
# it: measured where it exists, else composed from the exact sums and the operators)
FIX = {"transformation unit (wide mode, 3 rows)": ({8: 3}, 0, 0, "xform_wide"),
       "rebase unit (3 components)": ({4: 3}, 0, 0, "rebase_unit"),
       "intersection unit (origin path, te + t')": ({9: 1}, 9 + 4 + 1, 6, None)}


def yosys(script, log):
    r = subprocess.run(["yosys", "-q", "-l", log, "-p", script], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"yosys failed, see {log}: {r.stderr.strip()[-400:]}")
    return open(log).read()


def cells(log):
    """Cell counts of the last `stat` in a Yosys log."""
    part = log[log.rfind("Number of cells:"):]
    out = {}
    for m in re.finditer(r"^\s+(\$?[A-Za-z_][\w$]*)\s+(\d+)\s*$", part, re.M):
        out[m.group(1)] = out.get(m.group(1), 0) + int(m.group(2))
    return out


def luts_of(c):
    return sum(v for k, v in c.items() if re.fullmatch(r"LUT\d", k))


def ffs_of(c):
    return sum(v for k, v in c.items() if re.fullmatch(r"FD[RSCP]E(_1)?", k))


LUTRAM_BITS = {"RAM32M": 64 * 2, "RAM64M": 64 * 3, "RAM32X1D": 32, "RAM64X1D": 64, "RAM128X1D": 128,
               "RAM256X1S": 256, "RAM64X1S": 64, "RAM32X1S": 32, "RAM128X1S": 128}


def top_module(mods):
    """The name of the top module of a Yosys write_json netlist (it carries the parameters)."""
    return next(n for n, v in mods.items() if int(v.get("attributes", {}).get("top", "0"), 2))


def xilinx_flow(top, flatten, extra=""):
    """synth_xilinx without its SAT-based `share` pass, which takes tens of minutes on the
    transformation unit's 9 multiply-add chains and finds nothing to share in these datapaths."""
    f = (" -flatten" if flatten else "") + extra
    return (f"synth_xilinx -top {top}{f} -run :coarse; techmap -map +/cmp2lut.v -map +/cmp2lcu.v -D LUT_WIDTH=6; "
            f"alumacc; opt; memory -nomap; opt_clean; synth_xilinx -top {top}{f} -run map_memory:")


# 7-series cells a register-to-register path passes through: LUTs and LUT RAM reads count one
# level each; carry chains, wide-function muxes, inverters and DSP48E1 slices (registers off)
# count none (dedicated logic, not LUT levels; a DSP48E1's inputs whose way has one of its registers
# end a path, comb_input); everything else (flip-flops, SRLs, block RAM) and the ports end a path.
LEVEL_CELLS = {**{f"LUT{k}": 1 for k in range(1, 7)}, **{k: 1 for k in ("RAM32M", "RAM64M", "RAM32X1D", "RAM64X1D",
               "RAM128X1D", "RAM256X1S", "RAM64X1S", "RAM32X1S", "RAM128X1S")},
               "CARRY4": 0, "MUXF7": 0, "MUXF8": 0, "INV": 0, "DSP48E1": 0}


def comb_input(cell, port):
    """Whether a cell's input port reaches its outputs without a clock edge: a LUT RAM's read
    addresses do (ADDRA..ADDRD, DPRA, A); its write data and enable are written at the edge, so a
    path ends there as at a flip-flop. A DSP48E1's data and control inputs do when none of the
    slice's registers on their way to its outputs is used (dsp_comb); its clock enables and resets
    never (they steer its registers)."""
    ctype = cell["type"]
    if ctype == "DSP48E1":
        return dsp_comb(cell.get("parameters", {}), port)
    return ctype not in LUTRAM_BITS or port.startswith(("ADDR", "DPRA")) or re.fullmatch(r"A\d*", port) is not None


# DSP48E1: the registers between each input and the outputs (the A, B and D registers, the
# pre-adder's, the multiplier's where it is used, the output's); xilinx_dsp packs flip-flops of the
# RTL into them, so a slice with one is a register on those inputs' paths, as a flip-flop would be
DSP_INPUT_REGS = {"A": ("AREG", "MREG", "PREG"), "ACIN": ("AREG", "MREG", "PREG"), "B": ("BREG", "MREG", "PREG"),
                  "BCIN": ("BREG", "MREG", "PREG"), "C": ("CREG", "PREG"), "D": ("DREG", "ADREG", "MREG", "PREG"),
                  "PCIN": ("PREG",), "CARRYCASCIN": ("PREG",), "MULTSIGNIN": ("PREG",),
                  "OPMODE": ("OPMODEREG", "PREG"), "ALUMODE": ("ALUMODEREG", "PREG"),
                  "INMODE": ("INMODEREG", "MREG", "PREG"), "CARRYIN": ("CARRYINREG", "PREG"),
                  "CARRYINSEL": ("CARRYINSELREG", "PREG")}


def dsp_registered(cell):
    """A DSP48E1 with a register on some data input's way: its outputs start paths as a flip-flop's."""
    return cell["type"] == "DSP48E1" and any(
        not dsp_comb(cell.get("parameters", {}), p) for p in DSP_INPUT_REGS if p in cell["connections"])


def dsp_comb(params, port):
    """Whether a DSP48E1 input reaches its outputs without a register (DSP_INPUT_REGS; a parameter
    Yosys leaves out has the cell library's default: every register on, the multiplier used, no
    pre-adder)."""
    def value(k, default):
        v = params.get(k)
        if v is None:
            return default
        v = v.strip() if isinstance(v, str) else v
        return int(v, 2) if isinstance(v, str) and v and set(v) <= {"0", "1"} else v
    mult = value("USE_MULT", "MULTIPLY") != "NONE"
    dport = value("USE_DPORT", "FALSE") == "TRUE"
    regs = DSP_INPUT_REGS.get(port)
    if regs is None:  # CLK, CE*, RST*
        return False
    return not any(value(r, 1) for r in regs if (r != "MREG" or mult) and (r != "ADREG" or dport))


def lut_levels(js):
    """The most LUT levels between two registers (or ports) of the flattened netlist js."""
    return lut_path(js)[0]


def lut_path(js, module=None):
    """lut_levels and its deepest path: the levels and the path's level cells, first to last, each as
    (cell type, the name of a net it drives). With module (of a hierarchical netlist): that module's
    own cells, its submodules' ports ending paths as registers do."""
    mods = json.load(open(js))["modules"]  # the top and the cell library
    mod = mods[module or top_module(mods)]
    driver, cells = {}, mod["cells"]
    for name, c in cells.items():
        for port, bits in c["connections"].items():
            if c.get("port_directions", {}).get(port) == "output":
                for b in bits:
                    driver[b] = name
    depth, prev = {}, {}
    for start in cells:  # longest path by depth-first search with an explicit stack (no recursion limit)
        stack = [start]
        while stack:
            n = stack[-1]
            if n in depth:
                stack.pop()
                continue
            c = cells[n]
            if c["type"] not in LEVEL_CELLS:
                depth[n] = 0
                stack.pop()
                continue
            ins = [driver[b] for p, bits in c["connections"].items()
                   if c.get("port_directions", {}).get(p) == "input" and comb_input(c, p)
                   for b in bits if b in driver]
            todo = [d for d in ins if d not in depth and d != n]
            if todo:
                stack.extend(todo)
                continue
            feed = [(depth[d], d) for d in ins if cells[d]["type"] in LEVEL_CELLS and d != n]
            best = max(feed, default=(0, None))
            depth[n], prev[n] = LEVEL_CELLS[c["type"]] + best[0], best[1]
            stack.pop()
    if not depth:
        return 0, []
    n = max(depth, key=depth.get)
    names = net_names(mod)
    path = []
    while n is not None:
        c = cells[n]
        outs = [b for p, bits in c["connections"].items() if c.get("port_directions", {}).get(p) == "output"
                for b in bits]
        path.append((c["type"], names.get(outs[0], "?") if outs else "?"))
        n = prev.get(n)
    return depth[max(depth, key=depth.get)], path[::-1]


def net_names(mod):
    """Per net bit its name: the shortest user-given one (Yosys's own names start with $)."""
    names = {}
    for net, d in mod.get("netnames", {}).items():
        for b in d["bits"]:
            if isinstance(b, int) and (b not in names or (names[b].startswith("$"), len(names[b])) >
                                       (net.startswith("$"), len(net))):
                names[b] = net
    return names


def module_levels(top, params, flat=True):
    """--levels: one module's LUT6 levels from its registers and ports as the DynRTP's are measured
    (xilinx_flow per module; hier_lut_levels, and flattened after mapping its deepest path), each
    submodule's levels alone and the deepest path of its own cells (submodule ports as path ends)."""
    tag = re.sub(r"[^A-Za-z0-9]+", "_", "_".join([top] + [f"{k}{v}" for k, v in params.items()]))
    reads = " ".join(f"read_verilog -sv {f};" for f in RTL)
    chp = f"chparam {' '.join(f'-set {k} {v}' for k, v in params.items())} {top}; " if params else ""
    log, js = os.path.join(OUT, f"levels_{tag}.log"), os.path.join(OUT, f"levels_{tag}.json")
    hier = js[:-len(".json")] + "_hier.json"
    t0 = time.time()
    tail = f"; flatten; stat; write_json {js}" if flat else "; stat"
    c = cells(yosys(f"{reads} {chp}{xilinx_flow(top, flatten=False)}; write_json {hier}{tail}", log))
    mods = json.load(open(hier))["modules"]
    depth = hier_lut_levels(mods, top_module(mods))
    print(f"{top} {' '.join(f'{k}={v}' for k, v in params.items())}: {depth[top_module(mods)]} LUT6 levels, "
          f"{luts_of(c)} LUT6, {ffs_of(c)} FF ({round(time.time() - t0)} s; {log})")
    if flat:
        levels, path = lut_path(js)
        print(f"  deepest path ({levels}), flattened:")
        for typ, net in path:
            if LEVEL_CELLS.get(typ):
                print(f"    {typ:8} {net}")
    for name, v in sorted(depth.items(), key=lambda x: -x[1]):
        own, path = lut_path(hier, name)
        print(f"  {key_name(name)}: {v} levels with its submodules; its own cells {own}: " +
              " > ".join(f"{t}:{n}" for t, n in path if LEVEL_CELLS.get(t) and not n.startswith("$")))


# iCE40 cell counts of a cell dict (module_cells, hierarchy_totals): logic, flip-flops, block RAM, multipliers
ICE40_COUNTS = {"SB_LUT4": lambda c: c.get("SB_LUT4", 0),
                "SB_DFF*": lambda c: sum(v for k, v in c.items() if k.startswith("SB_DFF")),
                "SB_RAM40_4K": lambda c: c.get("SB_RAM40_4K", 0), "SB_MAC16": lambda c: c.get("SB_MAC16", 0)}


def module_ice40(top, params):
    """--ice40: one module's synth_ice40 -dsp totals as the DynRTP's are measured (module by module,
    module_netlists, its netlists kept in build/synth/ice40_<module and parameters>/) and per part
    (its own cells, each kind of submodule with all instances: parts_of) LUT4, flip-flops, block RAM."""
    tag = re.sub(r"[^A-Za-z0-9]+", "_", "_".join([top] + [f"{k}{v}" for k, v in params.items()]))
    mods, name, cpu = module_netlists("ice40", top, params, os.path.join(OUT, f"ice40_{tag}"))
    own = module_cells(mods)
    sub, tot = hierarchy_totals(own, name)
    counts = ICE40_COUNTS
    print(f"{top} {' '.join(f'{k}={v}' for k, v in params.items())}: " +
          ", ".join(f"{f(tot)} {k}" for k, f in counts.items()) + f" ({sum(cpu.values())} s of Yosys CPU)")
    parts = {k: parts_of(own, sub, name, f) for k, f in counts.items()}
    for part in sorted(parts["SB_LUT4"], key=lambda p: -parts["SB_LUT4"][p]):
        print(f"  {part}: " + ", ".join(f"{parts[k][part]} {k}" for k in counts))
    for mem, (n, blocks, bits) in sorted(bram_memories(mods, name).items(), key=lambda kv: -kv[1][1]):
        print(f"  block RAM {mem}: {n} memories, {blocks} SB_RAM40_4K, {bits} bits stored")


def xilinx(top, e, m, edge_eps=0, terms=0):
    log = os.path.join(OUT, f"{top}_e{e}m{m}{f'_edge{edge_eps}' if edge_eps else ''}{f'_n{terms}' if terms else ''}_xilinx.log")
    reads = " ".join(f"read_verilog -sv {f};" for f in RTL)
    flow = xilinx_flow(top, flatten=True)
    extra = (f" -set EDGE_EPS {edge_eps}" if edge_eps else "") + (f" -set N {terms}" if terms else "")
    js = log[:-len(".log")] + ".json"
    c = cells(yosys(f"{reads} chparam -set E {e} -set M {m}{extra} {top}; {flow}; stat; write_json {js}", log))
    srl = sum(v for k, v in c.items() if k.startswith("SRL"))
    return {"luts": luts_of(c), "srl": srl, "ffs": ffs_of(c), "dsp": c.get("DSP48E1", 0),
            "bram": c.get("RAMB18E1", 0) + 2 * c.get("RAMB36E1", 0), "carry4": c.get("CARRY4", 0),
            "lut6_levels": lut_levels(js)}


# For a clock-to-clock Fmax the operator gets input registers: the path from them through the
# combinational core to its first pipeline register is the one a clock constrains.
TIMING_WRAPPER = """module time_{top} (input logic clk_i, input logic [{w}:0] a_i, input logic [{w}:0] b_i,
                   output logic [{ow}:0] res_o);
  logic [{w}:0] a_q, b_q;
  always_ff @(posedge clk_i) begin a_q <= a_i; b_q <= b_i; end
  {inst}
endmodule
"""
TIMING_INST = {
    "f24_add": "f24_add #(.E({e}), .M({m})) u (.clk_i(clk_i), .rst_ni(1'b1), .en_i(1'b1), .valid_i(1'b1), .a_i(a_q), "
               ".b_i(b_q), .sub_i(1'b0), .valid_o(), .res_o(res_o));",
    "f24_mul": "f24_mul #(.E({e}), .M({m})) u (.clk_i(clk_i), .rst_ni(1'b1), .en_i(1'b1), .valid_i(1'b1), .a_i(a_q), "
               ".b_i(b_q), .valid_o(), .res_o(res_o));",
    "f24_div": "f24_div #(.E({e}), .M({m})) u (.clk_i(clk_i), .rst_ni(1'b1), .en_i(1'b1), .valid_i(1'b1), .a_i(a_q), "
               ".b_i(b_q), .valid_o(), .res_o(res_o));",
    "f24_cmp": "f24_cmp #(.E({e}), .M({m})) u (.clk_i(clk_i), .rst_ni(1'b1), .en_i(1'b1), .valid_i(1'b1), .a_i(a_q), "
               ".b_i(b_q), .valid_o(), .flags_o(), .min_o(res_o), .max_o());",
    # one term (with N >= 2 the exact dot product does not fit an HX8K); hi ^ lo keeps both words' logic
    "f24_sum_exact": "logic [{e}+{m}:0] hi, lo; f24_sum_exact #(.E({e}), .M({m}), .N(1)) u (.clk_i(clk_i), .rst_ni(1'b1), "
                     ".en_i(1'b1), .valid_i(1'b1), .a_i(a_q), .b_i(b_q), .valid_o(), .hi_o(hi), .lo_o(lo)); "
                     "assign res_o = hi ^ lo;",
    # unary: b_q drives nothing and is removed
    "f24_sqrt": "f24_sqrt #(.E({e}), .M({m})) u (.clk_i(clk_i), .rst_ni(1'b1), .en_i(1'b1), .valid_i(1'b1), .a_i(a_q), "
                ".valid_o(), .res_o(res_o));",
    "f24_to_i32": "f24_to_i32 #(.E({e}), .M({m})) u (.clk_i(clk_i), .rst_ni(1'b1), .en_i(1'b1), .valid_i(1'b1), "
                  ".a_i(a_q), .valid_o(), .res_o(res_o));",
}
TIMING_OUT_BITS = {"f24_to_i32": 32}  # result width where it is not the format's


def ice40(top, e, m):
    log = os.path.join(OUT, f"{top}_e{e}m{m}_ice40.log")
    js = os.path.join(OUT, f"{top}_e{e}m{m}.json")
    wrapper = os.path.join(OUT, f"time_{top}.sv")
    with open(wrapper, "w") as f:
        f.write(TIMING_WRAPPER.format(top=top, w=e + m, ow=TIMING_OUT_BITS.get(top, 1 + e + m) - 1,
                                      inst=TIMING_INST[top].format(e=e, m=m)))
    reads = " ".join(f"read_verilog -sv {f};" for f in RTL + [wrapper])
    c = cells(yosys(f"{reads} synth_ice40 -top time_{top} -json {js}; stat", log))
    lcs = c.get("SB_LUT4", 0)
    inputs = 1 if top in RGS_OPERATORS else 2  # (the wrapper's input registers not counted)
    res = {"lut4": lcs, "ff": sum(v for k, v in c.items() if k.startswith("SB_DFF")) - inputs * (1 + e + m),
           "fmax_mhz": None}
    pnr_log = os.path.join(OUT, f"{top}_e{e}m{m}_nextpnr.log")
    r = subprocess.run(["nextpnr-ice40", "--hx8k", "--package", "ct256", "--json", js, "--timing-allow-fail",
                        "--seed", "1", "--quiet", "-l", pnr_log], capture_output=True, text=True, timeout=900)
    if r.returncode == 0:
        f = re.findall(r"Max frequency for clock[^:]*: ([0-9.]+) MHz", open(pnr_log).read())
        res["fmax_mhz"] = float(f[-1]) if f else None
    else:
        res["pnr"] = "does not fit HX8K" if "Unable to place" in r.stderr + open(pnr_log).read() else "failed"
    return res


# memory interface and list unit: (name, module, parameters, latency)
MB_E7M16 = 4 * ((12 * 24 + 27 + 31) // 32)  # matrix line bytes: one packed triangle record
CONTROL = [
    ("list_unit", "list_unit", {"THREADS": 64}, "2 after its word"),
    ("cache_dm kd nodes 4 KB / 8 B", "cache_dm", {"LINE_BYTES": 8, "SIZE_BYTES": 4096}, "hit 2"),
    ("cache_dm lists 2 KB / 4 B", "cache_dm", {"LINE_BYTES": 4, "SIZE_BYTES": 2048}, "hit 2"),
    (f"cache_dm matrices 6 KB / {MB_E7M16} B", "cache_dm", {"LINE_BYTES": MB_E7M16, "SIZE_BYTES": 6144}, "hit 2"),
    ("cache_dm shading 4 KB / 16 B", "cache_dm", {"LINE_BYTES": 16, "SIZE_BYTES": 4096}, "hit 2"),
    (f"cache_read matrices 6 KB / {MB_E7M16} B, {MB_E7M16 // 4} words", "cache_read",
     {"LINE_BYTES": MB_E7M16, "SIZE_BYTES": 6144, "WORDS": MB_E7M16 // 4, "OUTSTANDING": 16}, "hit 4"),
    ("mem_port 4 requesters", "mem_port", {"N": 4, "DW": 8 * MB_E7M16}, "0"),
    ("thread_sched 64 threads, 5 units", "thread_sched", {"THREADS": 64, "UNITS": 5}, "1"),
    ("tile_ctrl", "tile_ctrl", {}, "1"),
]


def control_key(name):
    return ("c", name, 16)


def control(name, top, params):
    """synth_xilinx and synth_ice40 of a module without floating point: LUTs, FFs, BRAM (and bits)."""
    tag = re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_")
    reads = " ".join(f"read_verilog -sv {f};" for f in RTL)
    chp = " ".join(f"-set {k} {v}" for k, v in params.items())
    js = os.path.join(OUT, f"ctl_{tag}_xilinx.json")
    cx = cells(yosys(f"{reads} chparam {chp} {top}; synth_xilinx -top {top} -flatten; stat; write_json {js}",
                     os.path.join(OUT, f"ctl_{tag}_xilinx.log")))
    ci = cells(yosys(f"{reads} chparam {chp} {top}; synth_ice40 -top {top}; stat",
                     os.path.join(OUT, f"ctl_{tag}_ice40.log")))
    return {"xilinx_luts": luts_of(cx),
            "xilinx_lutram_cells": sum(v for k, v in cx.items() if k in LUTRAM_BITS),
            "xilinx_lutram_bits": sum(v * LUTRAM_BITS[k] for k, v in cx.items() if k in LUTRAM_BITS),
            "xilinx_ffs": ffs_of(cx),
            "xilinx_bram18": cx.get("RAMB18E1", 0) + 2 * cx.get("RAMB36E1", 0), "lut6_levels": lut_levels(js),
            "ice40_lut4": ci.get("SB_LUT4", 0), "ice40_ff": sum(v for k, v in ci.items() if k.startswith("SB_DFF")),
            "ice40_bram": ci.get("SB_RAM40_4K", 0), "ice40_bram_bits": 4096 * ci.get("SB_RAM40_4K", 0)}


# The whole DynRTP at the paper's configuration (issue 23, goal 4): one pipe, 64 threads, caches of
# 4 (kd nodes), 2 (lists) and 6 KB (matrices) and the 4 KB shading cache. Synthesized per module, not
# flattened: each distinct module is mapped once however many instances it has (64 threads, 8 block
# controllers), and Yosys's `stat` sums the hierarchy. The prototype's whole chip (Virtex-II 6000, 56%
# of the logic: about 37,800 LUT4; 78% of the memory) and Table 2's 75 KB of memory stand beside it.
DYNRTP_PARAMS = {"E": 7, "M": 16, "THREADS": 64, "NODE_KB": 4, "LIST_KB": 2, "MAT_KB": 6, "SHADE_KB": 4}
PROTOTYPE_LUT4, TABLE2_BITS = 37800, 75 * 1024 * 8
DYNRTP_JSON = os.path.join(OUT, "dynrtp.json")  # the measured figures, merged into synth.json's "dynrtp"


def blackbox(m):
    return int(m.get("attributes", {}).get("blackbox", "0") or "0", 2) != 0


def module_cells(mods):
    """Per module: its own cells by type (submodule instances by module name); not the cell library."""
    out = {}
    for name, m in mods.items():
        if blackbox(m):
            continue
        c = {}
        for cell in m.get("cells", {}).values():
            c[cell["type"]] = c.get(cell["type"], 0) + 1
        out[name] = c
    return out


def hierarchy_totals(own, top):
    """Per module: the cells of its whole subtree by type (instances expanded), from module_cells."""
    memo = {}

    def total(name):
        if name not in memo:
            t = {}
            for typ, n in own[name].items():
                for k, v in (total(typ).items() if typ in own else [(typ, 1)]):
                    t[k] = t.get(k, 0) + n * v
            memo[name] = t
        return memo[name]
    return {name: total(name) for name in own}, total(top)


def hier_summaries(mods, top):
    """Per module of top's hierarchy: the most LUT levels between two of its registers ("inside"), the
    levels from its registers to each output bit ("reg_out"), from each input bit to each output bit it
    reaches without a register ("through") and from each input bit to a register inside ("in_to_reg"),
    by (port, bit), submodules composed at every instance (LEVEL_CELLS as lut_levels)."""
    summary = {}
    for name in hier_order(mods, top):
        summary[name] = module_summary(mods, name, summary)[0]
    return summary


def hier_order(mods, top):
    """The modules of top's hierarchy, submodules before their parents."""
    order, seen = [], set()

    def visit(name):  # the hierarchy is a DAG of modest depth
        if name in seen:
            return
        seen.add(name)
        for c in mods[name].get("cells", {}).values():
            if c["type"] in mods and not blackbox(mods[c["type"]]):
                visit(c["type"])
        order.append(name)
    visit(top)
    return order


def module_summary(mods, name, summary):
    """hier_summaries of one module, its submodules' summaries given, and what deepest_path walks back
    along: its nets' levels (value: levels from a register, {input bit: levels}), their drivers, where
    its deepest inner path ends ("inside_at") and each input bit's deepest path into a register
    ("in_to_reg_at"): (the net, None for a register's input or the submodule input (cell, port, bit))."""
    mod = mods[name]
    ports = mod.get("ports", {})
    in_bits = {b: (p, i) for p, d in ports.items() if d["direction"] == "input" for i, b in enumerate(d["bits"])}
    cells, driver = mod.get("cells", {}), {}
    for cname, c in cells.items():
        sub = summary.get(c["type"])
        for port, bits in c["connections"].items():
            out = c.get("port_directions", {}).get(port) == "output" if sub is None else \
                mods[c["type"]]["ports"].get(port, {}).get("direction") == "output"
            if out:
                for i, b in enumerate(bits):
                    driver[b] = (cname, port, i)
    memo, worst = {}, [0, None]
    in_to_reg, in_to_reg_at = {}, {}

    def value(bit):
        """(levels from a register, {input bit: levels}) of a net, iteratively."""
        stack = [bit]
        while stack:
            b = stack[-1]
            if b in memo:
                stack.pop()
                continue
            if b in in_bits:
                memo[b] = (NONE, {b: 0})
                stack.pop()
                continue
            if b not in driver:  # a constant or an undriven bit
                memo[b] = (NONE, {})
                stack.pop()
                continue
            c, port, i = cells[driver[b][0]], driver[b][1], driver[b][2]
            sub = summary.get(c["type"])
            if sub is None and c["type"] not in LEVEL_CELLS:  # a register, RAM, buffer: a start
                memo[b] = (0, {})
                stack.pop()
                continue
            need = cell_inputs(c, port, i, sub)
            todo = [x for x, _ in need if x not in memo and isinstance(x, int)]
            if todo:
                stack.extend(todo)
                continue
            step = LEVEL_CELLS[c["type"]] if sub is None else 0
            r = sub["reg_out"].get((port, i), NONE) if sub is not None else 0 if dsp_registered(c) else NONE
            d = {}
            for x, l in need:
                if not isinstance(x, int):
                    continue
                xr, xd = memo[x]
                r = max(r, xr + l + step)
                for k, v in xd.items():
                    if d.get(k, NONE) < v + l + step:
                        d[k] = v + l + step
            memo[b] = (r, d)
            stack.pop()
        return memo[bit]

    def endpoint(bit, extra, at=None):
        """A path ends extra levels after net bit (a register input, or at a submodule's input at)."""
        if not isinstance(bit, int):
            return
        r, d = value(bit)
        if r + extra > worst[0]:
            worst[:] = [r + extra, (bit, at)]
        for k, v in d.items():
            if v + extra > in_to_reg.get(k, -1):
                in_to_reg[k], in_to_reg_at[k] = v + extra, (bit, at)

    for cname, c in cells.items():
        sub = summary.get(c["type"])
        if sub is not None:
            if sub["inside"] > worst[0]:
                worst[:] = [sub["inside"], cname]
            for port, bits in c["connections"].items():
                if mods[c["type"]]["ports"].get(port, {}).get("direction") == "input":
                    for i, b in enumerate(bits):
                        if (port, i) in sub["in_to_reg"]:
                            endpoint(b, sub["in_to_reg"][(port, i)], (cname, port, i))
        else:  # a register's inputs, a LUT RAM's written ones
            for port, bits in c["connections"].items():
                if c.get("port_directions", {}).get(port) == "input" and \
                        (c["type"] not in LEVEL_CELLS or not comb_input(c, port)):
                    for b in bits:
                        endpoint(b, 0)
    reg_out, through = {}, {}
    for p, d in ports.items():
        if d["direction"] == "output":
            for i, b in enumerate(d["bits"]):
                if isinstance(b, int):
                    r, dd = value(b)
                    reg_out[(p, i)] = r
                    through[(p, i)] = {in_bits[k]: v for k, v in dd.items()}
    entry = {"inside": worst[0], "reg_out": reg_out, "through": through,
             "in_to_reg": {in_bits[k]: v for k, v in in_to_reg.items()}}
    return entry, {"value": value, "driver": driver, "cells": cells, "in_bits": in_bits, "names": net_names(mod),
                   "inside_at": worst[1], "in_to_reg_at": in_to_reg_at}


NONE = -1 << 30  # the levels of a path that does not exist


def cell_inputs(c, port, i, sub):
    """The nets a cell's output bit (port, i) is reached from without a register, each with the levels
    it adds beyond the cell's own: a level cell's inputs (comb_input) 0, a submodule's its "through"."""
    if sub is None:
        return [(x, 0) for p, bits in c["connections"].items()
                if c.get("port_directions", {}).get(p) == "input" and comb_input(c, p) for x in bits]
    return [(c["connections"][p][j], l) for (p, j), l in sub["through"].get((port, i), {}).items()]


def hier_lut_levels(mods, top):
    """Per module of top's hierarchy: the most LUT levels between two registers (or its ports) of a
    hierarchical 7-series netlist, paths through module ports included (hier_summaries)."""
    def levels(s):  # the module as a top: its ports end paths too
        return max([s["inside"]] + list(s["reg_out"].values()) + list(s["in_to_reg"].values()) +
                   [v for t in s["through"].values() for v in t.values()])
    return {name: levels(s) for name, s in hier_summaries(mods, top).items()}


def deepest_path(mods, top, summary=None):
    """The deepest path of hier_lut_levels(mods, top)[top] across module ports: its levels and its steps,
    first to last, each (instance path, cell type, the net it drives): the register (or top input) it
    starts from, its level cells, and ("D", net) the register input it ends at (none at a top output).
    summary: hier_summaries of a hierarchy that holds top's, if made already."""
    summary = summary or hier_summaries(mods, top)
    traces = {}

    def trace(name):  # module_summary again for the modules along the path only (its memo is large)
        if name not in traces:
            traces[name] = module_summary(mods, name, summary)[1]
        return traces[name]

    def level(name, bit, src):
        r, d = trace(name)["value"](bit)
        return r if src is None else d.get(src, NONE)

    def back(name, inst, bit, src, v):
        """The steps from src (None: a register; else an input bit) to net bit of module name, v levels."""
        t, steps = trace(name), []
        while bit not in t["in_bits"]:
            cname, port, i = t["driver"][bit]
            c = t["cells"][cname]
            sub = summary.get(c["type"])
            if sub is not None and src is None and sub["reg_out"].get((port, i)) == v:
                return back(c["type"], inst + (cname,), mods[c["type"]]["ports"][port]["bits"][i], None, v) + steps[::-1]
            step = 0 if sub is not None else LEVEL_CELLS.get(c["type"])
            found = step is not None and next(((x, l) for x, l in cell_inputs(c, port, i, sub) if isinstance(x, int)
                                               and level(name, x, src) + l + step == v), None)
            if not found:  # a register, RAM or registered DSP48E1: the start
                steps.append((inst, c["type"], t["names"].get(bit, "?")))
                break
            x, l = found
            if sub is not None:
                sub_in = mods[c["type"]]["ports"]
                p, j = next(k for k, lv in sub["through"][(port, i)].items()
                            if c["connections"][k[0]][k[1]] == x and lv == l)
                steps += back(c["type"], inst + (cname,), sub_in[port]["bits"][i], sub_in[p]["bits"][j], l)[::-1]
            else:
                steps.append((inst, c["type"], t["names"].get(bit, "?")))
            bit, v = x, v - l - step
        return steps[::-1]

    def into(name, inst, at, bit, extra):
        """The steps from net bit on, extra levels, into a register: at None (a register's input) or a
        submodule's input (cell, port, bit), entered there."""
        if at is None:
            return [(inst, "D", trace(name)["names"].get(bit, "?"))]
        cname, port, i = at
        sub = trace(name)["cells"][cname]["type"]
        k = mods[sub]["ports"][port]["bits"][i]
        nxt, sub_at = trace(sub)["in_to_reg_at"][k]
        v = level(sub, nxt, k)
        return back(sub, inst + (cname,), nxt, k, v) + into(sub, inst + (cname,), sub_at, nxt, extra - v)

    def inside(name, inst):
        at = trace(name)["inside_at"]
        if isinstance(at, str):  # a submodule's own
            return inside(mods[name]["cells"][at]["type"], inst + (at,))
        bit, end = at
        r = level(name, bit, None)
        return back(name, inst, bit, None, r) + into(name, inst, end, bit, summary[name]["inside"] - r)

    s = summary[top]
    ports = [(v, "out", p, None) for p, v in s["reg_out"].items()] + [(v, "in", p, None) for p, v in s["in_to_reg"].items()]
    ports += [(v, "through", p, q) for p, t in s["through"].items() for q, v in t.items()]
    v, kind, p, q = max(ports, default=(NONE, None, None, None))
    bits = lambda port: mods[top]["ports"][port[0]]["bits"][port[1]]
    if s["inside"] >= v:
        return s["inside"], inside(top, ())
    if kind == "in":
        nxt, at = trace(top)["in_to_reg_at"][bits(p)]
        return v, back(top, (), nxt, bits(p), level(top, nxt, bits(p))) + into(top, (), at, nxt,
                                                                               v - level(top, nxt, bits(p)))
    return v, back(top, (), bits(p), None if kind == "out" else bits(q), v)


def print_path(mods, top, levels, steps):
    """deepest_path's steps by module instance: the instance path, its module, its levels and named nets."""
    print(f"{key_name(top)}: {levels} LUT6 levels, deepest path:")
    group = []
    for n, step in enumerate(steps):
        group.append(step)
        if n + 1 == len(steps) or steps[n + 1][0] != step[0]:
            inst, typ = step[0], top
            for cname in inst:
                typ = mods[typ]["cells"][cname]["type"]
            own = sum(LEVEL_CELLS.get(t, 0) for _, t, _ in group)
            print(f"  {'/'.join(inst) or '(top)'} ({key_name(typ)}, {own}): " +
                  " > ".join(t if net.startswith("$") else f"{t}:{net}" for _, t, net in group))
            group = []


def port_levels(hier, ports):  # hier: a file name, or the netlist's modules (changed here)
    """--ports: per port of a --levels netlist's top, its most levels from the top's registers, from its
    inputs and into its registers (None: no such path), the top's IBUF/OBUF as wires."""
    mods = json.load(open(hier))["modules"] if isinstance(hier, str) else hier
    top = top_module(mods)
    mod = mods[top]
    bufs = [n for n, c in mod["cells"].items() if c["type"] in ("IBUF", "OBUF")]
    wire = {mod["cells"][n]["connections"]["O"][0]: mod["cells"][n]["connections"]["I"][0] for n in bufs}
    for n in bufs:
        del mod["cells"][n]
    for c in mod["cells"].values():
        c["connections"] = {p: [wire.get(b, b) for b in bits] for p, bits in c["connections"].items()}
    for d in mod["ports"].values():
        d["bits"] = [wire.get(b, b) for b in d["bits"]]
    s = hier_summaries(mods, top)[top]
    most = lambda vals: max(vals, default=None)
    return {port: (most(v for (p, _), v in s["reg_out"].items() if p == port),
                   most(v for (p, _), t in s["through"].items() if p == port for v in t.values()),
                   most(v for (p, _), v in s["in_to_reg"].items() if p == port)) for port in ports}


DYNRTP_DIR = os.path.join(OUT, "dynrtp")  # per module: its mapped netlist, named by the hash of what made it


def elaborate(top, params, folder, files):
    """top with params elaborated (every module derived with its parameters) into one RTLIL file in
    folder: its path, its modules (rtlil_modules) and the top's derived name."""
    os.makedirs(folder, exist_ok=True)
    il = os.path.join(folder, "elab.il")
    reads = " ".join(f"read_verilog -sv {f};" for f in files)
    chp = f"chparam {' '.join(f'-set {k} {v}' for k, v in params.items())} {top};" if params else ""
    # written aside and renamed: another part's run may be reading it (the same text, elaborated alike)
    yosys(f"{reads} {chp} hierarchy -check -top {top}; write_rtlil {il}.tmp", il + ".log")
    os.replace(il + ".tmp", il)
    mods = rtlil_modules(il)
    return il, mods, next(n for n, text in mods.items() if "attribute \\top 1" in text.split("\nmodule ")[0])


def rtlil_modules(path):
    """The modules of a write_rtlil file: name -> its text, its attributes first (a module's `end` is the
    only one at the start of a line)."""
    mods, cur, name = {}, [], None
    for line in open(path):
        if name is None and line.startswith("module "):
            name = line.split()[1]
        if name is not None or line.startswith("attribute "):
            cur.append(line)
        else:
            cur = []
        if name is not None and line == "end\n":
            mods[name], cur, name = "".join(cur), [], None
    return mods


def renumbered(text):
    """A module's RTLIL with Yosys's automatic name numbers ($procmux$1234, ...) counted from 1 in the
    order they appear: the numbers come from one counter over the whole elaboration, so a change in
    one module would otherwise change the text of every module elaborated after it (names such as
    $memwr$...$39627_ADDR included). The sources' folder is left out of the names and attributes that
    hold it, so that a run in another checkout finds the same netlists."""
    seen = {}
    text = text.replace(ROOT + "/", "")
    return re.sub(r"\$(\d+)(?!\d)", lambda g: "$" + str(seen.setdefault(g[1], len(seen) + 1)), text)


def rtlil_children(text):
    """The module types a module's cells instantiate (not Yosys's internal $ cells)."""
    types = (line.split()[1] for line in text.splitlines() if line.startswith("  cell "))
    return {t for t in types if t.startswith("\\") or t.startswith("$paramod")}


def module_flow(part, top):
    """One module mapped on its own, its submodules black boxes, without I/O or clock buffers (it is not
    the chip's top): what the whole hierarchy mapped without flattening does to it."""
    if part == "ice40":  # up to the check label: its autoname renames every object one at a time
        return f"synth_ice40 -dsp -noflatten -top {top} -run :check"
    return xilinx_flow(top, flatten=False, extra=" -noiopad -noclkbuf")


def module_netlists(part, top, params, folder, files=RTL):
    """Every module of top's hierarchy (with params) mapped for part ('xilinx', 'ice40'), each distinct
    module once, SYNTH_JOBS (default: the CPUs) Yosys processes at a time, largest first: the whole
    DynRTP's method. A module's netlist is kept in folder under the hash of its RTLIL, its submodules'
    ports and the flow, so a run stopped midway, or one after an RTL change, maps only what is new.
    Returns the modules (as a hierarchical write_json has them, the top marked), the top's name and per
    module its Yosys CPU seconds."""
    il, texts, top = elaborate(top, params, folder, files)
    used, todo = set(), [top]
    while todo:
        m = todo.pop()
        if m not in used:
            used.add(m)
            todo += [c for c in rtlil_children(texts[m]) if c in texts]

    def ports(m):
        return "".join(l for l in texts[m].splitlines(True) if re.match(r"\s+wire .*\b(input|output|inout) ", l))

    def key(m):
        made_of = [module_flow(part, "TOP"), renumbered(texts[m])] + [ports(c) for c in sorted(rtlil_children(texts[m]))]
        return hashlib.sha1("\0".join(made_of).encode()).hexdigest()[:20]

    def mapped(m):
        path = os.path.join(folder, f"{part}_{key(m)}.json")
        if not os.path.exists(path):
            full, log = path + ".full", path + ".log"
            cpu = yosys(f"read_rtlil {il}; hierarchy -top {m}; blackbox * {m} %d; hierarchy -top {m}; "
                        f"{module_flow(part, m)}; write_json {full}", log)
            cpu = re.search(r"CPU: user ([\d.]+)s system ([\d.]+)s", cpu)
            cpu = round(float(cpu[1]) + float(cpu[2]))
            kept = {"module": m, "cpu_seconds": cpu, "netlist": json.load(open(full))["modules"][json_name(m)]}
            os.remove(full)
            json.dump(kept, open(path + ".tmp", "w"))
            os.replace(path + ".tmp", path)  # only a whole netlist is ever found under its name
            print(f"synth: {part}: {key_name(json_name(m))} mapped, {cpu} s", file=sys.stderr, flush=True)
            return kept
        return json.load(open(path))

    order = sorted(used, key=lambda m: -len(texts[m]))
    with cf.ThreadPoolExecutor(max_workers=int(os.environ.get("SYNTH_JOBS", os.cpu_count() or 1))) as pool:
        done = dict(zip(order, pool.map(mapped, order)))
    mods = {}
    for m, d in done.items():
        mods[json_name(m)] = dict(d["netlist"], attributes=dict(d["netlist"].get("attributes", {}),
                                                                top="1" if m == top else "0"),
                                  memories=rtlil_memories(texts[m]))
    return mods, json_name(top), {json_name(m): d["cpu_seconds"] for m, d in done.items()}


def rtlil_memories(text):
    """A module's memories before mapping: name -> (width, depth)."""
    return {n: (int(w), int(d)) for w, d, n in re.findall(r"^  memory width (\d+) size (\d+) \\(\S+)$", text, re.M)}


def bram_memories(mods, top):
    """The memories mapped to SB_RAM40_4K (its cells named <memory>.<row>.<column>) in top's hierarchy, by
    module kind, memory (its generate blocks' copies together) and shape: "module memory WxD" -> [memories,
    blocks, bits stored (W x D)], all instances: how full the blocks are (a memory of 64 words uses a
    quarter of a 256 x 16 block's rows)."""
    own = module_cells(mods)
    copies = {}

    def walk(m, n):  # instances of each module under top
        copies[m] = copies.get(m, 0) + n
        for typ, k in own[m].items():
            if typ in own:
                walk(typ, n * k)
    walk(top, 1)
    out = {}
    for m, n in copies.items():
        blocks = {}
        for name, c in mods[m].get("cells", {}).items():
            if c["type"] == "SB_RAM40_4K":
                mem = re.sub(r"\.\d+\.\d+$", "", name)
                blocks[mem] = blocks.get(mem, 0) + 1
        for mem, b in blocks.items():
            w, d = mods[m]["memories"][mem]
            acc = out.setdefault(f"{key_name(m)} {mem.split('.')[-1]} {w}x{d}", [0, 0, 0])
            for i, v in enumerate((n, n * b, n * w * d)):
                acc[i] += v
    return out


def json_name(m):
    """A module's name as write_json gives it (a public name without its backslash)."""
    return m[1:] if m.startswith("\\") else m


def dynrtp_xilinx():
    """synth_xilinx of the whole DynRTP, module by module (xilinx_figures)."""
    mods, top, cpu = module_netlists("xilinx", "dynrtp", DYNRTP_PARAMS, DYNRTP_DIR)
    return dict(xilinx_figures(mods, top), xilinx_seconds=sum(cpu.values()))


def xilinx_figures(mods, top):
    """LUT6, flip-flops, DSP48E1, RAM and LUT6 levels of a hierarchical 7-series netlist, and per unit of
    the top (each with its submodules, all instances) its LUT6 and its own LUT6 levels (its ports as
    path ends): which unit dominates, and where the deepest paths are."""
    own = module_cells(mods)
    sub, tot = hierarchy_totals(own, top)
    depth = hier_lut_levels(mods, top)
    units, levels = {}, {}
    for typ, n in own[top].items():
        if typ in own:
            units[key_name(typ)] = units.get(key_name(typ), 0) + n * luts_of(sub[typ])
            levels[key_name(typ)] = max(levels.get(key_name(typ), 0), depth[typ])
    return {"xilinx_lut6": luts_of(tot), "xilinx_ff": ffs_of(tot),
            "xilinx_srl": sum(v for k, v in tot.items() if k.startswith("SRL")), "xilinx_dsp": tot.get("DSP48E1", 0),
            "xilinx_bram18": tot.get("RAMB18E1", 0) + 2 * tot.get("RAMB36E1", 0),
            "xilinx_lutram_bits": sum(v * LUTRAM_BITS[k] for k, v in tot.items() if k in LUTRAM_BITS),
            "max_lut6_levels": depth[top], "xilinx_units_lut6": units, "xilinx_units_lut6_levels": levels}


def dynrtp_path(units):
    """--dynrtp-path: the whole DynRTP's deepest path of LUT6 levels (deepest_path) on the 7-series netlists of
    --dynrtp xilinx (module_netlists: a module whose RTL changed since is mapped again), and each named
    unit's of the top (a module name: every instance's kind) with its ports as path ends."""
    mods, top, _ = module_netlists("xilinx", "dynrtp", DYNRTP_PARAMS, DYNRTP_DIR)
    summary = hier_summaries(mods, top)
    for name in [top] + sorted({c["type"] for c in mods[top]["cells"].values() if key_name(c["type"]) in units}):
        print_path(mods, name, *deepest_path(mods, name, summary))


def key_name(module):
    """'$paramod$...\\rgs_ctrl' or '$paramod\\rr_pick\\N=...' -> 'rgs_ctrl'."""
    return re.sub(r"^\$paramod\$[0-9a-f]+\\|^\$paramod\\|\\.*$", "", module)


def dynrtp_ice40():
    """synth_ice40 -dsp of the whole DynRTP, module by module: LUT4, flip-flops, SB_MAC16, block RAM bits,
    and per unit of the top (with its submodules, all instances) its LUT4."""
    mods, top, cpu = module_netlists("ice40", "dynrtp", DYNRTP_PARAMS, DYNRTP_DIR)
    own = module_cells(mods)
    sub, tot = hierarchy_totals(own, top)
    c = {k: f(tot) for k, f in ICE40_COUNTS.items()}
    lut4 = ICE40_COUNTS["SB_LUT4"]
    mems = bram_memories(mods, top)
    return {"ice40_lut4": c["SB_LUT4"], "ice40_ff": c["SB_DFF*"], "ice40_dsp": c["SB_MAC16"],
            "ice40_bram": c["SB_RAM40_4K"], "bram_bits": 4096 * c["SB_RAM40_4K"],
            "bram_bits_used": sum(v[2] for v in mems.values()), "ice40_bram_memories": mems,
            "ice40_units_lut4": parts_of(own, sub, top, lut4),
            "ice40_unit_parts_lut4": unit_parts(own, sub, top, lut4),
            "ice40_seconds": sum(cpu.values())}


def unit_parts(own, sub, top, count):
    """parts_of each unit of top, the instances of a unit's modules (several parameter sets) summed."""
    out = {}
    for u, n in own[top].items():
        if u in own:
            acc = out.setdefault(key_name(u), {})
            for p, v in parts_of(own, sub, u, count).items():
                acc[p] = acc.get(p, 0) + n * v
    return out


def parts_of(own, sub, module, count):
    """A module's count (count: of a cell dict) by its submodules' kinds, each with its own submodules and
    all instances, and its own cells apart ("(own)"): where a unit's logic is."""
    parts = {"(own)": count({k: v for k, v in own[module].items() if k not in own})}
    for typ, n in own[module].items():
        if typ in own:
            parts[key_name(typ)] = parts.get(key_name(typ), 0) + n * count(sub[typ])
    return parts


def dynrtp(parts):
    """Measure the given parts ('xilinx', 'ice40') and merge them into DYNRTP_JSON and synth.json."""
    for part in parts:
        new = dynrtp_xilinx() if part == "xilinx" else dynrtp_ice40()
        # read after measuring: a run of the other part may have written its figures meanwhile
        res = json.load(open(DYNRTP_JSON)) if os.path.exists(DYNRTP_JSON) else {}
        rtl = subprocess.run(["git", "-C", ROOT, "log", "-1", "--format=%h", "--", "rtl"], capture_output=True, text=True)
        res.update(new, date=time.strftime("%Y-%m-%d", time.gmtime()), rtl_commit=rtl.stdout.strip() or "?")
        json.dump(res, open(DYNRTP_JSON, "w"), indent=1)
        print(f"synth: dynrtp {part}: {res}", file=sys.stderr, flush=True)
    return res


SYNTH_JSON = os.path.join(OUT, "synth.json")


def load_results():
    """build/synth/synth.json as main()'s result dict (the "dynrtp" object apart: DYNRTP_JSON)."""
    return {parse_key(k): v for k, v in json.load(open(SYNTH_JSON)).items() if k != "dynrtp"}


def save_results(res):
    """synth.json: every module's entry, and the whole DynRTP's figures as "dynrtp" where measured."""
    out = {f"{k[0]}:{k[1]}:e7m{k[2]}": v for k, v in res.items()}
    if os.path.exists(DYNRTP_JSON):
        out["dynrtp"] = json.load(open(DYNRTP_JSON))
    json.dump(out, open(SYNTH_JSON, "w"), indent=1)


def parse_key(key):
    """'i:f24_add:e7m16' or 'x:f24_sum_exact:e7m16:n9' -> the key of main()'s result dict."""
    kind, top, fmt = key.split(":", 2)
    m = fmt.split("m", 1)[1]
    return (kind, top, int(m) if m.isdigit() else m)


# the entries measured again by --redo since the last full run, one key a line (named in docs/synth.md)
REDONE = os.path.join(OUT, "redone.txt")


def redone():
    return [k for k in open(REDONE).read().splitlines() if k] if os.path.exists(REDONE) else []


def redo(keys):
    """Measure the given entries again, keep the others from build/synth/synth.json."""
    before = redone()
    with open(REDONE, "w") as f:
        f.write("".join(k + "\n" for k in before + [k for k in keys if k not in before]))

    def measure(key):
        kind, top, m = parse_key(key)
        mm, _, opt = str(m).partition(":")
        if kind == "c":
            return next(control(n, t, p) for n, t, p, _ in CONTROL if n == top)
        if kind == "i":
            return ice40(top, 7, int(mm))
        return xilinx(top, 7, int(mm), int(opt[4:]) if opt.startswith("edge") else 0,
                      int(opt[1:]) if opt.startswith("n") else 0)

    new = {}
    with cf.ThreadPoolExecutor(max_workers=2) as pool:  # two Yosys processes at a time, as a whole run
        for key, r in zip(keys, pool.map(measure, keys)):
            new[parse_key(key)] = r
            print(f"synth: {key}: {r}", file=sys.stderr, flush=True)
    # read again: another --redo may have written its entries meanwhile
    res = load_results()
    res.update(new)
    save_results(res)
    write(res)


def main():
    args = sys.argv[1:]
    if args and (args[0] in ("-h", "--help") or
                 args[0] not in ("--only-control", "--redo", "--dynrtp", "--dynrtp-path", "--levels", "--ports", "--ice40")):
        # a full run takes hours: an unknown argument is an error, never a start
        print(__doc__)
        sys.exit(0 if args[0] in ("-h", "--help") else f"synth.py: unknown argument {args[0]} (see above)")
    if len(args) > 1 and args[0] == "--ports":
        for port, (reg, thr, into) in port_levels(args[1], args[2:]).items():
            print(f"{port}: from registers {reg}, from inputs {thr}, into registers {into}")
        return
    os.makedirs(OUT, exist_ok=True)
    if "--only-control" in sys.argv[1:]:
        if not os.path.exists(SYNTH_JSON):
            sys.exit("synth.py --only-control: no build/synth/synth.json to merge into (run make synth once)")
        res = load_results()
        with cf.ThreadPoolExecutor(max_workers=2) as pool:
            jobs = {control_key(n): pool.submit(control, n, t, p) for n, t, p, _ in CONTROL}
            for k, f in jobs.items():
                res[k] = f.result()
                print(f"synth: {k[1]}: {res[k]}", file=sys.stderr, flush=True)
        save_results(res)
        write(res)
        return
    if len(sys.argv) > 2 and sys.argv[1] == "--levels":
        return module_levels(sys.argv[2], dict(a.split("=", 1) for a in sys.argv[3:] if a != "--hier"),
                             "--hier" not in sys.argv[3:])
    if len(sys.argv) > 1 and sys.argv[1] == "--dynrtp-path":
        return dynrtp_path(sys.argv[2:])
    if len(sys.argv) > 2 and sys.argv[1] == "--ice40":
        return module_ice40(sys.argv[2], dict(a.split("=", 1) for a in sys.argv[3:]))
    if len(sys.argv) > 2 and sys.argv[1] == "--redo":
        return redo(sys.argv[2:])
    if len(sys.argv) > 1 and sys.argv[1] == "--dynrtp":
        parts = sys.argv[2:] or ["xilinx", "ice40"]
        if any(p not in ("xilinx", "ice40") for p in parts):
            sys.exit("synth.py --dynrtp: parts are xilinx and ice40")
        dynrtp(parts)
        if os.path.exists(SYNTH_JSON):
            res = load_results()
            save_results(res)
            write(res)
        else:  # no module figures here: only the DynRTP's section of docs/synth.md (its last) is rewritten
            path = os.path.join(ROOT, "docs", "synth.md")
            doc = open(path).read()
            head = doc.find("\n## The whole DynRTP")
            open(path, "w").write((doc if head < 0 else doc[:head]).rstrip("\n") + "\n" + "\n".join(dynrtp_section()) + "\n")
        return
    if os.path.exists(REDONE):
        os.remove(REDONE)
    jobs = {}
    with cf.ThreadPoolExecutor(max_workers=2) as pool:
        for n, t, p, _ in CONTROL:
            jobs[control_key(n)] = pool.submit(control, n, t, p)
        jobs[("i", "f24_sum_exact", 16)] = pool.submit(ice40, "f24_sum_exact", 7, 16)
        for top in OPERATORS + RGS_OPERATORS + UNITS + ACCURACY_UNITS + PIPE_UNITS:
            jobs[("x", top, 16)] = pool.submit(xilinx, top, 7, 16)
        for top in OPERATORS + RGS_OPERATORS:
            jobs[("i", top, 16)] = pool.submit(ice40, top, 7, 16)
        for m in WIDTHS:
            if m == 16:
                continue
            for top in OPERATORS + RGS_OPERATORS + ["isect_unit"]:
                jobs[("x", top, m)] = pool.submit(xilinx, top, 7, m)
        jobs[("x", "isect_unit", f"16:edge{ROBUST_EDGE_EPS}")] = pool.submit(xilinx, "isect_unit", 7, 16, ROBUST_EDGE_EPS)
        for n in SUM_TERMS:
            jobs[("x", "f24_sum_exact", f"16:n{n}")] = pool.submit(xilinx, "f24_sum_exact", 7, 16, 0, n)
        for m in SUM_WIDTHS:
            if m != 16:
                jobs[("x", "f24_sum_exact", f"{m}:n9")] = pool.submit(xilinx, "f24_sum_exact", 7, m, 0, 9)
        res = {}
        for k, f in jobs.items():
            res[k] = f.result()
            print(f"synth: {k[1]} e7m{k[2]} {'xilinx' if k[0] == 'x' else 'ice40' if k[0] == 'i' else ''}: {res[k]}",
                  file=sys.stderr, flush=True)
    dynrtp(["xilinx", "ice40"])
    save_results(res)
    write(res)


def write(res):
    again = redone()
    md = ["# Synthesis figures (generated by `make synth`, scripts/synth.py; do not edit)", "",
          "Yosys (Debian 0.23) `synth_xilinx -flatten` (7-series cells) and `synth_ice40` + `nextpnr-ice40 --hx8k` "
          "for the operators. Every operator is pipelined inside (PULP FPnew style): its combinational "
          "segments are separated by cuts that get the STAGES pipeline registers evenly (rtl/README.md), so "
          "the iCE40 Fmax, measured with registered inputs and without retiming, is the clock of the pipelined "
          "operator at its default depth. The units chain the pipelined operators and delay the operands that "
          "join later (f24_pipe), which Xilinx maps to SRL shift registers (SRL column), iCE40 to flip-flops.", "",
          "## Pipelined operators on iCE40 HX8K (e7m16), before and after", "",
          "Before: each operator a combinational core followed by its delay line (make synth at commit 0abb082, "
          f"2026-11-24); after: registers inside the operators at the default STAGES (`make synth`, "
          f"{time.strftime('%Y-%m-%d', time.gmtime())}"
          + (f"; re-measured with `python3 scripts/synth.py --redo {' '.join(shlex.quote(k) for k in again)}`" if again else "") + ").", "",
          "| operator | latency before | LUT4 before | FFs before | Fmax MHz before | latency (STAGES) | LUT4 | FFs | Fmax MHz |",
          "|---|---:|---:|---:|---:|---:|---:|---:|---:|"] + [
          f"| {t}{' (N = 1)' if t == 'f24_sum_exact' else ''} | "
          + (f"{BEFORE[t][0]} | {BEFORE[t][1]} | {BEFORE[t][2]} | {BEFORE[t][3]:.1f}" if t in BEFORE else "- | - | - | -")
          + f" | {LATENCY[t]} | "
          f"{res[('i', t, 16)]['lut4']} | {res[('i', t, 16)]['ff']} | "
          f"{res[('i', t, 16)]['fmax_mhz'] if res[('i', t, 16)].get('fmax_mhz') else res[('i', t, 16)].get('pnr', '-')} |"
          for t in OPERATORS + ["f24_sum_exact"] + RGS_OPERATORS] + ["",
          "f24_sum_exact with one term (N = 1: its whole datapath but the carry-save adder of the terms; "
          "with N >= 2 it does not fit the HX8K's 7680 logic cells). f24_sqrt and f24_to_i32 (the RGS's "
          "shading) were pipelined from the start: no before. The units' latencies follow from the "
          "operators' (rtl/README.md): xform_unit MUL + 3 ADD, isect_unit DIV + MUL + 2 ADD + CMP, trav_node "
          "ADD + DIV + 2 CMP.", "",
          "## Modules at e7m16 (the paper's 24-bit format)", "",
          "| module | latency | LUTs | SRL (pipeline shift registers) | FFs | DSP48E1 | BRAM | CARRY4 | LUT6 levels | iCE40 LUT4 | iCE40 FFs | iCE40 Fmax MHz |",
          "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for top in OPERATORS + RGS_OPERATORS + UNITS + [u for u in PIPE_UNITS if ("x", u, 16) in res]:
        x = res[("x", top, 16)]
        i = res.get(("i", top, 16))
        fmax = "-" if not i else (f"{i['fmax_mhz']:.1f}" if i.get("fmax_mhz") else i.get("pnr", "-"))
        md.append(f"| {top} | {LATENCY[top]} | {x['luts']} | {x['srl']} | {x['ffs']} | {x['dsp']} | {x['bram']} | "
                  f"{x['carry4']} | {x.get('lut6_levels', '-')} | {i['lut4'] if i else '-'} | {i['ff'] if i else '-'} | {fmax} |")
    tot = {k: sum(res[("x", u, 16)][k] for u in UNITS) for k in ("luts", "srl", "ffs", "dsp")}
    ops = [sum(FP_UNITS[u][j] for u in UNITS) for j in range(4)]
    md += ["", "LUT6 levels: the most LUTs on a path between two registers (or ports) of the flattened "
           "7-series netlist (`lut_levels` in scripts/synth.py over Yosys's `write_json`): LUTs and LUT RAM "
           "reads count one level, carry chains, MUXF7/F8 and DSP48E1 slices none. Issue 23 asks for at most "
           "8 between any two registers of the whole DynRTP.",
           "", "## One DynRTP's floating-point datapaths", "",
           f"One transformation unit + one intersection unit + one traversal node decision (4 rays): "
           f"**{tot['luts']} LUTs (+ {tot['srl']} SRL shift registers for the pipeline), {tot['ffs']} FFs, {tot['dsp']} DSP48E1** (7-series). fp24 operators: "
           f"{ops[0]} add/sub, {ops[1]} mul, {ops[2]} div, {ops[3]} comparisons; the paper's Table 2 for one pipeline: "
           "16 add, 11 mul, 5 div, 13 cmp (our traversal decision counts min/max and both interval tests of 4 rays "
           "as 16 comparisons).", "",
           "Not included (the list unit and the caches: their own section below): the list unit (no floating point), the traversal stack and thread state (Table 2: 44.5 KB), "
           "the caches (Table 2: 15.6 KB for kd nodes, lists and matrices; the cycle model adds a 4 KB shading cache, "
           "so its cache data is 4 + 2 + 6 + 4 = 16 KB per pipe), the RGS/shader and the control. The prototype's whole pipeline with 64 threads "
           "used 56% of a Virtex-II 6000's logic (about 37,800 of its 67,584 LUT4s) and 78% of its memory. "
           f"In LUT4 terms (iCE40 mapping of the operators x their counts) our datapaths need about "
           f"{ops[0] * res[('i', 'f24_add', 16)]['lut4'] + ops[1] * res[('i', 'f24_mul', 16)]['lut4'] + ops[2] * res[('i', 'f24_div', 16)]['lut4'] + ops[3] * res[('i', 'f24_cmp', 16)]['lut4']} "
           "LUT4s without DSP blocks (the multipliers in logic), i.e. the floating-point datapaths alone would "
           "take a large part of that budget if built fully unrolled with II = 1 dividers; the prototype's "
           "dividers and 4-ray traversal were evidently shared more tightly.", "",
           "## Across mantissa widths (E = 7, synth_xilinx)", "",
           "| M | " + " | ".join(f"{t} LUTs / DSP" for t in OPERATORS + RGS_OPERATORS + ["isect_unit"]) + " |",
           "|---:|" + "---:|" * (len(OPERATORS + RGS_OPERATORS) + 1)]
    for m in WIDTHS:
        row = [f"{res[('x', t, m)]['luts']} / {res[('x', t, m)]['dsp']}" for t in OPERATORS + RGS_OPERATORS + ["isect_unit"]]
        md.append(f"| {m} | " + " | ".join(row) + " |")
    exact, robust = res[("x", "isect_unit", 16)], res[("x", "isect_unit", f"16:edge{ROBUST_EDGE_EPS}")]
    md += ["", "## Robust edge option (docs/stress.md)", "",
           f"isect_unit at e7m16 with EDGE_EPS = {ROBUST_EDGE_EPS} (u, v >= -2^-{ROBUST_EDGE_EPS}, u + v <= 1 + 2^-{ROBUST_EDGE_EPS}): "
           f"{robust['luts']} LUTs / {robust['dsp']} DSP against {exact['luts']} / {exact['dsp']} for the exact bounds "
           f"({robust['luts'] - exact['luts']:+d} LUTs); the latency and issue rate are unchanged."]
    md += control_section(res)
    md += accuracy_section(res)
    md += dynrtp_section()
    open(os.path.join(ROOT, "docs", "synth.md"), "w").write("\n".join(md) + "\n")
    print("\n".join(md))


def control_section(res):
    """The list unit, the caches and the memory port (no floating point)."""
    md = ["", "## List unit and memory interface (no floating point)", "",
          "rtl/list_unit.sv at the paper's 64 threads (the mailboxes of 64 threads x 2 levels x 4 rays x 8 "
          "entries: 131,072 key bits + the round-robin pointers), rtl/cache_dm.sv as the four caches of the cycle "
          "model's defaults (16 outstanding requests each) and rtl/mem_port.sv with those four requesters. "
          "Xilinx: `synth_xilinx -flatten` (LUT RAM counted apart from the LUTs, block RAM in RAMB18 units); iCE40: "
          "`synth_ice40` (SB_RAM40_4K blocks of 4 Kbit). Memories that Yosys does not map to block RAM (the list "
          "unit's 36 small memories, the caches' request tables) become LUT RAM or flip-flops.", "",
          "| module | latency | LUTs | LUT RAM (bits) | FFs | RAMB18 | LUT6 levels | iCE40 LUT4 | iCE40 FFs | iCE40 BRAM (bits) |",
          "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for name, _, _, lat in CONTROL:
        r = res.get(control_key(name))
        if not r:
            continue
        md.append(f"| {name} | {lat} | {r['xilinx_luts']} | {r['xilinx_lutram_cells']} ({r['xilinx_lutram_bits']}) | "
                  f"{r['xilinx_ffs']} | {r['xilinx_bram18']} | {r.get('lut6_levels', '-')} | {r['ice40_lut4']} | {r['ice40_ff']} | "
                  f"{r['ice40_bram']} ({r['ice40_bram_bits']}) |")
    tot = {k: sum(res[control_key(n)][k] for n, t, _, _ in CONTROL
                  if control_key(n) in res and t in ("cache_dm", "mem_port"))
           for k in ("xilinx_luts", "xilinx_ffs", "xilinx_bram18", "ice40_lut4")}
    md += ["", f"The four caches and the port together: {tot['xilinx_luts']} LUTs, {tot['xilinx_ffs']} FFs, "
           f"{tot['xilinx_bram18']} RAMB18 (7-series), {tot['ice40_lut4']} iCE40 LUT4s. Most of it is the caches' "
           "request tables, which hold a whole line per outstanding request (16 x 320 bits in the matrix cache) so "
           "that hits can pass misses and a line refilled meanwhile cannot change an answer. The matrix cache's read "
           "port (cache_read, not in the sums) finds a read's line, its index modulo 153 and its offset in the "
           "40-byte line without a divider, in a stage of its own (hit latency 4 with its ring): per-chunk tables of "
           "constants, three adder trees, the remainders' carry and one reduction by comparisons. A "
           "table without the data (answers read from the data array, a conflicting fill held back while an answer "
           "waits) would take a fraction of this; the list unit's mailboxes are block RAM as intended (one RAMB18 "
           "per ray and slot; iCE40: 68 of 4 Kbit, more than an HX8K's 32)."]
    return md


def accuracy_section(res):
    """The exact dot product and the area of the accuracy datapath (docs/numerics.md)."""
    add, mul = res[("x", "f24_add", 16)], res[("x", "f24_mul", 16)]
    md = ["", "## Accuracy datapath (docs/numerics.md)", "",
          "The exact dot product `f24_sum_exact` (rtl/f24_sum_exact.sv: N exact products, a 128-bit window, a "
          "double-word result; its N multipliers included), at e7m16 by term count and with 9 terms across widths:", "",
          "| module | LUTs | DSP48E1 | CARRY4 |", "|---|---:|---:|---:|"]
    for n in SUM_TERMS:
        x = res[("x", "f24_sum_exact", f"16:n{n}")]
        md.append(f"| f24_sum_exact, e7m16, {n} terms | {x['luts']} | {x['dsp']} | {x['carry4']} |")
    for m in SUM_WIDTHS:
        if m != 16:
            x = res[("x", "f24_sum_exact", f"{m}:n9")]
            md.append(f"| f24_sum_exact, e7m{m}, 9 terms | {x['luts']} | {x['dsp']} | {x['carry4']} |")
    md += ["", "The units built from it (synth_xilinx at e7m16; valid/ready, one ray per cycle; co-simulated by "
           "rtl/tb/tb_wide.cpp): xform_wide, the transformation unit's wide mode (3 x 8 terms, all 24 products "
           "in one pass), and rebase_unit (3 x 4 terms, te beside):", "",
           "| module | latency | LUTs | SRL | FFs | DSP48E1 | CARRY4 | LUT6 levels |", "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for top in ACCURACY_UNITS:
        x = res.get(("x", top, 16))
        if x:
            md.append(f"| {top} | {LATENCY[top]} | {x['luts']} | {x['srl']} | {x['ffs']} | {x['dsp']} | {x['carry4']} | "
                      f"{x.get('lut6_levels', '-')} |")
    md += ["", "The whole fix at e7m16: the units above as measured, the intersection unit's origin path (its RTL "
           "is part of isect_rebased, with the test and the triangle's transformations) composed from the exact sum and the operators above (an exact sum's own multipliers counted):", "",
           "| unit | exact sums | extra add / mul | LUTs | DSP48E1 |", "|---|---|---:|---:|---:|"]
    total_l = total_d = 0
    for unit, (sums, adds, muls, top) in FIX.items():
        if ("x", top, 16) in res:
            luts, dsp, how = res[("x", top, 16)]["luts"], res[("x", top, 16)]["dsp"], f" ({top}, measured)"
        else:
            luts = sum(k * res[("x", "f24_sum_exact", f"16:n{n}")]["luts"] for n, k in sums.items()) + adds * add["luts"] + muls * mul["luts"]
            dsp = sum(k * res[("x", "f24_sum_exact", f"16:n{n}")]["dsp"] for n, k in sums.items()) + adds * add["dsp"] + muls * mul["dsp"]
            how = " (composed)"
        total_l, total_d = total_l + luts, total_d + dsp
        md.append(f"| {unit}{how} | " + ", ".join(f"{k} x {n} terms" for n, k in sums.items()) +
                  f" | {adds} / {muls} | {luts} | {dsp} |")
    base = sum(res[("x", u, 16)]["luts"] for u in UNITS)
    md.append(f"| **total** | | | **{total_l}** | **{total_d}** |")
    md += ["", f"Against the three datapaths above ({base} LUTs) the fix adds {100 * total_l / max(1, base):.0f}% of their "
           "LUTs; the intersection unit's test itself gains one adder (t = te + t', in rtl/isect_unit.sv)."]
    return md


# The RGS's structure since the whole run above (its per-module figures in rtl/README.md)
def dynrtp_section():
    """The whole DynRTP at the paper's configuration beside the prototype (issue 23, goal 4)."""
    if not os.path.exists(DYNRTP_JSON):
        return []
    d = json.load(open(DYNRTP_JSON))
    cfg = ", ".join(f"{k} = {v}" for k, v in DYNRTP_PARAMS.items())
    get = lambda k: f"{d[k]:,}" if k in d else "not measured"
    md = ["", "## The whole DynRTP beside the prototype (issue 23, goal 4)", "",
          f"rtl/dynrtp.sv at the paper's configuration ({cfg}; RGS_BLOCKS and the rest at their defaults), "
          "synthesized per module without flattening (`python3 scripts/synth.py --dynrtp`, part of `make synth` "
          f"and `make check-full`; {d.get('date', '?')}, rtl/ as of commit {d.get('rtl_commit', '?')}): each distinct "
          "module mapped once by a Yosys run of its own, its submodules black boxes, and counted once per instance ("
          + ", ".join(f"{n} {d[k]:,} CPU s" for n, k in (("7-series", "xilinx_seconds"), ("iCE40", "ice40_seconds"))
                      if k in d) + ").", "",
          "| | this DynRTP | the prototype (one pipe, 64 threads, whole chip) |", "|---|---:|---:|",
          f"| iCE40 LUT4 (`synth_ice40 -dsp`) | {get('ice40_lut4')} | about {PROTOTYPE_LUT4:,} (56% of a Virtex-II 6000) |",
          f"| iCE40 flip-flops | {get('ice40_ff')} | - |",
          f"| iCE40 multiplier blocks (SB_MAC16) | {get('ice40_dsp')} | - |",
          f"| block RAM bits (iCE40 SB_RAM40_4K x 4096) | {get('bram_bits')} | {TABLE2_BITS:,} (Table 2: 75 KB) |",
          f"| of them stored (the memories' width x depth) | {get('bram_bits_used')} | - |",
          f"| 7-series LUT6 (`synth_xilinx`) | {get('xilinx_lut6')} | - |",
          f"| 7-series flip-flops / SRL | {get('xilinx_ff')} / {get('xilinx_srl')} | - |",
          f"| 7-series DSP48E1 | {get('xilinx_dsp')} | - |",
          f"| 7-series RAMB18 (RAMB36 as 2) / LUT RAM bits | {get('xilinx_bram18')} / {get('xilinx_lutram_bits')} | - |",
          f"| most LUT6 levels between two registers | {get('max_lut6_levels')} | goal: at most 8 |"]
    mems = sorted(d.get("ice40_bram_memories", {}).items(), key=lambda kv: -kv[1][1])
    if mems:
        md += ["", "The iCE40's block RAM by memory (all copies; a block is 256 x 16 bits or narrower and deeper, "
               "one read and one write port):", "", "| module memory width x depth | memories | SB_RAM40_4K | bits stored "
               "(of the blocks') |", "|---|---:|---:|---:|"]
        md += [f"| {k} | {n:,} | {b:,} | {v:,} ({100 * v / (4096 * b):.0f}%) |" for k, (n, b, v) in mems]
    lut6, lut4 = d.get("xilinx_units_lut6", {}), d.get("ice40_units_lut4", {})
    units = sorted(set(lut6) | set(lut4), key=lambda u: -lut4.get(u, lut6.get(u, 0)))
    if units:
        share = lambda v, whole: f"{v:,} ({100 * v / max(1, whole):.1f}%)" if v is not None else "-"
        lv = d.get("xilinx_units_lut6_levels", {})
        md += ["", "Where the logic is (the top's units, each with its submodules, all instances), and each unit's "
               "most LUT6 levels on its own (its ports as path ends):", "",
               "| unit | iCE40 LUT4 (share) | 7-series LUT6 (share) | LUT6 levels |", "|---|---:|---:|---:|"]
        md += [f"| {u} | {share(lut4.get(u), d.get('ice40_lut4', 0))} | {share(lut6.get(u), d.get('xilinx_lut6', 0))} "
               f"| {lv.get(u, '-')} |" for u in units]
        parts = d.get("ice40_unit_parts_lut4", {})
        for u in [u for u in units[:2] if u in parts]:
            whole = max(1, sum(parts[u].values()))
            md += ["", f"Inside {u} (iCE40 LUT4 by part, all instances; (own): its own cells): "
                   + ", ".join(f"{p} {v:,} ({100 * v / whole:.1f}%)" for p, v in
                               sorted(parts[u].items(), key=lambda kv: -kv[1]) if v) + "."]
        md += ["", f"{units[0]} dominates. LUT6 levels: `hier_lut_levels` composes, per module, the levels "
               "from its registers to each output bit, from each input bit to the output bits it reaches without a "
               "register, and from each input bit to a register inside; on a small hierarchy it gives the count of "
               "`lut_levels` on the same netlist flattened after mapping. `python3 scripts/synth.py --dynrtp-path "
               "[UNIT ...]` names the deepest path (the module instances along it, their levels and cells); "
               "rtl/README.md (\"The deepest paths named\") has the paths of this run and what was fixed."]
    return md


if __name__ == "__main__":
    main()
