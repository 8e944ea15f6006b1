#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Extremes stress suite (issue #8): the solid alone (solid-app standalone, 1 rank, small meshes)
# and the coupled loop (Turek-Hron FSI1 coarse, fluid-app + solid-app, MPMD 1 + 1 ranks) over
#   nu = 0.49, 0.499, 0.4999 (Cook's membrane, Tet10 and Hex20; small and finite strain);
#   E = 1e3 ... 1e11 Pa under a fixed tip load (cantilever, finite strain, Tet10 and Hex20);
#   Prony tau = 1e-6 ... 1e8 s against dt = 1e-3 ... 1e3 s (creep of a cube: the response must
#   stay between the instantaneous and the long-term elastic ones);
#   single-level load jumps (0 -> a large load in one level);
#   coupled: nominal, E x0.01 / x0.1 / x100, nu 0.499, inflow x0.1 / x5, gravity on the beam
#   switched on in one level (2 and 20 m/s^2), Prony tau small and large against the level
#   steps, a jump to a very soft relaxed beam in one level.
# Every case runs under a hard wall-clock limit (a hang is a failure) and is classified as
#   converged  exit 0 and finite results (and, for the creep cases, inside the elastic bounds);
#   diagnosed  non-zero exit with an `error:` line naming the failed check, nothing non-finite
#              written as an accepted result;
#   FAILED     hang (killed at the limit), NaN/inf accepted, a check violated after exit 0, or a
#              crash without an `error:` line.
# Writes OUT/results.csv, OUT/README.md (the table + what it means) and OUT/error_vs_runtime.csv
# (the cases with an analytic reference: creep vs the standard-linear-solid creep law, stiff
# cantilevers vs Timoshenko). Exits 1 if a case is FAILED or misses its fixed expectation
# (e.g. nominal FSI1, nu = 0.4999 Hex20 and E = 1e11 must converge).
#
# usage: scripts/verify extremes [options]     (FSI_SKIP_BUILD=1 to use build/bin as it is)
#        scripts/verify.d/extremes.sh [options] (directly; what CTest does)
#   --quick            a small fast subset (about a minute): 7 solid cases + nominal FSI1
#   --solid-only       skip the coupled cases (no fluid-app / OpenFOAM needed)
#   --only REGEX       run only the cases whose name matches REGEX (grep -E); through
#                      scripts/verify keep a creep case in (the plot needs a reference row)
#   --out DIR          results folder (default $FSI_VERIFY_DIR, else verification/extremes)
#   --work DIR         run folders, one per case (default runs/extremes; wiped per case)
#   --timeout S        wall-clock limit of a solid case [s] (default 300)
#   --coupled-timeout S  wall-clock limit of a coupled case [s] (default 300; the programs'
#                      own --comm-timeout is 120 s)
#   --list             print the case names (with --quick: the quick subset) and exit
# Environment: FSI_BUILD_DIR (binaries in FSI_BUILD_DIR/bin), FSI_PYTHON.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=${FSI_ROOT:-$(cd "$here/../.." && pwd)}
export FSI_ROOT=$root
source "$root/scripts/env.sh"
py=$FSI_PYTHON
helper=$here/extremes/report.py

quick=0 solid_only=0 only='' list=0
out=${FSI_VERIFY_DIR:-$root/verification/extremes}
work=$root/runs/extremes
t_solid=300 t_coupled=300
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1; shift ;;
    --solid-only) solid_only=1; shift ;;
    --only) only=${2:?--only needs a REGEX}; shift 2 ;;
    --out) out=${2:?--out needs a folder}; shift 2 ;;
    --work) work=${2:?--work needs a folder}; shift 2 ;;
    --timeout) t_solid=${2:?--timeout needs seconds}; shift 2 ;;
    --coupled-timeout) t_coupled=${2:?--coupled-timeout needs seconds}; shift 2 ;;
    --list) list=1; shift ;;
    -h|--help) awk 'NR > 2 && !/^#/ {exit} NR > 2 {sub(/^# ?/, ""); print}' "$0"; exit 0 ;;
    *) echo "error: extremes.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done

