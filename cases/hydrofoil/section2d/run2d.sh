#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# 2-D section mode of the hydrofoil case: the foil section in the tunnel's x-y plane, one cell
# thick, Re_c = 9.96e4, slip (symmetry) tunnel walls at y = +-0.254 m. Meshes, solves the rigid
# steady flow with fluid-app -rigid and prints C_L, C_D, C_M (quarter chord, nose-up positive).
#
#   cases/hydrofoil/section2d/run2d.sh --out DIR [--level K] [--flow laminar|transition|turbulent]
#       [--scheme upwind|linearUpwind] [--tolerance 1e-6] [--max-iterations 6000] [--mesh-only]
#       [--tc 0.12] [--cli 0.5] [--tu 0.01] [--length-scale 0.001] [--init-from RUN]
#       [--algorithm simple] [--band-tolerance B] [--band-window N]
#
#   --level K         mesh level (0 coarsest; every level refines all lengths by sqrt 2)
#   --level-along K, --level-across K  refine along the foil and the wake (n_side, n_te,
#                     n_wake) or across the layers (n_normal, first-cell height) alone to
#                     level K (default --level): separate-refinement studies
#   --tolerance T     stop when the estimated force error left is below T |F| for 100
#                     consecutive iterations (fsiDict rigid.estimateForceError,
#                     stableIterations; residuals are not required)
#   --max-iterations  SIMPLE iteration cap (the run is reported as not converged if reached)
#   --tu, --length-scale  inlet turbulence intensity and length scale (m) of the RAS models:
#                     k = 1.5 (Tu U)^2, omega = sqrt(k) / (Cmu^0.25 l) at the inlet and as the
#                     initial field (default: the values of fluid/0.orig/k and omega)
#   --init-from RUN   start from the solution of another run2d.sh run (RUN/case, e.g. the next
#                     coarser level, same flow model), mapped with mapFields (nearest cell):
#                     grid sequencing, fewer iterations; the stopping test is unchanged
#   --algorithm simple  classic SIMPLE instead of the case's SIMPLEC (tools/setFlow.sh). Under
#                     SIMPLEC the section keeps U 0.9 / turbulence 0.8 with either scheme
#                     (setFlow.sh --relaxation; the 3-D case's 0.7 for linearUpwind leaves the
#                     section's cycle in place and took level 1 to the 8 000-iteration cap)
#   --band-tolerance B  the solve may also stop in the mean (fsiDict rigid.bandTolerance, blocks
#                     of 100 iterations; ../rigid.sh): for classic SIMPLE's force wander or a
#                     SIMPLEC limit cycle; C_L, C_D, C_M and y+ are then the mean flow's (fluid-app
#                     averages the fields over the two blocks); 0 (default): off
#   --band-window N   the band rule's block length (fsiDict rigid.bandWindow; default 100): at
#                     least one period of the slowest oscillation, so that two blocks' means
#                     agree (level 3's SIMPLEC cycle has a period of ~420 iterations: 1000)
# Writes DIR/mesh (the C-grid as MSH 2.2 and its parameters), DIR/case (OpenFOAM case, fields for ParaView in the last
# time folder, postProcessing/forcesFinal and yPlus) and DIR/section2d.csv (one row: level,
# cells, flow, scheme, iterations, converged, C_L, C_D, C_M, y+ max / mean on the foil, CPU and
# wall seconds of the solve, and for a solve that did not converge the C_L range over
# SIMPLE_WINDOW (default 300) further iterations of simpleFoam: cl_min, cl_max; then the x/c
# from which the suction and the pressure side boundary layers are turbulent,
# turb_from_suction, turb_from_pressure, and the x/c from which the flow at the wall is
# reversed (separated), sep_suction, sep_pressure: blstate.py, whose per-face skin friction
# and nu_t/nu are in DIR/boundary-layer.csv). A solve that did not converge also prints
# fluid-app's own C_L band over its last SIMPLE_WINDOW iterations (from its
# postProcessing/fsi/rigidIterations.csv). fluid-app must be on PATH (scripts/run and
# scripts/verify put build/bin there).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
out="" level=0 flow=laminar scheme=linearUpwind tol=1e-6 maxIt=6000 meshOnly=0 tc=0.12 cli=0.5 te=blunt
tu="" lscale="" initFrom="" levelArgs=() algorithm="" band=0 bandWindow=100
die() { echo "error: section2d/run2d.sh: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
        --out) out="$2"; shift 2 ;;
        --level) level="$2"; shift 2 ;;
        --level-along|--level-across)
            [[ "${2:-}" =~ ^[0-6]$ ]] || die "$1 '${2:-}' must be 0..6"
            levelArgs+=("$1" "$2"); shift 2 ;;
        --flow) flow="$2"; shift 2 ;;
        --scheme) scheme="$2"; shift 2 ;;
        --tolerance) tol="$2"; shift 2 ;;
        --max-iterations) maxIt="$2"; shift 2 ;;
        --mesh-only) meshOnly=1; shift ;;
        --tc) tc="$2"; shift 2 ;;
        --cli) cli="$2"; shift 2 ;;
        --te) te="$2"; shift 2 ;;
        --tu) tu="$2"; shift 2 ;;
        --length-scale) lscale="$2"; shift 2 ;;
        --init-from) initFrom="$2"; shift 2 ;;
        --algorithm) algorithm="$2"; shift 2 ;;
        --band-tolerance) band="$2"; shift 2 ;;
        --band-window) bandWindow="$2"; shift 2 ;;
        -h|--help) sed -n '3,43p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) die "unknown option '$1' (see --help)" ;;
    esac
