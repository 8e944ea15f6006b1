#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Coupled elastic t = 0 state of the hydrofoil on the boundary-layer (cgrid) presets coarse /
# medium / fine: the study of scripts/verify.d/hydrofoil.sh (run.sh --material baseline, fluid 2
# ranks + solid 1 rank, the preset's Tet10 foil) with k-omega SST and the rigid study's flow
# model (scripts/verify.d/hydrofoil-3d-rigid.sh: H3D_SCHEME, H3D_ALGORITHM, H3D_ROOT_WALL), on
# the same systematic cgrid refinement. Each level's fluid starts from that study's converged
# rigid flow of the same preset and model (run.sh --init-from): level 0's first solve then only
# confirms the rigid state, and a level costs its coupling iterations instead of a solve from
# rest. Run scripts/verify hydrofoil-3d-rigid with the same H3D_* first.
# The model is turbulent-SCHEME-ALGORITHM-cgrid[-slip]-baseline. Its runs and hydrofoil.sh's
# own files go to this folder's MODEL/ (outside git); this folder's levels.csv,
# error_vs_runtime.csv and richardson.csv hold one block of rows per model (a leading `model`
# column; a study replaces its own rows), and the observed order, extrapolated value and
# GCI_fine of the tip AOA, tip deflection, lift and drag (scripts/history_gci.py --steady) go
# to this folder's gci.csv and verification/hydrofoil/gci.csv (rows of other models kept).
# Environment: HYDROFOIL_LEVELS, HYDROFOIL_REUSE, HYDROFOIL_TIMEOUT as hydrofoil.sh;
# HYDROFOIL_RUNS (default this folder's MODEL/); H3D_RUNS: the rigid study's run folders
# (default verification/hydrofoil-3d-rigid/runs, that study's default);
# H3D_SCHEME (upwind | linearUpwind), H3D_ALGORITHM (simplec | simple), H3D_ROOT_WALL
# (wall | slip) as that study; HYDROFOIL_OSCILLATION_WINDOW as hydrofoil.sh, default 20 with
# linearUpwind (the second-order coupled runs of cases/hydrofoil/README.md), unset otherwise;
# HYDROFOIL_COUPLING_TOLERANCE as hydrofoil.sh, default 1e-6 m with linearUpwind: at the case's
# 5e-6 m the coarse state was accepted at |r|/sqrt(n) 3.9e-6 m, 0.52 % above its lift at 8.7e-7 m
# (2026-12-06), the size of the coarse-medium difference the study measures;
# HYDROFOIL_BAND_TOLERANCE and HYDROFOIL_BAND_MEAN as hydrofoil.sh, defaults 5e-3 and 1e-4 with
# linearUpwind (the mean as the rigid study's H3D_BAND_MEAN): the fine level's moved mesh keeps
# the force swinging by +-0.3-0.7 % (lift; a two-iteration cycle), so at the fluid
# accuracy 5e-5 and the case's band 2e-3 every one of its solves ran to the 400-iteration cap and
# the level was never accepted (2026-12-06; cases/hydrofoil/README.md).
# HYDROFOIL_SOLID_ELEMENT (tet10 | hex20) and HYDROFOIL_SOLID_MESH_FROM as hydrofoil.sh: the
# model gets -hex20, and -solid-PRESET when one structural mesh serves every level (only the fluid
# is refined: cases/hydrofoil/README.md, "The structure's share of the coupled mesh study").
# HYDROFOIL_MAPPING and HYDROFOIL_MAPPING_SMOOTHING as hydrofoil.sh (unset: run.sh's default on
# this mesh, moving-least-squares with smoothing 0): the model gets -mls for moving-least-squares
# (-TYPE for a type other than nearest-projection), and -smoothR for a smoothing radius other than
# 2e-4 (cases/hydrofoil/README.md, "The trailing edge's share", "The mapping follows the fluid
# mesh"); HYDROFOIL_MAPPING=nearest-projection alone gives the studies' models before 2026-12-08.
# HYDROFOIL_SHAPE_CHECK=1: afterwards every level's accepted state is solved on to convergence
# at its shape (cases/hydrofoil/tools/shapeCheck.sh: rigid.sh --shape-from with the rigid
# study's stopping test: force error 1e-5 held 100 iterations, or in the mean, band 1e-4 and
# block means within 1e-4 with linearUpwind, band 1e-3 with upwind; at most
# HYDROFOIL_SHAPE_MAX_ITERATIONS, default 3000), and this folder's shape.csv gets one row per
# level: the coupled and the converged lift and drag and their change, the fluid iteration
# error the accepted levels carry (second order: coarse about 700 iterations, medium 900, fine
# about an hour on 2 cores); with three levels both gci.csv files get the rows
# shape_lift_N@t=0 and shape_drag_N@t=0 (their order and GCI). With HYDROFOIL_REUSE=1 a level's
# finished shape run is kept, so the check can follow a finished study, and a shape run stopped
# from outside (a session's end) goes on from its latest restart point (shapeCheck.sh --resume;
# one stopped before its first restart point is refused by rigid.sh: remove its shape-baseline
# folder).
set -euo pipefail
: "${FSI_VERIFY_DIR:?run through scripts/verify hydrofoil-cgrid}"
root=${FSI_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
rigidRuns=${H3D_RUNS:-$root/verification/hydrofoil-3d-rigid/runs}
algorithm=${H3D_ALGORITHM:-simplec} scheme=${H3D_SCHEME:-upwind} rootWall=${H3D_ROOT_WALL:-wall}
case "$algorithm" in simple|simplec) ;; *) echo "error: hydrofoil-cgrid: H3D_ALGORITHM='$algorithm' must be simple or simplec" >&2; exit 2 ;; esac
case "$scheme" in upwind|linearUpwind) ;; *) echo "error: hydrofoil-cgrid: H3D_SCHEME='$scheme' must be upwind or linearUpwind" >&2; exit 2 ;; esac
case "$rootWall" in wall) suffix="" ;; slip) suffix=-slip ;; *) echo "error: hydrofoil-cgrid: H3D_ROOT_WALL='$rootWall' must be wall or slip" >&2; exit 2 ;; esac
# the structure, when not the preset's own Tet10 foil (hydrofoil.sh: HYDROFOIL_SOLID_ELEMENT,
# HYDROFOIL_SOLID_MESH_FROM): -hex20, and -solid-PRESET for one structural mesh on every level
solidTag=""
case "${HYDROFOIL_SOLID_ELEMENT:-tet10}" in tet10) ;; hex20) solidTag=-hex20 ;; *) echo "error: hydrofoil-cgrid: HYDROFOIL_SOLID_ELEMENT='$HYDROFOIL_SOLID_ELEMENT' must be tet10 or hex20" >&2; exit 2 ;; esac
if [ -n "${HYDROFOIL_SOLID_MESH_FROM:-}" ]; then
    [ "${HYDROFOIL_SOLID_MESH_FROM//LEVEL/}" = "$HYDROFOIL_SOLID_MESH_FROM" ] || { echo "error: hydrofoil-cgrid: HYDROFOIL_SOLID_MESH_FROM='$HYDROFOIL_SOLID_MESH_FROM': give one folder for every level (without LEVEL)" >&2; exit 2; }
    solidSummary=$HYDROFOIL_SOLID_MESH_FROM/mesh/mesh-summary.txt
    [ -f "$solidSummary" ] || { echo "error: hydrofoil-cgrid: HYDROFOIL_SOLID_MESH_FROM: no $solidSummary (a run or mesh folder made by mesh.sh)" >&2; exit 2; }
    solidTag+=-solid-$(head -n 1 "$solidSummary" | tr ' ' '\n' | sed -n 's/^preset=//p')
