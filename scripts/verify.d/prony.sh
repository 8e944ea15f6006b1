#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Viscoelastic creep of a cube (cases/solid/prony): eps_xx at t = 0.1, 1, 10 s against the
# analytic creep compliance of reference/prony.md, for time steps dt = 0.1, 0.05, 0.02, 0.01 s
# (the "levels" of this study are time resolutions; size = number of time levels).
# PRONY_DTS overrides the list; driven by scripts/verify prony.
set -euo pipefail
: "${FSI_VERIFY_DIR:?run through scripts/verify prony}"
root=${FSI_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
source "$(dirname "$0")/solid-common"
case_dir=$root/cases/solid/prony
csv=$FSI_VERIFY_DIR/error_vs_runtime.csv
echo "level,size,cores,wall_s,quantity,value,reference,rel_error" > "$csv"
gmsh -3 -order 2 "$case_dir/cube.geo" -o "$FSI_VERIFY_DIR/cube.msh" > "$FSI_VERIFY_DIR/log.gmsh" 2>&1
for dt in ${PRONY_DTS:-0.1 0.05 0.02 0.01}; do
  run=$FSI_VERIFY_DIR/run-dt$dt
  mkdir -p "$run"
  cp "$FSI_VERIFY_DIR/cube.msh" "$run/"
  sed "s/^    dt: .*/    dt: $dt/; s/^    vtu: true/    vtu: false/" "$case_dir/creep.yaml" > "$run/creep.yaml"
  run_solid "$run/creep.yaml" "$run/output" "$run/log.solid-app"
  levels=$(($(wc -l < "$run/output/history.csv") - 1))
  echo "prony: dt=$dt: $levels levels, $wall s"
  awk -F, -v l="dt$dt" -v s="$levels" -v w="$wall" 'NR > 1 {
    t = $1 + 0; if (t != 0.1 && t != 1 && t != 10) next;
    J = 2e-6 - 4.2504e-7 * exp(-t / 0.142681) - 5.7496e-7 * exp(-t / 14.0173);
    ref = 1e4 * (1 / 9e7 + J / 3);
    printf "%s,%s,1,%.3f,eps_xx(t=%g),%.9e,%.9e,%.6e\n", l, s, w, t, $2, ref, ($2 - ref) / ref }' \
    "$run/output/history.csv" >> "$csv"
done
cat "$csv"
