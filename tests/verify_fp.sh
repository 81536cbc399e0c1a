#!/usr/bin/env bash
# make verify-fp: the big fp24 verification. For every format, `saarcor f24verify` checks the
# integer and fast paths against MPFR on the edge set plus N random vectors per operation, and
# every input of the unary operations for formats of at most 24 bits. Formats run in parallel
# (one per core). Writes build/verify-fp/<format>.{txt,json} and build/verify-fp/report.md.
# Usage: tests/verify_fp.sh BUILD N FORMAT...
set -euo pipefail
build=$1 n=$2
shift 2
out=$build/verify-fp
mkdir -p "$out"
echo "verify-fp: $n random vectors per operation, formats: $*  (logs in $out/)"
t0=$(date +%s)
printf '%s\n' "$@" | xargs -P "$(nproc)" -I{} bash -c '
  "$0/w/{}/saarcor" f24verify -n "$1" --exhaustive --json "$2/{}.json" >"$2/{}.txt" 2>&1
  rc=$?; echo $rc >"$2/{}.rc"; echo "  {}: $(tail -1 "$2/{}.txt") (exit $rc)"' "$build" "$n" "$out"
python3 - "$out" "$n" "$(( $(date +%s) - t0 ))" "$@" <<'PY'
import json, sys
out, n, secs, formats = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]
rows, bad = [], 0
for f in formats:
    d = json.load(open(f"{out}/{f}.json"))
    for kind in ("random", "exhaustive"):
        rs = [r for r in d["results"] if r["set"] == kind]
        if not rs:
            continue
        hw = sum(r["hw_mismatches"] for r in rs); fast = sum(r["fast_mismatches"] for r in rs)
        bad += hw + fast
        rows.append((f, kind, len(rs), sum(r["vectors"] for r in rs), hw, fast, sum(r["seconds"] for r in rs)))
with open(f"{out}/report.md", "w") as o:
    o.write(f"# fp24 verification against MPFR\n\n`make verify-fp`: edge set + {n:,} random vectors per "
            f"operation, exhaustive unary operations for formats of at most 24 bits; wall time {secs} s.\n\n"
            "| format | set | operations | vectors | integer-path mismatches | fast-path mismatches | seconds |\n"
            "|---|---|---|---|---|---|---|\n")
    for r in rows:
        o.write(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]:,} | {r[4]} | {r[5]} | {r[6]:.1f} |\n")
    o.write(f"\n**{'ALL RESULTS AGREE WITH MPFR' if bad == 0 else f'{bad} MISMATCHES'}**\n")
print(open(f"{out}/report.md").read())
sys.exit(1 if bad else 0)
PY
