#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Loads of the hydrofoil turned by a FIXED pitch on the boundary-layer (cgrid) presets coarse /
# medium / fine: the coupled t = 0 study (hydrofoil-cgrid) without the coupling. Each level starts
# from the rigid study's converged flow of its mesh (scripts/verify hydrofoil-3d-rigid, run it
# first), turns the whole foil by H3P_ANGLE about the spanwise axis through the root quarter chord
# (fluid-app -prescribed, type rotation; the mesh follows by the case's fsiInverseDistance
# motion) and solves to an estimated force error of 1e-5 |F| held 100 iterations (or in the mean
# over two 100-iteration blocks within +-1e-3), as the rigid study. The mapping, the structure
# and the coupling iteration play no part: where the coupled state refines badly and this study
# does too, the cause is the flow on the turned foil (cases/hydrofoil/README.md, "Loads of a
# fixed pitched foil").
# Writes here (one block of rows per model in each file): levels.csv (one row per level: cells,
# iterations, converged, in_the_mean, lift,
# drag, root moment M_z about (0.3685, 0, 0), their change from the unturned rigid flow, CPU and
# wall seconds), gci.csv (scripts/history_gci.py --rigid: observed order, extrapolated value,
# GCI_fine of lift_N, drag_N, root_moment_z_Nm), error_vs_runtime.csv (reference: the
# extrapolated value in the asymptotic range, else the finest level's).
# Cost on 2 cores: coarse ~3 min, medium ~6 min, fine ~21 min.
# Environment:
#   H3P_ANGLE      pitch [deg], nose-up positive (default -2: about the coupled state's tip twist);
#                  with H3P_SHAPE=twist the tip's twist
#   H3P_SHAPE      pitch (default: the whole foil turned) | twist: the coupled state's kind of
#                  shape, fixed: each section at z > 0 turned about the spanwise line through the
#                  root quarter chord by H3P_ANGLE z / 0.1 m (fluid-app -prescribed, type twist),
#                  plus a bending H3P_TIP_DEFLECTION (z / 0.1 m)^2 in -y (the lift's direction);
#                  the loads of one deformed shape on every mesh, without the structure
#   H3P_TIP_DEFLECTION  [m] the twist shape's tip deflection (default 0; the second-order coupled
#                  t = 0 state: about 4.6e-3 m at -2.1 deg, verification/hydrofoil-cgrid)
#   H3P_RUNS       run folders (default $FSI_VERIFY_DIR/runs, not tracked)
#   H3P_REUSE=1    keep a level whose RUN/case/log.pitch finished instead of redoing it
#   H3P_BAND, H3P_BAND_MEAN  the solve's bandTolerance / bandMeanTolerance (fsiDict; default: the
#                  rigid flow's, i.e. the rigid study's H3D_BAND / H3D_BAND_MEAN). 2026-12-06,
#                  second order: the turned medium flow kept a +-2e-4 |F| swing and stopped in
#                  the mean at 1e-4 after 2 500 iterations; the fine one swung by +-1.4 % and
#                  did not stop with 5e-4 / 2e-4 in 1 463 (stopped by hand); first order: 1e-3
#   H3P_MAX_ITERATIONS  cap on each level's SIMPLE iterations (default: the rigid flow's fsiDict
#                  rigid/maxIterations, 3 000; at least 200, the band rule's two blocks). A level
#                  that reaches it unconverged gets converged 0 in levels.csv, and gci.csv then
#                  says asymptotic_range no. The second-order fine level runs at about 1.8 s per
#                  iteration on 2 cores: 3 000 iterations are 1.5 h
#   H3D_RUNS, H3D_ALGORITHM, H3D_SCHEME, H3D_ROOT_WALL  the rigid study's run folders and model
#                  (as hydrofoil-cgrid: upwind or linearUpwind, wall or slip; default the
#                  first-order no-slip study): each level starts from that model's converged flow
#                  and keeps its settings (scheme, relaxation, root wall); run folders and the
#                  model label carry them (turbulent-SCHEME-ALGORITHM-cgrid[-slip]-pitchANGLE, or
#                  -twistANGLE[-bendDEFLECTION] with H3P_SHAPE=twist)
set -euo pipefail
: "${FSI_VERIFY_DIR:?run through scripts/verify hydrofoil-pitch}"
root=${FSI_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
export PATH=${FSI_BUILD_DIR:-$root/build}/bin:$PATH
export LD_LIBRARY_PATH=${FSI_BUILD_DIR:-$root/build}/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
angle=${H3P_ANGLE:--2}
shape=${H3P_SHAPE:-pitch} tipDeflection=${H3P_TIP_DEFLECTION:-0}
runs=${H3P_RUNS:-$FSI_VERIFY_DIR/runs}
rigidRuns=${H3D_RUNS:-$root/verification/hydrofoil-3d-rigid/runs}
algorithm=${H3D_ALGORITHM:-simplec} scheme=${H3D_SCHEME:-upwind} rootWall=${H3D_ROOT_WALL:-wall}
reuse=${H3P_REUSE:-0}
band=${H3P_BAND:-} bandMean=${H3P_BAND_MEAN:-}
maxIterations=${H3P_MAX_ITERATIONS:-}
[ -z "$maxIterations" ] || { [[ "$maxIterations" =~ ^[1-9][0-9]{0,5}$ ]] && [ "$maxIterations" -ge 200 ]; } ||
  { echo "error: hydrofoil-pitch: H3P_MAX_ITERATIONS '$maxIterations' must be an integer >= 200 (the band rule's two 100-iteration blocks), e.g. 1500" >&2; exit 2; }
for v in "$band" "$bandMean"; do
  [ -z "$v" ] || awk -v b="$v" 'BEGIN { exit !(b ~ /^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$/ && b > 0 && b <= 0.1) }' ||
    { echo "error: hydrofoil-pitch: H3P_BAND / H3P_BAND_MEAN '$v' must be a fraction of |F| in (0, 0.1], e.g. 5e-4" >&2; exit 2; }
done
np=2
die() { echo "error: hydrofoil-pitch: $*" >&2; exit 2; }
awk -v a="$angle" 'BEGIN { exit !(a ~ /^[-+]?[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$/ && a != 0 && a >= -15 && a <= 15) }' ||
  die "H3P_ANGLE='$angle' must be a pitch in degrees, non-zero, within -15..15 (e.g. -2)"
case "$shape" in pitch|twist) ;; *) die "H3P_SHAPE='$shape' must be pitch (the whole foil turned) or twist (linear from the root)" ;; esac
awk -v d="$tipDeflection" 'BEGIN { exit !(d ~ /^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$/ && d <= 0.03) }' ||
  die "H3P_TIP_DEFLECTION='$tipDeflection' must be a tip deflection in m, 0..0.03 (e.g. 4.6e-3)"
