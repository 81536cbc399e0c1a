#!/usr/bin/env bash
# render --vcd / --vcd-cycles / --usage-plot (docs/cycle-model.md): the waveform parses
# (tests/vcd_reader.py, and GTKWave's vcd2fst when installed), its signals add up to the --stats
# counters over a whole frame, a window holds exactly its cycles and the same values as the whole
# run, the file is the same for any host thread count, and the plot's means are the --stats usage.
set -u
cd "$(dirname "$0")/.."
BIN=${SAARCOR_BIN:-build/saarcor}
T=$(mktemp -d /tmp/saarcor-test-vcd-XXXXXX)
trap 'rm -rf "$T"' EXIT
source tests/case_lib.sh

# a small frame on 2 pipes at 100 MHz (a cycle is 10000 ps)
SCENE=(room --width 48 --height 32 --max-depth 1 --mode cycle --pipes 2 --threads-per-pipe 8 --clock-mhz 100)

py() { PYTHONPATH=tests python3 -c "$@"; }

t_whole_frame() {
  "$BIN" render "${SCENE[@]}" -o "$T/a.png" --stats "$T/a.json" --vcd "$T/a.vcd" --vcd-cycles 0:1000000000 >/dev/null
  py "
import json, vcd_reader
v = vcd_reader.Vcd('$T/a.vcd'); c = json.load(open('$T/a.json'))['cycle']
assert v.timescale == '1ps' and 'one cycle = 10000 ps' in v.comment, (v.timescale, v.comment)
P = 10000
assert v.times[0] == 0 and v.times[-1] == c['cycles'] * P, (v.times[0], v.times[-1], c['cycles'])
end = v.times[-1]
for u, s in c['units'].items():
    busy = sum(v.integral(v.find('dynrtc.pipe%d.%s' % (p, u), 'busy'), 0, end) for p in range(2)) // P
    ops = sum(v.integral(v.find('dynrtc.pipe%d.%s' % (p, u), 'issue'), 0, end) for p in range(2)) // P
    assert busy == s['busy_cycles'] and ops == s['operations'], (u, busy, s['busy_cycles'], ops, s['operations'])
for k in ('kd_nodes', 'lists', 'matrices', 'shading'):
    m = c['memory'][k]
    look = sum(v.integral(v.find('dynrtc.pipe%d.cache_%s' % (p, k), 'lookups'), 0, end) for p in range(2)) // P
    miss = sum(v.integral(v.find('dynrtc.pipe%d.cache_%s' % (p, k), 'misses'), 0, end) for p in range(2)) // P
    assert look == m['lookups'] and miss == m['lookups'] - m['hits'], (k, look, miss, m)
for p in range(2):  # everything requested arrived, every block finished
    for name in ('mem_port.outstanding', 'cache_kd_nodes.fills'):
        sc, n = name.split('.')
        assert v.changes[v.find('dynrtc.pipe%d.%s' % (p, sc), n)][-1][1] == 0, name
    assert v.changes[v.find('dynrtc.pipe%d' % p, 'threads_in_flight')][-1][1] == 0
print('busy, issues, lookups and misses equal --stats over', c['cycles'], 'cycles')
"
}

t_window() {
  "$BIN" render "${SCENE[@]}" -o "$T/a.png" --vcd "$T/all.vcd" --vcd-cycles 0:1000000000 >/dev/null
  "$BIN" render "${SCENE[@]}" -o "$T/b.png" --vcd "$T/w.vcd" --vcd-cycles 1000:3000 >/dev/null
  "$BIN" render "${SCENE[@]}" -o "$T/c.png" --vcd "$T/d.vcd" >/dev/null  # default: cycles 0..19999
  py "
import vcd_reader
P = 10000
a, w, d = (vcd_reader.Vcd('$T/%s.vcd' % n) for n in ('all', 'w', 'd'))
assert w.times[0] == 1000 * P and w.times[-1] == 3000 * P, (w.times[0], w.times[-1])
assert d.times[0] == 0 and d.times[-1] == min(20000 * P, a.times[-1]), (d.times[-1], a.times[-1])
for ident, (scope, name, _) in w.vars.items():  # the window holds the whole run's values
    full = a.find(scope, name)
    assert w.integral(ident, 1000 * P, 3000 * P) == a.integral(full, 1000 * P, 3000 * P), (scope, name)
print('window 1000:3000 and the default window match the whole run')
"
}

t_threads_and_errors() {
  "$BIN" render "${SCENE[@]}" -o "$T/a.png" --vcd "$T/t1.vcd" --threads 1 >/dev/null
  "$BIN" render "${SCENE[@]}" -o "$T/a.png" --vcd "$T/t2.vcd" --threads 2 >/dev/null
  cmp "$T/t1.vcd" "$T/t2.vcd"
  if command -v vcd2fst >/dev/null; then vcd2fst "$T/t1.vcd" "$T/t1.fst" >/dev/null; fi
  for bad in "--vcd-cycles 5:5" "--vcd-cycles 7" "--vcd-cycles a:9" "--mode functional --vcd x.vcd" \
             "--mode cycle --usage-plot x.svg --mpi"; do
    rc=0; "$BIN" render room $bad --vcd "$T/x.vcd" 2>"$T/err" >/dev/null || rc=$?
    [[ $rc -eq 2 && $(wc -l <"$T/err") -eq 1 ]] || { echo "'$bad': exit $rc"; cat "$T/err"; exit 1; }
  done
  rc=0; "$BIN" render "${SCENE[@]}" -o "$T/a.png" --vcd "$T/no/such/dir.vcd" 2>"$T/err" >/dev/null || rc=$?
  [[ $rc -eq 3 && $(wc -l <"$T/err") -eq 1 ]] || { echo "unwritable: exit $rc"; cat "$T/err"; exit 1; }
  echo "same file for 1 and 2 host threads; bad windows exit 2, an unwritable file exit 3"
}

t_usage_plot() {
  "$BIN" render "${SCENE[@]}" -o "$T/a.png" --stats "$T/a.json" --usage-plot "$T/u.svg" >/dev/null
  py "
import json, re, xml.etree.ElementTree as ET
c = json.load(open('$T/a.json'))['cycle']
svg = ET.parse('$T/u.svg').getroot()
ns = '{http://www.w3.org/2000/svg}'
assert len(svg.findall(ns + 'polyline')) == 5
means = {m.group(1): float(m.group(2)) for t in svg.iter(ns + 'text') for m in [re.match(r'(\w+) ([\d.]+)%$', t.text or '')] if m}
names = {'RGS': 'rgs', 'transformation': 'xform', 'traversal': 'trav', 'list': 'list', 'intersection': 'isect'}
for n, k in names.items():
    assert abs(means[n] - 100 * c['units'][k]['usage']) < 0.051, (n, means.get(n), c['units'][k]['usage'])
print('5 lines, legend means equal --stats usage:', means)
"
}

run_case vcd_whole_frame_matches_stats t_whole_frame
run_case vcd_window_bounds t_window
run_case vcd_threads_and_errors t_threads_and_errors
run_case vcd_usage_plot t_usage_plot
exit $((fails != 0))
