#!/usr/bin/env python3
"""make bench-accuracy: how far the hardware's images are from the truth, at 1024x768.

For every generated scene and the shared scenes present in ../shared/scenes, renders through the
units (`saarcor render`, fp24, functional mode, ray depth 3, shadows) and with the
double-precision reference (`saarcor reference`), and measures PSNR and the share of pixels
differing by more than 4/255 (`saarcor compare`), and the per-ray primary hit agreement, relative
t error and barycentric error (`saarcor compare-hits`). Both renderers run with 2 host threads;
their times are wall-clock seconds of one run (including nothing but the frame). Writes
OUT/accuracy.md and OUT/accuracy.json; if OUT/render.json (make bench-render) exists, its Embree
primary-ray times are put beside ours.

Then the golden scenes (tests/golden/images/cases.txt, at their sizes), per pixel: every pixel
whose fp24 image differs from the reference's by more than 4/255 is classified by its primary
hit (`compare-hits --classes`, on the units' fp24 ray and with --camera-rays on the reference's
binary64 one): a clear disagreement on the same fp24 ray (an error of the intersection path), an
ambiguous answer on it (both hits right within the tolerances: a shared edge, a coplanar overlap,
a graze; docs/numerics.md), a sub-ulp ray (the answers agree on the fp24 ray and differ only
with the binary64 camera ray: the RGS's rounding of the primary ray), or the same hit (the
difference then comes from shading or secondary rays); and the PSNR over the pixels that are
neither ambiguous nor sub-ulp. `--golden-only` runs this table alone (OUT/accuracy_golden.md).
"""
import json, math, os, re, subprocess, sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.path.join(ROOT, "build", "saarcor")
SHARED = os.path.join(ROOT, "..", "shared", "scenes")
SIZE = ["--width", "1024", "--height", "768"]
SCENES = [  # name in the tables, scene, extra options, name in render.json
    ("cornell", "cornell", [], "cornell"),
    ("room", "room", [], "room"),
    ("plants", "plants", [], "plants"),
    ("terrain", "terrain", [], "terrain"),
    ("animated (t=1.5 s)", "animated", ["--time", "1.5"], None),
    ("teapot", os.path.join(SHARED, "teapot.glb"), ["--ground"], "teapot.glb"),
    ("bunny", os.path.join(SHARED, "bunny.glb"), ["--ground"], "bunny.glb"),
    ("CesiumMilkTruck", os.path.join(SHARED, "CesiumMilkTruck.glb"), ["--ground"], "CesiumMilkTruck.glb"),
    ("gallery_ccby_503k", os.path.join(SHARED, "gallery_ccby_503k.glb"), ["--mem-mb", "256"], "gallery_ccby_503k.glb"),
]


def run(args):
    r = subprocess.run([BIN] + args, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(" ".join(args) + ": " + r.stderr.strip())
    return r.stdout


def bench(name, scene, opts, out):
    tmp = os.path.join(out, "accuracy")
    os.makedirs(tmp, exist_ok=True)
    stem = os.path.join(tmp, re.sub(r"\W+", "_", name))
    o = opts + SIZE
    render = run(["render", scene, "-o", stem + ".png", "--threads", "2", "--stats", stem + ".stats.json"] + o)
    ref = run(["reference", scene, "-o", stem + ".ref.exr", "--png", stem + ".ref.png", "--threads", "2"] + o)
    cmp = run(["compare", stem + ".png", stem + ".ref.png", "--threshold", "0.0157", "--diff", stem + ".diff.png"])
    run(["compare-hits", scene, "--json", stem + ".hits.json"] + o)
    stats = json.load(open(stem + ".stats.json"))
    hits = json.load(open(stem + ".hits.json"))
    return {
        "scene": name,
        "units_seconds": float(re.search(r" in ([0-9.]+) s", render).group(1)),
        "reference_seconds": float(re.search(r" in ([0-9.]+) s", ref).group(1)),
        "rays": stats["rays"], "rays_by_kind": stats["rays_by_kind"],
        "psnr_db": float(re.search(r"psnr_db (\S+)", cmp).group(1)),
        "differing_pct": float(re.search(r"\(([0-9.]+)%\)", cmp).group(1)),
        "hit_agreement": hits["agreement"], "t_rel_error": hits["t_rel_error"], "uv_error": hits["uv_error"],
    }


def read_ppm(path):
    """Width, height and bytes of a binary PPM (P6, 8 bits), as `saarcor compare --diff X.ppm` writes."""
    data = open(path, "rb").read()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos)
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    return int(fields[1]), int(fields[2]), data[pos + 1:]


