#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# tests/cases/hydrofoil/test_run_options.sh WORK
#
# run.sh refuses bad values of --band-tolerance, --band-mean-tolerance, --band-reference-force,
# --band-window, --oscillation-window, --fluid-tolerance (also a valid value with a solid config
# that lacks its line), --coupling-tolerance,
# --coupling-band-factor, --warm-start-flux,
# --mapping (also a valid type with a solid config that lacks its type line),
# --mapping-smoothing, --max-fluid-iterations, --fluid-mesh, --algorithm, --root-wall and
# --simple-acceleration, --solid-element and --solid-mesh-from (a folder without the element's
# mesh, of another section, or with --restart) (and a --fluid-mesh
# that contradicts the mesh of --mesh-from) before it writes anything:
# exit 2, one line on stderr naming the option, no mesh/ or results/ in the run folder; so is an
# --init-from case without a reconstructed solved time. `run.sh --check-only` exits 0 on valid
# options and writes nothing; it names the mapping, which follows the fluid mesh unless given and
# which a --restart keeps (a contradicting --mapping or --mapping-smoothing refused). Needs
# FSI_ROOT (the repository); no OpenFOAM run, no MPI.
# Also: tools/meshModel.sh names the default model of each mesh and preset, and
# `scripts/run cases/hydrofoil --help` prints run.sh's options and exits 0 without setup, build
# or a run folder. And the FSI1 runner (cases/turek-hron-fsi1/run.sh, which scripts/run also
# calls with --check-only first): exit 0 on valid options, a bad one refused in one line, nothing
# written either way. And rigid.sh / blcheck.sh refuse a bad --band-mean-tolerance the same way
# (blcheck.sh through rigid.sh --check-only, which passes valid options), and rigid.sh a bad
# --write-interval or --max-iterations and a --resume without a restart point (blcheck.sh: without
# a stopped run), and rigid.sh --shape-from an option that contradicts the coupled case's recorded
# flow model (fluidModel), or, without one, a missing --flow / --scheme; --resume one that
# contradicts its own case's; tools/shapeCheck.sh a --resume without a stopped shape solve.
# tools/fluidCase.sh --model-of reads a case's fluidModel (a malformed one refused). And
# scripts/bench-fsi refuses an unknown --rigid-stop.
# And mesh.sh refuses
# --preset finer unless --fluid-mesh cgrid --fluid-only.
set -uo pipefail
work=${1:?usage: test_run_options.sh WORK}
: "${FSI_ROOT:?set FSI_ROOT to the repository}"
fail=0
check() {   # check OPTION VALUE [MORE OPTIONS...]; $edit, when set: a command run in the copy first
  local dir=$work/run
  rm -rf "$dir"; mkdir -p "$dir"; cp -r "$FSI_ROOT/cases/hydrofoil/." "$dir/"
  [ -z "${edit:-}" ] || (cd "$dir" && eval "$edit")
  local rc=0
  (cd "$dir" && ./run.sh --material baseline "$@" > out.txt 2> err.txt) || rc=$?
  local lines; lines=$(wc -l < "$dir/err.txt")
  if [ "$rc" -ne 2 ]; then
    echo "FAIL: $*: exit $rc, expected 2"; fail=1
  elif [ "$lines" -ne 1 ] || ! grep -q -- "$1" "$dir/err.txt"; then
    echo "FAIL: $*: expected one line naming $1, got:"; cat "$dir/err.txt"; fail=1
  elif [ -e "$dir/mesh" ] || [ -e "$dir/results" ]; then
    echo "FAIL: $*: wrote mesh/ or results/ before refusing"; fail=1
  else
    echo "ok: $* -> $(cat "$dir/err.txt")"
  fi
}
check --band-tolerance 0
check --band-tolerance 1.5
check --band-tolerance abc
check --max-fluid-iterations 150
check --max-fluid-iterations 4e2
check --fluid-tolerance 0
check --fluid-tolerance 2
# a valid value, but a solid config without the line it sets (tools/setFluidTolerance.sh --check)
edit="sed -i '/^    max_force_tolerance: /d' solid/relaxed.yaml" check --fluid-tolerance 1e-4
check --band-mean-tolerance -1e-3
check --band-reference-force 0
check --band-reference-force 1N
check --oscillation-window 2
check --band-window 5
check --coupling-tolerance 0
check --warm-start-flux copied
check --coupling-band-factor -1
check --coupling-band-factor twenty
check --coupling-tolerance 5e-3   # a length in m: 5 mm is no tolerance
check --band-window 300   # 2 x 300 > the case's cap of 400
check --mapping rbf-quadratic
edit="sed -i '/^    type: nearest-projection/d' solid/viscoelastic.yaml" check --mapping moving-least-squares
check --mapping-smoothing -1e-4
check --mapping-smoothing 0.2mm
check --mapping-smoothing 0.05  # a radius in m: 5 cm smooths the whole foil
check --fluid-mesh blockMesh
check --algorithm piso
check --root-wall free
check --simple-acceleration andersen
check --simple-acceleration anderson:0
check --simple-acceleration anderson:51
# --fluid-mesh that contradicts the mesh of --mesh-from: refused before anything is written
fake=$work/fake-snappy-run
rm -rf "$fake"; mkdir -p "$fake/mesh"
echo "hydrofoil meshes (2026-12-05T00:00:00Z): preset=coarse tc=0.12 cli=0.5 meanline=a08 fluid-mesh=snappy" > "$fake/mesh/mesh-summary.txt"
check --fluid-mesh cgrid --mesh-from "$fake"
# --solid-element: an unknown element; --solid-mesh-from: a folder without the element's mesh,
# one of another section (t/c), and one with --restart: refused before anything is written
check --solid-element tet4
solidFake=$work/fake-solid-run
rm -rf "$solidFake"; mkdir -p "$solidFake/mesh/solid"
echo "hydrofoil meshes (2026-12-07T00:00:00Z): preset=fine tc=0.10 cli=0.5 meanline=a08 fluid-mesh=cgrid" > "$solidFake/mesh/mesh-summary.txt"
check --solid-mesh-from "$solidFake"                       # no foil-tet10.msh there
touch "$solidFake/mesh/solid/foil-tet10.msh"
check --solid-mesh-from "$solidFake" --mesh-from "$fake"   # t/c 0.10 against the run's 0.12
check --solid-mesh-from "$solidFake" --tc 0.10 --cli 0.4   # C_Li 0.5 against 0.4
check --solid-mesh-from "$solidFake" --restart
check --solid-mesh-from "$solidFake" --solid-element hex20 --tc 0.10   # no foil-hex20.msh there
# --init-from a case without a reconstructed solved time (decomposed only): refused up front
decomposed=$work/decomposed-case
rm -rf "$decomposed"; mkdir -p "$decomposed/constant/polyMesh" "$decomposed/system" "$decomposed/processor0/900"
check --init-from "$decomposed"
# --check-only: valid options exit 0 and write nothing; a bad one is refused as without it
dir=$work/run
rm -rf "$dir"; mkdir -p "$dir"; cp -r "$FSI_ROOT/cases/hydrofoil/." "$dir/"
before=$(cd "$dir" && find . | sort | md5sum)
if ! (cd "$dir" && ./run.sh --check-only --material baseline --scheme linearUpwind --root-wall slip \
        --oscillation-window 20 --simple-acceleration anderson:5 --coupling-band-factor 0 \
        --solid-element hex20 --mapping moving-least-squares --mapping-smoothing 0 > out.txt 2> err.txt); then
    echo "FAIL: run.sh --check-only with valid options: non-zero exit"; cat "$dir/err.txt"; fail=1
