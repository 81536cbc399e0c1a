#!/usr/bin/env python3
"""make bench-precision: run time against image error across number formats.

Renders every generated scene and the shared scenes (the list of bench_accuracy.py) with every
built format eEmM (build/w/, `make widths`: M in {8, 10, ..., 20, 23} with E = 7, and e8m23, the
binary32 layout with subnormals flushed, labelled fp32) in functional and cycle mode, and with the
binary64 reference (tb/ref), which is the truth every row is measured against. Per scene and
format: simulator run time of both modes (1 host thread), modeled cycles per frame, PSNR and max
error of the image against the reference, share of pixels differing by more than 4/255, primary
hit agreement (saarcor compare-hits), the edge leak rate of the stress suite at that width
(build/bench/stress.json, make stress) and the operators' area at that width (build/synth/
synth.json, make synth). Names the knee of each curve and says whether M = 16 suffices.
Writes OUT/precision.md, precision.json (one object per row) and precision_<scene>.svg (gnuplot).

Options: --out DIR, --size WxH (256x192), --scenes a,b (names of the tables), --formats eEmM,...
(all of the list), --mpi N. The renders (every scene x format x mode, compare-hits, the references)
are independent jobs run first, two at a time, or across N MPI ranks with --mpi N (mpi_jobs.py,
`saarcor jobs --mpi`), each writing its files and a log; the comparisons and tables follow here.

An fp64 build of the units is not possible: the memory image is 32-bit words and the units'
numbers are 32-bit f24_t (docs/memory-image.md); the binary64 reference stands in as the fp64 row.
"""
import json, os, re, subprocess, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_accuracy import SCENES, SHARED  # noqa: E402  (the same scenes and options)
from mpi_jobs import run_all  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.path.join(ROOT, "build")
FORMATS = [("e7m8", 8), ("e7m10", 10), ("e7m12", 12), ("e7m14", 14), ("e7m16", 16), ("e7m18", 18), ("e7m20", 20),
           ("e7m23", 23), ("e8m23", 23)]


