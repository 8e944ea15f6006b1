#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Hydrofoil mesh study (cases/hydrofoil, presets coarse / medium / fine): the coupled steady
# ELASTIC baseline (run.sh --material baseline: E = 47.40 MPa, nu = 0.49, the viscoelastic run's
# t = 0 instantaneous state; fluid-app 2 ranks + solid-app 1 rank, Tet10 foil, MPMD).
# Quantities: tip_aoa [deg], tip_deflection [m] (lift-direction, -y, displacement of the tip
# mid-chord: mean of the tip leading and trailing edge points), lift = -Fy and drag = Fx [N].
# Reference: the finest level run (its own rows have rel_error 0); with three levels the
# observed order and a Richardson estimate per quantity go to richardson.csv (information only:
# the snapped meshes are not a geometric refinement sequence, so the order may be meaningless).
# Driven by scripts/verify hydrofoil; writes $FSI_VERIFY_DIR/error_vs_runtime.csv with the
# standard columns (size = fluid cells, cores = MPI ranks, wall_s = coupled solve, meshing
# excluded) and extra trailing columns cpu_s (user + sys of every process of the coupled solve,
# as the machine may be shared), mesh_wall_s, mesh_cpu_s, load1 (load average at the start),
# coupling_iterations, fluid_iterations.
# Environment:
#   HYDROFOIL_LEVELS   preset list, coarse to fine (default "coarse medium fine")
#   HYDROFOIL_RUNS     folder of the mesh-LEVEL/ and run-LEVEL/ folders (default $FSI_VERIFY_DIR)
#   HYDROFOIL_REUSE=1  keep a level's mesh (mesh-LEVEL/mesh/mesh-summary.txt) and finished run
#                      (run-LEVEL: its run time recorded and an accepted row in
#                      results/baseline/history.csv) instead of redoing them; a run stopped
#                      from outside (empty time.run, no accepted row) is done again
#   HYDROFOIL_TIMEOUT  longest wait of either program for the other [s] (default 3600: on fine
#                      the solid's set-up, RBF mapping of 49 k wetted nodes and the first
#                      factorization, took longer than run.sh's default 900 s under load)
#   HYDROFOIL_MAX_ERROR  if set (e.g. 0.10): fail unless every quantity of the second-finest
#                      level is within this relative error of the finest (the CTest check)
#   HYDROFOIL_FLUID_MESH snappy (default) | cgrid: mesh.sh --fluid-mesh (the boundary-layer mesh)
#   HYDROFOIL_FLOW, HYDROFOIL_SCHEME, HYDROFOIL_ALGORITHM  run.sh --flow / --scheme / --algorithm
#                      (defaults laminar, upwind and the case's SIMPLEC)
#   HYDROFOIL_ROOT_WALL wall (default, the paper's tunnel) | slip: run.sh --root-wall
#   HYDROFOIL_OSCILLATION_WINDOW  N: run.sh --oscillation-window N (honest coupled solves: no stop
#                      at a turning point of the force; default unset, the case's off)
#   HYDROFOIL_COUPLING_TOLERANCE  T [m]: run.sh --coupling-tolerance T (the interface tolerance
#                      |r|/sqrt(n); default unset, the case's 5e-6). The coupled state carries an
#                      error of about |last change| x r_last / r_previous in each quantity; near the
#                      case's torsional divergence 5e-6 m was worth 0.5 % of lift (second order, coarse)
#   HYDROFOIL_FLUID_TOLERANCE  F: run.sh --fluid-tolerance F (every coupled solve's force accuracy;
#                      default unset, the case's 5e-5). Its noise in the interface residual is
#                      about 2e-6 m near the case's torsional divergence, so a 1e-6 m coupling
#                      tolerance may stall at 5e-5 (a coarse level with the fine structure did:
#                      cases/hydrofoil/README.md, "The structure's share of the coupled mesh study")
#   HYDROFOIL_BAND_TOLERANCE  B: run.sh --band-tolerance B (a solve without a steady state may be
#                      accepted in the mean when its force stays within +-B |F| over two blocks;
#                      default unset, the case's 2e-3)
#   HYDROFOIL_BAND_MEAN  M: run.sh --band-mean-tolerance M (a solve without a steady state is
#                      accepted in the mean when its two blocks' mean forces differ by <= M |F|;
#                      default unset, the fluid accuracy asked). For a flow that swings about a
#                      mean (second order on the moved fine cgrid mesh: +-0.3 %, means to 5e-5)
#   HYDROFOIL_SOLID_ELEMENT  tet10 (default) | hex20: run.sh --solid-element (Hex20 with the
#                      projected dilatation)
#   HYDROFOIL_SOLID_MESH_FROM  a run or mesh folder, LEVEL in it replaced by the preset (e.g. a
#                      fixed .../mesh-fine): every level's structure meshed as there (run.sh
#                      --solid-mesh-from), so that only the fluid mesh is refined
#   HYDROFOIL_MAPPING  T: run.sh --mapping T (the interface mapping, e.g. moving-least-squares;
#                      default unset, run.sh's for the fluid mesh: nearest-projection on snappy,
#                      moving-least-squares on cgrid)
#   HYDROFOIL_MAPPING_SMOOTHING  R [m]: run.sh --mapping-smoothing R (default unset, run.sh's:
#                      2e-4 on snappy or with HYDROFOIL_MAPPING given, 0 with cgrid's default
#                      mapping; 0 = off)
#   HYDROFOIL_INIT_FROM  a path with LEVEL in it (e.g. .../turbulent-upwind-simple-LEVEL/rigid/case):
#                      each level's fluid starts from that OpenFOAM case's solution (run.sh
#                      --init-from), LEVEL replaced by the preset; must exist for every level
#   HYDROFOIL_GCI_OUT  with three levels: also write the observed order and GCI_fine of the tip
#                      AOA, tip deflection, lift and drag (scripts/history_gci.py --steady) into
#                      this CSV, as model HYDROFOIL_GCI_MODEL (default FLOW-SCHEME-ALGORITHM-
#                      MESH-baseline); the file's rows of other models are kept
set -euo pipefail
: "${FSI_VERIFY_DIR:?run through scripts/verify hydrofoil}"
root=${FSI_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
export FSI_ROOT=$root
case_dir=$root/cases/hydrofoil
export PATH=${FSI_BUILD_DIR:-$root/build}/bin:$PATH
levels=${HYDROFOIL_LEVELS:-"coarse medium fine"}
runs=${HYDROFOIL_RUNS:-$FSI_VERIFY_DIR}
reuse=${HYDROFOIL_REUSE:-0}
timeout=${HYDROFOIL_TIMEOUT:-3600}
npf=2 nps=1
fluidMesh=${HYDROFOIL_FLUID_MESH:-snappy}
flow=${HYDROFOIL_FLOW:-laminar} scheme=${HYDROFOIL_SCHEME:-upwind} algorithm=${HYDROFOIL_ALGORITHM:-}
rootWall=${HYDROFOIL_ROOT_WALL:-wall}
initPattern=${HYDROFOIL_INIT_FROM:-}
oscWindow=${HYDROFOIL_OSCILLATION_WINDOW:-}
couplingTol=${HYDROFOIL_COUPLING_TOLERANCE:-}
band=${HYDROFOIL_BAND_TOLERANCE:-} bandMean=${HYDROFOIL_BAND_MEAN:-}
fluidTol=${HYDROFOIL_FLUID_TOLERANCE:-}
solidElement=${HYDROFOIL_SOLID_ELEMENT:-} solidFromPattern=${HYDROFOIL_SOLID_MESH_FROM:-}
mapType=${HYDROFOIL_MAPPING:-} mapSmoothing=${HYDROFOIL_MAPPING_SMOOTHING:-}
case "$fluidMesh" in snappy|cgrid) ;; *) echo "error: hydrofoil: HYDROFOIL_FLUID_MESH='$fluidMesh' must be snappy or cgrid" >&2; exit 2 ;; esac
# Every level's run options, before anything is meshed or run: run.sh --check-only names a bad
# value (HYDROFOIL_FLOW/SCHEME/ALGORITHM/ROOT_WALL/OSCILLATION_WINDOW/COUPLING_TOLERANCE/FLUID_TOLERANCE/BAND_TOLERANCE/BAND_MEAN/SOLID_*/MAPPING*, a missing init
# case) in one line
runOptions() { # LEVEL: the run.sh options of that level (without --mesh-from) into opts
  opts=(--preset "$1" --material baseline --np-fluid "$npf" --np-solid "$nps" --timeout "$timeout"
        --flow "$flow" --scheme "$scheme" --root-wall "$rootWall")
  [ -z "$algorithm" ] || opts+=(--algorithm "$algorithm")
  [ -z "$oscWindow" ] || opts+=(--oscillation-window "$oscWindow")
  [ -z "$couplingTol" ] || opts+=(--coupling-tolerance "$couplingTol")
  [ -z "$fluidTol" ] || opts+=(--fluid-tolerance "$fluidTol")
  [ -z "$band" ] || opts+=(--band-tolerance "$band")
  [ -z "$bandMean" ] || opts+=(--band-mean-tolerance "$bandMean")
  [ -z "$initPattern" ] || opts+=(--init-from "${initPattern//LEVEL/$1}")
  [ -z "$solidElement" ] || opts+=(--solid-element "$solidElement")
  [ -z "$solidFromPattern" ] || opts+=(--solid-mesh-from "${solidFromPattern//LEVEL/$1}")
  [ -z "$mapType" ] || opts+=(--mapping "$mapType")
  [ -z "$mapSmoothing" ] || opts+=(--mapping-smoothing "$mapSmoothing")
}
for level in $levels; do
  [ -z "$initPattern" ] || [ -d "${initPattern//LEVEL/$level}/constant/polyMesh" ] || { echo "error: hydrofoil: HYDROFOIL_INIT_FROM: no OpenFOAM case ${initPattern//LEVEL/$level} for $level (run its rigid solve first, e.g. scripts/verify hydrofoil-3d-rigid)" >&2; exit 2; }
  runOptions "$level"
  (cd "$case_dir" && ./run.sh --check-only --fluid-mesh "$fluidMesh" "${opts[@]}") || exit 2