done
[ -n "$out" ] || die "--out DIR is required (a run folder outside git)"
[[ "$level" =~ ^[0-6]$ ]] || die "--level '$level' must be 0..6"
"$here/../tools/setFlow.sh" --check-only --flow "$flow" --scheme "$scheme" ${algorithm:+--algorithm "$algorithm"}
awk -v b="$band" 'BEGIN{exit !(b ~ /^[0-9.eE+-]+$/ && b + 0 >= 0 && b + 0 < 1)}' ||
    die "--band-tolerance '$band' must be 0 (off) or in (0, 1)"
[[ "$bandWindow" =~ ^[1-9][0-9]*$ ]] && [ "$bandWindow" -ge 10 ] ||
    die "--band-window '$bandWindow' must be an integer >= 10"
[ $((2 * bandWindow)) -le "$maxIt" ] || awk -v b="$band" 'BEGIN{exit !(b + 0 == 0)}' ||
    die "--band-window $bandWindow needs --max-iterations >= $((2 * bandWindow)) (two blocks)"
if [ -n "$tu$lscale" ]; then
    [ -n "$tu" ] && [ -n "$lscale" ] || die "--tu and --length-scale go together"
    [[ "$tu" =~ ^(0?\.[0-9]+|[0-9]\.?[0-9]*[eE]-[0-9]+)$ ]] && [[ "$lscale" =~ ^(0?\.[0-9]+|[0-9]\.?[0-9]*[eE]-[0-9]+)$ ]] \
        || die "--tu '$tu' and --length-scale '$lscale' must be numbers in (0, 1) (e.g. --tu 0.01 --length-scale 0.001)"
fi
[ -z "$initFrom" ] || { [ -f "$initFrom/section2d.csv" ] && [ -d "$initFrom/case" ]; } \
    || die "--init-from '$initFrom' is not a finished run2d.sh run (no section2d.csv / case)"
[ "$meshOnly" = 1 ] || command -v fluid-app > /dev/null || die "fluid-app not on PATH (run through scripts/run or scripts/verify, or add build/bin)"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}" FOAM_SIGFPE="${FOAM_SIGFPE:-false}"
py=${FSI_PYTHON:-/usr/bin/python3}
mkdir -p "$out"; out="$(cd "$out" && pwd)"
log() { echo "[section2d $(date +%H:%M:%S)] $*"; }

# ---- mesh: structured C-grid (mesh2d.py, Gmsh MSH 2.2) -> gmshToFoam ----------------------------
mesh="$out/mesh"
rm -rf "$mesh" "$out/case" "$out/section2d.csv"; mkdir -p "$mesh"
"$py" "$here/mesh2d.py" --level "$level" --out "$mesh" --tc "$tc" --cli "$cli" --te "$te" ${levelArgs[@]+"${levelArgs[@]}"} > "$mesh/log.mesh2d" 2>&1 \
    || { cat "$mesh/log.mesh2d"; die "mesh2d.py failed"; }
