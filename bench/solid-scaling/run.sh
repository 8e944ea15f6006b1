#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Solid linear-solver scaling: MUMPS factorization / solve time, CPU time, peak memory and
# accuracy against DOFs, on 1 and 2 ranks, per linear-solver setting, with solid-bench (a
# structured Tet10 box, nu = 0.49, clamped at x = 0, gravity; one static solve). Two shapes:
#   plate  NX x NX/2 x 2 cells: 2 cells through the thickness like the fine foil's Tet10 mesh;
#          40 k ... 1.02 M dofs (a 3-D block of 1 M dofs needs 15-19 GB in core: over budget)
#   block  16k x 8k x k cells, the foil's span:chord:thickness: 32 k ... 428 k dofs
# One line per case:
#   solid-bench: dofs=N ranks=R factor_s=X solve_s=X rss_mb=X analysis_s=X ... blr=on|off ...
# Variants (SCALING_VARIANTS):
#   default    this branch's defaults (METIS on the supervariable graph, OpenBLAS, low_rank off)
#   fullrank   the same, low_rank off explicitly
#   blr        low_rank on at SCALING_BLR_TOLERANCE (needs MUMPS with SCOTCH)
#   pord       MUMPS' own PORD ordering instead of METIS (low_rank off)
#   old        the settings before issue 14: reference BLAS (LD_LIBRARY_PATH to Debian's
#              libblas3/liblapack3), low_rank off
# Sizes: SCALING_SIZES, NX,NY,NZ cell triples; default the plate series 36,18,2 64,32,2 96,48,2
# 130,65,2 184,92,2 (40 k, 125 k, 279 k, 511 k, 1.02 M dofs) then the block series 32,16,2
# 48,24,3 64,32,4 80,40,5 (32 k, 99 k, 225 k, 428 k). Cases whose MUMPS estimate (analysis
# only, solid-bench --estimate) exceeds SCALING_MAX_MB (default 9000, total over ranks) are
# reported as skipped, not run. The "old" variant runs only up to SCALING_OLD_MAX_DOFS (300000).
# The real fine foil: with SCALING_FOIL_MESH=/path/foil-tet10.msh (cases/hydrofoil/mesh.sh --out
# DIR --preset fine --solid-only: DIR/solid/foil-tet10.msh) solid-app runs foil.yaml (one static
# solve, 493 k dofs) per rank count and variant fullrank / blr / old first, and prints the same
# line with mesh=foil (factor_cpu_s: rank 0's; cpu_s: all ranks' whole run).
# usage: bench/solid-scaling/run.sh [OUT_DIR]   (prints the lines; OUT_DIR/bench.log keeps them)
#   env: SCALING_SIZES, SCALING_RANKS ("1 2"), SCALING_VARIANTS ("fullrank blr pord old"),
#        SCALING_BLR_TOLERANCE (1e-7), SCALING_MAX_MB, SCALING_OLD_MAX_DOFS, SOLID_BENCH
#        (default $FSI_BUILD_DIR/bin/solid-bench). Runs niced (nice -n 5), one case at a time.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
source "$root/scripts/env.sh"
bench=${SOLID_BENCH:-$FSI_BUILD_DIR/bin/solid-bench}
out=${1:-$root/runs/solid-scaling}
mkdir -p "$out"
log=$out/bench.log
maxMb=${SCALING_MAX_MB:-9000}
oldMax=${SCALING_OLD_MAX_DOFS:-300000}
sizes=${SCALING_SIZES:-36,18,2 64,32,2 96,48,2 130,65,2 184,92,2 32,16,2 48,24,3 64,32,4 80,40,5}
blrTol=${SCALING_BLR_TOLERANCE:-1e-7}
refBlas=/usr/lib/x86_64-linux-gnu/blas:/usr/lib/x86_64-linux-gnu/lapack
[ -x "$bench" ] || { echo "run.sh: $bench not found; build the solid-bench target" >&2; exit 1; }
{
  echo "# solid-scaling $(date -u +%FT%TZ) commit $(git -C "$root" rev-parse --short HEAD) on $(hostname)"
  echo "# load: $(uptime)"
} | tee -a "$log"
app=${SOLID_APP:-$FSI_BUILD_DIR/bin/solid-app}
if [ -n "${SCALING_FOIL_MESH:-}" ]; then
  for ranks in ${SCALING_RANKS:-1 2}; do
    for variant in ${SCALING_FOIL_VARIANTS:-fullrank blr old}; do
      solver="{low_rank: off, check_residual: true}" env=()
      case $variant in
        blr) solver="{low_rank: on, low_rank_tolerance: $blrTol}" ;;
        old) env=(LD_LIBRARY_PATH="$refBlas${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}") ;;
      esac
      run=$out/foil-$variant-np$ranks
      mkdir -p "$run"
      sed -e "s#@MESH@#$SCALING_FOIL_MESH#" -e "s#@LINEAR_SOLVER@#$solver#" "$here/foil.yaml" > "$run/foil.yaml"
      (ulimit -v $(( (maxMb / ranks + 2500) * 1024 )); env "${env[@]}" nice -n 5 mpirun -np "$ranks" \
        /usr/bin/time -f "rss_kb %M cpu_s %U %S" "$app" "$run/foil.yaml" --out "$run/out" > "$run/log" 2>&1) || true
      t=$(grep "linear solver totals" "$run/log" || true)
      if [ -z "$t" ]; then echo "solid-bench: mesh=foil ranks=$ranks variant=$variant failed (see $run/log)" | tee -a "$log"; continue; fi
      dofs=$(sed -n 's/.*, \([0-9]*\) free dofs.*/\1/p' "$run/log" | head -1)
      rss=$(awk '/^rss_kb/ { if ($2 > m) m = $2 } END { printf "%.0f", m / 1024 }' "$run/log")
      cpu=$(awk '/^rss_kb/ { c += $4 + $5 } END { printf "%.2f", c }' "$run/log")
      fcpu=$(sed -n 's/.*factorization [0-9.]* s (cpu \([0-9.]*\)).*/\1/p' <<< "$t")
      blr=$(sed -n 's/.*BLR \(on\|off\).*/\1/p' <<< "$t")
      res=$(sed -n 's/.*last checked residual \([0-9.e+-]*\).*/\1/p' <<< "$t")
      mem=$(sed -n 's/.*factorization memory \([0-9]*\) MB.*/\1/p' <<< "$t")
      bwd=$(sed -n 's/.*backward error \([0-9.e+-]*\)).*/\1/p' <<< "$t")
      echo "solid-bench: dofs=$dofs ranks=$ranks factor_s=$(sed -n 's/.*factorization \([0-9.]*\) s.*/\1/p' <<< "$t") solve_s=$(sed -n 's/.*solve \([0-9.]*\) s.*/\1/p' <<< "$t") rss_mb=$rss analysis_s=$(sed -n 's/.*analysis \([0-9.]*\) s.*/\1/p' <<< "$t") factor_cpu_s=$fcpu cpu_s=$cpu blr=$blr residual=$res backward_error=$bwd mumps_mb=$mem mesh=foil variant=$variant load=$(cut -d' ' -f1 /proc/loadavg)" | tee -a "$log"
    done
  done
