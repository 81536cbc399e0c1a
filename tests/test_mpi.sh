#!/usr/bin/env bash
# render --mpi and jobs --mpi on localhost (docs/mpi.md): 2 and 3 ranks give the single-process
# image bit for bit in functional and cycle mode (and the same work counters), an animation split
# into frames gives the same files and statistics, jobs run across ranks with failures reported,
# a worker that dies ends the job with an error and a non-zero exit within a timeout, and --mpi
# without the library is a one-line error. Skips with a message if mpirun is missing.
set -u
cd "$(dirname "$0")/.."
B=${BUILD:-build}
T=$(mktemp -d /tmp/saarcor-test-mpi-XXXXXX)
trap 'rm -rf "$T"' EXIT
# we run as root in containers; shared memory without the single-copy mechanism works there
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
SIZE=(--width 96 --height 64 --threads 1)

# shellcheck source=case_lib.sh
source tests/case_lib.sh

mpi() { # ranks, command...
  local n=$1; shift
  timeout 120 mpirun --oversubscribe -np "$n" "$@"
}

# counters of two --stats files agree (all but the wall time and the mpi section); $3: also cycles
same_counters() {
  python3 - "$@" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for d in (a, b):
    for k in ("seconds", "mpi", "cycle", "host_rss_kb", "host_peak_rss_kb", "host"):  # time and host memory differ
        d.pop(k, None)
assert a == b, (a, b)
PY
}

t_render_functional() {
  $B/saarcor render room "${SIZE[@]}" -o "$T/one.png" --stats "$T/one.json" >/dev/null
  for n in 2 3; do
    mpi $n $B/saarcor render room "${SIZE[@]}" --mpi --mpi-tile 32 -o "$T/mpi$n.png" --stats "$T/mpi$n.json" >"$T/out$n"
    cmp "$T/one.png" "$T/mpi$n.png"
    same_counters "$T/one.json" "$T/mpi$n.json"
    grep -q "^mpi: $n ranks ($((n - 1)) worker boards), 6 items" "$T/out$n"
  done
  echo "2 and 3 ranks: the single-process image and counters"
}

# every board holds the whole memory image: boards x the single-process upload of the frame
t_image_traffic() {
  $B/saarcor render room "${SIZE[@]}" -o "$T/one.png" >"$T/one.out"
  $B/saarcor info room --json "$T/info.json" >/dev/null
  for n in 2 3; do
    mpi $n $B/saarcor render room "${SIZE[@]}" --mpi --mpi-tile 32 -o "$T/mpi$n.png" --stats "$T/mpi$n.json" >"$T/out$n"
    python3 - "$T/one.out" "$T/info.json" "$T/mpi$n.json" "$T/out$n" <<'PY'
import json, re, sys
one_kb = float(re.search(r"upload ([0-9.]+) KB", open(sys.argv[1]).read()).group(1))
image = 4 * sum(json.load(open(sys.argv[2]))["regions"].values())  # the whole memory image, bytes
m = json.load(open(sys.argv[3]))["mpi"]
assert m["image_bytes_per_board"] == image and f"{image / 1024:.1f}" == f"{one_kb:.1f}", (m, image, one_kb)
assert m["image_upload_bytes_total"] == m["boards"] * image, m
assert f"memory image {one_kb:.1f} KB per board, {m['boards'] * image / 1024:.1f} KB uploaded" in open(sys.argv[4]).read()
PY
  done
  # frames: each board loads the first frame's image, then uploads the changes of its frames
  $B/saarcor gen animated -o "$T/anim.glb" >/dev/null
  mpi 3 $B/saarcor render "$T/anim.glb" --width 48 --height 32 --threads 1 --frames 1:5 --mpi -o "$T/f.png" >"$T/fr"
  python3 - "$T/fr" <<'PY'
import re, sys
out = open(sys.argv[1]).read()
up = {int(f): float(kb) for kb, f in re.findall(r"upload ([0-9.]+) KB -> \S*f_000(\d)\.png", out)}
per, total = map(float, re.search(r"memory image ([0-9.]+) KB per board, ([0-9.]+) KB uploaded", out).groups())
assert per == up[1] and abs(total - (2 * per + sum(up[f] for f in (2, 3, 4, 5)))) < 0.5, (per, total, up)
PY
  echo "image $(python3 -c "import json; m = json.load(open('$T/mpi3.json'))['mpi']; print(m['image_bytes_per_board'], 'bytes per board,', m['image_upload_bytes_total'], 'to 2 boards')"); frames: + the per-frame changes"
}

