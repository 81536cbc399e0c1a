#!/usr/bin/env python3
"""make bench-longrun: memory of long animations. Renders frames 0..999 of the generated animated
scene (saarcor gen animated) in functional and in cycle mode at a small size, with --stats per
frame, and reports the program's resident set (VmRSS) and its peak (VmHWM) after frame 10 and
after frame 1000, from the host_rss_kb / host_peak_rss_kb fields each frame's stats file holds.
Constant memory means the two rows' figures agree within allocator noise. Writes
build/bench/longrun.md and longrun.json (one object per table row, keys = the column names, with
machine, command and date)."""
import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

BIN = "build/saarcor"
FRAMES = 1000
WIDTH, HEIGHT = 64, 48
COLUMNS = ["mode", "frames", "size", "rss_kb_frame_10", "rss_kb_frame_1000", "peak_rss_kb_frame_10",
           "peak_rss_kb_frame_1000", "peak_growth_kb", "max_rss_kb", "seconds"]


def machine():
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    return f"{platform.node()} ({os.cpu_count()} cores, {cpu})"


def run(mode, frames, tmp):
    out = os.path.join(tmp, mode)
    os.makedirs(out)
    cmd = [BIN, "render", "animated", "--mode", mode, "--frames", f"0:{frames - 1}", "--width", str(WIDTH),
           "--height", str(HEIGHT), "--threads", "2", "-o", os.path.join(out, "f.png"),
           "--stats", os.path.join(out, "s.json")]
    t0 = time.time()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    secs = time.time() - t0
    stats = [json.load(open(os.path.join(out, f"s_{f:04d}.json"))) for f in range(frames)]
    at = lambda n, k: stats[n - 1][k]  # frame n counted from 1: the n-th frame rendered
    return {"mode": mode, "frames": frames, "size": f"{WIDTH}x{HEIGHT}",
            "rss_kb_frame_10": at(10, "host_rss_kb"), "rss_kb_frame_1000": at(frames, "host_rss_kb"),
            "peak_rss_kb_frame_10": at(10, "host_peak_rss_kb"), "peak_rss_kb_frame_1000": at(frames, "host_peak_rss_kb"),
            "peak_growth_kb": at(frames, "host_peak_rss_kb") - at(10, "host_peak_rss_kb"),
            "max_rss_kb": max(s["host_rss_kb"] for s in stats), "seconds": round(secs, 1)}, " ".join(cmd)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="build/bench")
    ap.add_argument("--frames", type=int, default=FRAMES)
    args = ap.parse_args()
    if args.frames < 10:
        sys.exit("bench_longrun: --frames must be at least 10")
    os.makedirs(args.out, exist_ok=True)
    stamp = {"machine": machine(), "date": datetime.datetime.now().isoformat(timespec="seconds")}
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for mode in ("functional", "cycle"):
            print(f"bench-longrun: {mode}, {args.frames} frames ...", flush=True)
            row, cmd = run(mode, args.frames, tmp)
            rows.append(row | {"command": cmd} | stamp)
    json.dump(rows, open(os.path.join(args.out, "longrun.json"), "w"), indent=1)
    last = f"frame_{args.frames}"
    head = [c.replace("frame_1000", last) for c in COLUMNS]
    md = ["# Long runs: memory over an animation of the animated scene", "",
          f"`{BIN} render animated --frames 0:{args.frames - 1}` at {WIDTH}x{HEIGHT}, 2 host threads; resident set "
          "(VmRSS) and its peak (VmHWM) in KiB after the 10th and the last frame, from each frame's `--stats`. "
          "Constant memory: peak_growth_kb near 0.", "",
          "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    md += ["| " + " | ".join(str(r[c]) for c in COLUMNS) + " |" for r in rows]
    md += ["", f"Machine: {stamp['machine']}; date {stamp['date']}; `make bench-longrun`."]
    open(os.path.join(args.out, "longrun.md"), "w").write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