fi
for size in $sizes; do
  IFS=, read -r nx ny nz <<< "$size"
  for ranks in ${SCALING_RANKS:-1 2}; do
    for variant in ${SCALING_VARIANTS:-fullrank blr pord old}; do
      args=(--cells "$nx" "$ny" "$nz") env=()
      case $variant in
        default) ;;
        fullrank) args+=(--low-rank off) ;;
        blr) args+=(--low-rank on --tolerance "$blrTol") ;;
        pord) args+=(--low-rank off --ordering pord) ;;
        old) args+=(--low-rank off) env=(LD_LIBRARY_PATH="$refBlas${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}") ;;
        *) echo "run.sh: unknown variant $variant" >&2; exit 1 ;;
      esac
      est=$(env "${env[@]}" mpirun -np "$ranks" "$bench" "${args[@]}" --estimate 2>&1 | grep "estimate" || true)
      mb=$(sed -n 's/.*mumps_mb=\([0-9]*\).*/\1/p' <<< "$est")
      dofs=$(sed -n 's/.*dofs=\([0-9]*\).*/\1/p' <<< "$est")
      if [ -z "$mb" ]; then echo "solid-bench: cells=$nx,$ny,$nz ranks=$ranks variant=$variant estimate failed: $est" | tee -a "$log"; continue; fi
      if [ "$variant" = blr ]; then :; elif [ "$mb" -gt "$maxMb" ]; then
        echo "solid-bench: dofs=$dofs ranks=$ranks variant=$variant skipped: MUMPS estimate $mb MB > $maxMb MB (SCALING_MAX_MB)" | tee -a "$log"; continue
      fi
      if [ "$variant" = old ] && [ "$dofs" -gt "$oldMax" ]; then continue; fi
      # a guard against a BLR case that compresses less than hoped: address space per rank
      line=$(ulimit -v $(( (maxMb / ranks + 2500) * 1024 )); env "${env[@]}" nice -n 5 mpirun -np "$ranks" "$bench" "${args[@]}" 2>&1 | grep -E "^solid-bench:|rror|fault" | head -3 || true)
      echo "$line variant=$variant load=$(cut -d' ' -f1 /proc/loadavg)" | tee -a "$log"
    done
  done
done
