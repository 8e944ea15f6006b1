#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Turek-Hron CSM1 (static, gravity 2 m/s^2, St Venant-Kirchhoff, total Lagrangian, plane
# strain as a one-cell-thick Hex20 slab): ux(A), uy(A) against -7.187e-3 / -6.610e-2 m.
# Driven by scripts/verify csm1; writes $FSI_VERIFY_DIR/error_vs_runtime.csv.
# CSM1_LEVELS: "n:cores ..." (n = Hex20 cells through the beam depth; default 1:1 2:1 4:1 8:1 8:2).
# CSM1_ARC=0: clamp a straight edge at x = 0.25 instead of the cylinder arc.
set -euo pipefail
: "${FSI_VERIFY_DIR:?run through scripts/verify csm1}"
root=${FSI_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
source "$(dirname "$0")/solid-common"
case_dir=$root/cases/solid/csm1
levels=${CSM1_LEVELS:-"1:1 2:1 4:1 8:1 8:2"}
csv=$FSI_VERIFY_DIR/error_vs_runtime.csv
echo "level,size,cores,wall_s,quantity,value,reference,rel_error" > "$csv"
for lc in $levels; do
  n=${lc%%:*}; cores=${lc##*:}
  run=$FSI_VERIFY_DIR/run-n$n-np$cores
  mkdir -p "$run"
  gmsh -3 -order 2 -setnumber n "$n" -setnumber arc "${CSM1_ARC:-1}" "$case_dir/csm1.geo" \
       -o "$run/csm1.msh" > "$run/log.gmsh" 2>&1
  cp "$case_dir/csm1.yaml" "$run/"
  run_solid "$run/csm1.yaml" "$run/output" "$run/log.solid-app" "$cores"
  echo "csm1: n=$n on $cores core(s): $dofs dofs, $wall s ($run)"
  tail -1 "$run/output/history.csv" | awk -F, -v l="n$n" -v s="$dofs" -v c="$cores" -v w="$wall" '{
    ux = $2; uy = $3; rx = -7.187e-3; ry = -6.610e-2;
    printf "%s,%s,%s,%.3f,ux_A,%.6e,%s,%.6e\n", l, s, c, w, ux, rx, (ux - rx) / rx;
    printf "%s,%s,%s,%.3f,uy_A,%.6e,%s,%.6e\n", l, s, c, w, uy, ry, (uy - ry) / ry }' >> "$csv"
done
cat "$csv"
