#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Geometry and meshes of the hydrofoil case (paper section 2) into a run folder outside git.
#
#   cases/hydrofoil/mesh.sh --out DIR [--preset coarse|medium|fine|finer] [--tc 0.12] [--cli 0.5]
#                           [--meanline a08|a08mod] [--layers N] [--np N]
#                           [--fluid-only | --solid-only] [--curved]
#                           [--fluid-mesh snappy|cgrid] [--te sharp|blunt]
#   --preset finer: the mesh studies' fourth level (cgrid3d.py, about 2.8 M cells), with
#   --fluid-mesh cgrid --fluid-only only (scripts/verify.d/hydrofoil-3d-rigid.sh H3D_LEVELS)
#
# Writes
#   DIR/geometry/   section.csv, foil.stl (closed), foil.geo (Gmsh), snappy.stl (root extended)
#   DIR/fluid/      OpenFOAM v1912 case: the mesh (--fluid-mesh snappy: blockMesh + snappyHexMesh,
#                   no boundary layers; cgrid: tools/cgrid3d.py, the section's C-grid extruded
#                   along the span with y+ <= 1 layers on sides and tip; --te: its trailing
#                   edge), 0/ (all fields of fluid/0.orig), checkMesh log (must say "Mesh OK";
#                   the script fails otherwise)
#   DIR/solid/      foil-tet10.msh (v4), foil-tet10-msh22.msh (v2), foil-hex20.msh, foil-hex27.msh
#                   (second order, straight-sided; --curved: Tet10 mid-nodes on the curved
#                   surface, optimised by Gmsh, slow); physical groups volume, clamped, wetted
#   DIR/mesh-summary.txt  cell / node / element counts
# Needs Debian's openfoam (blockMesh, surfaceFeatureExtract, snappyHexMesh, checkMesh), gmsh and
# /usr/bin/python3 with numpy.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
preset=coarse tc=0.12 cli=0.5 meanline=a08 out="" layers="" np=1 doFluid=1 doSolid=1 curved=0
fluidMesh=snappy te=sharp

usage() { sed -n '2,/^[^#]/{/SPDX-License-Identifier/d;s/^# \{0,1\}//p}' "$0"; }
die() { echo "error: mesh.sh: $*" >&2; exit 1; }

while [ $# -gt 0 ]; do
    case "$1" in
        --preset) preset="$2"; shift 2 ;;
        --tc) tc="$2"; shift 2 ;;
        --cli) cli="$2"; shift 2 ;;
        --meanline) meanline="$2"; shift 2 ;;
        --out) out="$2"; shift 2 ;;
        --layers) layers="$2"; shift 2 ;;
        --np) np="$2"; shift 2 ;;
        --fluid-only) doSolid=0; shift ;;
        --curved) curved=1; shift ;;
        --solid-only) doFluid=0; shift ;;
        --fluid-mesh) fluidMesh="$2"; shift 2 ;;
        --te) te="$2"; shift 2 ;;
        -h|--help) usage; exit 0 ;;
        *) die "unknown option '$1' (see --help)" ;;
    esac
done
[ -n "$out" ] || die "--out DIR is required (a run folder outside git, e.g. /tmp/hydrofoil-coarse)"
case "$fluidMesh" in snappy|cgrid) ;; *) die "--fluid-mesh '$fluidMesh' unknown; use snappy or cgrid" ;; esac
# finer: the mesh studies' fourth level, a boundary-layer fluid mesh only (no snappy or solid preset)
if [ "$preset" = finer ]; then
    [ "$fluidMesh" = cgrid ] && [ "$doSolid" = 0 ] ||
        die "--preset finer is a mesh-study level: --fluid-mesh cgrid --fluid-only only"
else
    [ -f "$here/fluid/system/presets/$preset" ] || die "--preset '$preset' unknown; use coarse, medium or fine (or finer, the mesh studies' level, with --fluid-mesh cgrid --fluid-only)"