elif [ "$(cd "$dir" && rm out.txt err.txt && find . | sort | md5sum)" != "$before" ]; then
    echo "FAIL: run.sh --check-only wrote into the case folder"; fail=1
else
    echo "ok: run.sh --check-only with valid options: exit 0, nothing written"
fi
check --oscillation-window 2 --check-only
# the mapping follows the fluid mesh (README, "The mapping follows the fluid mesh"): run.sh
# --check-only names it; a --restart keeps the one its run started with (file mapping)
mapping() {   # mapping EXPECTED OPTIONS...: the mapping line of run.sh --check-only in $dir
  local want=$1 got; shift
  got=$(cd "$dir" && ./run.sh --check-only --material baseline "$@" 2> err.txt | grep -o 'mapping .*')
  if [ "$got" = "$want" ]; then echo "ok: run.sh --check-only $* -> $got"; else echo "FAIL: run.sh --check-only $*: '$got', expected '$want'"; cat "$dir/err.txt"; fail=1; fi
}
mapping "mapping moving-least-squares, smoothing radius 0 m"
mapping "mapping nearest-projection, smoothing radius 2.0e-4 m" --fluid-mesh snappy
mapping "mapping nearest-projection, smoothing radius 2.0e-4 m" --mapping nearest-projection
mapping "mapping moving-least-squares, smoothing radius 1e-4 m" --mapping-smoothing 1e-4
mapping "mapping rbf-pu, smoothing radius 0 m" --fluid-mesh snappy --mapping rbf-pu --mapping-smoothing 0
mkdir -p "$dir/mesh"
echo "hydrofoil meshes (2026-12-08T00:00:00Z): preset=coarse tc=0.12 cli=0.5 meanline=a08 fluid-mesh=cgrid" > "$dir/mesh/mesh-summary.txt"
echo "nearest-projection 2.0e-4" > "$dir/mapping"   # started with nearest-projection
mapping "mapping nearest-projection, smoothing radius 2.0e-4 m" --restart
mapping "mapping nearest-projection, smoothing radius 0.0002 m" --restart --mapping-smoothing 0.0002
rm "$dir/mapping"                                   # a run from before the file: the configs'
mapping "mapping nearest-projection, smoothing radius 2.0e-4 m" --restart
echo "moving-least-squares 0" > "$dir/mapping"
for opts in "--mapping nearest-projection" "--mapping-smoothing 2e-4"; do
  rc=0; (cd "$dir" && ./run.sh --check-only --material baseline --restart $opts > out.txt 2> err.txt) || rc=$?
  if [ "$rc" -eq 2 ] && [ "$(wc -l < "$dir/err.txt")" -eq 1 ] && grep -q -- "${opts%% *}.*a --restart keeps it" "$dir/err.txt"; then
    echo "ok: --restart $opts against a run started with moving-least-squares 0 -> $(cat "$dir/err.txt")"
  else
    echo "FAIL: --restart $opts against a run started with moving-least-squares 0: exit $rc"; cat "$dir/err.txt"; fail=1
  fi
