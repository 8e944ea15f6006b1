#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# One rigid steady solve of the 3-D foil (fluid-app -rigid) on a mesh.sh fluid case, with the
# loads, the foil's first-cell y+ and the cost:
#
#   cases/hydrofoil/rigid.sh --mesh DIR/fluid --out RUNDIR [--flow laminar|transition|turbulent]
#       [--scheme upwind|linearUpwind] [--np 2] [--tolerance 1e-5] [--max-iterations 3000]
#       [--init-from RUN] [--algorithm simple] [--band-tolerance B] [--band-mean-tolerance M]
#       [--root-wall wall|slip] [--write-interval 200] [--resume] [--shape-from CASE]
#       [--shape-displacement CSV] [--check-only]
#
#   --np N               fluid ranks (default 2; with --shape-from or --resume: the decomposition
#                        of the source case, which a given --np must match for --shape-from)
#   --tolerance T        stop when the estimated force error is <= T |F|, held 100 iterations
#                        (fsiDict rigid/estimateForceError; the 2-D section mode's criterion)
#   --max-iterations N   cap on SIMPLE iterations (not converged: reported, exit 0)
#   --init-from RUN      start from the flow of a finished rigid.sh run RUN (another mesh of the
#                        same domain, e.g. the next coarser preset; same flow model), mapped
#                        nearest-cell (tools/mapInitialFields.sh): grid sequencing, fewer
#                        iterations; the stopping test is unchanged
#   --algorithm simple   classic SIMPLE instead of the case's SIMPLEC (tools/setFlow.sh)
#   --root-wall slip     the tunnel's root wall z = 0 a slip wall (tools/rootWall.sh; default
#                        wall, the paper's no-slip): the second-order flow's steady state (README,
#                        "A steady second-order flow: the slip root wall")
#   --band-tolerance B   also stop "in the mean" (fsiDict rigid/bandTolerance, fluid-app/README.md):
#                        at the end of a 100-iteration block, when over the last two blocks the
#                        force stayed within +-B |F| and the blocks' means differ by <= T |F|.
#                        For classic SIMPLE, whose force wanders by ~1e-5 |F| per iteration
#                        once converged (the estimate above, up to 49 times the change, never
#                        holds); 0 (default): off. The fields written and the loads are
#                        then the mean flow's (fluid-app averages U, p and the turbulence
#                        fields over the two blocks)
#   --band-mean-tolerance M  with --band-tolerance: the two blocks' means may differ by
#                        <= max(T, M) |F| (fsiDict rigid/bandMeanTolerance; default 0: T). For a
#                        flow whose mean creeps by more than T per block long after the
#                        discretization error is settled (the second-order fine cgrid level:
#                        1e-5..6e-5 |F| per 100 iterations, README "A steady second-order flow")
#   --write-interval N   write the fields every N SIMPLE iterations (fsiDict rigid/writeInterval;
#                        default 200, 0: at the end only): restart points for --resume. On the
#                        finer cgrid level (2.7 M cells, ~4 s per iteration on 2 cores) a solve
#                        takes longer than a 3-hour session
#   --resume             go on with the solve in RUNDIR/case from its latest written iteration
#                        T (a run stopped from outside, e.g. at a session's end), with the same
#                        options: the case is not rebuilt (--init-from is then ignored; the flow
#                        model is the case's own, from its fluidModel, and an option that
#                        contradicts it is refused; a case made before 2026-12-07 has none),
#                        the cap stays --max-iterations in all (the rerun may do N - T), the
#                        stopping test starts anew. rigid.csv's iterations count
#                        from 0, its cpu_s and wall_s sum every run of the solve (below,
#                        runs; before 2026-12-07 the last run's only). Without a
#                        written iteration in RUNDIR/case: exit 2
#   --shape-from CASE    solve the foil in the shape of a coupled run: CASE is a coupled fluid
#                        case of run.sh (RUN/fluid-baseline, on the same --mesh; --np: its ranks); its
#                        written moved mesh (processor*/0/polyMesh/points, or 0/polyMesh/points
#                        with --np 1) and flow (the fields this case has) replace the case's
#                        initial ones. The flow model (--flow, --scheme, --algorithm,
#                        --root-wall) is CASE's own, from its fluidModel (tools/fluidCase.sh):
#                        an option that contradicts it is refused; a CASE made before
#                        2026-12-07 has none, then --flow and --scheme must be given. The
#                        converged coupled state's loads come back if its flow is steady; for
#                        one accepted in the mean it gives the frozen shape's steady or
#                        long-window mean loads. Not with --init-from or --resume (a resumed
#                        shape run keeps its mesh: --resume alone, tools/shapeCheck.sh --resume)
#   --shape-displacement CSV  solve the foil in a given displacement: CSV has the columns
#                        x,y,z,ux,uy,uz (a solid-app interface CSV, RUN/results/MODEL/interface/
#                        level_NNNN.csv, or a coupled fluid case's foil displacement written by
#                        tools/foilDisplacement.py; any preset's run), interpolated onto this
#                        mesh's foil points (tools/foilMotion.py --from-interface: moving least
#                        squares over the nearest nodes) and taken into the volume by the case's
#                        own motion solver (moveDynamicMesh); checkMesh must pass on the moved
#                        mesh. One coupled level's shape so replays on the fluid mesh of any
#                        preset, without the coupling (README, "The trailing edge's share").
#                        A CSV of another foil (a foil point more than 2 mm from every node) is
#                        refused before anything is made.
#                        The flow starts from rest, from --init-from, or with --shape-from CASE
#                        from CASE's flow (CASE's moved mesh is then replaced). Not with --resume
#   --check-only         validate the options' values and exit: 0, or 2 with the one-line error;
#                        writes nothing and needs neither --mesh, --out nor fluid-app (blcheck.sh
#                        calls it before it meshes)
#
# Writes RUNDIR/case (the OpenFOAM case, tools/fluidCase.sh) and RUNDIR/rigid.csv, one row:
# cells, flow, scheme, iterations, converged (in_the_mean 1: stopped by --band-tolerance, band
# the force's relative half-range over the last 200 iterations), lift = -F_y, drag = F_x (N), root pitching moment
# M_z about the root quarter chord (0.3685, 0, 0) (N m, the spanwise axis: nose-up positive, as
# the 2-D section mode's C_M), the foil's first-cell y+ (yPlus function object: max, mean over the faces, the
# fraction of foil faces with y+ <= 1, separately for the tip faces), CPU and wall seconds, and
# runs: how many runs the solve took (a resumed solve: 1 + its resumptions; CPU and wall seconds
# are then the sum over them, an earlier run stopped from outside counted from its log's start
# stamp to its last write, its CPU as ranks x wall).
# fluid-app must be on PATH (scripts/run and scripts/verify put the build's bin/ first).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mesh="" out="" flow=laminar scheme=upwind np=2 tol=1e-5 maxIt=3000 initFrom="" algorithm="" band=0 bandMean=0 rootWall=wall checkOnly=0
writeInterval=200 resume=0 shapeFrom="" shapeDisplacement=""
given=" "   # the model and --np options given (variable names), for --shape-from and --resume
die() { echo "error: rigid.sh: $*" >&2; exit 2; }
# fraction VALUE: VALUE is 0 or a number in (0, 1)
fraction() { awk -v v="$1" 'BEGIN{exit !(v ~ /^[0-9.eE+-]+$/ && v + 0 >= 0 && v + 0 < 1)}'; }
while [ $# -gt 0 ]; do
    case "$1" in
        --mesh) mesh="$2"; shift 2 ;;
        --out) out="$2"; shift 2 ;;
        --flow) flow="$2"; given+="flow "; shift 2 ;;
        --scheme) scheme="$2"; given+="scheme "; shift 2 ;;
        --np) np="$2"; given+="np "; shift 2 ;;
        --tolerance) tol="$2"; shift 2 ;;
        --max-iterations) maxIt="$2"; shift 2 ;;
        --init-from) initFrom="$2"; shift 2 ;;
        --algorithm) algorithm="$2"; given+="algorithm "; shift 2 ;;
        --band-tolerance) band="$2"; shift 2 ;;
        --band-mean-tolerance) bandMean="$2"; shift 2 ;;
        --root-wall) rootWall="$2"; given+="rootWall "; shift 2 ;;
        --write-interval) writeInterval="$2"; shift 2 ;;
        --resume) resume=1; shift ;;
        --shape-from) shapeFrom="$2"; shift 2 ;;
        --shape-displacement) shapeDisplacement="$2"; shift 2 ;;
        --check-only) checkOnly=1; shift ;;
        -h|--help) sed -n '3,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) die "unknown option '$1' (see --help)" ;;
    esac
