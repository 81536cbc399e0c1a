#!/usr/bin/env python3
"""make hls-check: proves that hls/ is in the C subset HLS tools accept, by compiling it alone.

Compiles every source of hls/fp24, hls/units and hls/top (or --src files) with GCC as a
freestanding program (no libc headers beyond <stdint.h>, -fno-builtin, general registers only)
and fails with one line per violation if
  * an object needs a symbol hls/ does not define (libc, libm, malloc, memcpy, ...): the objects
    are linked into one relocatable object and `nm -u` must print nothing;
  * the call graph has a cycle (recursion) or an indirect call (GCC -fcallgraph-info);
  * a float or double type appears (DWARF base types, and -mgeneral-regs-only rejects floating
    point code) or a variable-length array (-Werror=vla);
  * a loop has no static bound: GCC's loop analysis (-fdump-tree-loopinit-details lists the
    loops, -fdump-tree-ivcanon-details their proven iteration bounds) must prove at most
    MAX_TRIP iterations for every loop that survives to that pass (loops unrolled earlier have
    constant trip counts).
With --config NAME it compiles with -include hls/config_NAME.h (a reduced design written by
`saarcor profile SCENE -o hls/config_NAME.h`) and reports which functions the configuration
removed. Exit status: 0 clean, 1 violations, 2 usage or tool errors.
"""
import argparse
import concurrent.futures
import glob
import os
import re
import subprocess
import sys

MAX_TRIP = 1 << 30
CFLAGS = ["-std=c11", "-O2", "-g", "-ffreestanding", "-fno-builtin", "-mgeneral-regs-only", "-Werror=vla",
          "-Wall", "-Wextra", "-Werror", "-Wno-unknown-pragmas", "-Wno-unused-label",
          "-fdump-tree-loopinit-details-lineno", "-fdump-tree-ivcanon-details"]
# the call graph is taken before optimization, which could turn recursion into loops
CG_FLAGS = ["-std=c11", "-O0", "-ffreestanding", "-fno-builtin", "-w", "-fcallgraph-info"]
INCLUDES = ["-Ihls", "-Ihls/fp24", "-Ihls/units", "-Ihls/top"]


def default_sources():
    return sorted(glob.glob("hls/fp24/*.c") + glob.glob("hls/units/*.c") + glob.glob("hls/top/*.c"))


def compile_one(src, out, cg, config, extra_flags):
    """Compiles src for its call graph and with the dumps; its object, or None and the error."""
    stem = os.path.splitext(os.path.basename(src))[0]
    obj = os.path.join(out, stem + ".o")
    pre = ["-include", config] if config else []
    subprocess.run(["gcc"] + pre + CG_FLAGS + extra_flags + INCLUDES +
                   ["-dumpdir", cg + "/", "-c", src, "-o", os.path.join(cg, stem + ".o")], capture_output=True)
    cmd = ["gcc"] + pre + CFLAGS + extra_flags + INCLUDES + ["-dumpdir", out + "/", "-c", src, "-o", obj]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode == 0:
        return obj, None
    first = next((l for l in r.stderr.splitlines() if "error" in l), r.stderr.strip()[:200])
    return None, f"{src}: does not compile as freestanding integer C: {first.strip()}"


def compile_all(srcs, out, config, extra_flags):
    cg = os.path.join(out, "callgraph")
    os.makedirs(cg, exist_ok=True)
    # the compilers run on every core, the results kept in the sources' order
    with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 1) as pool:
        done = list(pool.map(lambda src: compile_one(src, out, cg, config, extra_flags), srcs))
    return [o for o, _ in done if o], [e for _, e in done if e]


def undefined_symbols(objs, out):
    combined = os.path.join(out, "hls_all.o")
    subprocess.run(["ld", "-r", "-o", combined] + objs, check=True)
    r = subprocess.run(["nm", "-u", combined], capture_output=True, text=True, check=True)
    syms = [l.split()[-1] for l in r.stdout.splitlines() if l.strip()]
    return [f"undefined external symbol {s} (hls/ may not call libc, libm or the host)" for s in syms], combined


