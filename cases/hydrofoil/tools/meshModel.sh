#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The case's default flow model for a fluid mesh (README, "The case default"):
#
#   cases/hydrofoil/tools/meshModel.sh MESH_SUMMARY
#   cases/hydrofoil/tools/meshModel.sh cgrid|snappy PRESET
#
# prints "FLUID_MESH FLOW ALGORITHM" for the mesh.sh summary MESH_SUMMARY (DIR/mesh/mesh-summary.txt,
# which names the fluid mesh and the preset) or for a fluid mesh and preset named directly:
#   cgrid  turbulent simplec   the boundary-layer mesh: k-omega SST, the case's SIMPLEC
#   cgrid  turbulent simple    a medium or fine boundary-layer mesh made before 2026-12-05 evening
#                              (its summary has no growth_relax=): classic SIMPLE, since SIMPLEC
#                              oscillates in its tip gap (README, "The tip gap's re-spaced cells")
#   snappy laminar   simplec   the snappyHexMesh mesh: the paper's laminar flow
# A summary without fluid-mesh= predates the boundary-layer mesh: snappy. A mesh named directly is
# a new one. run.sh takes its defaults from it; scripts/bench-fsi sets up its rigid solve with the
# same model.
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^[^#]/{/SPDX-License-Identifier/d;s/^# \{0,1\}//p}' "$0"; exit 0 ;; esac
die() { echo "error: meshModel.sh: $*" >&2; exit 2; }
case $# in
  1) [ -f "$1" ] || die "no mesh summary $1 (a mesh.sh output folder's mesh-summary.txt)"
     kind=$(sed -n '1s/.*fluid-mesh=\([a-z]*\).*/\1/p' "$1")
     preset=$(sed -n '1s/.*preset=\([a-z]*\).*/\1/p' "$1")
     gapFixed=$(grep -c 'growth_relax=' "$1" || true) ;;   # 0: made before the gap fix
  2) kind=$1 preset=$2 gapFixed=1 ;;
  *) die "usage: meshModel.sh MESH_SUMMARY | meshModel.sh cgrid|snappy PRESET" ;;
esac
case "${kind:-snappy}" in
  cgrid) if [ "$preset" = coarse ] || [ "$gapFixed" -gt 0 ]; then echo "cgrid turbulent simplec"
         else echo "cgrid turbulent simple"; fi ;;
  snappy) echo "snappy laminar simplec" ;;
  *) die "unknown fluid mesh '$kind' (cgrid or snappy)" ;;
esac
