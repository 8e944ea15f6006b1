#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Rigid 3-D hydrofoil on the boundary-layer (cgrid) presets coarse / medium / fine: a systematic
# refinement (every count x 1.3 per level, cases/hydrofoil/README.md "Boundary-layer fluid
# mesh"), one rigid steady solve per level with cases/hydrofoil/blcheck.sh (mesh, motion check at
# -12 deg / 30 mm, rigid.sh solve to an estimated force error of 1e-5 |F| held 100 iterations,
# first-cell y+ by OpenFOAM's yPlus function object).
# Quantities: lift -F_y, drag F_x [N] and the root pitching moment M_z about the root quarter
# chord [N m]. scripts/history_gci.py --rigid gives the observed order, the Richardson value and
# GCI_fine (Celik et al. 2008) -> gci.csv (quantity,model,levels,observed_order,extrapolated,
# gci_fine_pct, then convergence, the three values, the relative differences to the finest,
# asymptotic_ratio, asymptotic_range); the same rows go into verification/hydrofoil/gci.csv
# (the 3-D foil's file, beside the coupled t = 0 study's rows) as the model "rigid-MODEL".
# error_vs_runtime.csv: the standard columns (size = fluid cells, cores = MPI ranks, wall_s =
# the rigid solve); reference = the extrapolated value where the three levels are in the
# asymptotic range, else the finest level's value (its rows then have rel_error 0); extra
# columns cpu_s, iterations, converged, yplus_max, motion.
# levels.csv: every level's blcheck line as columns, after a column model.
# gci.csv, levels.csv and error_vs_runtime.csv hold one block of rows per model
# (flow-scheme-algorithm-cgrid[-slip]): a run replaces its own model's rows and keeps the others'.
# Cost alone on 2 cores (2026-12-05): first order 30 min (500-600 iterations per level),
# second order with the slip root wall 47 min with relaxation 0.9 / 0.8 (coarse from rest
# 1 100, medium and fine 800 iterations); with 0.7 (tools/setFlow.sh since 2026-12-06) and the
# default bands 1e-4: coarse 1 000, medium 1 500, fine 2 100 iterations, about 1 h 50 min
# (fine 57 min, 1.6 s per iteration; 2026-12-06).
# State: verification/hydrofoil-3d-rigid/README.md.
# Environment:
#   H3D_LEVELS    presets, coarse to fine (default "coarse medium fine"; three needed; "medium
#                 fine finer" adds the fourth level, about 2.8 M cells, and writes its rows under
#                 the model name with "-medium-fine-finer" appended; with H3D_REUSE=1 the medium
#                 and fine runs of the default study are kept)
#   H3D_FLOW      flow model (default turbulent: k-omega SST; see the README's flow models)
#   H3D_SCHEME    convection scheme (default upwind: the second-order schemes have no steady
#                 state at the root junction on this mesh, README "Rigid 3-D solve")
#   H3D_ALGORITHM pressure-velocity algorithm (default simplec: the case's SIMPLEC, which has a
#                 steady state on every preset since the tip gap's cells re-space evenly,
#                 README "The tip gap's re-spaced cells"; simple: classic SIMPLE, blcheck.sh
#                 --algorithm, the study of 2026-12-03/04 on the older meshes)
#   H3D_BAND      blcheck.sh --band-tolerance (default 1e-3, 1e-4 with linearUpwind): a level may also stop in the mean
#                 (force within +-1e-3 |F| over 200 iterations, the two 100-iteration blocks'
#                 means within the 1e-5 tolerance): classic SIMPLE's force keeps wandering once
#                 converged (coarse: ~5e-6 |F| per iteration, band 1.5e-5; medium: a period-6
#                 oscillation of +-6.4e-4 in lift), which the 1e-5 error estimate (up to 49
#                 times the change) never accepts; the loads are then the mean flow's (fluid-app
#                 averages the fields over the two blocks; until 2026-12-04 the last iterate's,
#                 as in the tracked study). 0: off. Default 1e-4 with linearUpwind: with
#                 relaxation 0.7 the second-order levels converge without a cycle, and at
#                 1e-3 the medium level stopped after 800 iterations with a band of +-7.5e-4,
#                 0.08 % above its state after 1 800 (2026-12-06), an iteration error that moved
#                 the lift's observed order from about 1.2 to 1.9
#   H3D_BAND_MEAN blcheck.sh --band-mean-tolerance: in the mean, the two blocks' means may
#                 differ by this instead of 1e-5 (default 1e-4 with linearUpwind, else 0: 1e-5).
#                 The second-order fine level's mean creeps by 1e-5..6e-5 |F| per block for
#                 1 000 iterations and more (2.4e-4 from iteration 1 500 to 2 400), where the lift's
#                 medium-fine difference is 6.6e-3: 1e-4 keeps the iteration error below 1/50 of
#                 the discretization error the study measures, and the fine level within the hour
#   H3D_ROOT_WALL slip: the tunnel's root wall a slip wall (blcheck.sh --root-wall; default wall,
#                 the paper's no-slip): with H3D_SCHEME=linearUpwind the second-order study, whose
#                 flow has no steady state with the no-slip root wall (README, "A steady
#                 second-order flow: the slip root wall"); run folders and model get "-slip"
#   H3D_RUNS      run folders (default $FSI_VERIFY_DIR/runs, not tracked)
#   H3D_REUSE=1   keep a level whose RUN/rigid/rigid.csv exists instead of redoing it, and go
#                 on with a level stopped during its rigid solve (a session's end: the solve
#                 writes a restart point every 200 iterations; blcheck.sh --resume) instead of
#                 starting it again. The same settings as the stopped run
#   H3D_SEQUENCE  1 (default): every level starts from the next coarser level's flow
#                 (blcheck.sh --init-from; grid sequencing, fewer iterations, the same stopping
#                 test); 0: every level from rest
set -euo pipefail
: "${FSI_VERIFY_DIR:?run through scripts/verify hydrofoil-3d-rigid}"
root=${FSI_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
export PATH=${FSI_BUILD_DIR:-$root/build}/bin:$PATH
levels=${H3D_LEVELS:-"coarse medium fine"}
flow=${H3D_FLOW:-turbulent}
scheme=${H3D_SCHEME:-upwind}
runs=${H3D_RUNS:-$FSI_VERIFY_DIR/runs}
algorithm=${H3D_ALGORITHM:-simplec}
case "$algorithm" in simple|simplec) ;; *) echo "error: hydrofoil-3d-rigid: H3D_ALGORITHM='$algorithm' must be simple or simplec" >&2; exit 2 ;; esac
reuse=${H3D_REUSE:-0}
rootWall=${H3D_ROOT_WALL:-wall}
case "$rootWall" in wall) suffix="" ;; slip) suffix=-slip ;; *) echo "error: hydrofoil-3d-rigid: H3D_ROOT_WALL='$rootWall' must be wall or slip" >&2; exit 2 ;; esac
if [ "$scheme" = linearUpwind ]; then
    band=${H3D_BAND:-1e-4} bandMean=${H3D_BAND_MEAN:-1e-4}