done
# tools/meshModel.sh: the model that run.sh defaults to for each mesh (README, "The case default")
model() {   # model EXPECTED ARGS...
  local got; got=$("$FSI_ROOT/cases/hydrofoil/tools/meshModel.sh" "${@:2}" 2>&1)
  if [ "$got" = "$1" ]; then echo "ok: meshModel.sh ${*:2} -> $got"; else echo "FAIL: meshModel.sh ${*:2}: '$got', expected '$1'"; fail=1; fi
}
model "cgrid turbulent simplec" cgrid coarse
model "cgrid turbulent simplec" cgrid medium
model "cgrid turbulent simplec" cgrid fine
model "snappy laminar simplec" snappy coarse
model "snappy laminar simplec" "$fake/mesh/mesh-summary.txt"
echo "hydrofoil meshes (2026-12-05T00:00:00Z): preset=medium tc=0.12 cli=0.5 meanline=a08 fluid-mesh=cgrid" > "$fake/mesh/mesh-summary.txt"
model "cgrid turbulent simple" "$fake/mesh/mesh-summary.txt"   # made before the even gap cells
echo "preset=medium te=sharp cells=595390 n_normal=47 growth_relax=1 gap_size_jump=17.1" >> "$fake/mesh/mesh-summary.txt"
model "cgrid turbulent simplec" "$fake/mesh/mesh-summary.txt"
echo "hydrofoil meshes (2026-11-20T00:00:00Z): preset=coarse tc=0.12 cli=0.5" > "$fake/mesh/mesh-summary.txt"
model "snappy laminar simplec" "$fake/mesh/mesh-summary.txt"   # older than the boundary-layer mesh
help_out=$work/help-run
rm -rf "$help_out"
if ! "$FSI_ROOT/scripts/run" "$FSI_ROOT/cases/hydrofoil" --preset medium --out "$help_out" --help \
        > "$work/help.txt" 2>&1; then
    echo "FAIL: scripts/run cases/hydrofoil --help: non-zero exit"; cat "$work/help.txt"; fail=1