app=$FSI_BUILD_DIR/bin/solid-app
if [ "$list" = 0 ]; then
  [ -x "$app" ] || { echo "error: extremes.sh: $app not found; build first (cmake --build build) or set FSI_BUILD_DIR" >&2; exit 2; }
  command -v gmsh > /dev/null || { echo "error: extremes.sh: gmsh not on PATH; run scripts/setup" >&2; exit 2; }
  if [ "$solid_only" = 0 ]; then
    [ -x "$FSI_BUILD_DIR/bin/fluid-app" ] ||
      { echo "error: extremes.sh: $FSI_BUILD_DIR/bin/fluid-app not found; build with FSI_WITH_FLUID=ON or pass --solid-only" >&2; exit 2; }
    command -v blockMesh > /dev/null ||
      { echo "error: extremes.sh: blockMesh not on PATH (OpenFOAM v1912); run scripts/setup or pass --solid-only" >&2; exit 2; }
  fi
  mkdir -p "$out" "$work"
  work=$(cd "$work" && pwd)
  out=$(cd "$out" && pwd)
  : > "$work/cases.list"
fi
export PATH=$FSI_BUILD_DIR/bin:$PATH

# --- the matrix ----------------------------------------------------------------------------
# Quick subset (also the CTest extremes_quick test).
quick_cases=" nu0.4999-cook-hex nu0.4999-cookfs-tet E1e3-cant-tet E1e11-cant-hex creep-tau1e-6-dt1e3 \
creep-tau1e8-dt1e-3 jump-P100-svk fsi1-nominal "
selected() { # NAME: is this case part of the run?
  local name=$1
  [ "$quick" = 0 ] || [[ "$quick_cases" == *" $name "* ]] || return 1
  [ -z "$only" ] || echo "$name" | grep -Eq -- "$only" || return 1
  [ "$solid_only" = 0 ] || [[ "$name" != fsi1-* ]] || return 1
  return 0
}

# meta NAME KEY VALUE: one line of the case's description (read by report.py)
meta() { printf '%s=%s\n' "$2" "$3" >> "$work/$1/case.meta"; }

# begin NAME PROGRAM EXPECT PARAMS: fresh run folder; returns 1 when the case is not selected
begin() {
  local name=$1
  selected "$name" || return 1
  if [ "$list" = 1 ]; then echo "$name"; return 1; fi
  rm -rf "${work:?}/$name"
  mkdir -p "$work/$name"
  : > "$work/$name/case.meta"
  meta "$name" name "$name"
  meta "$name" program "$2"
  meta "$name" expect "$3"
  meta "$name" params "$4"
  echo "$name" >> "$work/cases.list"
  return 0
}

# finish NAME RC WALL LIMIT: record the exit status and wall time; one progress line
finish() {
  local name=$1 rc=$2 wall=$3 limit=$4 pids
  meta "$name" rc "$rc"
  meta "$name" wall_s "$wall"
  meta "$name" limit_s "$limit"
  # processes left behind in the run folder (a coupled program that outlived the limit; give
  # the ones that are shutting down 10 s)
  local k
  for k in 0 1 2 3 4 5 6 7 8 9 10; do
    pids=$(find /proc -mindepth 2 -maxdepth 2 -name cwd \( -lname "$work/$name" -o -lname "$work/$name/*" \) \
             2> /dev/null | awk -F/ '{printf "%s ", $3}' || true)
    [ -z "${pids// /}" ] && break
    [ "$k" -lt 10 ] && sleep 1
  done
  if [ -n "${pids// /}" ]; then
    meta "$name" strays "$pids"
    # shellcheck disable=SC2086
    kill -9 $pids 2> /dev/null || true
  fi
  printf 'extremes: %-26s exit %3s  %7.1f s\n' "$name" "$rc" "$wall"
}

# timed LIMIT CMD...: run CMD under a hard wall-clock limit; sets rc and wall.
timed() {
  local limit=$1 start
  shift
  start=$(date +%s.%N)
  set +e
  timeout -k 15 "$limit" "$@"
  rc=$?
  set -e
  wall=$(echo "$start $(date +%s.%N)" | awk '{printf "%.2f", $2 - $1}')
}

mesh_dir=$work/meshes
meshes_done=0
make_meshes() { # the solid meshes, once per run
  [ "$meshes_done" = 1 ] && return 0
  mkdir -p "$mesh_dir"
  local g=(gmsh -3 -order 2)
  "${g[@]}" -setnumber n 1 -setnumber hex 0 "$root/cases/solid/cantilever/beam.geo" -o "$mesh_dir/cant-tet.msh" > "$mesh_dir/log.gmsh" 2>&1 &&
  "${g[@]}" -setnumber n 2 -setnumber hex 1 "$root/cases/solid/cantilever/beam.geo" -o "$mesh_dir/cant-hex.msh" >> "$mesh_dir/log.gmsh" 2>&1 &&
  "${g[@]}" -setnumber n 8 -setnumber hex 0 "$root/cases/solid/cook/cook.geo" -o "$mesh_dir/cook-tet.msh" >> "$mesh_dir/log.gmsh" 2>&1 &&
  "${g[@]}" -setnumber n 8 -setnumber hex 1 "$root/cases/solid/cook/cook.geo" -o "$mesh_dir/cook-hex.msh" >> "$mesh_dir/log.gmsh" 2>&1 &&
  "${g[@]}" "$root/cases/solid/prony/cube.geo" -o "$mesh_dir/cube.msh" >> "$mesh_dir/log.gmsh" 2>&1 ||
    { echo "error: extremes.sh: gmsh failed, see $mesh_dir/log.gmsh" >&2; exit 1; }
  meshes_done=1
}

