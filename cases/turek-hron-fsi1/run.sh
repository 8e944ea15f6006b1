#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Turek-Hron FSI1, coupled: fluid-app (OpenFOAM, steady SIMPLE + mesh motion) and solid-app
# (FE beam, driver). Run inside a COPY of this folder (scripts/run does that), with fluid-app
# and solid-app on PATH.
#
# usage: ./run.sh [--preset coarse|medium|fine] [--launch mpmd|port] [--material M]
#                 [--accelerator aitken|constant|iqn-ils] [--relaxation W] [--tolerance EPS]
#                 [--np-fluid N] [--timeout S] [--times T0,T1,...] [--mapping TYPE] [--mesh-only]
#                 [--restart] [--check-only]
#   --preset       mesh resolution of both sides (default coarse), see README.md
#   --launch       mpmd (default): mpirun -np N fluid-app -case fluid : -np 1 solid-app run.yaml
#                  port: two mpiruns through scripts/launch-port (needs FSI_ROOT or launch-port on PATH)
#   --material     elastic (default, solid.yaml) | viscoelastic (solid-visco.yaml: levels t = 0
#                  and t = 1e6 s) | instantaneous (solid-instantaneous.yaml: elastic with the
#                  Prony beam's instantaneous moduli)
#   --accelerator  override coupling.acceleration.type; --relaxation sets its (initial) omega
#                  (defaults: aitken 0.5, iqn-ils 0.5, constant 0.5)
#   --tolerance    coupling.convergence.absolute_tolerance [m] (default: the config's, 1e-8)
#   --mapping      override coupling.mapping.type (default: the config's rbf-thin-plate):
#                  nearest-neighbour | rbf-thin-plate | rbf-pu | nearest-projection (onto the
#                  beam's Quad8 faces) | moving-least-squares (linear fits to the beam's nodes
#                  around each fluid point); each with its defaults
#   --beam NX,NY   override the preset's beam cells along / across the beam (NY even)
#   --np-fluid     fluid ranks (default 1; > 1 decomposes the fluid mesh, hierarchical)
#   --timeout      comm timeout of both programs [s] (default by preset: coarse 600, medium 1800,
#                  fine 5400: the first fluid solve starts from rest and takes minutes on a loaded machine)
#   --times        override coupling.time with a list of levels (viscoelastic, first 0), e.g.
#                  0,0.5,1,2,1e6
#   --restart      continue an interrupted run in this folder from results/checkpoint/latest (same
#                  options otherwise; meshes and run.yaml are kept; the earlier logs are kept as
#                  log.*.partN); see scripts/fsi-restart-fluid
#   --check-only   validate the options and exit: 0, or 2 with the one-line error; writes nothing
#                  (scripts/run calls it before it makes the run folder)
# Writes log.fluid, log.solid, run.yaml (the config used) and results/: history.csv,
# coupling.csv, summary.csv (solid-app), forces.csv, benchmark.csv, summary.txt (tools/summary.py),
# fluid-coupling.csv (fluid-app's per-iteration log), wall_s.
set -euo pipefail
here=$(pwd)
usage() { sed -n '6,36p' "$0" | sed 's/^# \{0,1\}//'; exit "${1:-0}"; }

preset=coarse launch=mpmd material=elastic accelerator="" relaxation="" tolerance="" npf=1
timeout='' mesh_only=0 beam='' times='' restart=0 mapping='' check_only=0
while [ $# -gt 0 ]; do
  case "$1" in
    --preset) preset=$2; shift 2 ;;
    --launch) launch=$2; shift 2 ;;
    --material) material=$2; shift 2 ;;
    --accelerator) accelerator=$2; shift 2 ;;
    --relaxation) relaxation=$2; shift 2 ;;
    --tolerance) tolerance=$2; shift 2 ;;
    --np-fluid) npf=$2; shift 2 ;;
    --beam) beam=$2; shift 2 ;;
    --timeout) timeout=$2; shift 2 ;;
    --mesh-only) mesh_only=1; shift ;;
    --times) times=$2; shift 2 ;;
    --mapping) mapping=$2; shift 2 ;;
    --restart) restart=1; shift ;;
    --check-only) check_only=1; shift ;;
    -h|--help) usage 0 ;;
    *) echo "error: run.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
# Mesh presets: fluid blockMesh level (cells per direction x1, x2, x4) and the beam's Hex20
# cells along (nx) and across (ny) the beam.
case "$preset" in
  coarse) flevel=coarse nx=18 ny=2 t_default=600 ;;
  medium) flevel=medium nx=35 ny=2 t_default=1800 ;;
  fine)   flevel=fine   nx=70 ny=4 t_default=5400 ;;
  *) echo "error: run.sh: --preset must be coarse, medium or fine, got '$preset'" >&2; exit 2 ;;
