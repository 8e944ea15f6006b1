#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The paper's case end to end, inside a copy of cases/hydrofoil (scripts/run makes the copy):
#
#   ./scripts/run cases/hydrofoil [--preset coarse|medium|fine] [options]
#
# Options (after the case):
#   --material viscoelastic|baseline|relaxed|both|elastic
#                                           which runs (default both: the paper's comparison).
#                                           baseline = elastic, instantaneous modulus (t = 0);
#                                           relaxed = elastic, long-term modulus (t -> infinity);
#                                           both = baseline + viscoelastic; elastic = baseline +
#                                           relaxed (the two steady bounds, no time stepping)
#   --np-fluid N --np-solid M               ranks of each program (default 2 and 2: the two
#                                           programs take turns, so on a 2-core machine the
#                                           solid's phases use both cores; README.md,
#                                           "The solid's share")
#   --launch mpmd|port                      one mpirun A : B (default) or two + ompi-server
#   --tc T --cli C                          section thickness ratio and design lift (0.12, 0.5)
#   --end SECONDS                           last time level of the viscoelastic run (3600)
#   --timeout SECONDS                       longest wait for the peer (default 900)
#   --mesh-from DIR                         reuse the meshes of an earlier run folder (DIR/mesh)
#   --flow laminar|transition|turbulent     flow model (default: turbulent = k-omega SST on the
#                                           boundary-layer mesh, laminar, the paper's, on the snappy
#                                           mesh: README, "The case default"); transition =
#                                           Langtry-Menter kOmegaSSTLM (tools/setFlow.sh; README
#                                           "Flow models")
#   --scheme upwind|linearUpwind            convection of U and the turbulence fields (default
#                                           upwind; linearUpwind: second order, bounded)
#   --root-wall wall|slip                   the tunnel's root wall z = 0 (default wall: the paper's
#                                           no-slip tunnel); slip: a slip patch `root`
#                                           (tools/rootWall.sh), with which the second-order flow
#                                           has a steady state (README, "A steady second-order
#                                           flow: the slip root wall")
#   --algorithm simple|simplec              classic SIMPLE (consistent no, relaxation p 0.3,
#                                           U and turbulence 0.7) or the case's SIMPLEC (p 1, U
#                                           0.9; tools/setFlow.sh). Default: simplec (README,
#                                           "The case default"); simple on a medium or fine
#                                           boundary-layer mesh made before 2026-12-05 evening
#                                           (SIMPLEC oscillates in its tip gap: README, "The tip
#                                           gap's re-spaced cells"; tools/meshModel.sh)
#   --simple-acceleration none|anderson[:DEPTH]
#                                           the fluid's SIMPLE iterations plain (default) or
#                                           Anderson-mixed over the last DEPTH (5) iterations
#                                           (fvSolution SIMPLE.acceleration, fluid-app/README.md;
#                                           README, "Anderson-mixed SIMPLE iterations")
#   --fluid-mesh cgrid|snappy               fluid mesh (mesh.sh): cgrid (default), the boundary-
#                                           layer mesh, y+ <= 1 on the whole foil; snappy, the
#                                           snappyHexMesh mesh without layers: with it the model
#                                           defaults to the paper's (laminar, SIMPLEC), so
#                                           `--fluid-mesh snappy` is the paper's setup (the case
#                                           default before 2026-12-05). With --mesh-from or
#                                           --restart the mesh is the one in that folder
#                                           (mesh/mesh-summary.txt) and the model follows it
#   --solid-element tet10|hex20             the foil's finite elements (mesh.sh makes both): tet10
#                                           (default), plain quadratic tetrahedra; hex20, the
#                                           structured Hex20 mesh with the projected dilatation
#                                           (B-bar: no locking at nu = 0.49; the solid configs'
#                                           solid.element, config/solid.example.yaml). A --restart
#                                           keeps the element of the run's first start
#   --solid-mesh-from DIR                   the structural meshes of DIR/mesh/solid (another run or
#                                           mesh folder of the same section: t/c and C_Li
#                                           checked) instead of this run's own: a mesh study of
#                                           the fluid with one structure (README, "The structure's
#                                           share of the coupled mesh study"). Copied into this
#                                           run's mesh/solid; mesh/mesh-summary.txt names DIR.
#                                           Not with --restart (the run keeps its meshes)
#   --init-from CASE                        start every fluid solve's first iteration from the
#                                           solution of the OpenFOAM case CASE (reconstructed,
#                                           latest time; e.g. a rigid.sh/blcheck.sh rigid/case
#                                           on the same or another mesh), mapped onto this
#                                           mesh (tools/mapInitialFields.sh): level 0 then
#                                           starts from the rigid flow instead of from rest
#   --band-tolerance B                      accept a fluid solve "in the mean" when its force stays
#                                           within +-B |F| over two blocks of 100 iterations (fsiDict
#                                           coupled/bandTolerance; default: the case's 2e-3). For flows
#                                           without a steady state, e.g. second order on the
#                                           boundary-layer mesh (+-1 % at the root junction): README,
#                                           "Second order inside the coupled loop"
#   --band-mean-tolerance M                 ... and when the two blocks' means differ by <= M |F| (fsiDict
#                                           coupled/bandMeanTolerance; default 0: the fluid accuracy
#                                           asked, 5e-5). For a mean that wanders by ~1e-3 between
#                                           blocks; keep --fluid-tolerance tight, a loose one lets
#                                           the steady error estimate stop on the oscillation
#   --band-reference-force F                the band and the means are measured against max(|Fm|, F)
#                                           [N] instead of |Fm| (fsiDict coupled/bandReferenceForce;
#                                           default 0: |Fm|). For a history whose lift passes through
#                                           zero while the oscillation keeps its size: F = the t = 0
#                                           lift, e.g. 1 (README, "Second order inside the coupled loop")
#   --band-window N                         iterations per block of that rule (fsiDict coupled/
#                                           bandWindow; default the case's 100; 2 N <= the cap)
#   --oscillation-window N                  honest coupled solves: the force-error estimate is at least
#                                           half the range of an oscillating force over the last N
#                                           SIMPLE iterations (fsiDict coupled/oscillationWindow; default
#                                           the case's 0, off; 3..1000, about one period): no stop at a
#                                           turning point (README, "Honest fluid solves")
#   --warm-start-flux interpolated|kept     the flux of each coupled solve's first iteration after the
#                                           motion (fsiDict coupled/warmStart/flux; default the case's
#                                           interpolated, fvc::flux(U)); kept: the last solve's flux
#                                           corrected for the moved faces: no pressure-velocity ringing,
#                                           slower monotone solves (README, "A medium reference
#                                           history"; fluid-app/README.md)
#   --warm-start-max-coefficient C          the largest |c_j| of the secant warm start's flow
#                                           extrapolation (fsiDict coupled/warmStart/maxCoefficient;
#                                           default the case's 2; > 0; README, "The warm start's
#                                           largest coefficient")
#   --fluid-tolerance F                     the fluid's final and largest force accuracy (the solid
#                                           configs' coupling.fluid_accuracy final.force_tolerance and
#                                           max_force_tolerance; default 5e-5)
#   --coupling-tolerance T                  interface tolerance |r|/sqrt(n) < T [m] (the solid configs'
#                                           coupling.convergence.absolute_tolerance; default 5e-6,
#                                           within the equal-accuracy targets on coarse and medium;
#                                           2e-6 costs 2.3x the SIMPLE iterations on medium: README,
#                                           "The first medium reference was off")
#   --coupling-band-factor B                the coupling's widening for levels whose flow has no steady
#                                           state (the solid configs' coupling.convergence.band_factor:
#                                           an iteration whose fluid solve was accepted in the mean
#                                           converges at max(tolerance, B b rms(u)), b the solve's
#                                           relative band; default the configs' 20 (viscoelastic.yaml)
#                                           and 2 (baseline/relaxed); >= 0, 0 = never widened: README,
#                                           "Second order inside the coupled loop")
#   --max-fluid-iterations N                cap on the SIMPLE iterations of one coupled fluid solve
#                                           (fsiDict coupled/maxIterations; default the case's 400)
#   --mapping TYPE                          the interface mapping (the solid configs'
#                                           coupling.mapping.type). Default by fluid mesh: on the
#                                           boundary-layer (cgrid) mesh moving-least-squares with
#                                           no smoothing (each fluid point takes the linear field
#                                           fitted to the solid nodes around it: a fluid point
#                                           inside the solid's blunt trailing edge moves with the
#                                           section there, and the coupled mesh study converges;
#                                           README, "The mapping follows the fluid mesh"); on the
#                                           snappy mesh the configs' nearest-projection with
#                                           smoothing 2e-4. Or rbf-wendland-c2 | rbf-pu |
#                                           rbf-thin-plate | nearest-neighbour. The type's
#                                           coefficient block is the configs' (defaults where
#                                           absent); given, the smoothing radius is the configs'
#                                           2e-4 unless --mapping-smoothing says otherwise. A
#                                           --restart keeps the mapping of the run's first start
#                                           (file `mapping` in the run folder)
#   --mapping-smoothing R                   radius [m] of the moving-least-squares smoothing of the
#                                           mapped values on the fluid side (the solid configs'
#                                           coupling.mapping.smoothing_radius; 0 = off; default
#                                           0 with the cgrid mesh's default mapping, else the
#                                           configs' 2e-4). Nearest-projection needs it on the
#                                           boundary-layer mesh to keep the tip cells valid
#                                           (README, "The tip cells and the mapped displacement's
#                                           kink"); on the snappy meshes hardly a foil point has a
#                                           neighbour that close
#   --restart                               continue an interrupted run in this folder (same
#                                           options): finished runs are kept (a viscoelastic one
#                                           continues when --end is later than its last level:
#                                           a history extended, its summary.csv kept as
#                                           summary.csv.partN), an interrupted one
#                                           continues from results/<run>/checkpoint/latest
#                                           (scripts/fsi-restart-fluid + --restart), a run that
#                                           never started starts; logs of earlier parts are kept
#                                           as log.<run>.partN. The fsiDict options given (--band-*,
#                                           --oscillation-window, --max-fluid-iterations,
#                                           --warm-start-*) are set again, so a continued run may
#                                           change them; left out, the run's values stay
#   --check-only                            validate the options (and the --mesh-from /
#                                           --init-from folders) and exit: 0, or 2 with the
#                                           one-line error; writes nothing (scripts/run calls
#                                           it before it makes the run folder)
# Writes results/: history.csv (viscoelastic, one row per level), baseline/, relaxed/ and visco/
# (solid-app outputs: coupling.csv, history.csv, interface/, solid_*.vtu + solid.pvd), summary.csv and the
# PNG plots; the fluid fields of accepted levels are in fluid-*/ (OpenFOAM time folders).
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '3,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
: "${FSI_ROOT:?run through ./scripts/run cases/hydrofoil (FSI_ROOT unset)}"
source "$FSI_ROOT/scripts/env.sh"