def golden_case(name, scene, opts, out):
    """One golden case: differing pixels by the class of their primary hit, PSNR with and without the ambiguous ones."""
    stem = os.path.join(out, "accuracy_golden", name)
    os.makedirs(os.path.dirname(stem), exist_ok=True)
    run(["render", scene, "-o", stem + ".png", "--threads", "2"] + opts)
    run(["reference", scene, "-o", stem + ".ref.exr", "--png", stem + ".ref.png", "--threads", "2"] + opts)
    cmp = run(["compare", stem + ".png", stem + ".ref.png", "--threshold", "0.0157", "--diff", stem + ".diff.ppm"])
    run(["compare-hits", scene, "--classes", stem + ".classes"] + opts)
    run(["compare-hits", scene, "--camera-rays", "--classes", stem + ".camera.classes"] + opts)
    w, h, px = read_ppm(stem + ".diff.ppm")
    cls = {}
    for path, on_camera_ray in ((stem + ".camera.classes", True), (stem + ".classes", False)):
        for line in open(path):
            x, y, c = line.split()
            cls[(int(x), int(y))] = "sub-ulp" if on_camera_ray else c  # the fp24 ray's verdict wins
    count = {"ambiguous": 0, "disagree": 0, "sub-ulp": 0, "same": 0}
    sq_all = sq_clear = 0.0
    clear = 0
    for y in range(h):
        for x in range(w):
            d = px[3 * (y * w + x):3 * (y * w + x) + 3]
            sq = sum((v / 255) ** 2 for v in d)
            c = cls.get((x, y), "same")
            sq_all += sq
            if c not in ("ambiguous", "sub-ulp"):
                sq_clear += sq
                clear += 1
            if max(d) >= 5:  # more than 4/255
                count[c] += 1
    psnr = lambda s, n: 10 * math.log10(3 * n / s) if s > 0 else math.inf
    return {"case": name, "psnr_db": float(re.search(r"psnr_db (\S+)", cmp).group(1)),
            "psnr_unambiguous_db": psnr(sq_clear, clear), "differing": sum(count.values()),
            "differing_ambiguous": count["ambiguous"], "differing_disagree": count["disagree"],
            "differing_sub_ulp": count["sub-ulp"], "differing_same_hit": count["same"],
            "ambiguous_or_sub_ulp_pixels": sum(1 for c in cls.values() if c != "disagree")}


def golden_table(out):
    cases = os.path.join(ROOT, "tests", "golden", "images", "cases.txt")
    rows = []
    for line in open(cases):
        if not line.strip() or line.startswith("#"):
            continue
        name, scene, opts = (f.strip() for f in line.split("|")[:3])
        if scene.startswith("../shared/") and not os.path.exists(os.path.join(ROOT, scene)):
            print(f"bench-accuracy: golden {name}: skipped ({scene} absent)", file=sys.stderr)
            continue
        print(f"bench-accuracy: golden {name} ...", file=sys.stderr, flush=True)
        rows.append(golden_case(name, os.path.join(ROOT, scene) if scene.startswith("..") else scene, opts.split(), out))
    md = ["## Golden scenes, per pixel", "",
          "The cases of tests/golden/images/cases.txt at their sizes: fp24 image against the binary64 reference. Each "
          "pixel differing by more than 4/255 is classified by its primary hit (`saarcor compare-hits --classes`, on "
          "the units' fp24 ray, and with `--camera-rays` on the reference's binary64 ray through the pixel): *clear "
          "disagreement* on the same fp24 ray (an error of the intersection path), *ambiguous* on it (both answers "
          "right within distance 1e-4 (t + |o|) and barycentric 1e-3: a shared edge, a coplanar overlap, a graze), "
          "*sub-ulp ray* (the answers agree on the fp24 ray and differ only with the binary64 one: the rounding of "
          "the primary ray itself), or *same hit* (shading or secondary rays). *PSNR unambiguous*: over the pixels "
          "that are neither ambiguous nor sub-ulp.", "",
          "| case | PSNR dB | PSNR unambiguous dB | pixels > 4/255 | ambiguous | sub-ulp ray | clear disagreement | same hit |",
          "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        md.append(f"| {r['case']} | {r['psnr_db']:.2f} | {r['psnr_unambiguous_db']:.2f} | {r['differing']} | "
                  f"{r['differing_ambiguous']} | {r['differing_sub_ulp']} | {r['differing_disagree']} | "
                  f"{r['differing_same_hit']} |")
    return rows, md


