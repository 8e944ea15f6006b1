#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Rigid-foil check of the fluid case with Debian's stock simpleFoam (no mesh motion).
#
#   cases/hydrofoil/validate.sh --mesh DIR/fluid --out RUNDIR [--scheme upwind|linearUpwind|
#       limitedLinearV] [--np 1|2] [--iterations 300] [--simple simplec|simple]
#
# Copies the meshed case DIR/fluid (from mesh.sh) to RUNDIR, removes constant/dynamicMeshDict
# (stock simpleFoam builds a static fvMesh anyway), sets the convection scheme of div(phi,U)
# and the pressure-velocity algorithm, runs simpleFoam for a fixed number of iterations and
# prints the force convergence (tools/forceConvergence.py: first iteration at which every force
# component changed by < 0.1 % over the last 20 iterations) and the CPU / wall time per
# iteration.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mesh="" out="" scheme=upwind np=1 iterations=300 simple=simplec
die() { echo "error: validate.sh: $*" >&2; exit 1; }
while [ $# -gt 0 ]; do
    case "$1" in
        --mesh) mesh="$2"; shift 2 ;;
        --out) out="$2"; shift 2 ;;
        --scheme) scheme="$2"; shift 2 ;;
        --np) np="$2"; shift 2 ;;
        --iterations) iterations="$2"; shift 2 ;;
        --simple) simple="$2"; shift 2 ;;
        -h|--help) sed -n '3,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) die "unknown option '$1' (see --help)" ;;
    esac
done
[ -f "$mesh/constant/polyMesh/owner" ] || die "--mesh '$mesh' has no constant/polyMesh; run mesh.sh first"
[ -n "$out" ] || die "--out RUNDIR is required"
mesh="$(cd "$mesh" && pwd)"
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
export OMPI_MCA_btl_tcp_if_include=lo OMPI_MCA_oob_tcp_if_include=lo

case "$scheme" in
    upwind) div="bounded Gauss upwind" ;;
    linearUpwind) div="bounded Gauss linearUpwind grad(U)" ;;   # grad(U): cellLimited 1
    limitedLinearV) div="bounded Gauss limitedLinearV 1" ;;
    *) die "--scheme '$scheme' unknown; use upwind, linearUpwind or limitedLinearV" ;;
esac

rm -rf "$out"
mkdir -p "$out"
cp -r "$mesh/constant" "$mesh/system" "$mesh/0" "$out/"
rm -f "$out/constant/dynamicMeshDict" "$out/0/pointDisplacement"
cd "$out"
foamDictionary system/fvSchemes -entry "divSchemes/div(phi,U)" -set "$div" > /dev/null
foamDictionary system/controlDict -entry endTime -set "$iterations" > /dev/null
foamDictionary system/controlDict -entry writeInterval -set "$iterations" > /dev/null
if [ "$simple" = simple ]; then
    foamDictionary system/fvSolution -entry SIMPLE/consistent -set no > /dev/null
    foamDictionary system/fvSolution -entry relaxationFactors/fields/p -set 0.3 > /dev/null
    foamDictionary system/fvSolution -entry relaxationFactors/equations/U -set 0.7 > /dev/null
fi
if [ "$np" -gt 1 ]; then
    foamDictionary system/decomposeParDict -entry numberOfSubdomains -set "$np" > /dev/null
    foamDictionary system/decomposeParDict -entry coeffs/n -set "($np 1 1)" > /dev/null
    decomposePar -force > log.decomposePar 2>&1
    start=$(date +%s.%N)
    mpirun --allow-run-as-root --oversubscribe -np "$np" simpleFoam -parallel > log.simpleFoam 2>&1
else
    start=$(date +%s.%N)
    simpleFoam > log.simpleFoam 2>&1
fi
end=$(date +%s.%N)
total=$(echo "$end - $start" | bc -l)
echo "scheme=$scheme simple=$simple np=$np cells=$(awk '/^ *cells:/{print $2; exit}' "$mesh/log.checkMesh") wall_total_s=$(printf %.1f "$total") $(/usr/bin/python3 "$here/tools/forceConvergence.py" . --log log.simpleFoam)"
