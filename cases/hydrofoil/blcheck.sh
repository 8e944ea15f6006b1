#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Reproduces the boundary-layer mesh's figures of the README ("Boundary-layer fluid mesh") in one
# invocation: meshes a preset with --fluid-mesh cgrid, checks the mesh motion at -12 deg tip
# twist / 30 mm tip deflection (beam bending), solves the rigid foil (rigid.sh, SST upwind by
# default) and prints one line with the cells, the motion check, the first-cell y+ and the loads:
#
#   cases/hydrofoil/blcheck.sh --out RUNDIR [--preset coarse|medium|fine|finer] [--flow turbulent]
#       [--scheme upwind] [--np 2] [--max-iterations 3000] [--init-from BLCHECK_RUN]
#       [--algorithm simple] [--band-tolerance B] [--band-mean-tolerance M] [--root-wall wall|slip]
#       [--resume]
#
#   blcheck: preset=P cells=N motion=OK motion_max_nonorth_deg=X iterations=N converged=0|1
#     in_the_mean=0|1 band=X yplus_max=X yplus_mean=X yplus_le1_pct=X tip_yplus_max=X lift_N=X drag_N=X
#     root_moment_z_Nm=X cpu_s=X wall_s=X
#
# --init-from: the rigid solve starts from another blcheck.sh run's flow (e.g. the next coarser
# preset; rigid.sh --init-from BLCHECK_RUN/rigid). --algorithm simple: classic SIMPLE (rigid.sh).
# --band-tolerance B: the solve may also stop in the mean (rigid.sh; 0, the default: off).
# --band-mean-tolerance M: the blocks' means may then differ by M (rigid.sh; 0, the default: the
# solve's 1e-5).
# --root-wall slip: the tunnel's root wall a slip wall (rigid.sh; default wall, no-slip).
# --resume: RUNDIR holds a run stopped during its rigid solve (e.g. at a session's end): keep its
# mesh and motion check and go on with the solve from its latest restart point (rigid.sh
# --resume; the solve writes one every 200 iterations), or only print the line when the solve
# had finished (rigid/rigid.csv). Same options as the stopped run.
# Exit 1 when the motion check fails or the first-cell y+ exceeds 1 anywhere on the foil (the
# mesh's promise); the line is printed either way. Cost: coarse about 9 min on 2 cores (mesh
# 20 s, motion 30 s, rigid solve 8 min), medium ~25 min, fine more than an hour; finer (cgrid3d.py's
# fourth level for the mesh studies, about 2.8 M cells) about 2.2 times fine per iteration.
# Needs what mesh.sh and rigid.sh need (OpenFOAM v1912, gmsh, the build's bin/ on PATH).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
out="" preset=coarse flow=turbulent scheme=upwind np=2 maxIt=3000 initFrom="" algorithm="" band=0 bandMean=0 rootWall=wall
resume=0
die() { echo "error: blcheck.sh: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
        --out) out="$2"; shift 2 ;;
        --preset) preset="$2"; shift 2 ;;
        --flow) flow="$2"; shift 2 ;;
        --scheme) scheme="$2"; shift 2 ;;
        --np) np="$2"; shift 2 ;;
        --max-iterations) maxIt="$2"; shift 2 ;;
        --init-from) initFrom="$2"; shift 2 ;;
        --algorithm) algorithm="$2"; shift 2 ;;
        --band-tolerance) band="$2"; shift 2 ;;
        --band-mean-tolerance) bandMean="$2"; shift 2 ;;
        --root-wall) rootWall="$2"; shift 2 ;;
        --resume) resume=1; shift ;;
        -h|--help) sed -n '3,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) die "unknown option '$1' (see --help)" ;;
    esac