done
csv=$FSI_VERIFY_DIR/error_vs_runtime.csv
raw=$FSI_VERIFY_DIR/levels.csv
mkdir -p "$runs"
echo "level,size,cores,wall_s,cpu_s,mesh_wall_s,mesh_cpu_s,load1,coupling_iterations,fluid_iterations,tip_aoa,tip_deflection,lift,drag" > "$raw"
TIMEFORMAT='%R %U %S'
folders=()
for level in $levels; do
  m=$runs/mesh-$level r=$runs/run-$level
  if [ "$reuse" = 1 ] && [ -f "$m/mesh/mesh-summary.txt" ]; then
    echo "hydrofoil: $level: reusing the mesh in $m"
  else
    echo "hydrofoil: $level: meshing in $m ($(date +%H:%M:%S))"
    rm -rf "$m"; mkdir -p "$m"
    { time "$case_dir/mesh.sh" --out "$m/mesh" --preset "$level" --np "$npf" --fluid-mesh "$fluidMesh" > "$m/log.mesh" 2>&1; } 2> "$m/time.mesh" ||
      { echo "error: hydrofoil $level meshing failed, see $m/log.mesh" >&2; tail -5 "$m/log.mesh" >&2; exit 1; }
  fi
  # `time` writes time.run when run.sh ends, so a run killed midway leaves it empty
  if [ "$reuse" = 1 ] && [ -s "$r/time.run" ] && [ "$(wc -l < "$r/results/baseline/history.csv" 2> /dev/null || echo 0)" -ge 2 ]; then
    echo "hydrofoil: $level: reusing the run in $r"
  else
    echo "hydrofoil: $level: coupled baseline in $r ($(date +%H:%M:%S), load $(cut -d' ' -f1 /proc/loadavg))"
    rm -rf "$r"
    cp -r "$case_dir" "$r"
    cut -d' ' -f1 /proc/loadavg > "$r/load1"
    runOptions "$level"
    { time (cd "$r" && ./run.sh --mesh-from "$m" "${opts[@]}" > log.run 2>&1); } 2> "$r/time.run" ||
      { echo "error: hydrofoil $level run failed, see $r/log.run" >&2; tail -5 "$r/log.run" >&2; exit 1; }
  fi
  cells=$(sed -n 's/^fluid: cells \([0-9]*\).*/\1/p' "$m/mesh/mesh-summary.txt" | tail -n 1)
  read -r rw ru rs < "$r/time.run"
  mw="" mc=""
  if [ -s "$m/time.mesh" ]; then read -r mw mu ms < "$m/time.mesh"; mc=$(awk -v a="$mu" -v b="$ms" 'BEGIN { printf "%.1f", a + b }'); fi
  "$FSI_PYTHON" - "$r/results/baseline/history.csv" "$level" "$cells" "$((npf + nps))" "$rw" "$ru" "$rs" \
      "$mw" "$mc" "$(cat "$r/load1" 2>/dev/null || echo)" >> "$raw" <<'PY'
