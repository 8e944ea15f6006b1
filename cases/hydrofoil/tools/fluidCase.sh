#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The OpenFOAM case of one fluid run, from a mesh folder's fluid case and this case's settings.
#
#   cases/hydrofoil/tools/fluidCase.sh DEST MESH_FLUID NP [--flow F] [--scheme S]
#       [--algorithm simple] [--init-from SOURCE_CASE] [--root-wall wall|slip]
#       [--simple-acceleration none|anderson[:DEPTH]]
#
# Copies MESH_FLUID (a mesh.sh fluid case) to DEST (replaced), gives it this case's solver
# settings (fluid/system/fsiDict, fvSchemes, fvSolution: a mesh folder may predate them), the
# fields of every flow model that it lacks (fluid/0.orig), the flow model and scheme
# (tools/setFlow.sh, options passed on), and decomposes it for NP ranks (hierarchical; NP 1:
# serial, no processor folders). --init-from: the initial fields are SOURCE_CASE's solution
# mapped onto this mesh (tools/mapInitialFields.sh; grid sequencing). --root-wall slip: the
# tunnel's root wall z = 0 becomes a slip patch `root` (tools/rootWall.sh; default wall: the
# paper's no-slip tunnel). --simple-acceleration: sets fvSolution SIMPLE.acceleration (anderson:
# the SIMPLE iterations Anderson-mixed over the last DEPTH, default 5; none: plain; not given:
# the case's fluid/system/fvSolution; fluid-app/README.md). Used by run.sh for the
# coupled runs and by scripts/bench-fsi for its rigid baseline, so that both solve with the
# same settings; options other than --init-from go to tools/setFlow.sh. Records the model in
# effect in DEST/fluidModel (`flow F`, `scheme S`, `algorithm simple|simplec`, `root_wall W`):
# rigid.sh --shape-from solves a coupled case's shape on with that model.
#
#   cases/hydrofoil/tools/fluidCase.sh --model-of CASE
#
# The one reader of that record: prints CASE's model as this script's options, one `--option
# value` per line (--flow, --scheme, --algorithm, --root-wall); status 1 when CASE has no
# fluidModel (a case made before 2026-12-07); a line it does not know is an error naming the
# file and the line. Used by rigid.sh (--shape-from, --resume) and scripts/bench-fsi.
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^[^#]/{/SPDX-License-Identifier/d;s/^# \{0,1\}//p}' "$0"; exit 0 ;; esac
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
case_dir="$(cd "$here/.." && pwd)"
die() { echo "error: fluidCase.sh: $*" >&2; exit 2; }
if [ "${1:-}" = --model-of ]; then
  [ $# = 2 ] || die "usage: fluidCase.sh --model-of CASE"
  [ -f "$2/fluidModel" ] || exit 1
  while read -r key value; do
    case "$key" in
      ""|"#"*) ;;
      flow|scheme|algorithm|root_wall) [ -n "$value" ] || die "$2/fluidModel: '$key' has no value"
                                       echo "--${key/_/-} $value" ;;
      *) die "$2/fluidModel: unknown key '$key' (flow, scheme, algorithm, root_wall; remake the case with tools/fluidCase.sh)" ;;
    esac
  done < "$2/fluidModel"
  exit 0
fi
# --check-only [--simple-acceleration A]: validates A only (exit 2 with a one-line error), for the
# scripts that pass it on (run.sh, scripts/bench-fsi) before they write anything.
checkOnly=0
if [ "${1:-}" = --check-only ]; then
  checkOnly=1; shift; set -- - - 1 "$@"
