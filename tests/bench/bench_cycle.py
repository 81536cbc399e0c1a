#!/usr/bin/env python3
"""make bench-cycle: the cycle model beside the paper's Tables 3 and 4, scaling, simulator speed.

1. Every generated scene and the shared scenes present in ../shared/scenes, rendered in cycle
   mode at 512x384 and 1024x768 with primary rays and textured shading (--max-depth 0
   --no-shadows), 1 pipe, 64 threads, 90 MHz, default caches: fps, rays/s, unit usage, cache hit
   rates, external bandwidth, beside the paper's figures for the scenes that correspond (the
   room ~ Scene6, plants ~ SunCOR, terrain ~ Terrain, the 504k-triangle gallery ~ Conference's
   size).
2. Sweeps on the room at 512x384: threads per pipe 1, 2, 4, ..., 128 (1 pipe) and pipes 1, 2, 4, 8
   (32 threads each): modeled fps and speed-up.
3. The simulator's own speed (one host thread each, same primary rays): functional and cycle
   mode rays per host second, simulated cycles per host second, cycle/functional ratio (target
   >= 25%), and functional against Embree rtcIntersect1 (target >= 1/3), Embree measured in the
   same run by build/bench_render.
4. Per primary ray at 512x384 (issue 17, "at least as efficient as the 2004 prototype"): cycles,
   ray-triangle tests, transformation slots, shading and DynRTC bytes (after the caches), image
   bytes per unique triangle, the busiest unit's usage and the threads' memory wait, beside the
   paper's figure for the comparable scene, the issue's target, and the same figures before the
   issue (tests/bench/cycle_before.json: measured on the commit before the last change measured with this script's
   --record-before BIN, machine, command and date in the file).
Writes OUT/cycle.md, OUT/cycle.json and OUT/cycle_threads.svg (gnuplot, if installed).
Options: --quick (512x384 only, no sweeps' Embree), --record-before BIN (measure the per-ray
figures with another build, e.g. of the commit before a change, into cycle_before.json).
"""
import datetime, json, os, platform, re, shutil, subprocess, sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.path.join(ROOT, "build", "saarcor")
SHARED = os.path.join(ROOT, "..", "shared", "scenes")
PRIMARY = ["--max-depth", "0", "--no-shadows"]
SCENES = [  # table name, scene, extra options, paper scene, name in render.json
    ("room", "room", [], "Scene6", "room"),
    ("plants", "plants", [], "SunCOR", "plants"),
    ("terrain", "terrain", [], "Terrain", "terrain"),
    ("cornell", "cornell", [], None, "cornell"),
    ("animated", "animated", ["--time", "1.5"], None, None),
    ("teapot", os.path.join(SHARED, "teapot.glb"), [], None, "teapot.glb"),
    ("bunny", os.path.join(SHARED, "bunny.glb"), [], None, "bunny.glb"),
    ("CesiumMilkTruck", os.path.join(SHARED, "CesiumMilkTruck.glb"), [], None, "CesiumMilkTruck.glb"),
    ("gallery_ccby_503k", os.path.join(SHARED, "gallery_ccby_503k.glb"), ["--mem-mb", "256"], "Conference",
     "gallery_ccby_503k.glb"),
    ("subpass", os.path.join(SHARED, "subpass_scene_opaque.glb"), [], None, None),
]
BEFORE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cycle_before.json")
# The prototype per primary ray (paper Tables 3 and 4 at 90 MHz; the reading of them):
# cycles per ray, shading bytes per ray (28 with bilinear textures), DynRTC bytes per ray.
PAPER_RAY = {"Scene6": (7.5, 28, None), "SunCOR": (14.3, 28, 75), "Terrain": (28.8, 28, 86),
             "Conference": (20.7, 29, 30)}
# The targets: cycles per ray, DynRTC bytes per ray, bytes per triangle (shading <= 40 everywhere).
TARGET = {"cornell": (7.5, 30, None), "room": (10, 30, None), "subpass": (5, 30, None), "terrain": (29, 172, None),
          "plants": (14.3, 150, None), "bunny": (None, None, 90), "gallery_ccby_503k": (None, None, 90)}