done
[ -n "$out" ] || die "--out RUNDIR is required (a run folder outside git)"
case "$preset" in coarse|medium|fine|finer) ;; *) die "--preset must be coarse, medium, fine or finer (finer: the mesh studies' fourth level)" ;; esac
# the rigid solve's options, checked before anything is meshed (rigid.sh names the option)
rigidOptions=(--flow "$flow" --scheme "$scheme" --np "$np" --max-iterations "$maxIt"
    ${algorithm:+--algorithm "$algorithm"} --band-tolerance "$band" --band-mean-tolerance "$bandMean"
    --root-wall "$rootWall")
"$here/rigid.sh" --check-only "${rigidOptions[@]}" || exit 2
[ "$resume" = 1 ] || [ -z "$initFrom" ] || [ -f "$initFrom/rigid/rigid.csv" ] ||
    die "--init-from '$initFrom' is not a finished blcheck.sh run (no rigid/rigid.csv)"
[ "$resume" = 0 ] || { [ -d "$out/rigid/case" ] && [ -f "$out/log.motion" ] && [ -d "$out/mesh/fluid" ]; } ||
    die "--resume: '$out' is no stopped blcheck.sh run (needs mesh/fluid, log.motion and rigid/case)"
command -v fluid-app > /dev/null || die "fluid-app is not on PATH (put the build's bin/ first)"
log() { echo "[blcheck.sh $(date +%H:%M:%S)] $*"; }
mkdir -p "$out"; out="$(cd "$out" && pwd)"

motion=OK
if [ "$resume" = 1 ]; then
    grep -q "Mesh OK" "$out/log.motion" || motion=FAILED
    log "resuming the rigid solve in $out/rigid (mesh and motion check $motion kept)"
else
    log "meshing ($preset, cgrid) into $out/mesh"
    "$here/mesh.sh" --out "$out/mesh" --preset "$preset" --fluid-mesh cgrid --fluid-only --np "$np" \
        > "$out/log.mesh" 2>&1 || die "mesh.sh failed (see $out/log.mesh)"
    log "motion check: -12 deg tip twist, 30 mm tip deflection"
    "$here/tools/motionCheck.sh" --mesh "$out/mesh/fluid" --out "$out/motion" --tip-twist-deg -12 \
        --tip-deflection 0.030 --bending beam > "$out/log.motion" 2>&1 || motion=FAILED
fi
nonorth=$(awk '/non-orthogonality Max/ {print $4; exit}' "$out/motion/log.checkMesh" 2>/dev/null || true)
log "rigid solve ($flow, $scheme)"
if [ "$resume" = 1 ] && [ -f "$out/rigid/rigid.csv" ]; then
    log "the rigid solve had finished (rigid/rigid.csv): its line only"
elif [ "$resume" = 1 ]; then
    "$here/rigid.sh" --mesh "$out/mesh/fluid" --out "$out/rigid" "${rigidOptions[@]}" --resume \
        >> "$out/log.rigid" 2>&1 || die "rigid.sh --resume failed (see $out/log.rigid)"
else
    "$here/rigid.sh" --mesh "$out/mesh/fluid" --out "$out/rigid" "${rigidOptions[@]}" \
        ${initFrom:+--init-from "$(cd "$initFrom" && pwd)/rigid"} > "$out/log.rigid" 2>&1 ||
        die "rigid.sh failed (see $out/log.rigid)"
fi
/usr/bin/python3 - "$out/rigid/rigid.csv" "$preset" "$motion" "${nonorth:-nan}" <<'EOP'
import csv, sys
path, preset, motion, nonorth = sys.argv[1:5]
row = next(csv.DictReader(open(path)))
keys = ["iterations", "converged", "in_the_mean", "band", "yplus_max", "yplus_mean", "yplus_le1_pct", "tip_yplus_max",
        "lift_N", "drag_N", "root_moment_z_Nm", "cpu_s", "wall_s"]
print(f"blcheck: preset={preset} cells={row['cells']} motion={motion} "
      f"motion_max_nonorth_deg={nonorth} " + " ".join(f"{k}={row[k]}" for k in keys))
ok = motion == "OK" and float(row["yplus_max"]) <= 1.0
sys.exit(0 if ok else 1)
EOP