case="$out/case"
mkdir -p "$case"
cp -r "$here/../fluid/system" "$here/../fluid/constant" "$case/"
rm -rf "$case/system/presets" "$case/system/snappyHexMeshDict" "$case/system/blockMeshDict" \
       "$case/system/surfaceFeatureExtractDict"
cat > "$case/constant/dynamicMeshDict" <<'EOD'
FoamFile { version 2.0; format ascii; class dictionary; location "constant"; object dynamicMeshDict; }
dynamicFvMesh   staticFvMesh;   // 2-D section mode: rigid foil, no mesh motion
EOD
( cd "$case"
  gmshToFoam "$mesh/section2d.msh" > log.gmshToFoam 2>&1 || { tail -20 log.gmshToFoam; exit 1; }
  # patch types: Gmsh's physical names come in as generic patches
  "$py" "$here/../tools/patchTypes.py" constant/polyMesh/boundary frontAndBack:empty sides:symmetry \
      foil:wall inlet:patch outlet:patch || exit 1
  checkMesh > log.checkMesh 2>&1 || true
)
grep -q "^Mesh OK" "$case/log.checkMesh" || { grep -E "\*\*\*|FATAL" "$case/log.checkMesh" | head; die "checkMesh failed (see $case/log.checkMesh)"; }
cells=$(awk '/^ *cells:/{print $2; exit}' "$case/log.checkMesh")
foilFaces=$(awk '$1 == "foil" && $2 ~ /^[0-9]+$/ {print $2; exit}' "$case/log.checkMesh")
nonOrtho=$(awk '/Mesh non-orthogonality Max:/{print $4; exit}' "$case/log.checkMesh")
log "level $level: $cells cells, $foilFaces foil faces, max non-orthogonality $nonOrtho ($(cat "$mesh/section2d-mesh.txt"))"
[ "$meshOnly" = 0 ] || exit 0

# ---- case set-up --------------------------------------------------------------------------
cp -r "$here/../fluid/0.orig" "$case/0"
rm -f "$case/0/pointDisplacement"
relax=(); [ "$algorithm" = simple ] || relax=(--relaxation 0.9/0.8)
"$here/../tools/setFlow.sh" "$case" --flow "$flow" --scheme "$scheme" ${algorithm:+--algorithm "$algorithm"} \
    ${relax[@]+"${relax[@]}"} > /dev/null
fd() { foamDictionary "$case/$1" -entry "$2" -set "$3" > /dev/null; }
if [ -n "$tu$lscale" ]; then   # both given and checked with the options above
    read -r kIn omegaIn < <("$py" -c "import math, sys
tu, l = float(sys.argv[1]), float(sys.argv[2])
assert 0 < tu < 1 and 0 < l < 1
k = 1.5 * (tu * 2.0) ** 2
print('%.6g %.6g' % (k, math.sqrt(k) / (0.09 ** 0.25 * l)))" "$tu" "$lscale" 2> /dev/null) \
        || die "--tu '$tu' must be in (0, 1) and --length-scale '$lscale' in (0, 1) m"
    for f in k:$kIn omega:$omegaIn; do
        fd "0/${f%%:*}" internalField "uniform ${f#*:}"
        fd "0/${f%%:*}" boundaryField/inlet/value "uniform ${f#*:}"
    done
    log "inlet turbulence: Tu $tu, length scale $lscale m: k $kIn m^2/s^2, omega $omegaIn 1/s"
fi
if [ -n "$initFrom" ]; then   # a finished run2d.sh run, checked with the options above
    "$here/../tools/mapInitialFields.sh" "$case" "$initFrom/case" > /dev/null || die "--init-from '$initFrom': mapping failed"
    log "initial fields mapped from $initFrom"
fi
fd system/fsiDict rigid/maxIterations "$maxIt"
fd system/fsiDict rigid/forceTolerance "$tol"
fd system/fsiDict rigid/residualRequired false
fd system/fsiDict rigid/estimateForceError true
fd system/fsiDict rigid/minIterations 100
fd system/fsiDict rigid/stableIterations 100   # a pause of a slow oscillation does not stop it
fd system/fsiDict rigid/bandTolerance "$band"
fd system/fsiDict rigid/bandWindow "$bandWindow"
fd system/controlDict endTime "$maxIt"
fd system/controlDict writeInterval "$maxIt"
fd system/controlDict functions/forces/CofR "(0.3685 0 0)"
# first-cell y+ on the foil; evaluated after the solve (fluid-app steps time without running
# function objects: simpleFoam -postProcess evaluates forces and yPlus on the written fields)
fd system/controlDict functions/yPlus \
    '{ type yPlus; libs ("libfieldFunctionObjects.so"); writeControl writeTime; patches (foil); }'
# boundary-layer state (blstate.py): wall shear stress and pressure on the foil, cell centres;
# ASCII fields (small 2-D meshes) so that blstate.py reads nut and C
fd system/controlDict writeFormat ascii
fd system/controlDict functions/wallShearStress \
    '{ type wallShearStress; libs ("libfieldFunctionObjects.so"); writeControl writeTime; patches (foil); }'
fd system/controlDict functions/cellCentres \
    '{ type writeCellCentres; libs ("libfieldFunctionObjects.so"); writeControl writeTime; }'
fd system/controlDict functions/foilSurface \
    '{ type surfaces; libs ("libsampling.so"); writeControl writeTime; surfaceFormat raw;
       interpolationScheme cell; fields (wallShearStress p);
       surfaces ( foil { type patch; patches (foil); interpolate false; } ); }'

