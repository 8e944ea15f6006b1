#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Solid solver scaling: time per level (assembly / MUMPS), peak memory per rank and
# factorizations per level against DOFs, on 1 and 2 ranks. Tet10 cantilever meshes
# (cases/solid/cantilever/beam.geo, n = 2, 4, 6, 8 cells across: ~6 k ... ~280 k DOFs).
# usage: bench/solid-scaling/run.sh [OUT_DIR]   env: SCALING_LEVELS ("2 4 6 8"), SCALING_RANKS ("1 2"),
#        SOLID_APP (default $FSI_BUILD_DIR/bin/solid-app). Prints a table; writes OUT_DIR/scaling.csv.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
source "$root/scripts/env.sh"
app=${SOLID_APP:-$FSI_BUILD_DIR/bin/solid-app}
out=${1:-$root/runs/solid-scaling}
mkdir -p "$out"
csv=$out/scaling.csv
echo "n,dofs,ranks,wall_s,first_level_assembly_s,first_level_linear_s,later_level_linear_s,max_rss_mb_per_rank,analyses,factorizations,levels" > "$csv"
printf "%6s %8s %5s %8s %10s %10s %10s %10s %6s\n" n dofs ranks wall_s asm_l0_s mumps_l0_s mumps_l3_s rss_MB fact/lv
for n in ${SCALING_LEVELS:-2 4 6 8}; do
  run=$out/n$n
  mkdir -p "$run"
  [ -f "$run/beam.msh" ] || gmsh -3 -order 2 -setnumber n "$n" "$root/cases/solid/cantilever/beam.geo" \
                            -o "$run/beam.msh" > "$run/log.gmsh" 2>&1
  cp "$here/bench.yaml" "$run/"
  for ranks in ${SCALING_RANKS:-1 2}; do
    log=$run/log.np$ranks
    start=$(date +%s.%N)
    mpirun --oversubscribe --allow-run-as-root -np "$ranks" /usr/bin/time -f "rss_kb %M" \
      "$app" "$run/bench.yaml" --out "$run/out-np$ranks" > "$log" 2>&1
    wall=$(echo "$(date +%s.%N) - $start" | bc)
    dofs=$(grep -m1 "free dofs" "$log" | sed 's/.*, \([0-9]*\) free dofs.*/\1/')
    rss=$(grep "^rss_kb" "$log" | awk '{ if ($2 > m) m = $2 } END { printf "%.0f", m / 1024 }')
    a0=$(grep "assembly" "$log" | head -1 | sed 's/.*assembly \([0-9.]*\) s.*/\1/')
    l0=$(grep "linear solver" "$log" | head -1 | sed 's/.*linear solver \([0-9.]*\) s.*/\1/')
    l3=$(grep "linear solver" "$log" | tail -1 | sed 's/.*linear solver \([0-9.]*\) s.*/\1/')
    an=$(grep "solid-app: done" "$log" | sed 's/.* \([0-9]*\) analyses.*/\1/')
    fa=$(grep "solid-app: done" "$log" | sed 's/.* \([0-9]*\) factorizations.*/\1/')
    lv=$(grep "solid-app: done" "$log" | sed 's/.*done, \([0-9]*\) level.*/\1/')
    echo "$n,$dofs,$ranks,$wall,$a0,$l0,$l3,$rss,$an,$fa,$lv" >> "$csv"
    printf "%6s %8s %5s %8.2f %10s %10s %10s %10s %6s\n" "$n" "$dofs" "$ranks" "$wall" "$a0" "$l0" "$l3" "$rss" "$fa/$lv"
  done
done
echo "table: $csv"
