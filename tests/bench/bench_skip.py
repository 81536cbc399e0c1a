#!/usr/bin/env python3
"""make bench-skip: per scene, the general pipeline (render --general) against the one the scene
profile specializes, in cycle mode (1 pipe, 32 threads, 90 MHz, ray depth 3 with shadows):
cycles, work counters and the profile's skip bits, and a check that both images are identical bit
for bit (the benchmark fails otherwise). Writes build/bench/skip.md and skip.json."""
import argparse
import json
import os
import subprocess
import sys
import tempfile

BIN = "build/saarcor"
SHARED = "../shared/scenes"
GENERATED = ["cornell", "room", "terrain", "animated", "plants"]
SHARED_SCENES = ["teapot.glb", "bunny.glb", "cornell_box.glb", "CesiumMilkTruck.glb", "Box.glb"]
COUNTERS = ["traversal_steps", "leaves", "list_entries", "transformations", "intersections", "words_read"]


def render(scene, extra, tmp, tag):
    png, stats = os.path.join(tmp, tag + ".png"), os.path.join(tmp, tag + ".json")
    cmd = [BIN, "render", scene, "--mode", "cycle", "--width", "256", "--height", "192", "--max-depth", "3",
           "-o", png, "--stats", stats] + extra
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return png, json.load(open(stats))


def profile_bits(scene):
    out = subprocess.run([BIN, "profile", scene], check=True, capture_output=True, text=True).stdout
    return next(l.split(None, 2)[2] for l in out.splitlines() if l.startswith("run-time skips"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="build/bench")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    scenes = list(GENERATED)
    if os.path.isdir(SHARED):
        scenes += [os.path.join(SHARED, s) for s in SHARED_SCENES if os.path.exists(os.path.join(SHARED, s))]
    else:
        print(f"bench-skip: {SHARED} not found, generated scenes only")
    rows, ok = [], True
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            name = os.path.basename(scene)
            print(f"bench-skip: {name} ...", flush=True)
            gpng, gen = render(scene, ["--general"], tmp, "general")
            spng, spec = render(scene, [], tmp, "special")
            same = subprocess.run([BIN, "compare", gpng, spng, "--psnr-min", "1000"],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode == 0
            ok &= same
            rows.append({"scene": name, "skips": profile_bits(scene), "same_image": same,
                         "general": {k: gen[k] for k in COUNTERS} | {"cycles": gen["cycle"]["cycles"]},
                         "special": {k: spec[k] for k in COUNTERS} | {"cycles": spec["cycle"]["cycles"]}})
    json.dump(rows, open(os.path.join(args.out, "skip.json"), "w"), indent=1)

    def pct(r, k):
        g, s = r["general"][k], r["special"][k]
        return f"{g} -> {s} ({100.0 * (s - g) / g:+.1f}%)" if g else "0"

    with open(os.path.join(args.out, "skip.md"), "w") as f:
        f.write("# Skipping what a scene does not need: general vs specialized pipeline\n\n"
                "`make bench-skip` (tests/bench/bench_skip.py): `render --mode cycle` 256x192, ray depth 3 with "
                "shadows, 1 pipe, 32 threads, 90 MHz; general = `--general`, specialized = the scene profile's "
                "skips (saarcor profile). Images are compared bit for bit.\n\n"
                "| scene | skips | same image | cycles | intersections | transformations | traversal steps | "
                "leaves | list entries | words read |\n|---|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            f.write(f"| {r['scene']} | {r['skips']} | {'yes' if r['same_image'] else 'NO'} | {pct(r, 'cycles')} | "
                    f"{pct(r, 'intersections')} | {pct(r, 'transformations')} | {pct(r, 'traversal_steps')} | "
                    f"{pct(r, 'leaves')} | {pct(r, 'list_entries')} | {pct(r, 'words_read')} |\n")
    print(open(os.path.join(args.out, "skip.md")).read())
    if not ok:
        print("bench-skip: FAILED: an image differs between the general and the specialized pipeline")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