preset=coarse material=both npf=2 nps=2 launch=mpmd tc=0.12 cli=0.5 end="" timeout=900 meshFrom="" restart=0 checkOnly=0
solidElement="" solidFrom=""
flow="" scheme=upwind rootWall=wall algorithm="" fluidMesh="" initFrom="" band="" maxFluidIt="" fluidTol="" couplingTol="" bandFactor="" bandWindow="" bandMean="" bandRef="" oscWindow="" wsFlux="" wsMaxCoef="" mapSmoothing="" mapType="" acceleration=""
die() { echo "error: hydrofoil/run.sh: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
  case "$1" in
    --preset) preset=$2; shift 2 ;;
    --material) material=$2; shift 2 ;;
    --np-fluid) npf=$2; shift 2 ;;
    --np-solid) nps=$2; shift 2 ;;
    --launch) launch=$2; shift 2 ;;
    --tc) tc=$2; shift 2 ;;
    --cli) cli=$2; shift 2 ;;
    --end) end=$2; shift 2 ;;
    --timeout) timeout=$2; shift 2 ;;
    --mesh-from) meshFrom=$2; shift 2 ;;
    --flow) flow=$2; shift 2 ;;
    --scheme) scheme=$2; shift 2 ;;
    --algorithm) algorithm=$2; shift 2 ;;
    --simple-acceleration) [ $# -ge 2 ] || die "--simple-acceleration needs none or anderson[:DEPTH]"; acceleration=$2; shift 2 ;;
    --root-wall) [ $# -ge 2 ] || die "--root-wall needs wall or slip"; rootWall=$2; shift 2 ;;
    --fluid-mesh) fluidMesh=$2; shift 2 ;;
    --solid-element) [ $# -ge 2 ] || die "--solid-element needs tet10 or hex20"; solidElement=$2; shift 2 ;;
    --solid-mesh-from) [ $# -ge 2 ] || die "--solid-mesh-from needs a run or mesh folder"; solidFrom=$2; shift 2 ;;
    --init-from) [ $# -ge 2 ] || die "--init-from needs an OpenFOAM case folder"; initFrom=$2; shift 2 ;;
    --band-tolerance) [ $# -ge 2 ] || die "--band-tolerance needs a value"; band=$2; shift 2 ;;
    --band-mean-tolerance) [ $# -ge 2 ] || die "--band-mean-tolerance needs a value"; bandMean=$2; shift 2 ;;
    --band-reference-force) [ $# -ge 2 ] || die "--band-reference-force needs a value in N"; bandRef=$2; shift 2 ;;
    --oscillation-window) [ $# -ge 2 ] || die "--oscillation-window needs a value"; oscWindow=$2; shift 2 ;;
    --band-window) [ $# -ge 2 ] || die "--band-window needs a value"; bandWindow=$2; shift 2 ;;
    --warm-start-flux) [ $# -ge 2 ] || die "--warm-start-flux needs interpolated or kept"; wsFlux=$2; shift 2 ;;
    --warm-start-max-coefficient) [ $# -ge 2 ] || die "--warm-start-max-coefficient needs a number"; wsMaxCoef=$2; shift 2 ;;
    --fluid-tolerance) [ $# -ge 2 ] || die "--fluid-tolerance needs a value"; fluidTol=$2; shift 2 ;;
    --coupling-tolerance) [ $# -ge 2 ] || die "--coupling-tolerance needs a value in m"; couplingTol=$2; shift 2 ;;
    --coupling-band-factor) [ $# -ge 2 ] || die "--coupling-band-factor needs a number >= 0"; bandFactor=$2; shift 2 ;;
    --max-fluid-iterations) [ $# -ge 2 ] || die "--max-fluid-iterations needs a value"; maxFluidIt=$2; shift 2 ;;
    --mapping) [ $# -ge 2 ] || die "--mapping needs a type, e.g. moving-least-squares"; mapType=$2; shift 2 ;;
    --mapping-smoothing) [ $# -ge 2 ] || die "--mapping-smoothing needs a radius in m"; mapSmoothing=$2; shift 2 ;;
    --restart) restart=1; shift ;;
    --check-only) checkOnly=1; shift ;;
    -h|--help) sed -n '3,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown option '$1' (see --help)" ;;
  esac
