#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Turek-Hron CFD1 (steady, Re 20): drag and lift on cylinder + beam [N/m]
# against 14.29 / 1.119 on coarse, medium, fine (serial) and fine on 2 ranks.
# Driven by scripts/verify cfd1; writes $FSI_VERIFY_DIR/error_vs_runtime.csv.
# CFD1_LEVELS overrides the level list (e.g. "coarse medium").
set -euo pipefail
: "${FSI_VERIFY_DIR:?run through scripts/verify cfd1}"
root=${FSI_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
case_dir=$root/cases/turek-hron-cfd1
export FLUID_APP=${FLUID_APP:-${FSI_BUILD_DIR:-$root/build}/bin/fluid-app}
depth=0.01     # one-cell depth of cases/turek-hron-cfd1/blockMesh.py
drag_ref=14.29
lift_ref=1.119
levels=${CFD1_LEVELS:-"coarse:1 medium:1 fine:1 fine:2"}
csv=$FSI_VERIFY_DIR/error_vs_runtime.csv
echo "level,size,cores,wall_s,quantity,value,reference,rel_error" > "$csv"
for lc in $levels; do
  level=${lc%%:*}; cores=${lc##*:}
  run=$FSI_VERIFY_DIR/run-$level-np$cores
  echo "cfd1: $level on $cores core(s) in $run"
  "$case_dir/Allrun" "$level" "$run" "$cores" > /dev/null
  cells=$(grep -m1 "nCells:" "$run/log.blockMesh" | awk '{print $2}')
  wall=$(cat "$run/wall_s")
  force=$(grep "fsi: rigid force" "$run/log.fluid-app" | tail -1 | sed 's/.*total (\([^)]*\)).*/\1/')
  fx=$(echo "$force" | awk '{print $1}'); fy=$(echo "$force" | awk '{print $2}')
  awk -v l="$level" -v n="$cells" -v c="$cores" -v w="$wall" -v fx="$fx" -v fy="$fy" \
      -v d="$depth" -v dr="$drag_ref" -v lr="$lift_ref" 'BEGIN {
    drag = fx / d; lift = fy / d;
    printf "%s,%s,%s,%s,drag,%.6f,%s,%.6e\n", l, n, c, w, drag, dr, (drag - dr) / dr;
    printf "%s,%s,%s,%s,lift,%.6f,%s,%.6e\n", l, n, c, w, lift, lr, (lift - lr) / lr }' >> "$csv"
done
cat "$csv"