done
[ "$checkOnly" = 1 ] || [ -f "$mesh/constant/polyMesh/owner" ] || [ -f "$mesh/constant/polyMesh/owner.gz" ] ||
    die "--mesh '$mesh' has no constant/polyMesh; run mesh.sh first"
[ "$checkOnly" = 1 ] || [ -n "$out" ] || die "--out RUNDIR is required (a run folder outside git)"
[[ "$np" =~ ^[1-9][0-9]*$ ]] || die "--np '$np' must be a positive integer"
{ [[ "$maxIt" =~ ^[1-9][0-9]*$ ]] && [ "$maxIt" -ge 100 ]; } ||
    die "--max-iterations '$maxIt' must be an integer >= 100 (the stopping test holds 100 iterations)"
awk -v t="$tol" 'BEGIN{exit !(t + 0 > 0 && t + 0 < 1)}' || die "--tolerance '$tol' must be in (0, 1)"
fraction "$band" ||
    die "--band-tolerance '$band' must be 0 (off) or in (0, 1)"
[ "$maxIt" -ge 200 ] || awk -v b="$band" 'BEGIN{exit !(b + 0 == 0)}' ||
    die "--band-tolerance needs --max-iterations >= 200 (two blocks of 100)"
fraction "$bandMean" ||
    die "--band-mean-tolerance '$bandMean' must be 0 (off: the --tolerance) or in (0, 1)"