elif ! grep -q -- "--mapping-smoothing R" "$work/help.txt"; then
    echo "FAIL: scripts/run cases/hydrofoil --help: run.sh's options missing"; fail=1
elif [ -e "$help_out" ] || grep -q '^\[setup\]' "$work/help.txt"; then
    echo "FAIL: scripts/run cases/hydrofoil --help: ran setup or made the run folder"; fail=1
else
    echo "ok: scripts/run cases/hydrofoil --help"
fi
fsi1=$work/fsi1
rm -rf "$fsi1"; mkdir -p "$fsi1"; cp -r "$FSI_ROOT/cases/turek-hron-fsi1/." "$fsi1/"
before=$(ls -A "$fsi1" | sort | tr '\n' ' ')
fsi1check() {   # fsi1check EXPECTED_EXIT OPTIONS...: run.sh --check-only in the FSI1 copy
  local rc=0 want=$1; shift
  (cd "$fsi1" && ./run.sh --check-only "$@" > "$work/fsi1.out" 2> "$work/fsi1.err") || rc=$?
  if [ "$rc" -ne "$want" ]; then
    echo "FAIL: fsi1 run.sh --check-only $*: exit $rc, expected $want"; cat "$work/fsi1.err"; fail=1
  elif [ "$want" = 2 ] && { [ "$(wc -l < "$work/fsi1.err")" -ne 1 ] || ! grep -q -- "$1" "$work/fsi1.err"; }; then
    echo "FAIL: fsi1 run.sh --check-only $*: expected one line naming $1, got:"; cat "$work/fsi1.err"; fail=1
  elif [ "$(ls -A "$fsi1" | sort | tr '\n' ' ')" != "$before" ]; then
    echo "FAIL: fsi1 run.sh --check-only $*: wrote into the case folder"; fail=1
  else
    echo "ok: fsi1 run.sh --check-only $* -> exit $rc $(cat "$work/fsi1.err")"
  fi
}
fsi1check 0 --preset medium --accelerator iqn-ils --relaxation 0.4 --tolerance 1e-8
fsi1check 2 --np-fluid 0
fsi1check 2 --beam 3,3
fsi1check 2 --relaxation -1
fsi1check 2 --mapping rbf
fsi1check 0 --mapping moving-least-squares
# rigid.sh and blcheck.sh (the rigid mesh studies): a bad --band-mean-tolerance refused in one
# line naming it, exit 2, no run folder made
fakeMesh=$work/fake-fluid-mesh
rm -rf "$fakeMesh"; mkdir -p "$fakeMesh/constant/polyMesh"; : > "$fakeMesh/constant/polyMesh/owner"
refusedBefore() {   # refusedBefore RC NAMED SCRIPT ARGS...: SCRIPT refuses ARGS (exit RC; "nz": any
  # non-zero) in one line naming NAMED, before it makes its --out
  local want=$1 named=$2 script=$3 rc=0; shift 3
  rm -rf "$work/study-out"
  "$FSI_ROOT/cases/hydrofoil/$script" --out "$work/study-out" "$@" > "$work/study.out" 2> "$work/study.err" || rc=$?
  if { [ "$want" = nz ] && [ "$rc" -eq 0 ]; } || { [ "$want" != nz ] && [ "$rc" -ne "$want" ]; } ||
     [ "$(wc -l < "$work/study.err")" -ne 1 ] || ! grep -q -- "$named" "$work/study.err"; then
    echo "FAIL: $script $*: exit $rc, expected $want and one line naming $named:"; cat "$work/study.err"; fail=1
  elif [ -e "$work/study-out" ]; then
    echo "FAIL: $script $*: made its --out before refusing"; fail=1
  else
    echo "ok: $script $* -> $(cat "$work/study.err")"
  fi
}
studyCheck() { refusedBefore 2 --band-mean-tolerance "$@"; }
studyCheck rigid.sh --mesh "$fakeMesh" --band-tolerance 1e-3 --band-mean-tolerance 1.5
studyCheck rigid.sh --mesh "$fakeMesh" --band-mean-tolerance 1e-4x
studyCheck blcheck.sh --preset coarse --band-tolerance 1e-3 --band-mean-tolerance -1e-4
# restart points and --resume (a rigid solve longer than a session): bad values, and a --resume
# with nothing to go on from, refused in one line before anything is made
refusedBefore 2 --write-interval rigid.sh --mesh "$fakeMesh" --write-interval -5
refusedBefore 2 --max-iterations rigid.sh --mesh "$fakeMesh" --max-iterations 50
refusedBefore 2 --resume rigid.sh --mesh "$fakeMesh" --resume
refusedBefore 2 --resume blcheck.sh --preset coarse --resume
# --shape-displacement (a rigid solve in an interface CSV's shape): no such file, a file that is
# no interface CSV, or with --resume, refused in one line before anything is made
refusedBefore 2 "--shape-displacement '$work/none.csv': no such file" rigid.sh --mesh "$fakeMesh" --shape-displacement "$work/none.csv"
printf 'a,b\n1,2\n' > "$work/not-interface.csv"
refusedBefore 2 "is not an interface CSV" rigid.sh --mesh "$fakeMesh" --shape-displacement "$work/not-interface.csv"
printf '# level 0 time 0 s\nx,y,z,ux,uy,uz,fx,fy,fz\n0.37,0,0.05,0,-1e-3,0,0,0,0\n' > "$work/interface.csv"
refusedBefore 2 "not with --resume" rigid.sh --mesh "$fakeMesh" --resume --shape-displacement "$work/interface.csv"
# ... and a CSV of another geometry (a foil point 50 mm from every node), refused before the case
# is built: a mesh whose foil patch is two faces of a 2 mm x 1 mm plate at z = 0.1 m
fakeFoil=$work/fake-foil-mesh
rm -rf "$fakeFoil"; mkdir -p "$fakeFoil/constant/polyMesh"
{ printf 'FoamFile\n{\n    format ascii;\n}\n6\n(\n'
  printf '(0.3 0 0.1)\n(0.301 0 0.1)\n(0.302 0 0.1)\n(0.3 0.001 0.1)\n(0.301 0.001 0.1)\n(0.302 0.001 0.1)\n)\n'
} > "$fakeFoil/constant/polyMesh/points"
printf 'FoamFile\n{\n    format ascii;\n}\n3\n(\n3(0 1 4)\n4(4 5 2 1)\n4(3 4 1 0)\n)\n' > "$fakeFoil/constant/polyMesh/faces"
printf 'FoamFile\n{\n    format ascii;\n}\n1\n(\n    foil\n    {\n        type wall;\n        nFaces 2;\n        startFace 1;\n    }\n)\n' \
    > "$fakeFoil/constant/polyMesh/boundary"