# run_solid NAME: solid-app on NAME/case.yaml (written by the caller) under the limit
run_solid() {
  local name=$1 d=$work/$1
  (cd "$d" && timed "$t_solid" "$app" case.yaml --out output > log.solid-app 2>&1; echo "$rc $wall" > .rc)
  read -r rc wall < "$d/.rc"
  finish "$name" "$rc" "$wall" "$t_solid"
}

# Cook's membrane (plane strain slab, clamped at x = 0, shear traction on x = 48), n = 8.
# cook NAME EXPECT ELEM NU LAW KIN TRACTION
cook() {
  local name=$1 expect=$2 elem=$3 nu=$4 law=$5 kin=$6 tr=$7 el
  [ "$elem" = hex ] && el=Hex20 || el=Tet10
  begin "$name" solid "$expect" "Cook n=8 $el, $law, $kin, E=250 Pa, nu=$nu, traction $tr Pa (total $(awk -v t="$tr" 'BEGIN{print 16*t}') N)" || return 0
  make_meshes
  cat > "$work/$name/case.yaml" << EOF
solid:
  mesh: {file: $mesh_dir/cook-$elem.msh, volume: solid, clamped: [clamped]}
  material: {type: $law, E: 250.0, nu: $nu}
  kinematics: $kin
  newton: {absolute_tolerance: 1.0e-12}
  loads:
    tractions:
      - {surface: load, traction: [0.0, $tr, 0.0]}
    displacements:
      - {surface: faces, z: 0.0}
  output:
    vtu: false
    watch:
      - {name: C, point: [48.0, 60.0, 0.0]}
EOF
  meta "$name" watch "C"
  run_solid "$name"
}

# Cantilever 2 x 0.1 x 0.1 m (Tet10 n = 1: 1 x 1 x 20 boxes; Hex20 n = 2), total-lagrangian.
# cantilever NAME EXPECT ELEM LAW E NU FORCE_VECTOR [JUMP]
#   JUMP=jump: levels t = 0 (load factor 0) and t = 1 (factor 1): the whole load in one level.
#   KIN (default total-lagrangian) and RTOL (newton.residual_tolerance, with
#   absolute_tolerance 1e-12; default: the solver's) may be set for the call.
cantilever() {
  local name=$1 expect=$2 elem=$3 law=$4 E=$5 nu=$6 force=$7 jump=${8:-} el time=''
  local kin=${KIN:-total-lagrangian} newton='' tol=''
  if [ -n "${RTOL:-}" ]; then
    newton="  newton: {residual_tolerance: $RTOL, absolute_tolerance: 1.0e-12}"
    tol=", Newton tolerance $RTOL relative + 1e-12 N"
  fi
  [ "$elem" = hex ] && el=Hex20 || el=Tet10
  local what="one static level"
  if [ "$jump" = jump ]; then
    time="  time: {dt: 1.0, end: 1.0, load_factor: [[0.0, 0.0], [1.0, 1.0]]}"
    what="levels: 0 load, then the full load in one level"
  fi
  begin "$name" solid "$expect" "cantilever 2x0.1x0.1 m $el, $law, $kin, E=$E Pa, nu=$nu, tip force [$force] N$tol; $what" || return 0
  make_meshes
  cat > "$work/$name/case.yaml" << EOF
solid:
  mesh: {file: $mesh_dir/cant-$elem.msh, volume: solid, clamped: [clamped]}
  material: {type: $law, E: $E, nu: $nu}
  kinematics: $kin
$newton
  loads:
    forces:
      - {surface: tip, total: [$force]}
$time
  output:
    vtu: false
    watch:
      - {name: tip, point: [2.0, 0.0, 0.0]}
EOF
  meta "$name" watch "tip"
  [ "$jump" = jump ] && meta "$name" levels_planned 2
  # small-deflection reference (Timoshenko, kappa = 5/6) for the stiff ends of the E sweep
  meta "$name" timoshenko "$(awk -v E="$E" -v nu="$nu" -v f="$force" 'BEGIN {
      split(f, c, ","); P = -c[2]; L = 2; I = 0.1^4 / 12; A = 0.01; G = E / (2 * (1 + nu));
      printf "%.9e", -(P * L^3 / (3 * E * I) + P * L / (5 / 6 * G * A)) }')"
  run_solid "$name"
}

