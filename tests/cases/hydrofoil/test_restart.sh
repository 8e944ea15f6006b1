#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# tests/cases/hydrofoil/test_restart.sh WORK [--mesh-from RUNDIR]
#
# Restart of the main job: the coarse viscoelastic hydrofoil to t = 2 s (levels 0, 0.5, 2 s) is
# run once uninterrupted; a second run is killed (SIGKILL to its fluid-app processes, found by
# this run's case path) once level 1 is checkpointed, then continued with run.sh --restart. Every
# level's tip AOA must match within 1e-4 deg and Fy within 1e-5 relative (the coupling tolerance
# 5e-6 m of interface displacement). Measured 2026-11-22: 5.9e-6 deg, 3.4e-6. Then the finished,
# restarted run is extended with run.sh --restart --end 4: it must continue from its 2 s level to
# a last level at 4 s, keep every earlier row of history.csv unchanged and its summary.csv as
# summary.csv.part1. Last, scripts/converged-flow on the uninterrupted run's 2 s level: the
# accepted force within 1 % of the converged flow at that geometry. Needs fluid-app and solid-app
# on PATH and FSI_ROOT; meshes the coarse preset unless --mesh-from is given.
set -euo pipefail
work=${1:?usage: test_restart.sh WORK [--mesh-from RUNDIR]}
shift
meshArgs=()
[ "${1:-}" = --mesh-from ] && meshArgs=(--mesh-from "$2")
: "${FSI_ROOT:?set FSI_ROOT to the repository}"
opts=(--material viscoelastic --end 2)
rm -rf "$work"; mkdir -p "$work"
for d in ref kill; do mkdir -p "$work/$d"; cp -r "$FSI_ROOT/cases/hydrofoil/." "$work/$d/"; done
if [ ${#meshArgs[@]} -eq 0 ]; then
  # the snappy mesh (the paper's setup): a short, cheap history; later runs follow its mesh
  (cd "$work/ref" && ./run.sh "${opts[@]}" --fluid-mesh snappy > out.txt 2>&1)
  meshArgs=(--mesh-from "$work/ref")
else
  (cd "$work/ref" && ./run.sh "${opts[@]}" "${meshArgs[@]}" > out.txt 2>&1)
fi
echo "reference run done"
(cd "$work/kill" && ./run.sh "${opts[@]}" "${meshArgs[@]}" > out.txt 2>&1) &
runner=$!
latest=$work/kill/results/visco/checkpoint/latest
for _ in $(seq 1 1800); do
  level=$(sed -n 's/^level //p' "$latest" 2>/dev/null || true)
  [ -n "$level" ] && [ "$level" -ge 1 ] && break
  sleep 0.5
done
pids=""
for p in $(pgrep -x fluid-app || true); do   # this run's fluid-app processes only, not mpirun
  tr '\0' ' ' < "/proc/$p/cmdline" 2>/dev/null | grep -q -- "-case $work/kill/fluid-visco" && pids="$pids $p"
done
[ -n "$pids" ] || { echo "FAIL: no fluid-app of the second run to kill (it finished or failed first)"; exit 1; }
echo "killing fluid-app $pids after level $level"
kill -9 $pids
if wait "$runner"; then echo "FAIL: the killed run reported success"; exit 1; fi
(cd "$work/kill" && ./run.sh "${opts[@]}" --restart > out.restart.txt 2>&1) ||
  { echo "FAIL: the restart failed:"; tail -5 "$work/kill/out.restart.txt"; exit 1; }
"${FSI_PYTHON:-/usr/bin/python3}" - "$work/ref/results/visco/history.csv" "$work/kill/results/visco/history.csv" <<'PY'
import csv, sys
a, b = (list(csv.DictReader(open(p))) for p in sys.argv[1:])
assert [r["level"] for r in a] == [r["level"] for r in b], "levels differ: %s vs %s" % (
    [r["level"] for r in a], [r["level"] for r in b])
angle = next(k for k in a[0] if k.endswith("_deg"))
worst_deg = max(abs(float(x[angle]) - float(y[angle])) for x, y in zip(a, b))
worst_fy = max(abs(float(x["Fy"]) - float(y["Fy"])) / abs(float(x["Fy"])) for x, y in zip(a, b))
print("largest difference: %s %.1e deg, Fy %.1e relative" % (angle, worst_deg, worst_fy))
if worst_deg > 1e-4 or worst_fy > 1e-5:
    sys.exit("FAIL: the restarted run does not reproduce the uninterrupted one")
print("PASS: restart")
PY
cp "$work/kill/results/visco/history.csv" "$work/history-2s.csv"
(cd "$work/kill" && ./run.sh --material viscoelastic --end 4 "${meshArgs[@]}" --restart > out.extend.txt 2>&1) ||
  { echo "FAIL: the extension failed:"; tail -5 "$work/kill/out.extend.txt"; exit 1; }
grep -q "extended to --end 4 s" "$work/kill/out.extend.txt" ||
  { echo "FAIL: run.sh did not extend the finished run:"; tail -5 "$work/kill/out.extend.txt"; exit 1; }
[ -f "$work/kill/results/visco/summary.csv.part1" ] && [ -f "$work/kill/results/visco/summary.csv" ] ||
  { echo "FAIL: summary.csv.part1 (the 2 s run's) and a new summary.csv expected"; exit 1; }
"${FSI_PYTHON:-/usr/bin/python3}" - "$work/history-2s.csv" "$work/kill/results/visco/history.csv" <<'PY'
import csv, sys
before, after = (list(csv.DictReader(open(p))) for p in sys.argv[1:])
if abs(float(after[-1]["time"]) - 4.0) > 1e-9 or len(after) <= len(before):
    sys.exit("FAIL: the extended history ends at %s s with %d levels (%d before)"
             % (after[-1]["time"], len(after), len(before)))
for x, y in zip(before, after):
    for k in x:
        try:
            a, b = float(x[k]), float(y[k])
        except ValueError:
            continue
        if abs(a - b) > 1e-12 * (1 + abs(a)):
            sys.exit("FAIL: level %s's %s changed in the extension: %s -> %s" % (x["level"], k, x[k], y[k]))
print("PASS: extended from %s s to 4 s in %d more levels, earlier rows kept"
      % (before[-1]["time"], len(after) - len(before)))
PY
# scripts/converged-flow on the uninterrupted run's last level (2 s): the flow at that frozen
# geometry settles (range <= 1e-5 |F| over the second half of its <= 200 SIMPLE iterations) and the
# force the run accepted lies within 1 % of it (measured 2026-12-04: 0.029 %; the medium preset's
# 360 s level: 0.15 %).
"$FSI_ROOT/scripts/converged-flow" "$work/ref/fluid-visco" --iterations 200 --out "$work/converged-2s" \
  > "$work/converged-2s.txt" 2>&1 || { echo "FAIL: converged-flow:"; tail -5 "$work/converged-2s.txt"; exit 1; }
cat "$work/converged-2s.txt"
"${FSI_PYTHON:-/usr/bin/python3}" - "$work/converged-2s.txt" <<'PY'
import sys
line = next(l for l in open(sys.argv[1]) if l.startswith("converged-flow summary:"))
v = dict(kv.split("=") for kv in line.split(":", 1)[1].split())
if abs(float(v["time"]) - 2.0) > 1e-9:
    sys.exit("FAIL: converged-flow took time %s, the run's last level is 2 s" % v["time"])
print("converged-flow: accepted vs converged %.2e |F|, converged spread %.1e |F|"
      % (float(v["error_rel"]), float(v["spread_rel"])))
if not float(v["spread_rel"]) <= 1e-5:
    sys.exit("FAIL: the frozen-geometry flow did not settle")
if not float(v["error_rel"]) <= 0.01:
    sys.exit("FAIL: the accepted flow is %s |F| from the converged one (> 1 %%)" % v["error_rel"])
print("PASS: converged-flow")
PY
