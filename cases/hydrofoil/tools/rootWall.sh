#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Make the tunnel's root wall (the plane z = 0 that the foil is clamped to) a slip wall.
#
#   cases/hydrofoil/tools/rootWall.sh CASE
#
# CASE: an undecomposed OpenFOAM copy of the hydrofoil case (tools/fluidCase.sh, before
# decomposePar) whose `walls` patch holds the root wall. Moves the faces of `walls` on z = 0
# (within 1e-6 m) into a new patch `root` (topoSet + createPatch) and gives it, in every field
# file of CASE/0: U slip, pointDisplacement slip (the foil's root points slide on it, as on the
# other walls), nut calculated 0, and zero gradient for p, k, omega, ReThetat and gammaInt.
# Prints "root wall: slip (N faces)".
#
# Why (cases/hydrofoil/README.md, "A steady second-order flow: the slip root wall"): with the
# no-slip root wall the second-order flow has no steady state at the junction of the foil and the
# root wall (a limit cycle of +-1 % in lift); with a slip root wall it converges. A slip root
# wall removes the tunnel wall's boundary layer at the root, which the mesh (first cells 2 mm, wall
# functions) does not resolve anyway; the paper's tunnel is no-slip (`--root-wall wall`, the
# default of the scripts that take the option).
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^[^#]/{/SPDX-License-Identifier/d;s/^# \{0,1\}//p}' "$0"; exit 0 ;; esac
die() { echo "error: rootWall.sh: $*" >&2; exit 2; }
[ $# = 1 ] || die "usage: rootWall.sh CASE"
c=$1
[ -f "$c/constant/polyMesh/boundary" ] || die "'$c' is not a case with a mesh (constant/polyMesh/boundary)"
[ ! -d "$c/processor0" ] || die "'$c' is decomposed; make the root wall slip before decomposePar"
grep -q '^ *root$' "$c/constant/polyMesh/boundary" && die "'$c' already has a patch 'root'"
grep -q '^ *walls$' "$c/constant/polyMesh/boundary" || die "'$c' has no patch 'walls' to take the root wall from"
cat > "$c/system/topoSetDict.rootWall" <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object topoSetDict; }
actions
(
    { name rootWall; type faceSet; action new; source patchToFace; sourceInfo { patch walls; } }
    { name rootWall; type faceSet; action subset; source boxToFace;
      sourceInfo { box (-10 -10 -1e-6) (10 10 1e-6); } }
);
EOF
cat > "$c/system/createPatchDict.rootWall" <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object createPatchDict; }
pointSync false;
patches ( { name root; patchInfo { type patch; } constructFrom set; set rootWall; } );
EOF
(cd "$c" && topoSet -dict system/topoSetDict.rootWall > log.topoSet.rootWall 2>&1) ||
  die "topoSet failed ($c/log.topoSet.rootWall)"
(cd "$c" && createPatch -overwrite -dict system/createPatchDict.rootWall > log.createPatch.rootWall 2>&1) ||
  die "createPatch failed ($c/log.createPatch.rootWall)"
rm -rf "$c/constant/polyMesh/sets"
n=$(awk '/^ *root$/ { inRoot = 1 } inRoot && /nFaces/ { sub(";", "", $2); print $2; exit }' \
    "$c/constant/polyMesh/boundary")
n=${n:-0}
[ "$n" -gt 0 ] || die "no face of 'walls' lies on z = 0 in '$c'"
# createPatch leaves the field files alone: a `walls` entry with a value per face (mapped
# fields, tools/mapInitialFields.sh) would no longer fit the smaller patch, so such a value becomes
# uniform zero (the wall functions set theirs in the first iteration, noSlip is zero). Mapped
# fields are binary (the case's writeFormat): they are converted to ASCII first.
[ -d "$c/0" ] || die "'$c' has no initial fields (0/)"
format=$(foamDictionary "$c/system/controlDict" -entry writeFormat -value)
foamDictionary "$c/system/controlDict" -entry writeFormat -set ascii > /dev/null
(cd "$c" && foamFormatConvert -time 0 > log.foamFormatConvert.rootWall 2>&1) ||
  die "foamFormatConvert failed ($c/log.foamFormatConvert.rootWall)"
foamDictionary "$c/system/controlDict" -entry writeFormat -set "$format" > /dev/null
for f in "$c"/0/*; do
  [ -f "$f" ] || continue
  # only an explicit per-face value (a pattern entry such as "(walls|foil)" has a uniform one)
  v=$(foamDictionary "$f" -entry boundaryField/walls/value -value 2> /dev/null | cut -c1-10 | head -n 1) || true
  case "$v" in nonuniform*) ;; *) continue ;; esac
  zero="uniform 0"
  ! grep -q 'class *\(volVectorField\|pointVectorField\)' "$f" || zero="uniform (0 0 0)"
  foamDictionary "$f" -entry boundaryField/walls/value -set "$zero" > /dev/null
done
set_bc() { [ ! -f "$c/0/$1" ] || foamDictionary "$c/0/$1" -entry boundaryField/root -set "$2" > /dev/null; }
set_bc U "{ type slip; }"
set_bc pointDisplacement "{ type slip; }"
set_bc nut "{ type calculated; value uniform 0; }"
for f in p k omega ReThetat gammaInt; do set_bc "$f" "{ type zeroGradient; }"; done
echo "root wall: slip ($n faces)"