done
case "$material" in viscoelastic|baseline|relaxed|both|elastic) ;; *) die "--material must be viscoelastic, baseline, relaxed, both or elastic" ;; esac
case "$launch" in mpmd|port) ;; *) die "--launch must be mpmd or port" ;; esac
case "$fluidMesh" in ""|snappy|cgrid) ;; *) die "--fluid-mesh must be cgrid or snappy (got '$fluidMesh')" ;; esac
case "$algorithm" in ""|simple|simplec) ;; *) die "--algorithm must be simple or simplec (got '$algorithm')" ;; esac
case "$rootWall" in wall|slip) ;; *) die "--root-wall must be wall (the paper's no-slip tunnel) or slip (got '$rootWall')" ;; esac
case "$solidElement" in ""|tet10|hex20) ;; *) die "--solid-element must be tet10 or hex20 (got '$solidElement')" ;; esac
# The element of a restarted run is the one of its first start (solid-element, written then)
if [ "$restart" = 1 ] && [ -f solid-element ]; then
  [ -z "$solidElement" ] || [ "$solidElement" = "$(cat solid-element)" ] ||
      die "--solid-element $solidElement: this run started with $(cat solid-element); a --restart keeps it (leave the option out)"
  solidElement=$(cat solid-element)
fi
solidElement=${solidElement:-tet10}
if [ -n "$solidFrom" ]; then
  [ "$restart" = 0 ] || die "--solid-mesh-from: a --restart keeps the run's meshes (leave the option out)"
  [ -f "$solidFrom/mesh/mesh-summary.txt" ] && [ -f "$solidFrom/mesh/solid/foil-$solidElement.msh" ] ||
      die "--solid-mesh-from $solidFrom: no mesh/mesh-summary.txt and mesh/solid/foil-$solidElement.msh there (a run or mesh folder made by mesh.sh)"
  solidFrom=$(cd "$solidFrom" && pwd)
