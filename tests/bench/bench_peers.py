#!/usr/bin/env python3
"""make bench-peers: the table of tracers on the same primary rays (512x384).

Reads OUT/peers_rays.json (build/bench_peers: Embree rtcIntersect1/4/8/16 and our functional
mode trace only (trace_packet), 1 and 2 host threads, with Embree's hit/miss against ours, and our
functional frame with shading, 1 thread; all timed in one run by the Embree harness of
tests/bench/embree_scene.h) and adds our cycle mode (`saarcor render --mode cycle --max-depth 0
--no-shadows`, 1 pipe, defaults of docs/cycle-model.md): the simulator's rays per host second and
the modeled hardware's rays per second at 90 MHz. Every row says what it times: "trace only" (the
rays given, no ray generation or shading: Embree, trace_packet) or "with shading" (ray generation,
trace and shading of primary rays: our frame). Every ratio is against Embree rtcIntersect1 on 1
thread of the same run.
Writes OUT/peers.md, OUT/peers.json (one object per row, keys as the table's columns) and
OUT/peers_functional.json (the functional summary: per scene both ratios).
"""
import datetime, json, os, re, subprocess, sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.path.join(ROOT, "build", "saarcor")
SHARED = os.path.join(ROOT, "..", "shared", "scenes")


TRACE_ONLY, WITH_SHADING = "trace only", "with shading"  # the "work" of a row (bench_peers.c)
EMBREE_1 = "Embree rtcIntersect1"
FRAME = "units functional (RGS frame: ray generation + trace + shading)"
TRACE = "units functional (trace_packet)"


def cycle_row(scene, out):
    path = scene if "." not in scene else os.path.join(SHARED, scene)
    key = re.sub(r"\W+", "_", scene)
    st = os.path.join(out, f"peers_{key}_cycle.json")
    r = subprocess.run([BIN, "render", path, "--mode", "cycle", "--max-depth", "0", "--no-shadows", "--width", "512",
                        "--height", "384", "--threads", "1", "--mem-mb", "1024", "-o", os.path.join(out, "peers_cycle.png"),
                        "--stats", st], capture_output=True, text=True)
    if r.returncode != 0:
        return None
    s = json.load(open(st))
    return {"scene": scene, "tracer": "units cycle mode (1 pipe, 90 MHz model)", "work": WITH_SHADING, "threads": 1,
            "rays": s["rays"],
            "seconds": s["seconds"], "rays_per_second": s["rays"] / s["seconds"],
            "modeled_rays_per_second": s["cycle"]["rays_per_second"], "hit_agreement_with_units": None}


# name, stack entries of the top and the bottom level, cursor walker levels (a node or cell per ray)
ALGORITHMS = [("stack", 64, 64, 0), ("short-stack", 4, 4, 0), ("restart", 0, 0, 0), ("push-down", 0, 0, 0),
              ("ropes", 0, 0, 2), ("grid", 64, 0, 1), ("grid2", 0, 0, 2)]
ENTRY_BITS = 32 + 4 + 2 * 4 * 24  # node, ray mask, tn and tf of 4 rays (fp24)
CURSOR_BITS = 4 * 32  # a node or cell index per ray