bent=0; awk -v d="$tipDeflection" 'BEGIN { exit !(d > 0) }' && bent=1
[ "$bent" = 0 ] || [ "$shape" = twist ] ||
  die "H3P_TIP_DEFLECTION needs H3P_SHAPE=twist (a pitch turns the foil as a whole)"
label=$shape$angle
[ "$bent" = 0 ] || label=$label-bend$tipDeflection
case "$algorithm" in simple|simplec) ;; *) die "H3D_ALGORITHM='$algorithm' must be simple or simplec" ;; esac
case "$scheme" in upwind|linearUpwind) ;; *) die "H3D_SCHEME='$scheme' must be upwind or linearUpwind" ;; esac
case "$rootWall" in wall) suffix="" ;; slip) suffix=-slip ;; *) die "H3D_ROOT_WALL='$rootWall' must be wall or slip" ;; esac
levels="coarse medium fine"
for level in $levels; do
  src=$rigidRuns/turbulent-$scheme-$algorithm$suffix-$level
  [ -f "$src/rigid/rigid.csv" ] ||
    die "no rigid flow $src/rigid/rigid.csv for $level (run scripts/verify hydrofoil-3d-rigid first)"
done
command -v foamDictionary > /dev/null || die "foamDictionary not found (source OpenFOAM's etc/bashrc; scripts/verify does)"
mkdir -p "$runs"