fi
# The fluid mesh of this run: a new one (--fluid-mesh, default cgrid) or the one of --mesh-from /
# --restart; the model follows the mesh unless given (tools/meshModel.sh; README, "The case
# default"): k-omega SST with SIMPLEC on the boundary-layer mesh (classic SIMPLE on an older
# medium or fine one), the paper's laminar flow with the case's SIMPLEC on the snappy mesh.
summary=""
if [ "$restart" = 1 ]; then summary=$PWD/mesh/mesh-summary.txt; elif [ -n "$meshFrom" ]; then summary=$meshFrom/mesh/mesh-summary.txt; fi
meshWhat=("$summary")
[ -n "$summary" ] && [ -f "$summary" ] || meshWhat=("${fluidMesh:-cgrid}" "$preset")
read -r meshKind defaultFlow defaultAlgorithm < <("$FSI_ROOT/cases/hydrofoil/tools/meshModel.sh" "${meshWhat[@]}") ||
    die "cannot tell the fluid mesh of ${meshWhat[*]}"
[ -z "$fluidMesh" ] || [ "$fluidMesh" = "$meshKind" ] ||
    die "--fluid-mesh $fluidMesh: the fluid mesh in $(dirname "$(dirname "$summary")") is $meshKind (leave --fluid-mesh out with --mesh-from or --restart)"
fluidMesh=$meshKind
# The interface mapping follows the fluid mesh unless given (README, "The mapping follows the
# fluid mesh"): moving-least-squares without smoothing on the boundary-layer mesh, where the
# fluid's sharp trailing edge lies inside the solid's blunt one; the configs' own
# (nearest-projection, smoothing 2e-4) on the snappy mesh, whose stored references and studies
# were made with it. --mapping alone keeps the configs' smoothing radius. A restarted run keeps
# the mapping of its first start (file mapping, written then; runs without it used the configs').
mapDefaultType="" mapDefaultSmoothing=""
if [ "$restart" = 1 ] && [ -f mapping ]; then
  read -r startedType startedSmoothing < mapping
  [ -z "$mapType" ] || [ "$mapType" = "$startedType" ] ||
      die "--mapping $mapType: this run started with $startedType; a --restart keeps it (leave the option out)"
  [ -z "$mapSmoothing" ] || awk -v a="$mapSmoothing" -v b="$startedSmoothing" 'BEGIN{exit !(a + 0 == b + 0)}' ||
      die "--mapping-smoothing $mapSmoothing: this run started with $startedSmoothing; a --restart keeps it (leave the option out)"
  mapDefaultType=$startedType mapDefaultSmoothing=$startedSmoothing