# Creep of the unit cube (cases/solid/prony): sigma0 = 1e4 Pa step held, K = 10 MPa elastic,
# G0 = 1 MPa instantaneous, one Prony term g = 0.5 (abaqus-g: G_inf = 0.5 MPa), tau; 10 levels
# of dt after the instantaneous level t = 0.
# creep NAME TAU DT
creep() {
  local name=$1 tau=$2 dt=$3 end
  end=$(awk -v d="$dt" 'BEGIN{printf "%.6g", 10 * d}')
  begin "$name" solid converged "cube 2x2x2 Hex20, small strain, K=10 MPa, G0=1 MPa, g=0.5, tau=$tau s; dt=$dt s, 10 levels to t=$end s; sigma=1e4 Pa step" || return 0
  make_meshes
  cat > "$work/$name/case.yaml" << EOF
solid:
  mesh: {file: $mesh_dir/cube.msh, volume: solid}
  material:
    type: viscoelastic
    K: 10.0e6
    G: 1.0e6
    modulus_basis: instantaneous
    prony: {convention: abaqus-g, coefficients: [0.5], times: [$tau]}
  kinematics: small-strain
  newton: {residual_tolerance: 1.0e-12}
  loads:
    tractions:
      - {surface: x1, traction: [1.0e4, 0.0, 0.0]}
    displacements:
      - {surface: x0, x: 0.0}
      - {surface: y0, y: 0.0}
      - {surface: z0, z: 0.0}
  time: {dt: $dt, end: $end}
  output:
    vtu: false
    watch:
      - {name: probe, point: [1.0, 0.5, 0.5]}
EOF
  meta "$name" watch "probe"
  meta "$name" creep "$tau"
  meta "$name" levels_planned 11
  run_solid "$name"
}