[[ "$writeInterval" =~ ^(0|[1-9][0-9]*)$ ]] ||
    die "--write-interval '$writeInterval' must be 0 (fields at the end only) or a positive integer (e.g. 200)"
# ranksOf CASE: the ranks CASE is decomposed for (its processor folders; 1: serial)
ranksOf() {
    local n; n=$(find "$1" -maxdepth 1 -type d -name 'processor[0-9]*' 2> /dev/null | wc -l)
    echo $((n > 0 ? n : 1))
}
# takeModel CASE WHAT: CASE's recorded flow model (its fluidModel, tools/fluidCase.sh) becomes
# this solve's where no option gives it; an option that contradicts it is refused (WHAT names
# CASE). Status 1 when CASE records none.
takeModel() {
    local src=$1 what=$2 options option value var status=0
    options=$("$here/tools/fluidCase.sh" --model-of "$src") || status=$?
    [ "$status" -le 1 ] || exit "$status"   # a malformed record: fluidCase.sh said which line
    [ "$status" = 0 ] || return 1
    while read -r option value; do
        case "$option" in --flow|--scheme|--algorithm) var=${option#--} ;; --root-wall) var=rootWall ;; *) continue ;; esac
        if [[ "$given" == *" $var "* ]]; then
            [ "${!var}" = "$value" ] ||
                die "$what was solved with $option $value (its fluidModel): leave $option out or give $value"
        else
            printf -v "$var" '%s' "$value"
        fi
    done <<< "$options"
}
[ "$resume" = 1 ] || [ -z "$initFrom" ] || { [ -f "$initFrom/rigid.csv" ] && [ -d "$initFrom/case" ]; } ||
    die "--init-from '$initFrom' is not a finished rigid.sh run (no rigid.csv / case)"
if [ -n "$shapeDisplacement" ]; then
    [ "$resume" = 0 ] || die "--shape-displacement builds a new case: not with --resume (a resumed solve keeps its mesh)"
    [ -f "$shapeDisplacement" ] ||
        die "--shape-displacement '$shapeDisplacement': no such file; give a solid-app interface CSV, e.g. RUN/results/baseline/interface/level_0000.csv"
    head -2 "$shapeDisplacement" | grep -q '^x,y,z,ux,uy,uz' ||
        die "--shape-displacement '$shapeDisplacement' is not an interface CSV (no header line x,y,z,ux,uy,uz...: give a solid-app interface CSV or one of tools/foilDisplacement.py)"