import csv, sys
path, level, cells, ranks, rw, ru, rs, mw, mc, load = sys.argv[1:]
row = list(csv.DictReader(open(path)))[-1]
defl = -0.5 * (float(row["tip_le_uy"]) + float(row["tip_te_uy"]))
print(f"{level},{cells},{ranks},{float(rw):.1f},{float(ru) + float(rs):.1f},{mw},{mc},{load},"
      f"{row['coupling_iterations']},{row['fluid_iterations']},{float(row['tip_aoa_deg']):.6g},"
      f"{defl:.6e},{-float(row['Fy']):.6g},{float(row['Fx']):.6g}")
PY
  tail -n 1 "$raw"
  folders+=("$r")
done

# Errors against the finest level; Richardson information with three levels.
"$FSI_PYTHON" - "$raw" "$csv" "$FSI_VERIFY_DIR/richardson.csv" "${HYDROFOIL_MAX_ERROR:-}" <<'PY'
import csv, math, sys
raw, out, rich, max_error = sys.argv[1:]
rows = list(csv.DictReader(open(raw)))
if len(rows) < 2:
    sys.exit("error: hydrofoil study needs at least two levels (HYDROFOIL_LEVELS)")
quantities = ["tip_aoa", "tip_deflection", "lift", "drag"]
ref = rows[-1]
extra = ["cpu_s", "mesh_wall_s", "mesh_cpu_s", "load1", "coupling_iterations", "fluid_iterations"]
with open(out, "w") as f:
    f.write("level,size,cores,wall_s,quantity,value,reference,rel_error," + ",".join(extra) + "\n")
    for r in rows:
        for q in quantities:
            v, vr = float(r[q]), float(ref[q])
            f.write(f"{r['level']},{r['size']},{r['cores']},{r['wall_s']},{q},{v:.6g},{vr:.6g},"
                    f"{(v - vr) / vr + 0.0:.6e}," + ",".join(r[k] for k in extra) + "\n")