esac
timeout=${timeout:-$t_default}
if [ -n "$beam" ]; then nx=${beam%,*} ny=${beam#*,}; fi
case "$launch" in mpmd|port) ;; *) echo "error: run.sh: --launch must be mpmd or port" >&2; exit 2 ;; esac
case "$material" in
  elastic) config=solid.yaml ;;
  viscoelastic) config=solid-visco.yaml ;;
  instantaneous) config=solid-instantaneous.yaml ;;
  *) echo "error: run.sh: --material must be elastic, viscoelastic or instantaneous" >&2; exit 2 ;;
esac
case "$mapping" in ""|nearest-neighbour|rbf-thin-plate|rbf-pu|nearest-projection|moving-least-squares) ;;
  *) echo "error: run.sh: --mapping must be nearest-neighbour, rbf-thin-plate, rbf-pu, nearest-projection or moving-least-squares" >&2; exit 2 ;; esac
case "$accelerator" in ""|aitken|constant|iqn-ils) ;; *) echo "error: run.sh: --accelerator must be aitken, constant or iqn-ils" >&2; exit 2 ;; esac
die() { echo "error: run.sh: $*" >&2; exit 2; }
[[ "$npf" =~ ^[1-9][0-9]*$ ]] || die "--np-fluid must be a positive integer (got '$npf')"
[[ "$timeout" =~ ^[1-9][0-9]*$ ]] || die "--timeout must be a positive number of seconds (got '$timeout')"
[[ "$nx,$ny" =~ ^[1-9][0-9]*,[1-9][0-9]*$ ]] && [ $((ny % 2)) = 0 ] ||
  die "--beam must be NX,NY with positive integers, NY even (got '$nx,$ny')"
positive() { awk -v v="$1" 'BEGIN{exit !(v ~ /^[0-9.eE+-]+$/ && v + 0 > 0)}'; }
[ -z "$relaxation" ] || positive "$relaxation" || die "--relaxation must be a number > 0, e.g. 0.5 (got '$relaxation')"
[ -z "$tolerance" ] || positive "$tolerance" || die "--tolerance must be a length in m > 0, e.g. 1e-8 (got '$tolerance')"
[ "$check_only" = 0 ] || exit 0
# The channel generator is CFD1's (two wall patches: cylinder rigid, beam the interface).
generator=${FSI_ROOT:?run through ./scripts/run cases/turek-hron-fsi1 (FSI_ROOT unset)}/cases/turek-hron-cfd1/blockMesh.py
[ -f "$config" ] && [ -f "$generator" ] || { echo "error: run.sh: run me inside a copy of cases/turek-hron-fsi1 ($config or $generator missing)" >&2; exit 2; }
for p in fluid-app solid-app blockMesh gmsh mpirun; do
  command -v $p >/dev/null || { echo "error: run.sh: $p not on PATH (scripts/run puts build/bin first)" >&2; exit 2; }
done
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
export FOAM_SIGFPE=${FOAM_SIGFPE:-false}
export OMPI_MCA_btl_tcp_if_include=${OMPI_MCA_btl_tcp_if_include:-lo}
export OMPI_MCA_oob_tcp_if_include=${OMPI_MCA_oob_tcp_if_include:-lo}
py=${FSI_PYTHON:-/usr/bin/python3}

parallel=()
[ "$npf" -gt 1 ] && parallel=(-parallel)
restart_flags=()
if [ "$restart" = 1 ]; then
  # --- restart: keep meshes, config and results; point the fluid at the checkpointed level ---
  [ -f run.yaml ] && [ -f results/checkpoint/latest ] ||
    { echo "error: run.sh --restart: no results/checkpoint/latest here (run without --restart first)" >&2; exit 2; }
  "${FSI_ROOT}/scripts/fsi-restart-fluid" fluid results
  k=1; while [ -e "log.solid.part$k" ] || [ -e "log.fluid.part$k" ]; do k=$((k + 1)); done
  for f in log.solid log.fluid log.mpirun; do if [ -e "$f" ]; then mv "$f" "$f.part$k"; fi; done
  restart_flags=(--restart)
  echo "[fsi1] restarting ($material, launch $launch) from $(sed -n 's/^folder //p' results/checkpoint/latest)"
else
# --- meshes -----------------------------------------------------------------------------
echo "[fsi1] preset $preset: fluid $flevel, beam Hex20 ${nx} x ${ny} x 1; $material, launch $launch"
rm -rf fluid/0 fluid/processor* fluid/postProcessing results
cp -r fluid/0.orig fluid/0
"$py" "$generator" "$flevel" fluid/system/blockMeshDict
(cd fluid && blockMesh > log.blockMesh 2>&1) || { echo "error: blockMesh failed, see fluid/log.blockMesh" >&2; exit 1; }
fluid_cells=$(awk '/nCells:/ {print $2; exit}' fluid/log.blockMesh)
if [ "$npf" -gt 1 ]; then
  cat > fluid/system/decomposeParDict <<EOD
FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }
numberOfSubdomains $npf;
method          hierarchical;       // Debian's scotch/metis are stubs
coeffs { n ($npf 1 1); order xyz; }
EOD
  (cd fluid && decomposePar -force > log.decomposePar 2>&1) || { echo "error: decomposePar failed" >&2; exit 1; }