fi
case "$te" in sharp|blunt) ;; *) die "--te '$te' unknown; use sharp or blunt" ;; esac
[ "$fluidMesh" = cgrid ] || [ "$te" = sharp ] || die "--te applies to --fluid-mesh cgrid only (snappy meshes the section's blunt trailing edge)"
[ -z "$layers" ] || [ "$fluidMesh" = snappy ] || die "--layers applies to --fluid-mesh snappy only (cgrid has its own layers)"
out="$(realpath -m "$out")"
case "$out/" in
    "$here"/*) die "--out '$out' is inside cases/hydrofoil; generate into a run folder outside git" ;;
esac
mkdir -p "$out"

# Solid mesh presets: Tet10 size lc (m; lc/4 at the leading and trailing edges); Hex divisions
# along the chord (each of upper and lower side) x through the thickness x along the span
case "$preset" in
    coarse) lc=0.010; hexC=24; hexT=4; hexS=12 ;;
    medium) lc=0.006; hexC=40; hexT=6; hexS=20 ;;
    fine)   lc=0.004; hexC=64; hexT=8; hexS=32 ;;
esac

log() { echo "[mesh.sh $(date +%H:%M:%S)] $*"; }
summary="$out/mesh-summary.txt"
echo "hydrofoil meshes ($(date -u +%FT%TZ)): preset=$preset tc=$tc cli=$cli meanline=$meanline fluid-mesh=$fluidMesh" >> "$summary"

# ---- geometry ------------------------------------------------------------------------------
log "geometry (t/c=$tc, C_Li=$cli, $meanline)"
mkdir -p "$out/geometry"
/usr/bin/python3 "$here/geometry/naca66a08.py" --tc "$tc" --cli "$cli" --meanline "$meanline" \
    --out "$out/geometry" | tee -a "$summary"
# the snappyHexMesh surface reaches 2 mm through the root wall z = 0 for a clean intersection
tmpgeo="$(mktemp -d)"
/usr/bin/python3 "$here/geometry/naca66a08.py" --tc "$tc" --cli "$cli" --meanline "$meanline" \
    --stl-root-extension 0.002 --out "$tmpgeo" > /dev/null
mv "$tmpgeo/foil.stl" "$out/geometry/snappy.stl"
rm -rf "$tmpgeo"

# ---- fluid ---------------------------------------------------------------------------------
if [ "$doFluid" = 1 ]; then
    export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
    case="$out/fluid"
    log "fluid case -> $case (preset $preset, $fluidMesh)"
    rm -rf "$case"
    mkdir -p "$case/constant/triSurface"
    cp -r "$here/fluid/system" "$here/fluid/constant" "$case/"
    [ "$preset" = finer ] || cp "$here/fluid/system/presets/$preset" "$case/system/meshParameters"
    if [ "$fluidMesh" = cgrid ]; then
        /usr/bin/python3 "$here/tools/cgrid3d.py" --preset "$preset" --out "$case/cgrid" --tc "$tc" \
            --cli "$cli" --meanline "$meanline" --te "$te" | tee -a "$summary"
        ( cd "$case"
          gmshToFoam cgrid/cgrid3d.msh > log.gmshToFoam 2>&1 || { tail -20 log.gmshToFoam; exit 1; }
          # every boundary face belongs to a named patch; gmshToFoam collects the others (e.g.
          # unmatched faces between two cells) in defaultFaces
          ! grep -q defaultFaces constant/polyMesh/boundary ||
              { echo "error: mesh.sh: $case/constant/polyMesh/boundary has a defaultFaces patch (boundary faces cgrid3d.py did not name: unmatched cell faces); the mesh is unusable, please report it with $case/cgrid/cgrid3d-mesh.txt" >&2; exit 1; }
          /usr/bin/python3 "$here/tools/patchTypes.py" constant/polyMesh/boundary \
              inlet:patch outlet:patch walls:wall foil:wall )
        rm -f "$case/cgrid/cgrid3d.msh"
        # the Laplacian motion inverts the 5 um wall cells: explicit inverse-distance motion
        cp "$here/fluid/constant/dynamicMeshDict.inverseDistance" "$case/constant/dynamicMeshDict"
        rm -f "$case"/system/{blockMeshDict,snappyHexMeshDict,surfaceFeatureExtractDict,meshParameters}
        rm -rf "$case/system/presets" "$case/constant/triSurface"
    else
        if [ -n "$layers" ]; then
            if [ "$layers" -gt 0 ]; then
                foamDictionary -case "$case" system/meshParameters -entry addLayers -set true > /dev/null
                foamDictionary -case "$case" system/meshParameters -entry nLayers -set "$layers" > /dev/null
            else
                foamDictionary -case "$case" system/meshParameters -entry addLayers -set false > /dev/null
            fi
        fi
        cp "$out/geometry/snappy.stl" "$case/constant/triSurface/foil.stl"
        ( cd "$case"
          blockMesh > log.blockMesh 2>&1 || { tail -20 log.blockMesh; exit 1; }
          surfaceFeatureExtract > log.surfaceFeatureExtract 2>&1 || { tail -20 log.surfaceFeatureExtract; exit 1; }
          if [ "$np" -gt 1 ]; then
              foamDictionary system/decomposeParDict -entry numberOfSubdomains -set "$np" > /dev/null
              foamDictionary system/decomposeParDict -entry coeffs/n -set "($np 1 1)" > /dev/null
              decomposePar -force > log.decomposePar.mesh 2>&1
              OMPI_MCA_btl_tcp_if_include=lo OMPI_MCA_oob_tcp_if_include=lo \
              mpirun --allow-run-as-root --oversubscribe -np "$np" snappyHexMesh -overwrite -parallel \
                  > log.snappyHexMesh 2>&1 || { tail -30 log.snappyHexMesh; exit 1; }
              reconstructParMesh -constant > log.reconstructParMesh 2>&1
              rm -rf processor*
          else
              snappyHexMesh -overwrite > log.snappyHexMesh 2>&1 || { tail -30 log.snappyHexMesh; exit 1; }
          fi
          rm -f constant/polyMesh/{cellLevel,pointLevel,level0Edge,surfaceIndex,refinementHistory} )
    fi
    ( cd "$case"
      rm -rf 0
      cp -r "$here/fluid/0.orig" 0
      checkMesh > log.checkMesh 2>&1 || true
    )
    grep -q "^Mesh OK" "$case/log.checkMesh" || { grep -E "\*\*\*|Failed" "$case/log.checkMesh"; die "checkMesh failed on $case (see log.checkMesh)"; }
    grep -q "^    foil$\|^        foil$\|foil" "$case/constant/polyMesh/boundary" || die "no foil patch in the fluid mesh"
    cells=$(awk '/^ *cells:/{print $2; exit}' "$case/log.checkMesh")
    points=$(awk '/^ *points:/{print $2; exit}' "$case/log.checkMesh")
    foilFaces=$(awk '/^ *foil /{print $2; exit}' "$case/log.checkMesh")
    nonOrtho=$(awk '/Mesh non-orthogonality Max:/{print $4; exit}' "$case/log.checkMesh")
    skew=$(awk '/Max skewness =/{print $4; exit}' "$case/log.checkMesh")
    echo "fluid: cells $cells points $points foil-faces $foilFaces max-non-orthogonality $nonOrtho max-skewness $skew (checkMesh: Mesh OK)" | tee -a "$summary"
fi

# ---- solid ---------------------------------------------------------------------------------
# worst minJ/maxJ and worst inverse condition number (ICN, a shape measure, 1 = regular) of
# the 3-D elements, from the Gmsh plugin AnalyseMeshQuality: prints "JRATIO ICN"
elementQuality() {
    local q; q="$(mktemp --suffix=.geo)"
    cat > "$q" <<EOF
Merge "$1";
Plugin(AnalyseMeshQuality).JacobianDeterminant = 1;
Plugin(AnalyseMeshQuality).IGEMeasure = 0;
Plugin(AnalyseMeshQuality).ICNMeasure = 1;
Plugin(AnalyseMeshQuality).DimensionOfElements = 3;
Plugin(AnalyseMeshQuality).CreateView = 0;
Plugin(AnalyseMeshQuality).Run;
EOF
    gmsh "$q" -0 -o /dev/null 2>&1 | awk '/minJ\/maxJ/{sub(",", "", $5); j = $5}
        /ICN       =/{sub(",", "", $5); c = $5} END{print j, c}'
    rm -f "$q"
}
if [ "$doSolid" = 1 ]; then
    solid="$out/solid"
    mkdir -p "$solid"
    geo="$out/geometry/foil.geo"
    tetArgs=(-setnumber lc "$lc")
    if [ "$curved" = 1 ]; then tetArgs+=(-setnumber curved 1 -setnumber hoOpt 2); fi
    log "solid Tet10 (lc=$lc m, curved=$curved) -> $solid"
    gmsh "$geo" -3 -order 2 "${tetArgs[@]}" -format msh4 -o "$solid/foil-tet10.msh" \
        > "$solid/log.tet10" 2>&1 || { tail -20 "$solid/log.tet10"; die "gmsh Tet10 failed"; }
    gmsh "$solid/foil-tet10.msh" -save -format msh22 -o "$solid/foil-tet10-msh22.msh" \
        > "$solid/log.tet10-msh22" 2>&1 || die "gmsh msh22 conversion failed"
    log "solid Hex20 / Hex27 (chord $hexC, thickness $hexT, span $hexS)"
    hexArgs=(-setnumber hex 1 -setnumber nChord "$hexC" -setnumber nThick "$hexT"
             -setnumber nSpan "$hexS")
    gmsh "$geo" -3 -order 2 "${hexArgs[@]}" -string "Mesh.SecondOrderIncomplete = 1;" \
        -format msh4 -o "$solid/foil-hex20.msh" > "$solid/log.hex20" 2>&1 || die "gmsh Hex20 failed"
    gmsh "$geo" -3 -order 2 "${hexArgs[@]}" -format msh4 -o "$solid/foil-hex27.msh" \
        > "$solid/log.hex27" 2>&1 || die "gmsh Hex27 failed"
    for m in foil-tet10 foil-hex20 foil-hex27; do
        read -r r icn <<< "$(elementQuality "$solid/$m.msh")"
        echo "$m.msh: worst minJ/maxJ $r, worst ICN $icn" | tee -a "$summary"
        awk -v r="$r" 'BEGIN{exit !(r + 0 > 0)}' || die "$m.msh has elements with non-positive Jacobian ($r)"
    done
    /usr/bin/python3 "$here/tools/mshinfo.py" --require volume,clamped,wetted "$solid"/foil-*.msh \
        | tee -a "$summary"
fi
log "done: $summary"