fi
if [ -n "$shapeFrom" ]; then
    [ "$resume" = 0 ] && [ -z "$initFrom" ] ||
        die "--shape-from starts from the coupled case's flow: not with --init-from or --resume"
    [ -f "$shapeFrom/processor0/0/polyMesh/points" ] || [ -f "$shapeFrom/0/polyMesh/points" ] ||
        die "--shape-from '$shapeFrom' has no moved mesh (0/polyMesh/points or processor0/0/polyMesh/points); give a coupled run's fluid case, e.g. RUN/fluid-baseline"
    shapeRanks=$(ranksOf "$shapeFrom")
    if [[ "$given" == *" np "* ]]; then
        [ "$shapeRanks" -eq "$np" ] ||
            die "--shape-from '$shapeFrom' is decomposed for $shapeRanks rank(s) (1: serial); give --np $shapeRanks or leave --np out"
    else
        np=$shapeRanks
    fi
    for d in "$shapeFrom"/processor[0-9]*; do
        [ ! -d "$d" ] || [ -f "$d/0/polyMesh/points" ] ||
            die "--shape-from '$shapeFrom': ${d##*/} has no moved mesh 0/polyMesh/points (a coupled run stopped before its fields were written?); give a coupled run's finished fluid case"
    done
    # the flow model is the coupled case's own
    takeModel "$shapeFrom" "--shape-from '$shapeFrom'" ||
        [[ "$given" == *" flow "* && "$given" == *" scheme "* ]] ||
        die "--shape-from '$shapeFrom' has no fluidModel (made before 2026-12-07): give the coupled run's --flow and --scheme (and --algorithm, --root-wall as it ran)"
fi
# a resumed solve goes on with its case's model (a case made before 2026-12-07: the options given)
# and, unless --np is given, its decomposition
if [ "$resume" = 1 ] && [ -n "$out" ]; then
    takeModel "$out/case" "--resume: $out/case" || true
    [[ "$given" == *" np "* ]] || np=$(ranksOf "$out/case")
