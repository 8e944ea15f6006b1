#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Mesh-motion check: impose a bending + twist on the foil patch (tools/foilMotion.py), move the
# mesh once with the case's dynamicMeshDict (displacementLaplacian, quadratic inverseDistance)
# using stock moveDynamicMesh, and run checkMesh on the moved mesh.
#
#   tools/motionCheck.sh --mesh DIR/fluid --out RUNDIR [--tip-twist-deg -4] [--tip-deflection 0.003]
#                        [--bending beam|shear] [--opening-angle THETA] [--displacement-from FILE]
# (--bending: see foilMotion.py; beam, the default, turns the sections with the slope as the
# structural solver's displacement does. --opening-angle: fsiInverseDistanceCoeffs openingAngle
# for this motion, fsiInverseDistance meshes only; the moved points are written with 17 digits
# in RUNDIR/1/polyMesh/points. --displacement-from FILE: the foil's displacement of a coupled
# run's level instead of the bending + twist, FILE = its reconstructed ASCII pointDisplacement on
# the same mesh, e.g. RUN/fluid-visco/TIME/pointDisplacement after `reconstructPar -time TIME
# -fields '(pointDisplacement)'` and `foamFormatConvert -time TIME` with writeFormat ascii.)
# A mesh whose dynamicMeshDict selects fsiInverseDistance needs libfsiMeshMotion.so: taken from the build next to fluid-app on PATH (or FSI_BUILD_DIR).
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^[^#]/{/SPDX-License-Identifier/d;s/^# \{0,1\}//p}' "$0"; exit 0 ;; esac
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mesh="" out="" twist=-4 deflection=0.003 bending=beam openingAngle="" from=""
while [ $# -gt 0 ]; do
    case "$1" in
        --mesh) mesh="$2"; shift 2 ;;
        --out) out="$2"; shift 2 ;;
        --tip-twist-deg) twist="$2"; shift 2 ;;
        --tip-deflection) deflection="$2"; shift 2 ;;
        --bending) bending="$2"; shift 2 ;;
        --opening-angle) openingAngle="$2"; shift 2 ;;
        --displacement-from) from="$(cd "$(dirname "$2")" 2>/dev/null && pwd)/$(basename "$2")"; shift 2 ;;
        *) echo "error: motionCheck.sh: unknown option '$1'" >&2; exit 1 ;;
    esac
done
[ -f "$mesh/constant/polyMesh/owner" ] || { echo "error: motionCheck.sh: --mesh '$mesh' has no mesh" >&2; exit 1; }
[ -z "$from" ] || [ -f "$from" ] || { echo "error: motionCheck.sh: --displacement-from: no file $from" >&2; exit 1; }
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
if grep -q fsiMeshMotion "$mesh/constant/dynamicMeshDict" 2>/dev/null; then
    lib=""
    if [ -n "${FSI_BUILD_DIR:-}" ]; then lib="$FSI_BUILD_DIR/lib"
    elif command -v fluid-app > /dev/null; then lib="$(dirname "$(command -v fluid-app)")/../lib"; fi
    [ -f "$lib/libfsiMeshMotion.so" ] || { echo "error: motionCheck.sh: $mesh uses fsiInverseDistance, but libfsiMeshMotion.so was not found (build first; put the build's bin/ on PATH or set FSI_BUILD_DIR)" >&2; exit 1; }
    export LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
rm -rf "$out"; mkdir -p "$out"
cp -r "$mesh/0" "$mesh/constant" "$mesh/system" "$out/"
cd "$out"
foamDictionary system/controlDict -entry endTime -set 1 > /dev/null
foamDictionary system/controlDict -entry writeInterval -set 1 > /dev/null
foamDictionary system/controlDict -entry writeFormat -set ascii > /dev/null
foamDictionary system/controlDict -entry writePrecision -set 17 > /dev/null
if [ -n "$openingAngle" ]; then
    grep -q fsiInverseDistanceCoeffs constant/dynamicMeshDict ||
        { echo "error: motionCheck.sh: --opening-angle needs a mesh moved by fsiInverseDistance (constant/dynamicMeshDict)" >&2; exit 1; }
    foamDictionary constant/dynamicMeshDict -entry fsiInverseDistanceCoeffs/openingAngle -set "$openingAngle" > /dev/null
fi
foamDictionary system/controlDict -entry functions -remove > /dev/null
foamFormatConvert -constant > log.foamFormatConvert 2>&1
/usr/bin/python3 "$here/foilMotion.py" . --tip-twist-deg "$twist" --tip-deflection "$deflection" --bending "$bending" \
    ${from:+--from "$from"}
motion="twist=$twist deg deflection=$deflection m bending=$bending"
[ -z "$from" ] || motion="displacement from $from"
moveDynamicMesh > log.moveDynamicMesh 2>&1
checkMesh -latestTime > log.checkMesh 2>&1 || true
if grep -q "^Mesh OK" log.checkMesh; then
    echo "motion $motion: Mesh OK ($(grep 'non-orthogonality Max' log.checkMesh | tr -s ' '))"
else
    echo "motion $motion: FAILED: $(grep '\*\*\*' log.checkMesh | head -3 | tr -s ' ')"
    exit 1
fi