elif [ "$restart" = 0 ] && [ "$fluidMesh" = cgrid ] && [ -z "$mapType" ]; then
  mapDefaultType=moving-least-squares mapDefaultSmoothing=0
fi
if [ -n "$solidFrom" ]; then
  # section KEY SUMMARY: KEY's value (preset, tc, cli) on a mesh summary's first line (mesh.sh's).
  # The structure's section must be this run's: t/c and C_Li against the --mesh-from mesh's
  # (or --tc / --cli for a mesh made now)
  section() { head -n 1 "$2" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
  for k in tc cli; do
    theirs=$(section $k "$solidFrom/mesh/mesh-summary.txt")
    if [ -n "$meshFrom" ]; then ours=$(section $k "$summary"); elif [ $k = tc ]; then ours=$tc; else ours=$cli; fi
    awk -v a="$theirs" -v b="$ours" 'BEGIN{exit !(a != "" && b != "" && a + 0 == b + 0)}' ||
        die "--solid-mesh-from $solidFrom: its section has $k=${theirs:-?}, this run's $k=${ours:-?} (mesh both with the same --tc / --cli)"
  done
fi
flow=${flow:-$defaultFlow} algorithm=${algorithm:-$defaultAlgorithm}
[ "$algorithm" != simplec ] || algorithm=""
"$FSI_ROOT/cases/hydrofoil/tools/setFlow.sh" --check-only --flow "$flow" --scheme "$scheme" \
    ${algorithm:+--algorithm "$algorithm"}
"$FSI_ROOT/cases/hydrofoil/tools/fluidCase.sh" --check-only ${acceleration:+--simple-acceleration "$acceleration"}
# positive VALUE [UPPER]: VALUE is a number > 0 (and < UPPER)
positive() { awk -v v="$1" -v u="${2:-}" 'BEGIN{exit !(v ~ /^[0-9.eE+-]+$/ && v + 0 > 0 && (u == "" || v + 0 < u + 0))}'; }
[ -z "$band" ] || positive "$band" 1 || die "--band-tolerance '$band' must be a number in (0, 1), e.g. 1e-2"
[ -z "$bandMean" ] || positive "$bandMean" 1 ||
    die "--band-mean-tolerance '$bandMean' must be a number in (0, 1), e.g. 3e-3"
[ -z "$bandRef" ] || positive "$bandRef" ||
    die "--band-reference-force '$bandRef' must be a force in N > 0, e.g. 1 (the t = 0 lift)"
[ -z "$oscWindow" ] || { [[ "$oscWindow" =~ ^[1-9][0-9]*$ ]] && [ "$oscWindow" -ge 3 ] && [ "$oscWindow" -le 1000 ]; } ||
    die "--oscillation-window '$oscWindow' must be an integer in 3..1000 (about one period of the force's oscillation)"
case "$wsFlux" in ""|interpolated|kept) ;; *) die "--warm-start-flux must be interpolated or kept (got '$wsFlux')" ;; esac
[ -z "$wsMaxCoef" ] || awk -v c="$wsMaxCoef" 'BEGIN{exit !(c ~ /^[0-9.eE+-]+$/ && c + 0 > 0 && c + 0 <= 1e3)}' ||
  die "--warm-start-max-coefficient must be a number in (0, 1000] (got '$wsMaxCoef'), e.g. 2"
[ -z "$fluidTol" ] || positive "$fluidTol" 1 ||
    die "--fluid-tolerance '$fluidTol' must be a number in (0, 1), e.g. 3e-3"
# configsHave OPTION WHAT PATTERN...: every solid config has a line matching each PATTERN (the
# lines OPTION edits below), or stop naming the config, WHAT and the fix
configsHave() {
  local option=$1 what=$2 y p; shift 2
  for y in solid/baseline.yaml solid/relaxed.yaml solid/viscoelastic.yaml; do
    for p in "$@"; do
      grep -q "$p" "$y" || die "$option: $y has no $what (restore it from cases/hydrofoil/solid)"
    done
  done
}
if [ -n "$fluidTol" ]; then
  why=$(tools/setFluidTolerance.sh --check solid/baseline.yaml solid/relaxed.yaml solid/viscoelastic.yaml 2>&1) ||
      die "--fluid-tolerance: ${why#error: setFluidTolerance.sh: }"
fi
[ -z "$couplingTol" ] || positive "$couplingTol" 1e-3 ||
    die "--coupling-tolerance '$couplingTol' must be a length in m in (0, 1e-3), e.g. 2e-6"