else
    band=${H3D_BAND:-1e-3} bandMean=${H3D_BAND_MEAN:-0}
fi
model=$flow-$scheme-$algorithm-cgrid$suffix
# another triple of presets (e.g. "medium fine finer") is its own model block in the CSVs
[ "$levels" = "coarse medium fine" ] || model+=-$(echo $levels | tr ' ' '-')
np=2
set -- $levels
[ $# = 3 ] || { echo "error: hydrofoil-3d-rigid: H3D_LEVELS='$levels' must name three presets, coarse to fine" >&2; exit 2; }
mkdir -p "$runs"

folders=() previous=""
raw=$FSI_VERIFY_DIR/levels.csv lines=$FSI_VERIFY_DIR/levels.blcheck.tmp
: > "$lines"
for level in $levels; do
    r=$runs/$flow-$scheme-$algorithm$suffix-$level
    if [ "$reuse" = 1 ] && [ -f "$r/rigid/rigid.csv" ] && [ -f "$r/blcheck.txt" ]; then
        echo "hydrofoil-3d-rigid: reusing $r"
    else
        extra=()
        [ "$algorithm" = simplec ] || extra=(--algorithm "$algorithm")
        if [ "$reuse" = 1 ] && [ -d "$r/rigid/case" ] && [ -f "$r/log.motion" ]; then
            what=resumed extra+=(--resume)   # the log goes on
        else
            what=started
            rm -rf "$r"; : > "$r.log"
            [ -z "$previous" ] || [ "${H3D_SEQUENCE:-1}" != 1 ] || extra+=(--init-from "$previous")
        fi
        echo "hydrofoil-3d-rigid: $level $what ($(date +%H:%M:%S), load $(cut -d' ' -f1 /proc/loadavg))"
        # blcheck exits 1 when y+ > 1 or the motion check fails: recorded in its line, not fatal
        "$root/cases/hydrofoil/blcheck.sh" --out "$r" --preset "$level" --flow "$flow" \
            --scheme "$scheme" --np "$np" --band-tolerance "$band" \
            --band-mean-tolerance "$bandMean" --root-wall "$rootWall" ${extra[@]+"${extra[@]}"} \
            >> "$r.log" 2>&1 || true
        grep '^blcheck:' "$r.log" > "$r/blcheck.txt" ||
            { tail -5 "$r.log" >&2; echo "error: hydrofoil-3d-rigid: $level failed (see $r.log)" >&2; exit 1; }
    fi
    cat "$r/blcheck.txt" >> "$lines"
    tail -n 1 "$r/blcheck.txt"
    folders+=("$r") previous=$r
done

"$FSI_PYTHON" "$root/scripts/history_gci.py" --rigid --model "$model" \
    --out "$FSI_VERIFY_DIR/gci.csv" --table "${folders[@]}"
"$FSI_PYTHON" "$root/scripts/history_gci.py" --rigid --model "rigid-$model" \
    --out "$root/verification/hydrofoil/gci.csv" "${folders[@]}"

"$FSI_PYTHON" - "$lines" "$raw" "$model" "$root/scripts" <<'PY'
import os, sys
rawIn, rawOut, model, scripts = sys.argv[1:5]
sys.path.insert(0, scripts)
from model_csv import write_model_rows
lines = [dict([("model", model)] + [kv.split("=", 1) for kv in l.split()[1:]])
         for l in open(rawIn) if l.strip()]
write_model_rows(rawOut, list(lines[0].keys()), model, lines)
os.remove(rawIn)
PY
"$FSI_PYTHON" "$root/scripts/levels_error_csv.py" "$raw" "$FSI_VERIFY_DIR/gci.csv" \
    "$FSI_VERIFY_DIR/error_vs_runtime.csv" "$np" "$model" \
    --extra yplus_max motion