def float_types(combined):
    r = subprocess.run(["readelf", "--debug-dump=info", combined], capture_output=True, text=True, check=True)
    names = set()
    lines = r.stdout.splitlines()
    for i, line in enumerate(lines):
        if "DW_ATE_float" in line or "DW_ATE_complex_float" in line:
            for back in lines[max(0, i - 4):i]:
                m = re.search(r"DW_AT_name\s*:\s*(?:\(indirect string, offset: 0x[0-9a-f]+\):\s*)?(.+)$", back)
                if m:
                    names.add(m.group(1).strip())
    return [f"floating-point type '{n}' in the debug information" for n in sorted(names)]


def call_graph(out):
    edges, errors = {}, []
    for ci in glob.glob(os.path.join(out, "callgraph", "*.ci")):
        text = open(ci).read()
        for node in re.findall(r'node: \{ title: "([^"]+)"', text):
            edges.setdefault(node, set())
        for src, dst in re.findall(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"', text):
            if dst == "__indirect_call":
                errors.append(f"indirect call (function pointer) in {src}")
            edges.setdefault(src, set()).add(dst)
    # cycles: depth-first search with colours, iteratively (no recursion limit issues)
    colour, cycles = {}, []
    for root in sorted(edges):
        if colour.get(root):
            continue
        stack = [(root, iter(sorted(edges.get(root, ()))))]
        path = [root]
        colour[root] = 1
        while stack:
            node, it = stack[-1]
            nxt = next(it, None)
            if nxt is None:
                colour[node] = 2
                stack.pop()
                path.pop()
                continue
            if colour.get(nxt) == 1:
                cycles.append(path[path.index(nxt):] + [nxt])
            elif not colour.get(nxt):
                colour[nxt] = 1
                stack.append((nxt, iter(sorted(edges.get(nxt, ())))))
                path.append(nxt)
    errors += ["call graph cycle (recursion): " + " -> ".join(c) for c in cycles]
    functions = set(edges) | {d for ds in edges.values() for d in ds}
    return errors, functions


FP_OPS = {"add": ("f24_add", "f24_sub"), "mul": ("f24_mul",), "div": ("f24_div",), "sqrt": ("f24_sqrt",),
          "cmp": ("f24_lt", "f24_le", "f24_eq", "f24_min", "f24_max")}


# the working and packet values' operations (hls/fp24/f24.h): one operator per working-value
# site, one per lane per packet-value site; their own bodies (the wrappers) are no sites
FP_LANES = {"f24_": 1, "f24w_": 1, "f24q_": 4}


def fp_op(name):
    """(operator class, operators per site) of a callee, or None."""
    name = name.rpartition(":")[2]
    for prefix, n in FP_LANES.items():
        if name.startswith(prefix):
            for k, names in FP_OPS.items():
                if "f24_" + name[len(prefix):] in names:
                    return k, n
    return None


def fp_call_sites(out):
    """fp24 operator call sites in hls/units and hls/top: an upper bound of the operator instances
    an HLS tool allocates before it shares them."""
    sites = {k: 0 for k in FP_OPS}
    for ci in glob.glob(os.path.join(out, "callgraph", "*.ci")):
        for src, dst in re.findall(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"', open(ci).read()):
            op = fp_op(dst)
            if "fp24/" in src or op is None or fp_op(src) is not None:
                continue
            sites[op[0]] += op[1]
    return sites


def state_bytes(config, out):
    """Bytes of one thread's state (rgs_block: ray tree, packet, core state) in this configuration."""
    src = os.path.join(out, "state_size.c")
    with open(src, "w") as f:
        f.write('#include <stdio.h>\n#include "rgs.h"\nint main(void) { printf("%zu %zu\\n", '
                "sizeof(rgs_block), sizeof(trace_state)); return 0; }\n")
    exe = os.path.join(out, "state_size")
    pre = ["-include", config] if config else []
    r = subprocess.run(["gcc"] + pre + INCLUDES + [src, "-o", exe], capture_output=True, text=True)
    if r.returncode != 0:
        return 0, 0
    a, b = subprocess.run([exe], capture_output=True, text=True).stdout.split()
    return int(a), int(b)


def functions_of(text):
    """Splits a GCC tree dump into {function: section}."""
    parts = re.split(r"^;; Function ", text, flags=re.M)[1:]
    return {p.split()[0]: p for p in parts}


def loop_bounds(out):
    errors, loops = [], 0
    for init in sorted(glob.glob(os.path.join(out, "*.loopinit"))):
        iv_path = glob.glob(init.rsplit(".", 2)[0] + ".*.ivcanon")
        iv = functions_of(open(iv_path[0]).read()) if iv_path else {}
        src = os.path.basename(init).split(".c.")[0] + ".c"
        for fn, sec in functions_of(open(init).read()).items():
            found = sorted({int(n) for n in re.findall(r"^;; Loop (\d+)$", sec, re.M)} - {0})
            bounds = {int(n): int(b) for n, b in
                      re.findall(r"^Loop (\d+) iterates at most (\d+) times", iv.get(fn, ""), re.M)}
            for n in found:
                loops += 1
                header = re.search(rf"^;; Loop {n}\n;;  header (\d+)", sec, re.M)
                line = ""
                if header:
                    m = re.search(rf"<bb {header.group(1)}>.*?\[(\S+?):(\d+):\d+", sec, re.S)
                    line = f" (line {m.group(2)})" if m else ""
                b = bounds.get(n)
                if b is None:
                    errors.append(f"{src}: {fn}: loop {n}{line} has no static bound")
                elif b > MAX_TRIP:
                    errors.append(f"{src}: {fn}: loop {n}{line} is bounded only by its counter type ({b} iterations)")
    return errors, loops


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--config", help="configuration name: compile with -include hls/config_NAME.h")
    ap.add_argument("--src", nargs="*", help="sources to check instead of hls/")
    ap.add_argument("--out", default="build/hls-check", help="work folder")
    ap.add_argument("-D", action="append", default=[], help="extra macro definitions")
    args = ap.parse_args()
    name = args.config or "default"
    out = os.path.join(args.out, name)
    os.makedirs(out, exist_ok=True)
    for f in glob.glob(os.path.join(out, "*")) + glob.glob(os.path.join(out, "callgraph", "*")):
        if os.path.isfile(f):
            os.remove(f)
    config = None
    if args.config:
        config = f"hls/config_{args.config}.h"
        if not os.path.exists(config):
            print(f"hls-check: {config} not found (write it with: saarcor profile SCENE -o {config})", file=sys.stderr)
            return 2
    srcs = args.src or default_sources()
    objs, errors = compile_all(srcs, out, config, ["-D" + d for d in args.D])
    functions, loops = set(), 0
    if objs:
        undef, combined = undefined_symbols(objs, out)
        errors += undef + float_types(combined)
        cg_errors, functions = call_graph(out)
        errors += cg_errors
        loop_errors, loops = loop_bounds(out)
        errors += loop_errors
    for e in errors:
        print(f"hls-check [{name}]: {e}")
    size = 0
    if objs:
        r = subprocess.run(["size", "-t"] + objs, capture_output=True, text=True)
        size = int(r.stdout.splitlines()[-1].split()[0]) if r.returncode == 0 else 0
    sites = fp_call_sites(out) if objs else {}
    block, core = state_bytes(config, out) if not args.src else (0, 0)
    with open(os.path.join(out, "report.txt"), "w") as f:
        f.write(f"config {name}\nsources {len(srcs)}\nfunctions {len(functions)}\nloops {loops}\n"
                f"text_bytes {size}\nthread_state_bytes {block}\ncore_state_bytes {core}\nviolations {len(errors)}\n")
        f.write("".join(f"fp_{k} {v}\n" for k, v in sites.items()))
        f.write("".join("function " + fn + "\n" for fn in sorted(functions)))
    status = "FAILED" if errors else "clean"
    print(f"hls-check [{name}]: {status}: {len(srcs)} sources, {len(functions)} functions in the call graph, "
          f"{loops} loops with static bounds checked, {size} bytes of code, {len(errors)} violations")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