[ -z "$couplingTol" ] || configsHave --coupling-tolerance \
    "'absolute_tolerance:' line under coupling.convergence" '^    absolute_tolerance: '
[ -z "$bandFactor" ] || awk -v b="$bandFactor" 'BEGIN{exit !(b ~ /^[0-9.eE+-]+$/ && b + 0 >= 0 && b + 0 <= 1e3)}' ||
    die "--coupling-band-factor '$bandFactor' must be a number in [0, 1000], e.g. 0 (never widen the coupling tolerance)"
[ -z "$bandFactor" ] || configsHave --coupling-band-factor \
    "'band_factor:' line under coupling.convergence" '^    band_factor: '
[ "$solidElement" = tet10 ] || configsHave --solid-element "'kinematics:' line under solid" '^  kinematics: '
[ -z "$mapSmoothing" ] || awk -v r="$mapSmoothing" 'BEGIN{exit !(r ~ /^[0-9.eE+-]+$/ && r + 0 >= 0 && r + 0 < 1e-2)}' ||
    die "--mapping-smoothing '$mapSmoothing' must be a radius in m in [0, 1e-2), e.g. 2e-4 (0 = off)"
case "$mapType" in
  ""|nearest-projection|moving-least-squares|rbf-wendland-c2|rbf-pu|rbf-thin-plate|nearest-neighbour) ;;
  *) die "--mapping '$mapType' is not one of nearest-projection, moving-least-squares, rbf-wendland-c2, rbf-pu, rbf-thin-plate, nearest-neighbour" ;;
esac
[ -z "$mapType" ] || for y in solid/baseline.yaml solid/relaxed.yaml solid/viscoelastic.yaml; do
  grep -A1 '^  mapping:' "$y" | grep -q '^    type: ' ||
      die "--mapping: $y has no 'type:' line right under coupling.mapping (restore it from cases/hydrofoil/solid)"
done
[ -z "$mapSmoothing" ] || configsHave --mapping-smoothing \
    "'smoothing_radius:' line under coupling.mapping" '^    smoothing_radius: '
[ -z "$maxFluidIt" ] || { [[ "$maxFluidIt" =~ ^[1-9][0-9]*$ ]] && [ "$maxFluidIt" -ge 200 ]; } ||
    die "--max-fluid-iterations '$maxFluidIt' must be an integer >= 200 (the band rule's two blocks of 100)"
if [ -n "$bandWindow" ]; then
  cap=${maxFluidIt:-$(foamDictionary fluid/system/fsiDict -entry coupled/maxIterations -value 2> /dev/null || echo 400)}
  { [[ "$bandWindow" =~ ^[1-9][0-9]*$ ]] && [ "$bandWindow" -ge 10 ] && [ $((2 * bandWindow)) -le "$cap" ]; } ||
      die "--band-window '$bandWindow' must be an integer >= 10 with 2 x it <= the fluid cap $cap (--max-fluid-iterations)"
fi
[[ "$npf" =~ ^[1-9][0-9]*$ && "$nps" =~ ^[1-9][0-9]*$ ]] || die "--np-fluid/--np-solid must be positive integers"
if [ -n "$initFrom" ]; then
  [ -d "$initFrom/constant/polyMesh" ] || die "--init-from $initFrom: not an OpenFOAM case (no constant/polyMesh)"
  initFrom=$(cd "$initFrom" && pwd)
  why=$("$FSI_ROOT/cases/hydrofoil/tools/mapInitialFields.sh" --check "$initFrom" 2>&1) ||
      die "--init-from: ${why#error: mapInitialFields.sh: }"
fi
# the mapping this run uses: the options', the mesh's default, else the configs'
mapUsed=${mapType:-$mapDefaultType} smoothUsed=${mapSmoothing:-$mapDefaultSmoothing}
[ -n "$mapUsed" ] || mapUsed=$(grep -A1 '^  mapping:' solid/viscoelastic.yaml | sed -n 's/^    type: *\([a-z0-9-]*\).*/\1/p' || true)
[ -n "$smoothUsed" ] || smoothUsed=$(sed -n 's/^    smoothing_radius: *\([0-9.eE+-]*\).*/\1/p' solid/viscoelastic.yaml | head -n 1 || true)
smoothUsed=${smoothUsed:-0}
if [ "$checkOnly" = 1 ]; then
  [ -z "$mapUsed" ] || echo "run.sh: fluid mesh $fluidMesh, mapping $mapUsed, smoothing radius $smoothUsed m"
  exit 0
fi
command -v fluid-app >/dev/null && command -v solid-app >/dev/null || die "fluid-app/solid-app not on PATH (build first)"

run=$PWD
log() { echo "[hydrofoil $(date +%H:%M:%S)] $*"; }
start=$(date +%s)

if [ "$restart" = 1 ]; then
  [ -f "$run/mesh/mesh-summary.txt" ] || die "--restart: no mesh/ in $run (start the run without --restart)"
  log "restart: keeping the meshes in $run/mesh"