# Coupled FSI1 coarse in a copy of cases/turek-hron-fsi1; the copy's configs are patched.
# fsi1 NAME EXPECT PARAMS PATCH-ARGS... -- RUN.SH-ARGS...
#   patch args: E=X nu=X gamma=X tau=X gravity=G (on the config run.sh uses), U=FACTOR (inflow)
fsi1() {
  local name=$1 expect=$2 params=$3 d args=() patches=() material=elastic cfg
  shift 3
  while [ $# -gt 0 ] && [ "$1" != -- ]; do patches+=("$1"); shift; done
  [ $# -gt 0 ] && shift
  args=("$@")
  begin "$name" coupled "$expect" "$params" || return 0
  d=$work/$name
  cp -r "$root/cases/turek-hron-fsi1/." "$d/"
  for ((i = 0; i < ${#args[@]}; i++)); do [ "${args[i]}" = --material ] && material=${args[i + 1]}; done
  [ "$material" = viscoelastic ] && cfg=$d/solid-visco.yaml || cfg=$d/solid.yaml
  local p
  for p in "${patches[@]}"; do
    "$py" "$helper" patch "$d" "$cfg" "$p" ||
      { echo "error: extremes.sh: cannot patch $p into $cfg (did the case's format change?)" >&2; exit 1; }
  done
  local planned=1 t
  for ((i = 0; i < ${#args[@]}; i++)); do
    if [ "${args[i]}" = --times ]; then t=${args[i + 1]}; planned=$(echo "$t" | tr ',' '\n' | wc -l); fi
  done
  [ "$material" = viscoelastic ] && [ "$planned" = 1 ] && planned=2
  meta "$name" levels_planned "$planned"
  meta "$name" watch "A"
  (cd "$d" && timed "$t_coupled" ./run.sh --preset coarse --launch mpmd --timeout 120 "${args[@]}" > log.run 2>&1
   echo "$rc $wall" > .rc)
  read -r rc wall < "$d/.rc"
  finish "$name" "$rc" "$wall" "$t_coupled"
}

# --- solid alone ------------------------------------------------------------------------------
for nu in 0.49 0.499 0.4999; do
  for elem in tet hex; do
    # small strain, F = 1 N (cook-incompressible.yaml): quadratic elements must not lock
    cook "nu$nu-cook-$elem" converged "$elem" "$nu" linear-elastic small-strain 0.0625
    # finite strain, neo-Hooke, F = 100 N (|u_C| ~ 8 on a 48 x 60 panel)
    cook "nu$nu-cookfs-$elem" any "$elem" "$nu" neo-hookean total-lagrangian 6.25
  done
done
for E in 1e3 1e5 1e7 1e9 1e11; do
  case $E in 1e9|1e11) expect=converged ;; *) expect=any ;; esac
  for elem in tet hex; do
    cantilever "E$E-cant-$elem" "$expect" "$elem" linear-elastic "$E" 0.3 "0.0, -100.0, 0.0"
  done
done
# stiff and lightly loaded, with the Newton tolerances of cases/turek-hron-fsi1 (1e-10 relative,
# 1e-12 N): strains of 1e-8, a linear problem in the small-strain case
KIN=small-strain RTOL=1.0e-10 cantilever "E1e11-P0.1-tight-ss" converged hex linear-elastic 1e11 0.3 "0.0, -0.1, 0.0"
RTOL=1.0e-10 cantilever "E1e11-P0.1-tight-tl" converged hex linear-elastic 1e11 0.3 "0.0, -0.1, 0.0"
# a very soft bar pushed axially: St Venant-Kirchhoff has no compressive state beyond
# P/(EA) = 0.19 (limit point at stretch 1/sqrt 3), neo-Hooke has; plus Euler buckling
cantilever "E1e3-compress-svk" any tet linear-elastic 1e3 0.3 "-10.0, 0.0, 0.0"
cantilever "E1e3-compress-nh" any tet neo-hookean 1e3 0.3 "-10.0, 0.0, 0.0"
for tau in 1e-6 1e-2 1e2 1e8; do
  for dt in 1e-3 1 1e3; do creep "creep-tau$tau-dt$dt" "$tau" "$dt"; done
done
cantilever "jump-P100-svk" any tet linear-elastic 1e7 0.3 "0.0, -100.0, 0.0" jump
cantilever "jump-P1e4-svk" any tet linear-elastic 1e7 0.3 "0.0, -1.0e4, 0.0" jump
cantilever "jump-P1e4-nh" any tet neo-hookean 1e7 0.3 "0.0, -1.0e4, 0.0" jump

# --- coupled -------------------------------------------------------------------------------
if [ "$solid_only" = 0 ]; then
  fsi1 fsi1-nominal converged "FSI1 coarse, E=1.4e6 Pa, nu=0.4, Ubar=0.2 m/s (Re 20), steady"
  fsi1 fsi1-E0.01 any "E x0.01 = 1.4e4 Pa (very soft beam)" E=1.4e4
  fsi1 fsi1-E0.1 any "E x0.1 = 1.4e5 Pa" E=1.4e5
  fsi1 fsi1-E100 converged "E x100 = 1.4e8 Pa" E=1.4e8
  fsi1 fsi1-nu0.499 any "nu = 0.499 (E = 1.4e6 Pa)" nu=0.499
  fsi1 fsi1-U0.1 converged "inflow x0.1 (Ubar 0.02 m/s, Re 2)" U=0.1
  fsi1 fsi1-U5 any "inflow x5 (Ubar 1 m/s, Re 100: unsteady in reality; steady SIMPLE)" U=5
  # gravity on the beam (rho 1000 kg/m^3) switched on in the single level, on top of the flow:
  # 2 m/s^2 (CSM1's load: a few cm), 20 m/s^2 (the beam would reach the channel wall: the fluid
  # mesh cannot follow, the fluid's mesh-quality check must end the run)
  fsi1 fsi1-gravity2 any "gravity 2 m/s^2 on the beam in one level (CSM1 load) + the flow" gravity=2
  fsi1 fsi1-gravity20 diagnosed "gravity 20 m/s^2 on the beam in one level: the beam would reach the channel wall" gravity=20
  fsi1 fsi1-visco-tau1e-6 any "Prony gamma 0.5, tau=1e-6 s; levels 0, 1e-3, 1, 1e3 s" tau=1e-6 -- \
    --material viscoelastic --times 0,1e-3,1,1e3
  fsi1 fsi1-visco-tau1e8 any "Prony gamma 0.5, tau=1e8 s; levels 0, 1e-3, 1, 1e3 s" tau=1e8 -- \
    --material viscoelastic --times 0,1e-3,1,1e3
  fsi1 fsi1-visco-jump any "Prony long-term E=1.4e5 Pa, gamma 99 (instantaneous x100), tau=1 s; levels 0 then 1e6 s: relaxed x100 in one level" \
    E=1.4e5 gamma=99 -- --material viscoelastic --times 0,1e6
fi

[ "$list" = 1 ] && exit 0
[ -s "$work/cases.list" ] || { echo "error: extremes.sh: no case selected (check --only / --quick)" >&2; exit 2; }
mode=full
[ "$quick" = 1 ] && mode=quick
"$py" "$helper" report "$work" "$out" --mode "$mode"