# bench_precision.py --mpi 2: its renders as jobs across ranks, the same error columns as one process
t_bench_precision() {
  for f in e7m16 e8m23; do
    [[ -x build/w/$f/saarcor ]] || { echo "build/w/$f/saarcor missing (make build/w/$f/saarcor)"; return 1; }
  done
  local args=(--scenes cornell --formats e7m16,e8m23 --size 32x24)
  python3 tests/bench/bench_precision.py "${args[@]}" --out "$T/p1" >/dev/null 2>"$T/p1.err" || { cat "$T/p1.err"; return 1; }
  python3 tests/bench/bench_precision.py "${args[@]}" --out "$T/p2" --mpi 2 >/dev/null 2>"$T/p2.err" || { cat "$T/p2.err"; return 1; }
  grep -c "render\|reference\|compare-hits" "$T/p2/precision/jobs.txt" | grep -qx 7
  python3 - "$T/p1/precision.json" "$T/p2/precision.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for rows in (a, b):
    for r in rows:
        r.pop("functional_s"); r.pop("cycle_s")  # timings differ
assert len(a) == 2 and a == b, (a, b)
print("bench_precision --mpi 2 (cornell, e7m16 + e8m23, 32x24): 7 jobs, rows equal one process's:",
      ", ".join(f"{r['format']} {r['psnr_db']:.2f} dB" for r in a))
PY
}

t_render_cycle() {
  $B/saarcor render room "${SIZE[@]}" --mode cycle -o "$T/one.png" --stats "$T/one.json" >/dev/null
  for n in 2 3; do
    mpi $n $B/saarcor render room "${SIZE[@]}" --mode cycle --mpi --mpi-tile 32 -o "$T/mpi$n.png" --stats "$T/mpi$n.json" >/dev/null
    cmp "$T/one.png" "$T/mpi$n.png"
    same_counters "$T/one.json" "$T/mpi$n.json"
  done
  # combined statistics: the pipes of all boards, deterministic (no timing enters them)
  mpi 3 $B/saarcor render room "${SIZE[@]}" --mode cycle --mpi --mpi-tile 32 -o "$T/again.png" --stats "$T/again.json" >/dev/null
  python3 - "$T/mpi3.json" "$T/again.json" <<'PY'
import json, sys
a, b = (json.load(open(p))["cycle"] for p in sys.argv[1:3])
for d in (a, b):
    d.pop("seconds", None)
assert a == b, "combined cycle statistics differ between two runs"
assert a["pipes"] == 2 and a["tiles"] == 24, (a["pipes"], a["tiles"])
print("3 ranks: same image, counters; cycles", a["cycles"], "on 2 boards, the same in two runs")
PY
}

t_frames() {
  $B/saarcor gen animated -o "$T/anim.glb" >/dev/null
  mkdir -p "$T/s" "$T/m"
  $B/saarcor render "$T/anim.glb" --width 48 --height 32 --threads 1 --mode cycle --frames 1:5 -o "$T/s/f.png" --stats "$T/s/st.json" >/dev/null
  mpi 3 $B/saarcor render "$T/anim.glb" --width 48 --height 32 --threads 1 --mode cycle --frames 1:5 --mpi -o "$T/m/f.png" --stats "$T/m/st.json" >/dev/null
  for f in 1 2 3 4 5; do
    cmp "$T/s/f_000$f.png" "$T/m/f_000$f.png"
    python3 -c "
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for d in (a, b):
    for k in ('seconds', 'host_rss_kb', 'host_peak_rss_kb', 'host'):  # host: what this board's image held before
        d.pop(k, None)
    d['cycle'].pop('seconds', None)
assert a == b" "$T/s/st_000$f.json" "$T/m/st_000$f.json"
  done
  echo "frames 1..5 on 2 workers: same images and statistics (cycles included)"
}