def traversal_rows(scene, out):
    """The traversal unit's algorithms on the same primary rays (cycle mode, 1 pipe): per ray work
    and modeled cycles, and the image against the stack's."""
    path = scene if "." not in scene else os.path.join(SHARED, scene)
    key = re.sub(r"\W+", "_", scene)
    rows = []
    for algo, top, bottom, cursors in ALGORITHMS:
        st, png = os.path.join(out, f"peers_{key}_{algo}.json"), os.path.join(out, f"peers_{key}_{algo}.png")
        r = subprocess.run([BIN, "render", path, "--mode", "cycle", "--max-depth", "0", "--no-shadows", "--width", "512",
                            "--height", "384", "--threads", "1", "--mem-mb", "1024", "--traversal", algo, "-o", png,
                            "--stats", st], capture_output=True, text=True)
        if r.returncode != 0:
            return rows
        s = json.load(open(st))
        n = s["rays"]
        upload = re.search(r"upload ([0-9.]+) KB", r.stdout)
        same = subprocess.run([BIN, "compare", png, os.path.join(out, f"peers_{key}_stack.png")], capture_output=True,
                              text=True).stdout
        diff = float(re.search(r"\(([0-9.]+)%\)", same).group(1)) if same else None
        rows.append({"scene": scene, "algorithm": algo, "stack entries": f"{top}/{bottom}",
                     "walker bits per thread": (top + bottom) * ENTRY_BITS + cursors * CURSOR_BITS,
                     "image MB": float(upload.group(1)) / 1024 if upload else None,
                     "node visits per ray": s["traversal_steps"] / n, "leaves or cells per ray": s["leaves"] / n,
                     "intersections per ray": s["intersections"] / n, "words per ray": s["words_read"] / n,
                     "cycles per ray": s["cycle"]["cycles"] / n, "pixels differing from stack %": diff,
                     "machine_command_date": None})
    return rows


def find(rows, scene, tracer, threads=1):
    return next((r for r in rows if r["scene"] == scene and r["tracer"] == tracer and r["threads"] == threads), None)


def functional_summary(rows, scenes):
    """Per scene: our functional mode with shading and trace only, each against Embree rtcIntersect1
    on 1 thread (the issue's target: with shading >= 1/3)."""
    out = []
    for sc in scenes:
        e, f, t = (find(rows, sc, x) for x in (EMBREE_1, FRAME, TRACE))
        if e:
            out.append({"scene": sc, "embree_rtcintersect1_rays_per_second": e["rays_per_second"],
                        "with_shading_rays_per_second": f and f["rays_per_second"],
                        "with_shading_vs_embree": f and f["vs_embree_1thread"],
                        "trace_only_rays_per_second": t and t["rays_per_second"],
                        "trace_only_vs_embree": t and t["vs_embree_1thread"]})
    return out


def fmt(v, digits, scale=1.0):
    return f"{v / scale:.{digits}f}" if v is not None else "-"


def summary_md(summary):
    md = ["## Functional mode against Embree rtcIntersect1 (1 host thread each, same rays, same run)", "",
          "*with shading*: the render command's functional frame (`saarcor render SCENE --width 512 --height 384 "
          "--max-depth 0 --no-shadows --threads 1` without loading and writing: RGS ray generation, trace, shading); "
          "*trace only*: trace_packet on the same rays, generated before timing. Target of issue 19: with shading "
          ">= 1/3 of Embree.", "",
          "| scene | Embree rtcIntersect1 M rays/s | with shading M rays/s | with shading / Embree | "
          "trace only M rays/s | trace only / Embree |", "|---|---:|---:|---:|---:|---:|"]
    for s in summary:
        md.append(f"| {s['scene']} | {fmt(s['embree_rtcintersect1_rays_per_second'], 3, 1e6)} | "
                  f"{fmt(s['with_shading_rays_per_second'], 3, 1e6)} | {fmt(s['with_shading_vs_embree'], 3)} | "
                  f"{fmt(s['trace_only_rays_per_second'], 3, 1e6)} | {fmt(s['trace_only_vs_embree'], 3)} |")
    return md