: > "$fakeFoil/constant/polyMesh/owner"
refusedBefore 2 "not this foil's interface" rigid.sh --mesh "$fakeFoil" --shape-displacement "$work/interface.csv"
# --shape-from (a rigid solve in a coupled run's shape): a case without a moved mesh, one
# decomposed for other ranks, one with a rank folder lacking the moved mesh, or with --init-from,
# refused in one line before anything is made
fakeShape=$work/fake-shape fakeRigid=$work/fake-rigid
rm -rf "$fakeShape" "$fakeRigid"
mkdir -p "$fakeShape/processor0/0/polyMesh" "$fakeShape/processor1" "$fakeRigid/case"
: > "$fakeRigid/rigid.csv"
refusedBefore 2 "--shape-from '$fakeRigid' has no moved mesh" rigid.sh --mesh "$fakeMesh" --shape-from "$fakeRigid"
: > "$fakeShape/processor0/0/polyMesh/points"
refusedBefore 2 "give --np 2" rigid.sh --mesh "$fakeMesh" --np 1 --shape-from "$fakeShape"
refusedBefore 2 "processor1 has no moved mesh" rigid.sh --mesh "$fakeMesh" --np 2 --shape-from "$fakeShape"
refusedBefore 2 "not with --init-from" rigid.sh --mesh "$fakeMesh" --shape-from "$fakeShape" --init-from "$fakeRigid"
# the shape solve's flow model is the coupled case's (its fluidModel): a contradicting option is
# refused, the recorded model passes rigid.sh --check-only without model options; a case without
# fluidModel (made before 2026-12-07) needs --flow and --scheme
mkdir -p "$fakeShape/processor1/0/polyMesh"; : > "$fakeShape/processor1/0/polyMesh/points"
refusedBefore 2 "has no fluidModel" rigid.sh --mesh "$fakeMesh" --np 2 --shape-from "$fakeShape"
printf '# the flow model of this case (tools/fluidCase.sh)\nflow turbulent\nscheme linearUpwind\nalgorithm simplec\nroot_wall slip\n' \
    > "$fakeShape/fluidModel"