t_jobs() {
  printf '# a comment\ntouch %s/a\n\ntouch %s/b\nexit 3\ntouch %s/c\n' "$T" "$T" "$T" >"$T/jobs.txt"
  set +e
  mpi 3 $B/saarcor jobs --mpi "$T/jobs.txt" >"$T/out" 2>"$T/err"; local rc=$?
  set -e
  [[ $rc -ne 0 ]] || { echo "a failed job must give a non-zero exit"; return 1; }
  grep -q "jobs: 4 run, 1 failed, 2 workers" "$T/out"
  grep -q "job 3 failed with exit status 3" "$T/err"
  ls "$T/a" "$T/b" "$T/c" >/dev/null
  printf 'true\ntrue\n' >"$T/ok.txt"
  mpi 2 $B/saarcor jobs --mpi "$T/ok.txt" | grep "jobs: 2 run, 0 failed"
}

t_rank_death() {
  set +e
  SAARCOR_MPI_FAULT=2:1 timeout 60 mpirun --oversubscribe -np 3 -x SAARCOR_MPI_FAULT \
    $B/saarcor render room "${SIZE[@]}" --mpi --mpi-tile 16 -o "$T/dead.png" >"$T/out" 2>"$T/err"; local rc=$?
  set -e
  [[ $rc -ne 0 && $rc -ne 124 ]] || { echo "exit $rc: expected a non-zero exit, not a timeout"; return 1; }
  grep -q "rank 2 .*exited on signal 9" "$T/err" || { cat "$T/err"; return 1; }
  [[ ! -e "$T/dead.png" ]]
  echo "a dead worker ends the job: exit $rc, $(grep -m1 'exited on signal' "$T/err" | sed 's/^ *//')"
}

t_errors() {
  set +e
  SAARCOR_MPI_LIB="$T/nothing.so" $B/saarcor render room --mpi -o "$T/x.png" 2>"$T/e1"; local a=$?
  $B/saarcor render room "${SIZE[@]}" --mpi -o "$T/x.png" 2>"$T/e2"; local b=$?
  $B/saarcor render room --mpi --aov "$T/a.exr" 2>"$T/e3"; local c=$?
  $B/saarcor render room --mpi --mode cycle --mpi-tile 24 2>"$T/e4"; local d=$?
  SAARCOR_MPI_LIB="$T/nothing.so" $B/saarcor jobs --mpi "$T/none" 2>"$T/e5"; local e=$?
  set -e
  [[ $a -eq 4 && $(wc -l <"$T/e1") -eq 1 ]] && grep -q "cannot load libsaarcor_mpi.so" "$T/e1"
  [[ $b -eq 2 ]] && grep -q "needs at least 2 ranks" "$T/e2"
  [[ $c -eq 2 && $d -eq 2 && $e -eq 4 ]]
  echo "missing library, one rank, --aov, bad --mpi-tile: one-line errors"
}

t_no_libmpi_in_program() {
  ! ldd $B/saarcor | grep -q libmpi || { echo "build/saarcor must not link libmpi"; return 1; }
  ldd $B/libsaarcor_mpi.so | grep -q libmpi
  echo "build/saarcor does not link libmpi; build/libsaarcor_mpi.so does"
}

run_case mpi_errors t_errors
run_case mpi_program_free_of_libmpi t_no_libmpi_in_program
if ! command -v mpirun >/dev/null 2>&1; then
  for c in mpi_render_functional mpi_image_traffic mpi_render_cycle mpi_frames mpi_jobs mpi_bench_precision mpi_rank_death; do
    echo "[ RUN      ] $c"; echo "mpirun not found (install openmpi-bin: make deps)"; echo "[  SKIPPED ] $c"
  done
  exit $((fails != 0))
fi
run_case mpi_render_functional t_render_functional
run_case mpi_image_traffic t_image_traffic
run_case mpi_render_cycle t_render_cycle
run_case mpi_frames t_frames
run_case mpi_jobs t_jobs
run_case mpi_bench_precision t_bench_precision
run_case mpi_rank_death t_rank_death
exit $((fails != 0))