def run(binary, args):
    r = subprocess.run([binary] + args, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(" ".join([binary] + args) + ": " + r.stderr.strip())
    return r.stdout


def seconds(log):
    return float(re.search(r"^rendered .* in ([0-9.]+) s", open(log).read(), re.M).group(1))


def jobs(scene, opts, fmts, stem):
    """The expensive, independent commands of one scene: the reference, and per format the renders
    in both modes and compare-hits; (argv, log) each, stdout and stderr to the log (mpi_jobs.py)."""
    js = [([os.path.join(BUILD, "saarcor"), "reference", scene, "-o", stem + "_ref.exr", "--png", stem + "_ref.png",
            "--threads", "1"] + opts, stem + "_ref.log")]
    for fmt in fmts:
        b, s = os.path.join(BUILD, "w", fmt, "saarcor"), f"{stem}_{fmt}"
        js += [([b, "render", scene, "-o", s + ".png", "--threads", "1", "--stats", s + ".json"] + opts, s + ".log"),
               ([b, "render", scene, "--mode", "cycle", "-o", s + "_cycle.png", "--threads", "1", "--stats",
                 s + "_cycle.json"] + opts, s + "_cycle.log"),
               ([b, "compare-hits", scene, "--json", s + "_hits.json"] + opts, s + "_hits.log")]
    return js


def one(fmt, stem):
    """One row from the files the jobs wrote, and the image compared with the reference."""
    s = f"{stem}_{fmt}"
    cmp = run(os.path.join(BUILD, "w", fmt, "saarcor"), ["compare", s + ".png", stem + "_ref.png", "--threshold", "0.0157"])
    same = open(s + ".png", "rb").read() == open(s + "_cycle.png", "rb").read()
    hits = json.load(open(s + "_hits.json"))
    return {"format": fmt, "functional_s": seconds(s + ".log"), "cycle_s": seconds(s + "_cycle.log"),
            "cycles": json.load(open(s + "_cycle.json"))["cycle"]["cycles"],
            "psnr_db": float(re.search(r"psnr_db (\S+)", cmp).group(1)),
            "max_error": float(re.search(r"max_abs_error (\S+)", cmp).group(1)),
            "differing_pct": float(re.search(r"\(([0-9.]+)%\)", cmp).group(1)),
            "hit_agreement": hits["agreement"], "hit_agreement_unambiguous": hits.get("agreement_unambiguous"),
            "uv_p99": hits["uv_error"]["p99"], "modes_identical": same}


def side_tables():
    leaks, area = {}, {}
    try:
        for r in json.load(open(os.path.join(BUILD, "bench", "stress.json"))):
            if r["case"].startswith("edges-") and r["build"] in dict(FORMATS):
                n, l = leaks.get(r["build"], (0, 0))
                leaks[r["build"]] = (n + r["rays"], l + r["leaks"])
    except (OSError, ValueError, KeyError):
        pass
    try:
        syn = json.load(open(os.path.join(BUILD, "synth", "synth.json")))
        for fmt, m in FORMATS[:-1]:
            sum9 = syn.get(f"x:f24_sum_exact:e7m{m}:n9", {}).get("luts")
            area[fmt] = (sum(syn[f"x:{op}:e7m{m}"]["luts"] for op in ("f24_add", "f24_mul", "f24_div", "f24_cmp")),
                         syn[f"x:isect_unit:e7m{m}"]["luts"], sum9)
    except (OSError, ValueError, KeyError):
        pass
    return {k: l / n for k, (n, l) in leaks.items()}, area


def good(r):
    """Indistinguishable in 8 bits: at most 0.1% of pixels off by more than 4/255, >= 99.9% hit agreement."""
    return r["differing_pct"] <= 0.1 and r["hit_agreement"] >= 0.999


def knee(rows):
    """Smallest E = 7 width from which on every wider one is good(): where more bits stop paying."""
    e7 = [r for r in rows if r["format"].startswith("e7")]
    for i, r in enumerate(e7):
        if all(good(x) for x in e7[i:]):
            return int(r["format"][3:])
    return None


def plot(out, name, rows):
    dat = os.path.join(out, f"precision_{name}.dat")
    with open(dat, "w") as f:
        for r in rows:
            if r["format"].startswith("e7"):
                f.write(f"{r['format'][3:]} {r['psnr_db']} {r['cycles'] / 1e6} {r['functional_s']}\n")
    svg = os.path.join(out, f"precision_{name}.svg")
    script = (f"set terminal svg size 640,400; set output '{svg}'; set title '{name}: image error and cost against mantissa bits (E = 7)';"
              "set xlabel 'mantissa bits M'; set ylabel 'PSNR against binary64 (dB)'; set y2label 'modeled Mcycles / simulator s';"
              "set ytics nomirror; set y2tics; set key bottom right; set grid;"
              f"plot '{dat}' u 1:2 w lp t 'PSNR dB' axes x1y1, '' u 1:3 w lp t 'Mcycles per frame' axes x1y2,"
              " '' u 1:4 w lp t 'functional s' axes x1y2")
    subprocess.run(["gnuplot", "-e", script], check=True)
    return os.path.basename(svg)


def arg(name, default):
    return sys.argv[sys.argv.index(name) + 1] if name in sys.argv else default


def main():
    out = arg("--out", os.path.join(BUILD, "bench"))
    size = arg("--size", "256x192").split("x")
    ranks = int(arg("--mpi", "0"))
    fmts = arg("--formats", ",".join(f for f, _ in FORMATS)).split(",")
    names = arg("--scenes", ",".join(n for n, *_ in SCENES)).split(",")
    os.makedirs(os.path.join(out, "precision"), exist_ok=True)
    leaks, area = side_tables()
    all_rows, md = [], ["# Run time against error across number formats (generated by `make bench-precision`)", "",
                        f"Machine: {os.uname().nodename}, {os.cpu_count()} cores; command: `make bench-precision`; "
                        f"{size[0]}x{size[1]}, ray depth 3 with shadows; 1 host thread per render, " +
                        (f"{ranks - 1} renders at a time ({ranks} MPI ranks). " if ranks else "two renders at a time. ") +
                        "Truth: the binary64 reference (tb/ref; an fp64 build of the units is impossible with 32-bit memory "
                        "words). *leaks*: edge leak rate of the stress suite at that width (make stress); *area*: LUTs of "
                        "one f24 add + mul + div + cmp / of isect_unit / of the accuracy datapath's 9-term exact dot "
                        "product f24_sum_exact where synthesized (make synth, E = 7; docs/numerics.md). *unambiguous*: "
                        "primary-hit agreement over the rays whose answers are not ambiguous, *uv p99*: barycentric error "
                        "(saarcor compare-hits on the units' rays). e8m23 is the binary32 layout "
                        "(fp32, subnormals flushed).", ""]
    scenes = []
    for name, scene, opts, _ in SCENES:
        if name not in names:
            continue
        if scene.startswith(SHARED) and not os.path.exists(scene):
            print(f"bench-precision: {name}: skipped ({scene} absent)", file=sys.stderr)
            continue
        key = re.sub(r"\W+", "_", name)
        scenes.append((name, scene, opts + ["--width", size[0], "--height", size[1]], key,
                       os.path.join(out, "precision", key)))
    # every render first, as one set of independent jobs (across MPI ranks with --mpi N)
    print(f"bench-precision: {', '.join(n for n, *_ in scenes)}: {len(fmts)} formats ...", file=sys.stderr, flush=True)
    run_all(os.path.join(BUILD, "saarcor"), [j for _, scene, o, _, stem in scenes for j in jobs(scene, o, fmts, stem)],
            ranks, os.path.join(out, "precision", "jobs.txt"))
    for name, scene, o, key, stem in scenes:
        rows = [one(f, stem) for f in fmts]
        k = knee(rows)
        verdict = ("no width reaches the quality bar" if k is None else
                   f"knee at M = {k}: " + ("16 bits are the right choice" if k == 16 else
                                           "16 bits have margin" if k < 16 else "16 bits are not enough"))
        md += [f"## {name}", "", f"![{name}]({plot(out, key, rows)})", "", f"**{verdict}** (knee: the smallest M from "
               "which on every wider format has at most 0.1% of pixels off by more than 4/255 and at least 99.9% "
               "primary hit agreement with the binary64 reference).", "",
               "| format | functional s | cycle s | Mcycles/frame | PSNR dB | max error | pixels > 4/255 | hit agreement | unambiguous | uv p99 | modes identical | edge leaks | area ops / isect / exact sum LUTs |",
               "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|"]
        for r in rows:
            r.update(scene=name, knee_m=k, edge_leak_rate=leaks.get(r["format"]), area_luts=area.get(r["format"]))
            lk = f"{100 * r['edge_leak_rate']:.2f}%" if r["edge_leak_rate"] is not None else "-"
            ar = (f"{r['area_luts'][0]} / {r['area_luts'][1]} / {r['area_luts'][2] if r['area_luts'][2] else '-'}"
                  if r["area_luts"] else "-")
            ua = r["hit_agreement_unambiguous"]
            label = r["format"] + (" (fp32)" if r["format"] == "e8m23" else "")
            md.append(f"| {label} | {r['functional_s']:.2f} | {r['cycle_s']:.2f} | {r['cycles'] / 1e6:.2f} | {r['psnr_db']:.2f} | "
                      f"{r['max_error']:.3f} | {r['differing_pct']:.3f}% | {100 * r['hit_agreement']:.3f}% | "
                      f"{f'{100 * ua:.3f}%' if ua is not None else '-'} | {r['uv_p99']:.1e} | "
                      f"{'yes' if r['modes_identical'] else '**no**'} | {lk} | {ar} |")
        md.append("")
        all_rows += rows
    json.dump(all_rows, open(os.path.join(out, "precision.json"), "w"), indent=1)
    open(os.path.join(out, "precision.md"), "w").write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