# ---- solve --------------------------------------------------------------------------------
log "fluid-app -rigid: flow $flow, scheme $scheme${algorithm:+, algorithm $algorithm}, estimated force error <= $tol |F|$(awk -v b="$band" 'BEGIN{if (b + 0 > 0) printf ", or in the mean within +-%s", b}'), cap $maxIt"
t0=$(date +%s.%N)
( cd "$case" && /usr/bin/time -f "%U %S" -o time.txt fluid-app -rigid > log.fluid-app 2>&1 ) \
    || { tail -20 "$case/log.fluid-app"; die "fluid-app failed (see $case/log.fluid-app)"; }
t1=$(date +%s.%N)
( cd "$case" && simpleFoam -postProcess -latestTime > log.postProcess 2>&1 ) \
    || { tail -20 "$case/log.postProcess"; die "simpleFoam -postProcess failed (see $case/log.postProcess)"; }
rm -rf "$case/postProcessing/forcesFinal"
mv "$case/postProcessing/forces" "$case/postProcessing/forcesFinal"
onsets=$("$py" "$here/blstate.py" "$case" "$out/boundary-layer.csv" | tee "$case/log.blstate" \
    | sed -n 's/^blstate-onsets: //p') || die "blstate.py failed (see $case/log.blstate)"
[ -n "$onsets" ] || die "blstate.py printed no onsets (see $case/log.blstate)"
# not converged: SIMPLE_WINDOW more iterations with Debian's simpleFoam and the forces function
# object, to show how far the forces still move (C_L range, columns cl_min / cl_max)
window=${SIMPLE_WINDOW:-300}
if ! awk -F, 'NR == 2 && $11 == 1 {ok = 1} END {exit !ok}' "$case/postProcessing/fsi/forces.csv"; then
    log "not converged within $maxIt iterations: $window more with simpleFoam to record the force range"
    last=$(foamListTimes -case "$case" -latestTime 2>/dev/null | tail -1)
    foamDictionary "$case/system/controlDict" -entry endTime -set $((last + window)) > /dev/null
    foamDictionary "$case/system/controlDict" -entry writeInterval -set $((last + window)) > /dev/null
    ( cd "$case" && simpleFoam > log.simpleFoam.window 2>&1 ) || log "simpleFoam window failed (see log.simpleFoam.window)"
fi
"$py" - "$case" "$level" "$cells" "$flow" "$scheme" "$t0" "$t1" "$out/section2d.csv" "$window" $onsets <<'EOP'
import csv, glob, math, os, re, sys
(case, level, cells, flow, scheme, t0, t1, outCsv, window, onSuction, sepSuction, onPressure,
 sepPressure) = sys.argv[1:]
