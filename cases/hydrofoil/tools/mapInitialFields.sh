#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Initial fields of a case from the solution of another case on a different mesh of the same
# domain (grid sequencing: start a level from the next coarser level's converged flow).
#
#   cases/hydrofoil/tools/mapInitialFields.sh DEST_CASE SOURCE_CASE
#   cases/hydrofoil/tools/mapInitialFields.sh --check SOURCE_CASE   only validate the source
#                                                                   (run.sh, before it writes)
#
# Maps the solved fields (U, p and the turbulence fields k, omega, nut, ReThetat, gammaInt that
# SOURCE_CASE's latest time folder has) onto DEST_CASE's start time (an undecomposed case: run
# before decomposePar) with OpenFOAM's mapFields -consistent (same patch names); the fields the
# source lacks (pointDisplacement, other models' fields) keep their initial values. Nearest-cell
# mapping: v1912's default direct method crashes on these meshes. The source's latest time must
# be reconstructed (rigid.sh and run2d.sh do so). Writes DEST_CASE/log.mapFields; exit 2 with a
# one-line error naming the folder when there is nothing to map or mapFields fails.
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^[^#]/{/SPDX-License-Identifier/d;s/^# \{0,1\}//p}' "$0"; exit 0 ;; esac
die() { echo "error: mapInitialFields.sh: $*" >&2; exit 2; }
[ $# = 2 ] || die "usage: mapInitialFields.sh DEST_CASE SOURCE_CASE (or --check SOURCE_CASE)"
dest=$1
[ "$dest" = --check ] || [ -d "$dest/constant/polyMesh" ] || die "'$dest' is not a case with a mesh (constant/polyMesh)"
[ -d "$2/constant" ] && [ -d "$2/system" ] || die "'$2' is not a case (constant/, system/)"
srcCase="$(cd "$2" && pwd)"
srcTime=$(foamListTimes -case "$srcCase" -latestTime 2>/dev/null | tail -1)
[ -n "$srcTime" ] && [ -f "$srcCase/$srcTime/U" ] ||
    die "'$srcCase' has no solved (reconstructed) time folder with U; run it to the end first (a decomposed case: reconstructPar -latestTime there)"
[ "$dest" != --check ] || exit 0
# a source with the solved fields only: mapFields fails on the written cell-centre and y+ fields
src="$(mktemp -d "${TMPDIR:-/tmp}/mapSource.XXXXXX")"
trap 'rm -rf "$src"' EXIT
mkdir -p "$src/$srcTime"
cp -r "$srcCase/system" "$srcCase/constant" "$src/"
for f in U p k omega nut ReThetat gammaInt; do
    [ ! -f "$srcCase/$srcTime/$f" ] || cp "$srcCase/$srcTime/$f" "$src/$srcTime/"
done
( cd "$dest" && mapFields "$src" -consistent -sourceTime latestTime -mapMethod mapNearest \
    > log.mapFields 2>&1 ) || { tail -20 "$dest/log.mapFields" >&2; die "mapFields from '$srcCase' failed (see $dest/log.mapFields)"; }
# mapFields renames the destination's fields that the source lacks (e.g. pointDisplacement, the
# transition fields of an SST source) to NAME.unmapped: they keep their initial values
startTime=$(foamDictionary "$dest/system/controlDict" -entry startTime -value 2>/dev/null || echo 0)
for f in "$dest/$startTime"/*.unmapped; do
    [ -e "$f" ] || continue
    mv "$f" "${f%.unmapped}"
done
echo "mapInitialFields.sh: $dest: fields of $srcCase time $srcTime mapped (nearest cell)"
