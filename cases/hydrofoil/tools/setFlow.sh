#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Select the flow model and the convection scheme of an OpenFOAM copy of the hydrofoil case.
#
#   cases/hydrofoil/tools/setFlow.sh CASE [--flow laminar|transition|turbulent]
#                                         [--scheme upwind|linearUpwind] [--algorithm simple|simplec]
#                                         [--relaxation U/T]
#
#   --flow laminar      the paper's model (default)
#          transition   Langtry-Menter kOmegaSSTLM (needs first-cell y+ <= 1)
#          turbulent    k-omega SST
#   --scheme upwind        first order, bounded (default)
#            linearUpwind  second order, bounded, cell-limited gradients (U and the
#                          turbulence fields); under SIMPLEC with U and the turbulence fields
#                          relaxed by 0.7 instead of the case's 0.9 / 0.8: with 0.9 / 0.8 the
#                          turned foil's flow (coupled or pitched) swings in a slow cycle of
#                          +-0.6-1.7 % that does not settle in 1 500 iterations, with 0.7 it
#                          converges monotonically (README "A steady second-order flow")
#   --algorithm simple     classic SIMPLE (consistent no; relaxation p 0.3, U 0.7, turbulence
#                          0.7) instead of the case's SIMPLEC (consistent yes; p 1, U 0.9,
#                          turbulence 0.8, or 0.7 / 0.7 with linearUpwind). Not given: the
#                          case's algorithm stays (SIMPLE.consistent); every relaxation factor
#                          is set from the algorithm and the scheme, so a case set before with
#                          another combination ends with this one's values. SIMPLEC is the faster one where it is stable; on the older
#                          medium and fine cgrid meshes it is not (README "The tip gap's
#                          re-spaced cells": a growing two-iteration oscillation in the tip gap)
#   --relaxation U/T       the momentum (U) and turbulence (k, omega, ReThetat, gammaInt)
#                          equations' relaxation factors in (0, 1] instead of the ones above,
#                          e.g. 0.9/0.8: the 2-D section study's SIMPLEC factors with
#                          linearUpwind (section2d/run2d.sh; 0.7 does not remove its cycle there)
#
# Copies fluid/flow/<flow> to CASE/constant/turbulenceProperties and sets divSchemes of
# CASE/system/fvSchemes. The fields of every model are in fluid/0.orig (k, omega, nut,
# ReThetat, gammaInt are read only by the RAS models). Prints "flow=F scheme=S algorithm=A" (A the
# algorithm in effect: the one given, else the case's).
# `setFlow.sh --check-only [options]` only validates the options (exit 2 with a one-line error):
# the scripts that pass them on call it before they write anything.
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^[^#]/{/SPDX-License-Identifier/d;s/^# \{0,1\}//p}' "$0"; exit 0 ;; esac
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
die() { echo "error: setFlow.sh: $*" >&2; exit 2; }
[ $# -ge 1 ] || die "usage: setFlow.sh CASE [--flow laminar|transition|turbulent] [--scheme upwind|linearUpwind]"
case="$1"; shift   # --check-only: no case
flow=laminar scheme=upwind algorithm="" relaxation=""
while [ $# -gt 0 ]; do
    case "$1" in
        --flow) flow="$2"; shift 2 ;;
        --scheme) scheme="$2"; shift 2 ;;
        --algorithm) algorithm="$2"; shift 2 ;;
        --relaxation) relaxation="$2"; shift 2 ;;
        *) die "unknown option '$1' (use --flow, --scheme, --algorithm, --relaxation)" ;;
    esac
done
case "$algorithm" in ""|simple|simplec) ;; *) die "--algorithm '$algorithm' unknown; use simple or simplec (the case's, also when left out)" ;; esac
[ -f "$here/fluid/flow/$flow" ] || die "--flow '$flow' unknown; use laminar, transition or turbulent"
case "$scheme" in upwind|linearUpwind) ;; *) die "--scheme '$scheme' unknown; use upwind or linearUpwind" ;; esac
[ -z "$relaxation" ] || awk -v r="$relaxation" 'BEGIN { n = split(r, f, "/"); ok = n == 2;
    for (i = 1; i <= n; ++i) ok = ok && f[i] ~ /^[0-9.eE+-]+$/ && f[i] + 0 > 0 && f[i] + 0 <= 1; exit !ok }' ||
    die "--relaxation '$relaxation' must be U/T, two factors in (0, 1], e.g. 0.9/0.8"
[ "$case" != --check-only ] || exit 0
[ -f "$case/system/fvSchemes" ] || die "'$case' is not an OpenFOAM case (no system/fvSchemes)"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
cp "$here/fluid/flow/$flow" "$case/constant/turbulenceProperties"
set_() { foamDictionary "$case/system/fvSchemes" -entry "$1" -set "$2" > /dev/null; }
case "$scheme" in
    upwind)
        set_ "divSchemes/div(phi,U)" "bounded Gauss upwind"
        for f in k omega ReThetat gammaInt; do set_ "divSchemes/div(phi,$f)" "bounded Gauss upwind"; done ;;
    linearUpwind)
        # cellLimited Gauss linear 1 gradients (fvSchemes gradSchemes): bounded reconstruction
        set_ "divSchemes/div(phi,U)" "bounded Gauss linearUpwind grad(U)"
        for f in k omega ReThetat gammaInt; do
            set_ "divSchemes/div(phi,$f)" "bounded Gauss linearUpwind grad($f)"
        done ;;
esac
sol() { foamDictionary "$case/system/fvSolution" -entry "$1" -set "$2" > /dev/null; }
# Every factor is set from (algorithm, scheme), so a case set before (e.g. linearUpwind, or
# classic SIMPLE) gets the new combination's values, not a mix. Without --algorithm the case's
# algorithm stays (SIMPLE.consistent yes: SIMPLEC).
effective=$algorithm
if [ -z "$effective" ]; then
    consistent=$(foamDictionary "$case/system/fvSolution" -entry SIMPLE/consistent -value 2> /dev/null || echo no)
    case "$consistent" in yes|on|true|1) effective=simplec ;; *) effective=simple ;; esac
fi
if [ "$effective" = simple ]; then
    consistent=no relaxP=0.3 relaxU=0.7 relaxT=0.7
elif [ "$scheme" = linearUpwind ]; then
    consistent=yes relaxP=1 relaxU=0.7 relaxT=0.7
else
    consistent=yes relaxP=1 relaxU=0.9 relaxT=0.8
fi
[ -z "$relaxation" ] || relaxU=${relaxation%/*} relaxT=${relaxation#*/}
sol SIMPLE/consistent "$consistent"
sol relaxationFactors/fields/p "$relaxP"
sol relaxationFactors/equations/U "$relaxU"
sol 'relaxationFactors/equations/"(k|omega|ReThetat|gammaInt)"' "$relaxT"
echo "flow=$flow scheme=$scheme algorithm=$effective"
