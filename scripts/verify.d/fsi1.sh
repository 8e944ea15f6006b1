#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Turek-Hron FSI1 (steady, coupled fluid-app + solid-app, MPMD, 1 + 1 ranks): ux(A), uy(A)
# [m] and drag, lift on cylinder + beam [N/m] (force / depth 0.01 m) against the Featflow
# finest values, on the presets coarse, medium, fine of cases/turek-hron-fsi1.
# Driven by scripts/verify fsi1; writes $FSI_VERIFY_DIR/error_vs_runtime.csv
# (size = fluid cells; the beam's Hex20 cells are in $FSI_VERIFY_DIR/run-LEVEL/mesh_size).
# FSI1_LEVELS overrides the preset list (e.g. "coarse medium"); FSI1_LAUNCH mpmd|port;
# FSI1_REUSE=1 keeps a level whose run folder already has results/benchmark.csv (no re-run).
set -euo pipefail
: "${FSI_VERIFY_DIR:?run through scripts/verify fsi1}"
root=${FSI_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
export FSI_ROOT=$root
case_dir=$root/cases/turek-hron-fsi1
export PATH=${FSI_BUILD_DIR:-$root/build}/bin:$PATH
levels=${FSI1_LEVELS:-"coarse medium fine"}
launch=${FSI1_LAUNCH:-mpmd}
cores=2   # 1 fluid rank + 1 solid rank
csv=$FSI_VERIFY_DIR/error_vs_runtime.csv
echo "level,size,cores,wall_s,quantity,value,reference,rel_error" > "$csv"
for level in $levels; do
  run=$FSI_VERIFY_DIR/run-$level
  if [ "${FSI1_REUSE:-0}" = 1 ] && [ -f "$run/results/benchmark.csv" ]; then
    echo "fsi1: $level: reusing $run"
  else
    echo "fsi1: $level in $run"
    rm -rf "$run"
    cp -r "$case_dir" "$run"
    (cd "$run" && ./run.sh --preset "$level" --launch "$launch" > log.run 2>&1) ||
      { echo "error: fsi1 $level failed, see $run/log.run" >&2; tail -5 "$run/log.run" >&2; exit 1; }
  fi
  cells=$(awk '{print $1}' "$run/mesh_size")
  wall=$(cat "$run/results/wall_s")
  # benchmark.csv: level,time,quantity,value,reference,rel_error (one level: t = 0)
  awk -F, -v l="$level" -v n="$cells" -v c="$cores" -v w="$wall" \
      'NR > 1 { printf "%s,%s,%s,%s,%s,%s,%s,%s\n", l, n, c, w, $3, $4, $5, $6 }' \
      "$run/results/benchmark.csv" >> "$csv"
  cat "$run/results/summary.txt"
done
cat "$csv"
