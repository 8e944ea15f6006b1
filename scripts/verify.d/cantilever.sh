#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Slender cantilever (2 x 0.1 x 0.1 m, E = 2 GPa, nu = 0, tip shear 1000 N): tip deflection
# against Timoshenko beam theory P L^3/(3 E I) + P L/(kappa G A), kappa = 5/6 (1.60240e-1 m).
# Tet10 (n = 1, 2, 3, 4 cells through the depth, 20 n along) and Hex20 (n = 2, 3, 4; Hex20 with
# 2x2x2 reduced integration needs >= 2 cells across unconstrained directions: with one cell its
# spurious modes connect along the beam and MUMPS reports a singular matrix).
# CANTILEVER_LEVELS: "tet:n:cores hex:n:cores ..."; driven by scripts/verify cantilever.
set -euo pipefail
: "${FSI_VERIFY_DIR:?run through scripts/verify cantilever}"
root=${FSI_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
source "$(dirname "$0")/solid-common"
case_dir=$root/cases/solid/cantilever
levels=${CANTILEVER_LEVELS:-"tet:1:1 tet:2:1 tet:3:1 tet:4:1 hex:2:1 hex:3:1 hex:4:1 tet:4:2"}
ref=$(awk 'BEGIN { P = 1000; L = 2; E = 2e9; G = E / 2; b = 0.1; h = 0.1; I = b * h^3 / 12;
                   printf "%.10e", P * L^3 / (3 * E * I) + P * L / (5 / 6 * G * b * h) }')
csv=$FSI_VERIFY_DIR/error_vs_runtime.csv
echo "level,size,cores,wall_s,quantity,value,reference,rel_error" > "$csv"
for spec in $levels; do
  kind=${spec%%:*}; rest=${spec#*:}; n=${rest%%:*}; cores=${rest##*:}
  hex=0; [ "$kind" = hex ] && hex=1
  run=$FSI_VERIFY_DIR/run-$kind-n$n-np$cores
  mkdir -p "$run"
  gmsh -3 -order 2 -setnumber n "$n" -setnumber hex "$hex" "$case_dir/beam.geo" -o "$run/beam.msh" \
       > "$run/log.gmsh" 2>&1
  cp "$case_dir/cantilever.yaml" "$run/"
  run_solid "$run/cantilever.yaml" "$run/output" "$run/log.solid-app" "$cores"
  echo "cantilever: $kind n=$n on $cores core(s): $dofs dofs, $wall s"
  name=Tet10; [ "$hex" = 1 ] && name=Hex20
  tail -1 "$run/output/history.csv" | awk -F, -v l="$kind-n$n" -v s="$dofs" -v c="$cores" -v w="$wall" \
      -v r="$ref" -v q="tip_deflection_$name" '{
    d = -$3; printf "%s,%s,%s,%.3f,%s,%.6e,%.6e,%.6e\n", l, s, c, w, q, d, r, (d - r) / r }' >> "$csv"
done
cat "$csv"