row = next(csv.DictReader(open(os.path.join(case, "postProcessing/fsi/forces.csv"))))
rho, U, c, dz = 998.2, 2.0, 0.05, 0.001
q = 0.5 * rho * U * U
fx, fy = float(row["Fx"]), float(row["Fy"])
# moment about the quarter chord from the forces function object (last line: total moment)
mom = sorted(glob.glob(os.path.join(case, "postProcessing/forcesFinal/*/moment.dat")))[-1]
last = [l for l in open(mom) if l.strip() and not l.startswith("#")][-1]
nums = [float(v) for v in re.findall(r"[-+]?\d+\.?\d*(?:[eE][-+]?\d+)?", last)]
mz = nums[3]                      # time, total (Mx My Mz), ...
fo = [l for l in open(mom.replace("moment.dat", "force.dat")) if l.strip() and not l.startswith("#")][-1]
foF = [float(v) for v in re.findall(r"[-+]?\d+\.?\d*(?:[eE][-+]?\d+)?", fo)][1:3]
if abs(foF[0] - fx) + abs(foF[1] - fy) > 1e-6 * math.hypot(fx, fy):
    sys.exit("section2d: forces of fluid-app (%g %g) and of the forces function object (%g %g) differ"
             % (fx, fy, foF[0], foF[1]))
cpu = sum(float(v) for v in open(os.path.join(case, "time.txt")).read().split()[:2])
yp = [l for l in open(os.path.join(case, "log.postProcess")) if "patch foil y+ :" in l]
ypMin = ypMax = ypMean = float("nan")
if yp:
    m = re.search(r"min = ([-+\deE.]+), max = ([-+\deE.]+), average = ([-+\deE.]+)", yp[-1])
    if m:
        ypMin, ypMax, ypMean = map(float, m.groups())
def clBand(fys):
    """(C_L min, C_L max) of a list of F_y [N]; NaN for fewer than two values."""
    if len(fys) < 2:
        return float("nan"), float("nan")
    return -max(fys) / (q * c * dz), -min(fys) / (q * c * dz)


clMin = clMax = float("nan")
windowFiles = [p for p in glob.glob(os.path.join(case, "postProcessing/forces/*/force.dat"))
               if os.path.getsize(p) > 0]
if windowFiles:
    fys = []
    for l in open(sorted(windowFiles)[-1]):
        if l.strip() and not l.startswith("#"):
            v = [float(x) for x in re.findall(r"[-+]?\d+\.?\d*(?:[eE][-+]?\d+)?", l)]
            fys.append(v[2])
    clMin, clMax = clBand(fys)
r = dict(level=level, cells=cells, flow=flow, scheme=scheme,
         iterations=row["simpleIterations"], converged=row["converged"],
         C_L=-fy / (q * c * dz), C_D=fx / (q * c * dz), C_M=mz / (q * c * c * dz),
         yplus_max=ypMax, yplus_mean=ypMean, cpu_s=cpu, wall_s=float(t1) - float(t0),
         cl_min=clMin, cl_max=clMax, turb_from_suction=float(onSuction),
         sep_suction=float(sepSuction), turb_from_pressure=float(onPressure),
         sep_pressure=float(sepPressure), in_the_mean=row["inTheMean"], band=float(row["band"]))
# the solver's own force history (fluid-app's rigidIterations.csv): its C_L band over the
# last SIMPLE_WINDOW iterations of a solve that reached the cap, beside the simpleFoam window's
hist = os.path.join(case, "postProcessing/fsi/rigidIterations.csv")
if row["converged"] != "1" and os.path.exists(hist):
    fyOwn = [float(h["Fy"]) for h in csv.DictReader(open(hist))][-int(window):]
    if len(fyOwn) > 1:
        print("section2d: fluid-app's own C_L over its last %d iterations: %.6g .. %.6g"
              % ((len(fyOwn),) + clBand(fyOwn)))
with open(outCsv, "w") as f:
    f.write(",".join(r) + "\n")
    f.write(",".join(("%.8g" % v) if isinstance(v, float) else str(v) for v in r.values()) + "\n")
print("section2d: " + " ".join("%s=%s" % (k, ("%.6g" % v) if isinstance(v, float) else v)
                               for k, v in r.items()))
EOP