refusedBefore 2 "was solved with --scheme linearUpwind" rigid.sh --mesh "$fakeMesh" --np 2 --shape-from "$fakeShape" --scheme upwind
refusedBefore 2 "was solved with --root-wall slip" rigid.sh --mesh "$fakeMesh" --np 2 --shape-from "$fakeShape" --root-wall wall
for given in "" "--flow turbulent --scheme linearUpwind --root-wall slip --algorithm simplec"; do
    # shellcheck disable=SC2086  # $given: words on purpose
    if "$FSI_ROOT/cases/hydrofoil/rigid.sh" --check-only --np 2 --shape-from "$fakeShape" $given \
            > "$work/study.out" 2> "$work/study.err"; then
        echo "ok: rigid.sh --check-only --shape-from with the recorded model${given:+ (given: $given)}: exit 0"
    else
        echo "FAIL: rigid.sh --check-only --shape-from with the recorded model ($given):"; cat "$work/study.err"; fail=1
    fi
done
# without --np the shape solve takes the source's decomposition (a serial source: 1 rank, which
# the default 2 would contradict)
fakeSerial=$work/fake-serial
rm -rf "$fakeSerial"; mkdir -p "$fakeSerial/0/polyMesh"; : > "$fakeSerial/0/polyMesh/points"
cp "$fakeShape/fluidModel" "$fakeSerial/"
if "$FSI_ROOT/cases/hydrofoil/rigid.sh" --check-only --shape-from "$fakeSerial" > "$work/study.out" 2> "$work/study.err"; then
    echo "ok: rigid.sh --check-only --shape-from a serial case without --np: exit 0"
else
    echo "FAIL: rigid.sh --check-only --shape-from a serial case without --np:"; cat "$work/study.err"; fail=1
fi
refusedBefore 2 "give --np 1 or leave --np out" rigid.sh --mesh "$fakeMesh" --np 2 --shape-from "$fakeSerial"
# a resumed solve keeps its case's recorded model: a contradicting option is refused too
fakeResume=$work/fake-resume
rm -rf "$fakeResume"; mkdir -p "$fakeResume/case"; cp "$fakeShape/fluidModel" "$fakeResume/case/"
refusedBefore 2 "--resume: $fakeResume/case was solved with --flow turbulent" rigid.sh --mesh "$fakeMesh" --resume --flow laminar --out "$fakeResume"
refusedBefore 2 "has no written iteration" rigid.sh --mesh "$fakeMesh" --resume --out "$fakeResume"   # the model passes
# tools/fluidCase.sh --model-of, the one reader of the record (rigid.sh, scripts/bench-fsi): the
# recorded model as options, status 1 without a record, a line it does not know refused in one
# line naming the file (and rigid.sh stops with it)
want=$'--flow turbulent\n--scheme linearUpwind\n--algorithm simplec\n--root-wall slip'
got=$("$FSI_ROOT/cases/hydrofoil/tools/fluidCase.sh" --model-of "$fakeShape" 2> "$work/study.err") || got="exit $?"
if [ "$got" = "$want" ] && [ ! -s "$work/study.err" ]; then
    echo "ok: fluidCase.sh --model-of: the recorded model as four options"
