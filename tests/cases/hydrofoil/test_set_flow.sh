#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# tools/setFlow.sh on a copy of the fluid case (no mesh, no run; a few seconds):
#  - upwind keeps the case's SIMPLEC relaxation (p 1, U 0.9, turbulence 0.8) and sets upwind;
#  - linearUpwind under SIMPLEC relaxes U and the turbulence fields by 0.7 (the turned foil's
#    slow cycle, README "A steady second-order flow"), p stays 1, consistent stays yes;
#  - --algorithm simple: consistent no, p 0.3, U 0.7, turbulence 0.7, with either scheme;
#  - applied again to a case set before, the new combination's factors, not a mix (linearUpwind
#    then upwind: 0.9 / 0.8 again; --algorithm simple then simplec: consistent yes, p 1);
#  - --relaxation U/T overrides the equations' factors (the 2-D section's 0.9 / 0.8), and a
#    later call without it restores the scheme's;
#  - the flow model's turbulenceProperties is copied; a bad option: one line, exit 2;
#  - the line it prints names the algorithm in effect, also when --algorithm is left out.
# usage: test_set_flow.sh WORKDIR
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
source "$root/scripts/env.sh"   # OpenFOAM's tree (foamDictionary)
work=${1:?usage: test_set_flow.sh WORKDIR}
fail() { echo "FAIL: $*"; exit 1; }
value() { foamDictionary "$1/system/$2" -entry "$3" -value 2> /dev/null; }
check() {   # CASE LABEL div(phi,U) consistent p U turbulence
    local c=$1 what=$2
    [ "$(value "$c" fvSchemes 'divSchemes/div(phi,U)')" = "$3" ] || fail "$what: div(phi,U) is '$(value "$c" fvSchemes 'divSchemes/div(phi,U)')', expected '$3'"
    [ "$(value "$c" fvSolution SIMPLE/consistent)" = "$4" ] || fail "$what: consistent is not $4"
    [ "$(value "$c" fvSolution relaxationFactors/fields/p)" = "$5" ] || fail "$what: p relaxation is not $5"
    [ "$(value "$c" fvSolution relaxationFactors/equations/U)" = "$6" ] || fail "$what: U relaxation is not $6"
    [ "$(value "$c" fvSolution 'relaxationFactors/equations/"(k|omega|ReThetat|gammaInt)"')" = "$7" ] ||
        fail "$what: turbulence relaxation is not $7"
    echo "ok: $what"
}
fresh() {
    rm -rf "$work/$1"; mkdir -p "$work/$1"
    cp -r "$root/cases/hydrofoil/fluid/system" "$root/cases/hydrofoil/fluid/constant" "$work/$1/"
    echo "$work/$1"
}
setFlow=$root/cases/hydrofoil/tools/setFlow.sh

c=$(fresh upwind); "$setFlow" "$c" --flow turbulent --scheme upwind > /dev/null
check "$c" "turbulent upwind SIMPLEC" "bounded Gauss upwind" yes 1 0.9 0.8
cmp -s "$c/constant/turbulenceProperties" "$root/cases/hydrofoil/fluid/flow/turbulent" ||
    fail "turbulenceProperties is not fluid/flow/turbulent"

c=$(fresh lu); "$setFlow" "$c" --flow turbulent --scheme linearUpwind > /dev/null
check "$c" "turbulent linearUpwind SIMPLEC" "bounded Gauss linearUpwind grad(U)" yes 1 0.7 0.7
[ "$(value "$c" fvSchemes 'divSchemes/div(phi,omega)')" = "bounded Gauss linearUpwind grad(omega)" ] ||
    fail "linearUpwind: div(phi,omega) is not linearUpwind"

c=$(fresh lusimplec); "$setFlow" "$c" --flow laminar --scheme linearUpwind --algorithm simplec > /dev/null
check "$c" "laminar linearUpwind --algorithm simplec" "bounded Gauss linearUpwind grad(U)" yes 1 0.7 0.7

for scheme in upwind linearUpwind; do
    c=$(fresh simple-$scheme); "$setFlow" "$c" --flow turbulent --scheme $scheme --algorithm simple > /dev/null
    div="bounded Gauss upwind"; [ $scheme = upwind ] || div="bounded Gauss linearUpwind grad(U)"
    check "$c" "turbulent $scheme SIMPLE" "$div" no 0.3 0.7 0.7
done

c=$(fresh again); "$setFlow" "$c" --flow turbulent --scheme linearUpwind > /dev/null
"$setFlow" "$c" --flow turbulent --scheme upwind > /dev/null
check "$c" "linearUpwind, then upwind on the same case" "bounded Gauss upwind" yes 1 0.9 0.8
"$setFlow" "$c" --flow turbulent --scheme upwind --algorithm simple > /dev/null
printed=$("$setFlow" "$c" --flow turbulent --scheme upwind)
check "$c" "SIMPLE, then no --algorithm: SIMPLE stays" "bounded Gauss upwind" no 0.3 0.7 0.7
# the line it prints names the algorithm in effect (tools/fluidCase.sh records it in fluidModel)
[ "$printed" = "flow=turbulent scheme=upwind algorithm=simple" ] || fail "printed '$printed' (the case's SIMPLE kept)"
printed=$("$setFlow" "$c" --flow turbulent --scheme upwind --algorithm simplec)
[ "$printed" = "flow=turbulent scheme=upwind algorithm=simplec" ] || fail "printed '$printed' after --algorithm simplec"
echo "ok: the printed model names the algorithm in effect"
check "$c" "SIMPLE, then --algorithm simplec" "bounded Gauss upwind" yes 1 0.9 0.8

c=$(fresh relax); "$setFlow" "$c" --flow turbulent --scheme linearUpwind --relaxation 0.9/0.8 > /dev/null
check "$c" "linearUpwind SIMPLEC --relaxation 0.9/0.8 (the 2-D section's)" "bounded Gauss linearUpwind grad(U)" yes 1 0.9 0.8
"$setFlow" "$c" --flow turbulent --scheme linearUpwind > /dev/null
check "$c" "--relaxation, then without it: the scheme's factors again" "bounded Gauss linearUpwind grad(U)" yes 1 0.7 0.7

set +e
msg=$("$setFlow" --check-only --relaxation 0.9 2>&1); rc=$?
set -e
[ $rc = 2 ] && [ "$(printf '%s\n' "$msg" | wc -l)" = 1 ] && [[ $msg == *"--relaxation '0.9'"* ]] ||
    fail "a bad --relaxation: rc $rc, message '$msg'"
echo "ok: a bad --relaxation is refused in one line"
set +e
msg=$("$setFlow" --check-only --scheme quick 2>&1); rc=$?
set -e
[ $rc = 2 ] && [ "$(printf '%s\n' "$msg" | wc -l)" = 1 ] && [[ $msg == *"--scheme 'quick' unknown"* ]] ||
    fail "a bad --scheme: rc $rc, message '$msg'"
echo "ok: a bad --scheme is refused in one line"