fi
# the mapping run.sh uses on this mesh (its --help): unset, moving-least-squares with smoothing
# 0; a type given keeps the configs' smoothing 2e-4 unless HYDROFOIL_MAPPING_SMOOTHING says
# otherwise. The tags name it against the studies' first mapping (nearest-projection, 2e-4)
mapping=${HYDROFOIL_MAPPING:-moving-least-squares}
if [ -n "${HYDROFOIL_MAPPING:-}" ]; then smoothing=${HYDROFOIL_MAPPING_SMOOTHING:-2e-4}; else smoothing=${HYDROFOIL_MAPPING_SMOOTHING:-0}; fi
case "$mapping" in
  nearest-projection) ;;
  moving-least-squares) solidTag+=-mls ;;
  *) solidTag+=-$mapping ;;
esac
awk -v r="$smoothing" 'BEGIN{exit !(r ~ /^[0-9.eE+-]+$/ && r + 0 == 2e-4)}' || solidTag+=-smooth$smoothing
model=turbulent-$scheme-$algorithm-cgrid$suffix$solidTag-baseline
if [ "$scheme" = linearUpwind ]; then
    export HYDROFOIL_OSCILLATION_WINDOW=${HYDROFOIL_OSCILLATION_WINDOW:-20}
    export HYDROFOIL_COUPLING_TOLERANCE=${HYDROFOIL_COUPLING_TOLERANCE:-1e-6}
    export HYDROFOIL_BAND_TOLERANCE=${HYDROFOIL_BAND_TOLERANCE:-5e-3}
    export HYDROFOIL_BAND_MEAN=${HYDROFOIL_BAND_MEAN:-1e-4}
fi
# the shape check's rigid.sh options, checked before anything runs
shapeCheck=${HYDROFOIL_SHAPE_CHECK:-0}
case "$shapeCheck" in 0|1) ;; *) echo "error: hydrofoil-cgrid: HYDROFOIL_SHAPE_CHECK='$shapeCheck' must be 0 or 1" >&2; exit 2 ;; esac
# the study's model given too: runs made before 2026-12-07 do not record theirs (rigid.sh
# --shape-from checks it against the fluid case's fluidModel where there is one)
shapeOpts=(--flow turbulent --scheme "$scheme" --root-wall "$rootWall"
           --max-iterations "${HYDROFOIL_SHAPE_MAX_ITERATIONS:-3000}")