else
    echo "FAIL: fluidCase.sh --model-of printed '$got', expected '$want'"; fail=1
fi
rc=0; "$FSI_ROOT/cases/hydrofoil/tools/fluidCase.sh" --model-of "$fakeMesh" > "$work/study.out" 2>&1 || rc=$?
if [ "$rc" = 1 ] && [ ! -s "$work/study.out" ]; then
    echo "ok: fluidCase.sh --model-of a case without fluidModel: status 1, silent"
else
    echo "FAIL: fluidCase.sh --model-of a case without fluidModel: exit $rc, $(cat "$work/study.out")"; fail=1
fi
cp "$fakeShape/fluidModel" "$work/fluidModel.good"
echo "turbulence kOmegaSST" >> "$fakeShape/fluidModel"
refusedBefore 2 "$fakeShape/fluidModel: unknown key 'turbulence'" rigid.sh --mesh "$fakeMesh" --np 2 --shape-from "$fakeShape"
cp "$work/fluidModel.good" "$fakeShape/fluidModel"
# ... and it is what rigid.sh validates (a recorded value it does not know is refused)
sed -i 's/^scheme .*/scheme quick/' "$fakeShape/fluidModel"
refusedBefore 2 "--scheme 'quick' unknown" rigid.sh --mesh "$fakeMesh" --np 2 --shape-from "$fakeShape"
# tools/shapeCheck.sh (rigid.sh --shape-from on a run.sh run folder): no run, or not a finished one
refusedBefore 2 "give --run" tools/shapeCheck.sh
refusedBefore 2 "has no results/baseline/history.csv" tools/shapeCheck.sh --run "$fakeRigid"
# --resume without a stopped shape solve, or --resume among rigid.sh's options
fakeRun=$work/fake-run
rm -rf "$fakeRun"; mkdir -p "$fakeRun/results/baseline" "$fakeRun/fluid-baseline" "$fakeRun/mesh/fluid/constant/polyMesh"
: > "$fakeRun/mesh/fluid/constant/polyMesh/owner"
: > "$fakeRun/results/baseline/history.csv"
refusedBefore 2 "has no written iteration" tools/shapeCheck.sh --run "$fakeRun" --resume
refusedBefore 2 "are this tool's to set" tools/shapeCheck.sh --run "$fakeRun" -- --resume
# mesh.sh --preset finer (the mesh studies' fourth level) exists only as a cgrid fluid mesh:
# anything else is refused in one line naming it, before mesh.sh makes its --out
refusedBefore nz "--preset finer" mesh.sh --preset finer
refusedBefore nz "--preset finer" mesh.sh --preset finer --fluid-mesh cgrid
# rigid.sh --check-only (what blcheck.sh calls before it meshes): valid options exit 0 without a mesh
if "$FSI_ROOT/cases/hydrofoil/rigid.sh" --check-only --flow turbulent --scheme linearUpwind \
        --band-tolerance 1e-3 --root-wall slip > "$work/study.out" 2> "$work/study.err"; then
    echo "ok: rigid.sh --check-only with valid options: exit 0"
else
    echo "FAIL: rigid.sh --check-only with valid options:"; cat "$work/study.err"; fail=1
fi
# scripts/bench-fsi --rigid-stop: a value it does not know is refused in one line, before the
# bench makes its work folder
rc=0
"$FSI_ROOT/scripts/bench-fsi" --run --rigid-stop residuals --out "$work/bench-out" > "$work/study.out" 2> "$work/study.err" || rc=$?
if [ "$rc" = 2 ] && [ "$(wc -l < "$work/study.err")" = 1 ] && grep -q -- "--rigid-stop" "$work/study.err" &&
        [ ! -e "$work/bench-out" ]; then
    echo "ok: bench-fsi --rigid-stop residuals -> $(cat "$work/study.err")"
else
    echo "FAIL: bench-fsi --rigid-stop residuals: exit $rc:"; cat "$work/study.err"; fail=1
fi
exit $fail