def main():
    out = sys.argv[sys.argv.index("--out") + 1] if "--out" in sys.argv else os.path.join(ROOT, "build", "bench")
    os.makedirs(out, exist_ok=True)
    golden_rows, golden_md = golden_table(out)
    if "--golden-only" in sys.argv:
        json.dump(golden_rows, open(os.path.join(out, "accuracy_golden.json"), "w"), indent=1)
        open(os.path.join(out, "accuracy_golden.md"), "w").write("\n".join(golden_md) + "\n")
        print("\n".join(golden_md))
        return
    embree = {}
    try:
        embree = {s["scene"]: s for s in json.load(open(os.path.join(out, "render.json")))["scenes"]}
    except (OSError, ValueError, KeyError):
        pass
    rows = []
    for name, scene, opts, ename in SCENES:
        if scene.startswith(SHARED) and not os.path.exists(scene):
            print(f"bench-accuracy: {name}: skipped ({scene} absent)", file=sys.stderr)
            continue
        print(f"bench-accuracy: {name} ...", file=sys.stderr, flush=True)
        r = bench(name, scene, opts, out)
        e = embree.get(ename)
        r["embree_primary_seconds"] = e["embree_s"] if e else None
        r["units_primary_seconds_1thread"] = e["units_trace_s"] if e else None
        rows.append(r)
    json.dump({"width": 1024, "height": 768, "scenes": rows, "golden": golden_rows},
              open(os.path.join(out, "accuracy.json"), "w"), indent=1)
    with open(os.path.join(out, "accuracy.md"), "w") as md:
        md.write("# fp24 units against the double-precision reference, 1024x768\n\n"
                 "Ray depth 3 with shadows (docs/shading.md); `--ground` for the teapot, bunny and truck. "
                 "*PSNR* and *pixels > 4/255* compare the units' image with the reference's (8-bit); "
                 "*hit agreement*: primary rays hitting the same triangle or both missing (`saarcor compare-hits`); "
                 "*t error*, *uv error*: median / max over rays on the same triangle. *units s*, *reference s*: "
                 "the whole frame, 2 host threads, one run. *Embree s*: rtcIntersect1 on the same primary rays, "
                 "1 thread, next to the units' primary rays alone on 1 thread (`make bench-render`).\n\n"
                 "| scene | rays | PSNR dB | pixels > 4/255 | hit agreement | t error med / max | uv error med / max "
                 "| units s | reference s | units primary s (1 thr) | Embree primary s (1 thr) |\n"
                 "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n")
        for r in rows:
            fmt = lambda x: f"{x:.3f}" if x is not None else "-"
            md.write(f"| {r['scene']} | {r['rays']} | {r['psnr_db']:.2f} | {r['differing_pct']:.3f}% | "
                     f"{100 * r['hit_agreement']:.3f}% | {r['t_rel_error']['median']:.1e} / {r['t_rel_error']['max']:.1e} | "
                     f"{r['uv_error']['median']:.1e} / {r['uv_error']['max']:.1e} | {r['units_seconds']:.2f} | "
                     f"{r['reference_seconds']:.2f} | {fmt(r['units_primary_seconds_1thread'])} | "
                     f"{fmt(r['embree_primary_seconds'])} |\n")
        md.write("\n" + "\n".join(golden_md) + "\n")
    print(open(os.path.join(out, "accuracy.md")).read())


if __name__ == "__main__":
    main()