folders=()
for level in $levels; do
  src=$rigidRuns/turbulent-$scheme-$algorithm$suffix-$level
  r=$runs/$label-$scheme-$algorithm$suffix-$level c=$r/case
  if [ "$reuse" = 1 ] && grep -q '^End' "$c/log.pitch" 2> /dev/null; then
    echo "hydrofoil-pitch: reusing $r"
  else
    echo "hydrofoil-pitch: $level ($(date +%H:%M:%S), load $(cut -d' ' -f1 /proc/loadavg))"
    rm -rf "$r"; mkdir -p "$r"
    cp -r "$src/rigid/case" "$c"
    rm -rf "$c/postProcessing"
    # the one prescribed solve stops as the rigid study's did: its case's fsiDict `rigid` block
    # (rigid.sh's test) becomes `coupled`, from the rigid flow as it is
    foamDictionary -entry coupled -set "$(foamDictionary -entry rigid -value "$c/system/fsiDict")" \
      "$c/system/fsiDict" > /dev/null
    foamDictionary -entry coupled/warmStart -set "{ type previous; flux interpolated; }" \
      "$c/system/fsiDict" > /dev/null
    [ -z "$band" ] || foamDictionary -entry coupled/bandTolerance -set "$band" "$c/system/fsiDict" > /dev/null
    [ -z "$bandMean" ] || foamDictionary -entry coupled/bandMeanTolerance -set "$bandMean" "$c/system/fsiDict" > /dev/null
    [ -z "$maxIterations" ] ||
      foamDictionary -entry coupled/maxIterations -set "$maxIterations" "$c/system/fsiDict" > /dev/null
    if [ "$shape" = pitch ]; then
      motion="type rotation; origin (0.3685 0 0); axis (0 0 1); angle $angle;"
    else   # twist linear from the root (z = 0) to the tip (0.1 m), bending quadratic in -y
      motion="type twist; origin (0.3685 0 0); beamAxis (0 0 1); start 0; length 0.1;
      angle $angle; direction (0 -1 0); amplitude $tipDeflection;"
    fi
    foamDictionary -entry prescribed -set "{ $motion steps 1; solveFlow true; }" \
      "$c/system/fsiDict" > /dev/null
    foamDictionary -entry endTime -set 100000 "$c/system/controlDict" > /dev/null
    (cd "$c" && /usr/bin/time -f '%e %U %S' -o time.pitch \
        mpirun --oversubscribe -np "$np" fluid-app -prescribed -parallel > log.pitch 2>&1) ||
      { tail -5 "$c/log.pitch" >&2; echo "error: hydrofoil-pitch: $level failed (see $c/log.pitch)" >&2; exit 1; }
  fi
  # the case's function objects (forces: M_z) on the turned flow, as rigid.sh does after a solve
  if ! ls "$c"/postProcessing/forces/*/moment.dat > /dev/null 2>&1; then
    (cd "$c" && mpirun --oversubscribe -np "$np" simpleFoam -postProcess -parallel -time 1 \
        > log.postProcess 2>&1) ||
      { tail -5 "$c/log.postProcess" >&2; echo "error: hydrofoil-pitch: $level: simpleFoam -postProcess failed (see $c/log.postProcess)" >&2; exit 1; }
  fi
  # rigid.csv of the turned foil (history_gci.py --rigid reads it): the interface force of the
  # solve (the mean force when accepted in the mean) and M_z of the forces function object
  "$FSI_PYTHON" - "$c" "$src/rigid/rigid.csv" "$r/rigid.csv" <<'PY'
import csv, glob, re, sys
case, rigidCsv, out = sys.argv[1:]
rigid = next(csv.DictReader(open(rigidCsv)))
solves = list(csv.DictReader(open(case + "/postProcessing/fsi/coupling.csv")))
if not solves:
    sys.exit("error: hydrofoil-pitch: %s/postProcessing/fsi/coupling.csv has no finished solve" % case)
solve = solves[-1]   # fluid-app's record of the solve (the mean force when accepted in the mean)
iterations, converged, fx, fy = (solve[k] for k in ("simpleIterations", "converged", "Fx", "Fy"))
inMean = "converged in the mean" in open(case + "/log.pitch").read()
moments = sorted(glob.glob(case + "/postProcessing/forces/*/moment.dat"))
row = [l for l in open(moments[-1]) if not l.startswith("#")][-1]
mz = float(re.findall(r"\(([^)]*)\)", row)[0].split()[2])
wall, user, sys_ = open(case + "/time.pitch").read().split()
fields = ["cells", "flow", "scheme", "iterations", "converged", "in_the_mean", "band", "lift_N",
          "drag_N", "root_moment_z_Nm", "rigid_lift_N", "rigid_drag_N", "rigid_root_moment_z_Nm",
          "cpu_s", "wall_s"]
with open(out, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(fields)
    w.writerow([rigid["cells"], rigid["flow"], rigid["scheme"], iterations, converged,
                int(inMean), "", "%.6g" % -float(fy), "%.6g" % float(fx), "%.6g" % mz,
                rigid["lift_N"], rigid["drag_N"], rigid["root_moment_z_Nm"],
                "%.1f" % (float(user) + float(sys_)), "%.1f" % float(wall)])
PY
  tail -n 1 "$r/rigid.csv"
  folders+=("$r")
done

model=turbulent-$scheme-$algorithm-cgrid$suffix-$label
"$FSI_PYTHON" "$root/scripts/history_gci.py" --rigid --model "$model" --out "$FSI_VERIFY_DIR/gci.csv" \
    --table "${folders[@]}"
"$FSI_PYTHON" - "$FSI_VERIFY_DIR" "$model" "$root/scripts" "${folders[@]}" <<'PY'
import csv, os, sys
outDir, model, scripts = sys.argv[1:4]
folders = sys.argv[4:]
sys.path.insert(0, scripts)
from model_csv import write_model_rows
rows = [next(csv.DictReader(open(os.path.join(f, "rigid.csv")))) for f in folders]
names = ["coarse", "medium", "fine"]
changes = ["lift_change_N", "drag_change_N", "root_moment_z_change_Nm"]
levels = [dict([("model", model), ("preset", n)] + list(r.items()) +
               [(c, "%.6g" % (float(r[q]) - float(r["rigid_" + q])))
                for c, q in zip(changes, ("lift_N", "drag_N", "root_moment_z_Nm"))])
          for n, r in zip(names, rows)]
# one block of rows per model (scheme, root wall, angle): other models' rows are kept
write_model_rows(os.path.join(outDir, "levels.csv"), list(levels[0].keys()), model, levels)
PY
"$FSI_PYTHON" "$root/scripts/levels_error_csv.py" "$FSI_VERIFY_DIR/levels.csv" "$FSI_VERIFY_DIR/gci.csv" \
    "$FSI_VERIFY_DIR/error_vs_runtime.csv" "$np" "$model"