# The paper: Table 3 (fps at 512x384) and Table 4 (1024x768: fps, usage Trav/List/Transf/Int [%],
# hit rates Trav/List/Transf [%], bandwidth DynRTC/Shading/Total [MB/s]).
PAPER = {
    "Scene6": {"fps512": 60.8, "fps1024": 15.3, "usage": [68, 16, 85, 41], "hit": [99, 97, 99], "bw": [8, 218, 226],
               "triangles": "806"},
    "SunCOR": {"fps512": 32.1, "fps1024": 8.7, "usage": [46, 36, 29, 12], "hit": [90, 2, 6], "bw": [513, 202, 715],
               "triangles": "187,145,136"},
    "Terrain": {"fps512": 15.9, "fps1024": 4.2, "usage": [80, 27, 34, 18], "hit": [97, 27, 43], "bw": [283, 98, 381],
                "triangles": "10,469,866"},
    "Conference": {"fps512": 22.1, "fps1024": 5.7, "usage": [89, 25, 51, 28], "hit": [98, 63, 78], "bw": [135, 132, 267],
                   "triangles": "282,805"},
}


def run(args):
    r = subprocess.run([BIN] + args, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(" ".join(args) + ": " + r.stderr.strip())
    return r.stdout


def render(scene, opts, w, h, mode, extra, tmp):
    stats = os.path.join(tmp, "stats.json")
    out = run(["render", scene, "-o", os.path.join(tmp, "img.png"), "--mode", mode, "--width", str(w), "--height",
               str(h), "--stats", stats] + PRIMARY + opts + extra)
    s = json.load(open(stats))
    s["host_seconds"] = float(re.search(r" in ([0-9.]+) s", out).group(1))
    return s


def per_ray(binary, scene, opts, tmp):
    """The per-primary-ray figures of one scene at 512x384 with the given saarcor binary."""
    stats, info = os.path.join(tmp, "ray.json"), os.path.join(tmp, "info.json")
    one = ["--threads", "1", "--threads-per-pipe", "64", "--pipes", "1", "--clock-mhz", "90"]
    for args in (["render", scene, "-o", os.path.join(tmp, "ray.png"), "--mode", "cycle", "--width", "512",
                  "--height", "384", "--stats", stats] + PRIMARY + opts + one,
                 ["info", scene, "--json", info] + opts):
        r = subprocess.run([binary] + args, capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(" ".join(args) + ": " + r.stderr.strip())
    s, i = json.load(open(stats)), json.load(open(info))
    c, rays = s["cycle"], s["rays"]
    m, t = c["memory"], c["thread_cycles"]
    return {"cycles": c["cycles"] / rays, "tests": s["intersections"] / rays,
            "xform": s["transformations"] / rays, "shading": m["shading"]["bytes"] / rays,
            "dynrtc": sum(m[k]["bytes"] for k in ("kd_nodes", "lists", "matrices")) / rays,
            "bytes_per_triangle": 4.0 * sum(i["regions"].values()) / max(1, i["triangles"]),
            "busiest": 100 * max(u["usage"] for u in c["units"].values()),
            "memory_wait": 100 * t["memory"] / max(1, sum(t.values()))}


def record_before(binary, out):
    """--record-before BIN: the per-ray figures of BIN into cycle_before.json."""
    tmp = os.path.join(out, "cycle_tmp")
    os.makedirs(tmp, exist_ok=True)
    rows = {}
    for name, scene, opts, _, _ in SCENES:
        if scene.startswith(SHARED) and not os.path.exists(scene):
            continue
        print(f"bench-cycle: before: {name} ...", file=sys.stderr, flush=True)
        rows[name] = per_ray(binary, scene, opts, tmp)
    commit = subprocess.run(["git", "-C", os.path.dirname(os.path.abspath(binary)), "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip()
    json.dump({"machine": platform.node() + ", " + platform.machine() + f", {os.cpu_count()} cores",
               "command": "python3 tests/bench/bench_cycle.py --record-before " + binary, "commit": commit,
               "date": datetime.date.today().isoformat(), "scenes": rows}, open(BEFORE, "w"), indent=1)
    print(f"bench-cycle: wrote {BEFORE}", file=sys.stderr)


def cycle_row(s):
    c = s["cycle"]
    u, m = c["units"], c["memory"]
    return {
        "fps": c["fps"], "rays_per_s": c["rays_per_second"], "cycles": c["cycles"],
        "usage": [100 * u[k]["usage"] for k in ("trav", "list", "xform", "isect", "rgs")],
        "hit": [100 * m[k]["hit_rate"] for k in ("kd_nodes", "lists", "matrices")],
        "bw": [m["dynrtc_mb_per_s"], m["shading"]["mb_per_s"], m["total_mb_per_s"]],
        "threads_in_flight": c["threads_in_flight"], "host_seconds": s["host_seconds"],
        "intersections_per_ray": s["intersections"] / max(1, s["rays"]),
    }


def main():
    out = sys.argv[sys.argv.index("--out") + 1] if "--out" in sys.argv else os.path.join(ROOT, "build", "bench")
    quick = "--quick" in sys.argv
    os.makedirs(out, exist_ok=True)
    if "--record-before" in sys.argv:
        record_before(os.path.abspath(sys.argv[sys.argv.index("--record-before") + 1]), out)
        return
    tmp = os.path.join(out, "cycle_tmp")
    os.makedirs(tmp, exist_ok=True)
    one = ["--threads", "1", "--threads-per-pipe", "64", "--pipes", "1", "--clock-mhz", "90"]
    rows = []
    for name, scene, opts, paper, ename in SCENES:
        if scene.startswith(SHARED) and not os.path.exists(scene):
            print(f"bench-cycle: {name}: skipped ({scene} absent)", file=sys.stderr)
            continue
        print(f"bench-cycle: {name} ...", file=sys.stderr, flush=True)
        r = {"scene": name, "paper": paper, "render_json": ename, "per_ray": per_ray(BIN, scene, opts, tmp)}
        for w, h in ((512, 384),) if quick else ((512, 384), (1024, 768)):
            r[f"{w}"] = cycle_row(render(scene, opts, w, h, "cycle", one, tmp))
        f = render(scene, opts, 512, 384, "functional", ["--threads", "1"], tmp)
        r["functional_host_seconds_512"] = f["host_seconds"]
        r["rays_512"] = f["rays"]
        rows.append(r)

    print("bench-cycle: sweeps ...", file=sys.stderr, flush=True)
    sweep_t = []
    for t in (1, 2, 4, 8, 16, 32, 64, 128):
        s = render("room", [], 512, 384, "cycle", ["--threads", "1", "--threads-per-pipe", str(t)], tmp)
        sweep_t.append({"threads": t, "fps": s["cycle"]["fps"], "cycles": s["cycle"]["cycles"]})
    sweep_p = []
    for p in (1, 2, 4, 8):
        s = render("room", [], 512, 384, "cycle", ["--threads", "2", "--threads-per-pipe", "32", "--pipes", str(p)], tmp)
        sweep_p.append({"pipes": p, "fps": s["cycle"]["fps"], "cycles": s["cycle"]["cycles"],
                        "host_seconds": s["host_seconds"]})

    embree = {}
    bench_render = os.path.join(ROOT, "build", "bench_render")
    if not quick and os.path.exists(bench_render):
        print("bench-cycle: Embree and the functional units on the same primary rays (bench_render) ...",
              file=sys.stderr, flush=True)
        subprocess.run([bench_render, "--out", out], check=True, stdout=subprocess.DEVNULL)
        embree = {s["scene"]: s for s in json.load(open(os.path.join(out, "render.json")))["scenes"]}

    json.dump({"scenes": rows, "sweep_threads": sweep_t, "sweep_pipes": sweep_p, "embree": embree},
              open(os.path.join(out, "cycle.json"), "w"), indent=1)
    write_markdown(out, rows, sweep_t, sweep_p, embree, quick)
    plot(out, sweep_t, sweep_p)
    shutil.rmtree(tmp, ignore_errors=True)
    print(open(os.path.join(out, "cycle.md")).read())


def per_ray_table(md, rows):
    """Issue 17's table: the hardware's work per primary ray now, before the issue, the paper, the target."""
    before = json.load(open(BEFORE)) if os.path.exists(BEFORE) else {"scenes": {}}
    f = lambda x, d=1: "-" if x is None else f"{x:.{d}f}"
    md.write("## Per primary ray (512x384, issue 17: at least as efficient as the prototype)\n\n"
             "Now / before the issue (`tests/bench/cycle_before.json`: commit "
             f"{before.get('commit', '?')}, {before.get('date', '?')}, {before.get('machine', '?')}). "
             "DynRTC bytes are kd nodes, lists and matrices after the caches; shading bytes after the "
             "shading cache; bytes per triangle over all regions of the image and the scene's unique "
             "triangles. Paper: the prototype on the comparable scene (Tables 3 and 4). Target: the issue's.\n\n"
             "| scene | cycles/ray | tests/ray | transf. slots/ray | shading B/ray | DynRTC B/ray | B/triangle "
             "| busiest unit % | memory wait % | paper cycles / shading / DynRTC | target cycles / DynRTC / B/tri |\n"
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---|\n")
    for r in rows:
        n, b = r["per_ray"], before["scenes"].get(r["scene"])
        pair = lambda k, d=1: f(n[k], d) + (f" / {f(b[k], d)}" if b else "")
        p = PAPER_RAY.get(r["paper"], (None, None, None))
        t = TARGET.get(r["scene"], (None, None, None))
        md.write(f"| {r['scene']} | {pair('cycles')} | {pair('tests')} | {pair('xform')} | {pair('shading', 0)} | "
                 f"{pair('dynrtc', 0)} | {pair('bytes_per_triangle', 0)} | {f(n['busiest'], 0)} | "
                 f"{f(n['memory_wait'], 0)} | {r['paper'] or '-'}: {f(p[0])} / {f(p[1], 0)} / {f(p[2], 0)} | "
                 f"{f(t[0])} / {f(t[1], 0)} / {f(t[2], 0)} |\n")
    md.write("\nShading target: at most 40 bytes per primary ray on every scene; busiest unit at least 70% "
             "and memory wait at most 30% on cornell and room.\n\n")


def write_markdown(out, rows, sweep_t, sweep_p, embree, quick):
    f = lambda x, d=1: f"{x:.{d}f}"
    with open(os.path.join(out, "cycle.md"), "w") as md:
        md.write("# Cycle model: SaarCOR's Tables 3 and 4, scaling and simulator speed\n\n"
                 "Primary rays with textured shading (`--max-depth 0 --no-shadows`), 1 pipe, 64 threads, 90 MHz, "
                 "caches 4/2/6 KB, memory 1 GB/s with 10 cycles latency, default unit latencies "
                 "(docs/cycle-model.md). Paper rows: the SaarCOR prototype on the scene that corresponds "
                 "(different geometry; the comparison is of magnitudes, not of equal work).\n\n")
        per_ray_table(md, rows)
        md.write("## 512x384 (Table 3)\n\n| scene | fps | paper scene | paper fps | M rays/s | isect/ray |\n"
                 "|---|---:|---|---:|---:|---:|\n")
        for r in rows:
            p = PAPER.get(r["paper"])
            c = r["512"]
            md.write(f"| {r['scene']} | {f(c['fps'])} | {r['paper'] or '-'} | {f(p['fps512']) if p else '-'} | "
                     f"{f(c['rays_per_s'] / 1e6, 2)} | {f(c['intersections_per_ray'], 1)} |\n")
        if not quick:
            md.write("\n## 1024x768 (Table 4)\n\n| scene | fps | usage Trav/List/Transf/Int/RGS % | hit Trav/List/Transf % "
                     "| MB/s DynRTC/Shading/Total | threads in flight |\n|---|---:|---|---|---|---:|\n")
            for r in rows:
                c = r["1024"]
                md.write(f"| {r['scene']} | {f(c['fps'])} | {'/'.join(f(x, 0) for x in c['usage'])} | "
                         f"{'/'.join(f(x) for x in c['hit'])} | {'/'.join(f(x, 0) for x in c['bw'])} | "
                         f"{f(c['threads_in_flight'])} |\n")
                p = PAPER.get(r["paper"])
                if p:
                    md.write(f"| *paper: {r['paper']}* | *{f(p['fps1024'])}* | *{'/'.join(str(x) for x in p['usage'])}/-* | "
                             f"*{'/'.join(str(x) for x in p['hit'])}* | *{'/'.join(str(x) for x in p['bw'])}* | *64* |\n")
        md.write("\n## Threads per pipe (room, 512x384, 1 pipe)\n\n| threads | fps | speed-up over 1 | over half as many |\n"
                 "|---:|---:|---:|---:|\n")
        for i, s in enumerate(sweep_t):
            prev = sweep_t[i - 1]["fps"] if i else s["fps"]
            md.write(f"| {s['threads']} | {f(s['fps'])} | {f(s['fps'] / sweep_t[0]['fps'], 2)} | {f(s['fps'] / prev, 2)} |\n")
        md.write("\nThe paper: near-linear gains up to 32 threads, about 10% more at 64.\n\n"
                 "## Pipes (room, 512x384, 32 threads each, 1 GB/s per pipe)\n\n| pipes | fps | speed-up | host s (2 threads) |\n"
                 "|---:|---:|---:|---:|\n")
        for s in sweep_p:
            md.write(f"| {s['pipes']} | {f(s['fps'])} | {f(s['fps'] / sweep_p[0]['fps'], 2)} | {f(s['host_seconds'], 2)} |\n")
        md.write("\n## Simulator speed (512x384 primary rays, 1 host thread each)\n\n"
                 "| scene | functional M rays/s | cycle M rays/s | cycle / functional | M cycles per host s |\n"
                 "|---|---:|---:|---:|---:|\n")
        for r in rows:
            fr = r["rays_512"] / r["functional_host_seconds_512"]
            cr = r["rays_512"] / r["512"]["host_seconds"]
            md.write(f"| {r['scene']} | {f(fr / 1e6, 3)} | {f(cr / 1e6, 3)} | {f(100 * cr / fr, 0)}% | "
                     f"{f(r['512']['cycles'] / r['512']['host_seconds'] / 1e6, 2)} |\n")
        if embree:
            md.write("\n## Functional mode against Embree (1024x768 primary rays, 1 thread each, `bench_render`)\n\n"
                     "| scene | functional M rays/s | Embree rtcIntersect1 M rays/s | functional / Embree |\n|---|---:|---:|---:|\n")
            for name, e in embree.items():
                rays = 1024 * 768
                md.write(f"| {name} | {f(rays / e['units_trace_s'] / 1e6, 3)} | {f(rays / e['embree_s'] / 1e6, 2)} | "
                         f"{f(e['embree_s'] / e['units_trace_s'], 3)} |\n")
            md.write("\nTarget: functional at least 1/3 of Embree; see the closing note of the cycle-model issue "
                     "for where it stands.\n")


def plot(out, sweep_t, sweep_p):
    if not shutil.which("gnuplot"):
        print("bench-cycle: gnuplot not installed, no plot", file=sys.stderr)
        return
    data = os.path.join(out, "cycle_threads.dat")
    with open(data, "w") as d:
        for s in sweep_t:
            d.write(f"{s['threads']} {s['fps']}\n")
    script = (f"set terminal svg size 640,400; set output '{os.path.join(out, 'cycle_threads.svg')}';"
              "set logscale x 2; set xlabel 'threads per pipe'; set ylabel 'fps (room, 512x384, 90 MHz)';"
              "set grid; set key off; set title 'Multithreading hides latency (1 pipe)';"
              f"plot '{data}' with linespoints lw 2")
    subprocess.run(["gnuplot", "-e", script], check=False)


if __name__ == "__main__":
    main()