def main():
    out = sys.argv[sys.argv.index("--out") + 1] if "--out" in sys.argv else os.path.join(ROOT, "build", "bench")
    rows = json.load(open(os.path.join(out, "peers_rays.json")))
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    for sc in scenes:
        c = cycle_row(sc, out)
        if c:
            rows.append(c)
    stamp = f"{os.uname().nodename}, {os.cpu_count()} cores, `make bench-peers`, {datetime.date.today()}"
    trav = [t for sc in scenes for t in traversal_rows(sc, out)]
    for r in rows:
        base = find(rows, r["scene"], EMBREE_1)
        r["vs_embree_1thread"] = r["rays_per_second"] / base["rays_per_second"] if base else None
    summary = functional_summary(rows, scenes)
    for r in rows + trav + summary:
        r["machine_command_date"] = stamp
    json.dump(rows, open(os.path.join(out, "peers.json"), "w"), indent=1)
    json.dump(trav, open(os.path.join(out, "peers_traversal.json"), "w"), indent=1)
    json.dump(summary, open(os.path.join(out, "peers_functional.json"), "w"), indent=1)
    setup = next((r["embree_setup"] for r in rows if r.get("embree_setup")), "Embree 3")
    md = ["# Peers on the same primary rays (generated by `make bench-peers`)", "",
          f"{stamp}. 512x384 primary rays of the RGS (fp24, given to Embree as binary32). Embree: {setup} "
          "(tests/bench/embree_scene.h, docs/architecture.md); our rows are timed the same way in the same run. "
          "*work*: *trace only* = the rays are given, nothing else is timed; *with shading* = ray generation, "
          "trace and shading of the primary rays (max depth 0, no shadows). *vs Embree 1*: rays per second "
          "relative to rtcIntersect1 on 1 thread in the same run, whatever the row's work. *agreement*: Embree's "
          "hit/miss equal to trace_packet's. Cycle mode: the simulator's speed and the modeled hardware's rays "
          "per second.", ""]
    md += summary_md(summary)
    md += ["", "## All tracers", "",
           "| scene | tracer | work | threads | rays/s (host) | vs Embree 1 | modeled rays/s | agreement |",
           "|---|---|---|---:|---:|---:|---:|---:|"]
    for r in rows:
        ag = f"{100 * r['hit_agreement_with_units']:.3f}%" if r["hit_agreement_with_units"] is not None else "-"
        mod = f"{r['modeled_rays_per_second'] / 1e6:.2f} M" if r.get("modeled_rays_per_second") else "-"
        rel = f"{r['vs_embree_1thread']:.3f}" if r["vs_embree_1thread"] is not None else "-"
        md.append(f"| {r['scene']} | {r['tracer']} | {r.get('work', '-')} | {r['threads']} | "
                  f"{r['rays_per_second'] / 1e6:.3f} M | {rel} | {mod} | {ag} |")
    md += ["", "## Traversal algorithms of the traversal unit (same trees, same fp24 units; docs/traversal.md)", "",
           "Primary rays, cycle mode, 1 DynRTP at 90 MHz with the default caches. *stack entries*: top/bottom "
           "level. *walker bits per thread*: the traversal stacks of both levels for one packet (node, mask, tn/tf "
           "of 4 rays per entry) plus, for the cursor walkers, a node or cell index per ray and level. *image MB*: "
           "the whole memory image with the structures the algorithm walks (kd-trees always; rope records; grids). "
           "*node visits*: inner kd nodes; *leaves or cells*: kd leaves or grid cells visited.", "",
           "| scene | algorithm | stack entries | walker bits per thread | image MB | node visits per ray | "
           "leaves or cells per ray | intersections per ray | words per ray | cycles per ray | pixels differing from stack |",
           "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for t in trav:
        d = f"{t['pixels differing from stack %']:.4f}%" if t["pixels differing from stack %"] is not None else "-"
        mb = f"{t['image MB']:.2f}" if t["image MB"] is not None else "-"
        md.append(f"| {t['scene']} | {t['algorithm']} | {t['stack entries']} | {t['walker bits per thread']} | {mb} | "
                  f"{t['node visits per ray']:.2f} | {t['leaves or cells per ray']:.2f} | {t['intersections per ray']:.2f} | "
                  f"{t['words per ray']:.1f} | {t['cycles per ray']:.1f} | {d} |")
    open(os.path.join(out, "peers.md"), "w").write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