[ "$algorithm" = simplec ] || shapeOpts+=(--algorithm "$algorithm")
if [ "$scheme" = linearUpwind ]; then
    shapeOpts+=(--band-tolerance 1e-4 --band-mean-tolerance 1e-4)
else
    shapeOpts+=(--band-tolerance 1e-3)
fi
if [ "$shapeCheck" = 1 ]; then   # rigid.sh's own check, its message under this study's name
    shapeError=$("$root/cases/hydrofoil/rigid.sh" --check-only "${shapeOpts[@]}" 2>&1) ||
        { echo "error: hydrofoil-cgrid: the shape check (HYDROFOIL_SHAPE_MAX_ITERATIONS is rigid.sh's --max-iterations): ${shapeError#error: rigid.sh: }" >&2; exit 2; }
fi
export HYDROFOIL_FLUID_MESH=cgrid HYDROFOIL_FLOW=turbulent HYDROFOIL_SCHEME=$scheme
export HYDROFOIL_ALGORITHM=$algorithm HYDROFOIL_ROOT_WALL=$rootWall
export HYDROFOIL_INIT_FROM=$rigidRuns/turbulent-$scheme-$algorithm$suffix-LEVEL/rigid/case
study=$FSI_VERIFY_DIR
mkdir -p "$study/$model"
rm -f "$study/$model/richardson.csv" # written by hydrofoil.sh only with three levels
FSI_VERIFY_DIR=$study/$model bash "$(dirname "$0")/hydrofoil.sh" "$@"
set -- ${HYDROFOIL_LEVELS:-coarse medium fine}
runs=${HYDROFOIL_RUNS:-$study/$model}
# this model's block of the study's shared files
for f in levels.csv error_vs_runtime.csv richardson.csv; do
  [ -f "$study/$model/$f" ] || continue
  "$FSI_PYTHON" "$root/scripts/model_csv.py" tag "$study/$model/$f" "$study/$f" "$model"
done
# writeGci [--table]: with three levels, the model's order and GCI rows (history_gci.py --steady;
# with a shape check on every level also shape_lift_N@t=0 and shape_drag_N@t=0) into this
# folder's gci.csv and verification/hydrofoil/gci.csv; written after the coupled levels (a
# failed shape check keeps them) and again after the shape check
levelRuns=()
for level in "$@"; do levelRuns+=("$runs/run-$level"); done
writeGci() {
  [ ${#levelRuns[@]} = 3 ] || return 0
  "$FSI_PYTHON" "$root/scripts/history_gci.py" --steady --model "$model" --out "$study/gci.csv" \
      ${1+"$1"} "${levelRuns[@]}"
  "$FSI_PYTHON" "$root/scripts/history_gci.py" --steady --model "$model" \
      --out "$root/verification/hydrofoil/gci.csv" "${levelRuns[@]}"
}
writeGci --table

# the accepted shapes solved on to convergence (HYDROFOIL_SHAPE_CHECK=1)
[ "$shapeCheck" = 1 ] || exit 0
export PATH=${FSI_BUILD_DIR:-$root/build}/bin:$PATH   # rigid.sh runs fluid-app
shapeRuns=()
for level in "$@"; do
    r=$runs/run-$level
    if [ "${HYDROFOIL_REUSE:-0}" = 1 ] && [ -f "$r/shape-baseline/shape.csv" ]; then
        echo "hydrofoil-cgrid: $level: reusing the shape run in $r/shape-baseline"
    else
        how=()
        if [ "${HYDROFOIL_REUSE:-0}" = 1 ] && [ -d "$r/shape-baseline/case" ]; then   # as hydrofoil-3d-rigid
            echo "hydrofoil-cgrid: $level: going on with the stopped shape run in $r/shape-baseline ($(date +%H:%M:%S))"
            how=(--resume)
            [ ! -f "$r/log.shape" ] || mv "$r/log.shape" "$r/log.shape.before-resume"
        else
            echo "hydrofoil-cgrid: $level: the accepted shape solved on to convergence ($(date +%H:%M:%S))"
            rm -rf "$r/shape-baseline"
        fi
        "$root/cases/hydrofoil/tools/shapeCheck.sh" --run "$r" ${how[@]+"${how[@]}"} -- "${shapeOpts[@]}" > "$r/log.shape" 2>&1 ||
            { tail -5 "$r/log.shape" >&2; echo "error: hydrofoil-cgrid: $level shape check failed (see $r/log.shape)" >&2; exit 1; }
    fi
    tail -n 1 "$r/log.shape" 2> /dev/null || true
    shapeRuns+=("$level=$r/shape-baseline/shape.csv")
done
"$FSI_PYTHON" - "$study/shape.csv" "$model" "$root/scripts" "${shapeRuns[@]}" <<'PY'
import csv, sys
out, model, scripts = sys.argv[1:4]
sys.path.insert(0, scripts)
from model_csv import write_model_rows
rows = []
for arg in sys.argv[4:]:
    level, path = arg.split("=", 1)
    rows += [dict(r, model=model, level=level) for r in csv.DictReader(open(path))]
columns = ["model", "level"] + [c for c in rows[0] if c not in ("model", "level")]
write_model_rows(out, columns, model, rows)
PY
writeGci   # now with the shape checks' rows