print(f"reference: level {ref['level']} ({ref['size']} cells)")
for r in rows[:-1]:
    print(f"  {r['level']:>7}: " + "  ".join(
        f"{q} {100 * (float(r[q]) - float(ref[q])) / float(ref[q]):+.2f} %" for q in quantities))
if len(rows) >= 3:
    # h ~ cells^(-1/3); f = f* + C h^p through the last three levels (non-constant ratio):
    # solve (h3^p - h2^p) / (h2^p - h1^p) = (f3 - f2) / (f2 - f1) for p by bisection.
    a, b, c = rows[-3:]
    h = [float(x["size"]) ** (-1.0 / 3.0) for x in (a, b, c)]
    with open(rich, "w") as f:
        f.write("quantity,coarse_level,middle_level,fine_level,observed_order,richardson_estimate,"
                "finest_rel_to_estimate,note\n")
        for q in quantities:
            f1, f2, f3 = (float(x[q]) for x in (a, b, c))
            ratio = (f3 - f2) / (f2 - f1) if f2 != f1 else float("nan")
            note, p, est = "", float("nan"), float("nan")
            if not (0 < ratio < 1):
                note = "not monotone convergent" if ratio <= 0 else "differences do not shrink"
            else:
                g = lambda pp: (h[2] ** pp - h[1] ** pp) / (h[1] ** pp - h[0] ** pp) - ratio
                lo, hi = 1e-3, 10.0
                if g(lo) * g(hi) > 0:
                    note = "no order in (0, 10]"
                else:
                    for _ in range(200):
                        mid = 0.5 * (lo + hi)
                        lo, hi = (mid, hi) if g(lo) * g(mid) > 0 else (lo, mid)
                    p = 0.5 * (lo + hi)
                    C = (f3 - f2) / (h[2] ** p - h[1] ** p)
                    est = f3 - C * h[2] ** p
            rel = (f3 - est) / est if est == est and est != 0 else float("nan")
            f.write(f"{q},{a['level']},{b['level']},{c['level']},{p:.3g},{est:.6g},{rel:.3e},{note}\n")
    print(open(rich).read(), end="")
if max_error:
    tol = float(max_error)
    r = rows[-2]
    bad = [q for q in quantities if abs((float(r[q]) - float(ref[q])) / float(ref[q])) > tol]
    if bad:
        sys.exit(f"error: hydrofoil level {r['level']} differs from {ref['level']} by more than "
                 f"{100 * tol:g} % in {', '.join(bad)}; refine the presets or raise HYDROFOIL_MAX_ERROR")
    print(f"check: every quantity of {r['level']} within {100 * tol:g} % of {ref['level']}")
PY
cat "$csv"
if [ -n "${HYDROFOIL_GCI_OUT:-}" ] && [ ${#folders[@]} = 3 ]; then
  "$FSI_PYTHON" "$root/scripts/history_gci.py" --steady --table \
      --model "${HYDROFOIL_GCI_MODEL:-$flow-$scheme-${algorithm:-simplec}-$fluidMesh-baseline}" \
      --out "$HYDROFOIL_GCI_OUT" "${folders[@]}"
fi