fi
gmsh -3 -order 2 -setnumber nx "$nx" -setnumber ny "$ny" solid/beam.geo -o solid/beam.msh > solid/log.gmsh 2>&1 ||
  { echo "error: gmsh failed, see solid/log.gmsh" >&2; exit 1; }
solid_cells=$((nx * ny))
echo "$fluid_cells $solid_cells" > mesh_size
echo "[fsi1] fluid $fluid_cells cells, solid $solid_cells Hex20 cells"
[ "$mesh_only" = 1 ] && exit 0

# --- config -------------------------------------------------------------------------------
cp "$config" run.yaml
if [ -n "$accelerator" ] || [ -n "$relaxation" ]; then
  acc=${accelerator:-$(sed -n 's/^ *acceleration: {type: \([a-z-]*\).*/\1/p' "$config")}
  w=${relaxation:-0.5}
  case "$acc" in
    constant) line="  acceleration: {type: constant, constant: {relaxation: $w}}" ;;
    aitken)   line="  acceleration: {type: aitken, aitken: {initial_relaxation: $w}}" ;;
    iqn-ils)  line="  acceleration: {type: iqn-ils, iqn-ils: {initial_relaxation: $w}}" ;;
  esac
  sed -i "s/^  acceleration: .*/$line/" run.yaml
fi
if [ -n "$tolerance" ]; then
  sed -i "s/^\(    absolute_tolerance:\) [^ ]*/\1 $tolerance/" run.yaml
fi
if [ -n "$mapping" ]; then
  grep -q "^  mapping: {type: " run.yaml ||
    { echo "error: run.sh: --mapping needs a 'mapping: {type: ...}' line in $config" >&2; exit 2; }
  sed -i "s/^  mapping: {type: .*/  mapping: {type: $mapping}/" run.yaml
fi
if [ -n "$times" ]; then
  grep -q "^  time: {type: list" run.yaml ||
    { echo "error: run.sh: --times needs a 'time: {type: list ...}' line in $config (use --material viscoelastic)" >&2; exit 2; }
  sed -i "s/^  time: {type: list.*/  time: {type: list, times: [${times//,/, }]}/" run.yaml
fi
fi # restart

# --- coupled run ----------------------------------------------------------------------------
logrun=$here/tools/logrun
port_file=$here/fsi.port
rm -f "$port_file"
t0=$(date +%s.%N)
set +e
if [ "$launch" = mpmd ]; then
  mpirun --allow-run-as-root --oversubscribe --mca btl self,vader,tcp \
    -x WM_PROJECT_DIR -x FOAM_SIGFPE -x OMPI_MCA_btl_tcp_if_include -x OMPI_MCA_oob_tcp_if_include \
    -np "$npf" "$logrun" log.fluid 0 fluid-app -case fluid "${parallel[@]}" "${restart_flags[@]/--/-}" --launch mpmd --comm-timeout "$timeout" \
    : -np 1 "$logrun" log.solid "$npf" solid-app run.yaml "${restart_flags[@]}" --launch mpmd --comm-timeout "$timeout" \
    > log.mpirun 2>&1
  rc=$?
else
  lp=""
  if [ -n "${FSI_ROOT:-}" ] && [ -x "$FSI_ROOT/scripts/launch-port" ]; then lp=$FSI_ROOT/scripts/launch-port
  elif command -v launch-port >/dev/null; then lp=$(command -v launch-port)
  else echo "error: run.sh: --launch port needs scripts/launch-port (set FSI_ROOT to the repository)" >&2; exit 2; fi
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "$lp" --mpi-flag --oversubscribe --grace 30 \
    -np "$npf" "$logrun" log.fluid 0 fluid-app -case fluid "${parallel[@]}" "${restart_flags[@]/--/-}" --launch port --port-file "$port_file" --comm-timeout "$timeout" \
    : -np 1 "$logrun" log.solid 0 solid-app run.yaml "${restart_flags[@]}" --launch port --port-file "$port_file" --comm-timeout "$timeout" \
    > log.mpirun 2>&1
  rc=$?
fi
set -e
t1=$(date +%s.%N)
wall=$(echo "$t0 $t1" | awk '{printf "%.3f", $2 - $1}')
if [ $rc != 0 ]; then
  echo "error: the coupled run failed (exit $rc); see log.solid, log.fluid, log.mpirun:" >&2
  # (|| true: head may end grep by SIGPIPE, and pipefail + set -e would then exit 141)
  grep -h "error" log.solid log.fluid log.mpirun 2>/dev/null | head -5 >&2 || true
  exit $rc
fi
mkdir -p results
echo "$wall" > results/wall_s
cp fluid/postProcessing/fsi/coupling.csv results/fluid-coupling.csv 2>/dev/null || true
"$py" tools/summary.py . --depth "$("$py" -c 'import sys; sys.path.insert(0, sys.argv[1]); import blockMesh; print(blockMesh.DEPTH)' "$(dirname "$generator")")" --wall "$wall"