fi
"$here/tools/setFlow.sh" --check-only --flow "$flow" --scheme "$scheme" ${algorithm:+--algorithm "$algorithm"}
case "$rootWall" in wall|slip) ;; *) die "--root-wall '$rootWall' must be wall (the paper's no-slip tunnel) or slip" ;; esac
[ "$checkOnly" = 0 ] || exit 0
# --shape-displacement: the CSV must be this foil's, every foil point of the mesh within 2 mm of a
# node (foilMotion.py --check-gap), checked before anything is made (an uncompressed mesh only:
# replayShape checks again on the case)
if [ -n "$shapeDisplacement" ] && [ -f "$mesh/constant/polyMesh/points" ]; then
    message=$(/usr/bin/python3 "$here/tools/foilMotion.py" "$mesh" --from-interface "$shapeDisplacement" \
        --check-gap 2>&1 > /dev/null) || { message=${message##*$'\n'}; die "--shape-displacement: ${message#error: }"; }
fi
case="$out/case"
# latestWritten: the largest written iteration > 0 of the case (processor0's with np > 1), or 0
latestWritten() {
    local d=$case; [ "$np" -gt 1 ] && d=$case/processor0
    { ls "$d" 2> /dev/null || true; } | awk '/^[0-9]+$/ && $1 > 0 {if ($1 + 0 > m) m = $1 + 0} END {print m + 0}'
}
startIt=0
if [ "$resume" = 1 ]; then
    startIt=$(latestWritten)
    [ "$startIt" -gt 0 ] ||
        die "--resume: $case has no written iteration to go on from (start without --resume)"
    [ "$((maxIt - startIt))" -ge 100 ] ||
        die "--resume: $case is at iteration $startIt: fewer than 100 iterations left below --max-iterations $maxIt (raise it)"
    [ "$((maxIt - startIt))" -ge 200 ] || awk -v b="$band" 'BEGIN{exit !(b + 0 == 0)}' ||
        die "--resume: $((maxIt - startIt)) iterations left below --max-iterations $maxIt; --band-tolerance needs >= 200 (raise --max-iterations)"
fi
command -v fluid-app > /dev/null || die "fluid-app not on PATH (build first; scripts/run sets PATH)"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
export OMPI_MCA_btl_tcp_if_include=lo OMPI_MCA_oob_tcp_if_include=lo
log() { echo "[rigid.sh $(date +%H:%M:%S)] $*"; }

# takeShape SOURCE: the moved mesh and flow of the coupled case SOURCE become this case's initial
# state, rank by rank (the same mesh and decomposition, checked on the point addressing)
takeShape() {
    local src=$1 dirs=(.) d f r n=0
    [ "$np" -gt 1 ] && { dirs=(); for ((r = 0; r < np; r++)); do dirs+=("processor$r"); done; }
    for d in "${dirs[@]}"; do
        [ "$np" -eq 1 ] || cmp -s "$src/$d/constant/polyMesh/pointProcAddressing" \
            "$case/$d/constant/polyMesh/pointProcAddressing" ||
            die "--shape-from '$src': $d is not this mesh's decomposition (another --mesh or --root-wall?)"
        mkdir -p "$case/$d/0/polyMesh"
        cp "$src/$d/0/polyMesh/points" "$case/$d/0/polyMesh/points"
        for f in "$case/$d/0"/*; do
            [ -f "$f" ] && [ -f "$src/$d/0/${f##*/}" ] && [ "${f##*/}" != pointDisplacement ] || continue
            cp "$src/$d/0/${f##*/}" "$f"
            n=$((n + 1))
        done
    done
    log "initial mesh and flow: the shape of $src ($n field files)"
}

fd() { foamDictionary "$case/$1" -entry "$2" -set "$3" > /dev/null; }
# replayShape CSV: the foil moved to the displacement of the interface CSV (foilMotion.py
# --from-interface on each rank's part, then moveDynamicMesh with the case's motion solver): the
# moved points become the initial mesh (0/polyMesh/points, as takeShape's; a moved mesh taken by
# takeShape is dropped first, so that the motion starts from the mesh's own points), checkMesh
# must pass; the fields are converted to ASCII on the way, controlDict and 0/pointDisplacement
# are restored
replayShape() {
    local csv=$1 dirs=(.) d r lib message par=() run=()
    [ "$np" -gt 1 ] && { dirs=(); for ((r = 0; r < np; r++)); do dirs+=("processor$r"); done; par=(-parallel); run=(mpirun --oversubscribe -np "$np"); }
    lib="$(dirname "$(command -v fluid-app)")/../lib"
    [ -f "$lib/libfsiMeshMotion.so" ] || die "--shape-displacement: libfsiMeshMotion.so not found next to fluid-app ($lib)"
    cp "$case/system/controlDict" "$case/system/controlDict.rigid"
    fd system/controlDict writeFormat ascii
    fd system/controlDict writePrecision 17
    fd system/controlDict endTime 1
    fd system/controlDict writeInterval 1
    foamDictionary "$case/system/controlDict" -entry functions -remove > /dev/null
    for d in "${dirs[@]}"; do rm -f "$case/$d/0/polyMesh/points"; done
    ( cd "$case" && "${run[@]}" foamFormatConvert "${par[@]}" -constant > log.foamFormatConvert.shape 2>&1 ) ||
        die "--shape-displacement: foamFormatConvert failed (see $case/log.foamFormatConvert.shape)"
    for d in "${dirs[@]}"; do
        cp "$case/$d/0/pointDisplacement" "$case/$d/0/pointDisplacement.rigid"
        message=$(/usr/bin/python3 "$here/tools/foilMotion.py" "$case/$d" --from-interface "$csv" \
            2>&1 >> "$case/log.foilMotion") ||
            die "--shape-displacement on $case/$d: ${message##*$'\n'}"
    done
    ( cd "$case" && LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
        "${run[@]}" moveDynamicMesh "${par[@]}" > log.moveDynamicMesh 2>&1 ) ||
        die "--shape-displacement: moveDynamicMesh failed (see $case/log.moveDynamicMesh)"
    ( cd "$case" && "${run[@]}" checkMesh "${par[@]}" -time 1 > log.checkMesh.shape 2>&1 ) || true
    grep -q "^Mesh OK" "$case/log.checkMesh.shape" ||
        die "--shape-displacement: the moved mesh fails checkMesh ($(grep -m1 '\*\*\*' "$case/log.checkMesh.shape" | tr -s ' '); $case/log.checkMesh.shape)"
    for d in "${dirs[@]}"; do
        mkdir -p "$case/$d/0/polyMesh"
        mv "$case/$d/1/polyMesh/points" "$case/$d/0/polyMesh/points"
        mv "$case/$d/0/pointDisplacement.rigid" "$case/$d/0/pointDisplacement"
        rm -rf "${case:?}/$d/1"
    done
    mv "$case/system/controlDict.rigid" "$case/system/controlDict"
    log "initial mesh: the foil moved to the displacement of $csv; checkMesh: Mesh OK"
    sed 's/^foilMotion: /    /' "$case/log.foilMotion"
}

if [ "$resume" = 1 ]; then
    for f in log.fluid-app time.txt; do [ ! -f "$case/$f" ] || mv "$case/$f" "$case/$f.before-$startIt"; done
    rm -f "$out/rigid.csv"
    log "resuming $case from iteration $startIt"
else
    mkdir -p "$out"
    caseArgs=()
    [ -z "$initFrom" ] || caseArgs=(--init-from "$initFrom/case")
    [ -z "$algorithm" ] || caseArgs+=(--algorithm "$algorithm")
    caseArgs+=(--root-wall "$rootWall")
    "$here/tools/fluidCase.sh" "$case" "$mesh" "$np" --flow "$flow" --scheme "$scheme" ${caseArgs[@]+"${caseArgs[@]}"}
    [ "$rootWall" = wall ] || log "root wall z = 0: slip (tools/rootWall.sh)"
    [ -z "$initFrom" ] || log "initial fields mapped from $initFrom"
    [ -z "$shapeFrom" ] || takeShape "$(cd "$shapeFrom" && pwd)"
    [ -z "$shapeDisplacement" ] || replayShape "$(cd "$(dirname "$shapeDisplacement")" && pwd)/${shapeDisplacement##*/}"
fi
fd system/fsiDict rigid/maxIterations "$((maxIt - startIt))"
fd system/fsiDict rigid/writeInterval "$writeInterval"
fd system/fsiDict rigid/forceTolerance "$tol"
fd system/fsiDict rigid/residualRequired false
fd system/fsiDict rigid/estimateForceError true
fd system/fsiDict rigid/minIterations 100
fd system/fsiDict rigid/stableIterations 100
fd system/fsiDict rigid/bandTolerance "$band"
fd system/fsiDict rigid/bandWindow 100
fd system/fsiDict rigid/bandMeanTolerance "$bandMean"
fd system/controlDict endTime "$maxIt"
fd system/controlDict writeInterval "$maxIt"
fd system/controlDict startFrom latestTime
fd system/controlDict purgeWrite 1
# evaluated after the solve by simpleFoam -postProcess on the written fields (ASCII, so that the
# per-face values can be read): forces, y+ and the face centres of the foil
fd system/controlDict writeFormat ascii
fd system/controlDict functions/yPlus \
    '{ type yPlus; libs ("libfieldFunctionObjects.so"); writeControl writeTime; patches (foil); }'
fd system/controlDict functions/cellCentres \
    '{ type writeCellCentres; libs ("libfieldFunctionObjects.so"); writeControl writeTime; }'

par=()
[ "$np" -gt 1 ] && par=(-parallel)
log "fluid-app -rigid on $np rank(s): flow $flow, scheme $scheme${algorithm:+, algorithm $algorithm}, force error <= $tol |F|$(awk -v b="$band" 'BEGIN{if (b + 0 > 0) printf ", or in the mean within +-%s", b}')$(awk -v m="$bandMean" 'BEGIN{if (m + 0 > 0) printf " (block means within %s)", m}'), cap $maxIt"
t0=$(date +%s.%N)
( cd "$case" && /usr/bin/time -f "%U %S" -o time.txt \
    mpirun --oversubscribe -np "$np" fluid-app -rigid "${par[@]}" > log.fluid-app 2>&1 ) ||
    { tail -20 "$case/log.fluid-app"; die "fluid-app failed (see $case/log.fluid-app)"; }
t1=$(date +%s.%N)
postProcess() {
    ( cd "$case" && "$@" > log.postProcess 2>&1 ) ||
        { tail -20 "$case/log.postProcess"; die "simpleFoam -postProcess failed (see $case/log.postProcess)"; }
}
reconstruct() {
    ( cd "$case" && reconstructPar -latestTime > log.reconstructPar 2>&1 ) ||
        die "reconstructPar failed (see $case/log.reconstructPar)"
}
if [ "$np" -gt 1 ] && [ -f "$case/processor0/0/polyMesh/points" ]; then
    # a shape run's moved points are at time 0 of the processor folders only (reconstructPar
    # leaves them): its loads and y+ are evaluated on the ranks, then reconstructed
    postProcess mpirun --oversubscribe -np "$np" simpleFoam -postProcess -latestTime -parallel
    reconstruct
else
    [ "$np" -eq 1 ] || reconstruct
    postProcess simpleFoam -postProcess -latestTime
fi
cells=$(awk '/^ *cells:/{print $2; exit}' "$mesh/log.checkMesh" 2>/dev/null || echo nan)

/usr/bin/python3 - "$case" "$cells" "$flow" "$scheme" "$t0" "$t1" "$out/rigid.csv" "$np" "$here/tools" <<'EOP'
import csv, glob, os, re, sys
import numpy as np
case, cells, flow, scheme, t0, t1, outCsv, ranks, tools = sys.argv[1:]
sys.path.insert(0, tools)
from solveRunTime import earlierRuns, recordedCpu   # a resumed solve's runs

row = next(csv.DictReader(open(os.path.join(case, "postProcessing/fsi/forces.csv"))))
mom = sorted(glob.glob(os.path.join(case, "postProcessing/forces/*/moment.dat")))[-1]
last = [l for l in open(mom) if l.strip() and not l.startswith("#")][-1]
mz = float(re.sub(r"[()]", " ", last).split()[3])
time = sorted((d for d in os.listdir(case) if re.fullmatch(r"[0-9.e+-]+", d) and d != "0"), key=float)[-1]

def patchValues(field):
    """The foil patch's face values of a written ASCII field (scalars, or vectors as rows)."""
    s = open(os.path.join(case, time, field)).read()
    s = s[s.index("boundaryField"):]
    s = s[re.search(r"\n\s*foil\s*\{", s).end():]
    m = re.search(r"value\s+nonuniform\s+List<(scalar|vector)>\s*(\d+)\s*\(", s)
    n, body = int(m.group(2)), s[m.end():]
    if m.group(1) == "scalar":
        return np.array(body.split(None, n)[:n], dtype=float)
    return np.array([v.split() for v in re.findall(r"\(([^()]*)\)", body)[:n]], dtype=float)

yp = patchValues("yPlus")
cf = patchValues("C")
tip = cf[:, 2] > 0.100 - 1e-7          # faces of the tip plane z = 0.100
cpu = recordedCpu(os.path.join(case, "time.txt"))
if cpu is None:
    sys.exit("error: rigid.sh: %s/time.txt holds no time record of the solve" % case)
try:
    wallBefore, cpuBefore, runsBefore = earlierRuns(case, int(ranks))
except ValueError as e:   # the solve's result is kept; only its cost is then partial
    print("warning: rigid.sh: %s; cpu_s and wall_s count the last run only" % e, file=sys.stderr)
    wallBefore, cpuBefore, runsBefore = 0.0, 0.0, 0
res = dict(cells=cells, flow=flow, scheme=scheme, iterations=row["simpleIterations"],
           converged=row["converged"], in_the_mean=row["inTheMean"], band="%.3g" % float(row["band"]),
           lift_N="%.6g" % -float(row["Fy"]), drag_N="%.6g" % float(row["Fx"]),
           root_moment_z_Nm="%.6g" % mz, foil_faces=len(yp), yplus_max="%.3f" % yp.max(),
           yplus_mean="%.3f" % yp.mean(), yplus_le1_pct="%.2f" % (100.0 * np.mean(yp <= 1.0)),
           tip_faces=int(tip.sum()), tip_yplus_max="%.3f" % (yp[tip].max() if tip.any() else float("nan")),
           cpu_s="%.1f" % (cpu + cpuBefore), wall_s="%.1f" % (float(t1) - float(t0) + wallBefore),
           runs=runsBefore + 1)
with open(outCsv, "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(res))
    w.writeheader()
    w.writerow(res)
print("rigid: " + " ".join("%s=%s" % kv for kv in res.items()))
EOP