elif [ -n "$meshFrom" ]; then
  [ -f "$meshFrom/mesh/mesh-summary.txt" ] || die "--mesh-from $meshFrom: no mesh/mesh-summary.txt there"
  log "reusing the meshes of $meshFrom"
  rm -rf "$run/mesh" && cp -r "$meshFrom/mesh" "$run/mesh"
else
  log "meshing (preset $preset, t/c $tc, C_Li $cli, fluid mesh $fluidMesh)"
  "$FSI_ROOT/cases/hydrofoil/mesh.sh" --out "$run/mesh" --preset "$preset" --tc "$tc" --cli "$cli" \
      --np "$npf" --fluid-mesh "$fluidMesh" > "$run/log.mesh" 2>&1 || { tail -n 20 "$run/log.mesh" >&2; die "meshing failed (log.mesh)"; }
fi
grep -E "^fluid:|^solid" "$run/mesh/mesh-summary.txt" 2>/dev/null | sed 's/^/  /' || true
log "model: flow $flow, convection $scheme, pressure-velocity ${algorithm:-simplec}, fluid mesh $fluidMesh, root wall $rootWall"
if [ "$fluidMesh" = cgrid ] && [ "$algorithm" = simple ]; then
  log "note: with classic SIMPLE the coupled solves on the boundary-layer mesh converge slowly (a viscoelastic history takes hours; README, \"The case default\"); a mesh made now (without --mesh-from) runs SIMPLEC"
fi
if [ -n "$solidFrom" ]; then
  rm -rf "$run/mesh/solid" && cp -r "$solidFrom/mesh/solid" "$run/mesh/solid"
  sed -i '/^foil-[a-z0-9-]*\.msh: /d' "$run/mesh/mesh-summary.txt"
  { echo "solid meshes from $solidFrom (preset=$(section preset "$solidFrom/mesh/mesh-summary.txt"))"
    grep '^foil-[a-z0-9-]*\.msh: ' "$solidFrom/mesh/mesh-summary.txt" || true; } >> "$run/mesh/mesh-summary.txt"
  log "structural meshes from $solidFrom"
fi
solidMesh=$run/mesh/solid/foil-$solidElement.msh
[ -f "$solidMesh" ] || die "no structural mesh $solidMesh (mesh.sh makes foil-tet10.msh and foil-hex20.msh)"
echo "$solidElement" > "$run/solid-element"
if [ -n "$mapUsed" ]; then  # kept for a --restart
  echo "$mapUsed $smoothUsed" > "$run/mapping"
  log "mapping: $mapUsed, fluid-side smoothing radius $smoothUsed m"
fi
elementNote=""; [ "$solidElement" = tet10 ] || elementNote=", projected dilatation (B-bar)"
log "structure: $(basename "$solidMesh")$elementNote"

runs=()
case "$material" in
  both) runs=(baseline viscoelastic) ;;
  elastic) runs=(baseline relaxed) ;;
  *) runs=("$material") ;;
esac
mkdir -p "$run/results"
# setConfigNumber CFG KEY VALUE: CFG's line `    KEY: number` gets VALUE (its comment stays);
# nothing when VALUE is empty (the option was not given)
setConfigNumber() { [ -z "$3" ] || sed -i "s/^\(    $2:\) *[0-9.eE+-]*/\1 $3/" "$1"; }
# endsLater RUN OUT: RUN is the viscoelastic run and --end lies beyond its last checkpointed level
endsLater() {
  [ "$1" = viscoelastic ] && [ -n "$end" ] && [ -f "$2/checkpoint/latest" ] &&
      awk -v e="$end" -v t="$(sed -n 's/^time //p' "$2/checkpoint/latest")" \
          'BEGIN{exit !(t != "" && e + 0 > t + 1e-6 * (1 + t))}'
}