fi
[ $# -ge 3 ] || die "usage: fluidCase.sh DEST MESH_FLUID NP [--flow F] [--scheme S] [--algorithm simple] [--init-from SOURCE_CASE] [--root-wall wall|slip] [--simple-acceleration none|anderson[:DEPTH]]"
dest=$1 meshFluid=$2 np=$3; shift 3
initFrom="" rootWall=wall flowArgs=() acceleration=""
while [ $# -gt 0 ]; do
  case "$1" in
    --init-from) [ $# -ge 2 ] || die "--init-from needs a case folder"; initFrom=$2; shift 2 ;;
    --root-wall) [ $# -ge 2 ] || die "--root-wall needs wall or slip"; rootWall=$2; shift 2 ;;
    --simple-acceleration) [ $# -ge 2 ] || die "--simple-acceleration needs none or anderson[:DEPTH]"; acceleration=$2; shift 2 ;;
    *) flowArgs+=("$1"); shift ;;
  esac
done
[ -z "$acceleration" ] || [[ "$acceleration" =~ ^(none|anderson(:([1-9]|[1-4][0-9]|50))?)$ ]] ||
  die "--simple-acceleration '$acceleration' must be none or anderson[:DEPTH], DEPTH in 1..50 (e.g. anderson:5)"
[ "$checkOnly" = 0 ] || exit 0
[ -d "$meshFluid/constant/polyMesh" ] || die "$meshFluid is not a fluid case with a mesh"
[[ "$np" =~ ^[1-9][0-9]*$ ]] || die "NP '$np' must be a positive integer"
case "$rootWall" in wall|slip) ;; *) die "--root-wall '$rootWall' must be wall (the paper's no-slip tunnel) or slip" ;; esac
sourceRoot=0
[ -z "$initFrom" ] || ! grep -q '^ *root$' "$initFrom/constant/polyMesh/boundary" 2> /dev/null || sourceRoot=1
[ "$sourceRoot" = 0 ] || [ "$rootWall" = slip ] ||
  die "--init-from '$initFrom' has a slip root wall (patch root): give --root-wall slip, or start from a no-slip run"
rm -rf "$dest"
cp -r "$meshFluid" "$dest"
rm -rf "$dest"/processor*
cp "$case_dir/fluid/system/fsiDict" "$case_dir/fluid/system/fvSchemes" \
   "$case_dir/fluid/system/fvSolution" "$dest/system/"
for f in "$case_dir/fluid/0.orig"/*; do [ -e "$dest/0/$(basename "$f")" ] || cp "$f" "$dest/0/"; done
model=$("$here/setFlow.sh" "$dest" ${flowArgs[@]+"${flowArgs[@]}"})
# mapFields -consistent needs the source's patches: the root patch is made before the mapping
# when the source has one (a slip-root-wall run), after it otherwise
[ "$rootWall" = wall ] || [ "$sourceRoot" = 0 ] || "$here/rootWall.sh" "$dest" > /dev/null
[ -z "$initFrom" ] || "$here/mapInitialFields.sh" "$dest" "$initFrom" > /dev/null
[ "$rootWall" = wall ] || [ "$sourceRoot" = 1 ] || "$here/rootWall.sh" "$dest" > /dev/null
if [ "$acceleration" = none ]; then
  foamDictionary "$dest/system/fvSolution" -entry SIMPLE/acceleration -set "{ type none; }" >/dev/null
elif [ -n "$acceleration" ]; then
  depth=5; [ "$acceleration" = anderson ] || depth=${acceleration#anderson:}
  foamDictionary "$dest/system/fvSolution" -entry SIMPLE/acceleration -set "{ type anderson; depth $depth; }" >/dev/null
fi
# DEST/fluidModel: the model in effect, `key value` per line (flow, scheme, algorithm, root_wall),
# for the tools that solve on from this case's flow (rigid.sh --shape-from takes it from here)
{ echo "# the flow model of this case (tools/fluidCase.sh)"
  for kv in $model; do echo "${kv%%=*} ${kv#*=}"; done
  echo "root_wall $rootWall"; } > "$dest/fluidModel"
if [ "$np" -gt 1 ]; then
  foamDictionary "$dest/system/decomposeParDict" -entry numberOfSubdomains -set "$np" >/dev/null
  foamDictionary "$dest/system/decomposeParDict" -entry method -set hierarchical >/dev/null
  (cd "$dest" && decomposePar -force > log.decomposePar 2>&1) ||
    die "decomposePar failed ($dest/log.decomposePar)"
fi