for m in "${runs[@]}"; do
  short=$m; [ "$m" = viscoelastic ] && short=visco
  fluid=$run/fluid-$short
  out=$run/results/$short
  resume=()
  if [ "$restart" = 1 ] && [ -f "$out/summary.csv" ] && ! endsLater "$m" "$out"; then
    log "$m: finished before the restart, kept"
    continue
  elif [ "$restart" = 1 ] && [ -f "$out/checkpoint/latest" ]; then
    if [ -f "$out/summary.csv" ]; then
      k=1; while [ -e "$out/summary.csv.part$k" ]; do k=$((k + 1)); done
      log "$m: finished at t = $(sed -n 's/^time //p' "$out/checkpoint/latest") s; extended to --end $end s (its summary kept as summary.csv.part$k)"
      mv "$out/summary.csv" "$out/summary.csv.part$k"
    fi
    log "$m: continuing from $(sed -n 's/^folder //p' "$out/checkpoint/latest") of $out/checkpoint"
    "$FSI_ROOT/scripts/fsi-restart-fluid" "$fluid" "$out"
    k=1; while [ -e "$run/log.$short.part$k" ]; do k=$((k + 1)); done
    if [ -e "$run/log.$short" ]; then mv "$run/log.$short" "$run/log.$short.part$k"; fi
    resume=(--restart)
  fi
  if [ ${#resume[@]} -eq 0 ]; then
    # the mesh's fluid case with this case's settings, flow model and scheme, decomposed
    "$run/tools/fluidCase.sh" "$fluid" "$run/mesh/fluid" "$npf" --flow "$flow" --scheme "$scheme" \
        ${algorithm:+--algorithm "$algorithm"} ${initFrom:+--init-from "$initFrom"} --root-wall "$rootWall" \
        ${acceleration:+--simple-acceleration "$acceleration"}
  fi
  # the options given, as fsiDict coupled/KEY; also on --restart, so that a continued run can
  # change them (e.g. a wider band for levels whose flow lost its steady state); options left
  # out keep the fluid case's values
  for kv in bandTolerance="$band" maxIterations="$maxFluidIt" bandMeanTolerance="$bandMean" \
            bandReferenceForce="$bandRef" oscillationWindow="$oscWindow" bandWindow="$bandWindow" \
            warmStart/flux="$wsFlux" warmStart/maxCoefficient="$wsMaxCoef"; do
    [ -z "${kv#*=}" ] || foamDictionary "$fluid/system/fsiDict" -entry "coupled/${kv%%=*}" -set "${kv#*=}" > /dev/null
  done
  parallel=""
  [ "$npf" -gt 1 ] && parallel=-parallel
  cfg=$run/$m.yaml
  sed "s|@MESH@|$solidMesh|" "$run/solid/$m.yaml" > "$cfg"
  # Hex20 locks at nu = 0.49 as plain elements: the projected dilatation (solid.element)
  [ "$solidElement" != hex20 ] || sed -i 's/^  kinematics: .*/&\n  element:\n    type: projected-dilatation/' "$cfg"
  # the solid-config options given (configsHave checked their lines above)
  [ -z "$fluidTol" ] || "$run/tools/setFluidTolerance.sh" "$cfg" "$fluidTol"
  setConfigNumber "$cfg" absolute_tolerance "$couplingTol"
  setConfigNumber "$cfg" band_factor "$bandFactor"
  # the mapping: the options' (lines checked above), else the mesh's default where the config
  # has the line (a config edited by hand or by scripts/bench-fsi keeps its own otherwise)
  setConfigNumber "$cfg" smoothing_radius "${mapSmoothing:-$mapDefaultSmoothing}"
  mapSet=${mapType:-$mapDefaultType}
  [ -z "$mapSet" ] || sed -i "/^  mapping:/{n;s/^    type: [a-z0-9-]*/    type: $mapSet/}" "$cfg"
  if [ -n "$end" ] && [ "$m" = viscoelastic ]; then
    sed -i "s|^    end: .*|    end: $end|; s|^    hit: .*|    hit: []|" "$cfg"
  fi
  log "$m: fluid $npf rank(s), solid $nps rank(s), launch $launch; log in log.$short"
  fluidCmd=(fluid-app -case "$fluid" $parallel "${resume[@]/--/-}" --launch "$launch" --comm-timeout "$timeout")
  solidCmd=(solid-app "$cfg" --out "$out" "${resume[@]}" --launch "$launch" --comm-timeout "$timeout")
  if [ "$launch" = port ]; then
    fluidCmd+=(--port-file "$run/fsi-$short.port"); solidCmd+=(--port-file "$run/fsi-$short.port")
    cmd=("$FSI_ROOT/scripts/launch-port" -np "$npf" "${fluidCmd[@]}" : -np "$nps" "${solidCmd[@]}")
  else
    cmd=(mpirun --oversubscribe -np "$npf" "${fluidCmd[@]}" : -np "$nps" "${solidCmd[@]}")
  fi
  set +e
  "${cmd[@]}" 2>&1 | tee "$run/log.$short" | grep --line-buffered -E "^\[level|^error|WARNING|^solid-app: done" 
  rc=${PIPESTATUS[0]}
  set -e
  [ "$rc" -eq 0 ] || die "$m run failed (exit $rc); see $run/log.$short"
done

if [ -d "$run/results/visco" ]; then
  cp "$run/results/visco/history.csv" "$run/results/history.csv"
elif [ -d "$run/results/baseline" ]; then
  cp "$run/results/baseline/history.csv" "$run/results/history.csv"
elif [ -d "$run/results/relaxed" ]; then
  cp "$run/results/relaxed/history.csv" "$run/results/history.csv"
fi
log "plots and summary"
"$FSI_PYTHON" "$FSI_ROOT/scripts/plot_hydrofoil.py" "$run/results"
log "done in $(( $(date +%s) - start )) s: $run/results (history.csv, summary.csv, *.png)"
