#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The boundary-layer fluid mesh (mesh.sh --fluid-mesh cgrid, coarse) and its motion:
#  - mesh.sh fails unless checkMesh says "Mesh OK" (aspect ratio < 1000 included);
#  - the first cells on the foil's sides and over its tip are at most 5 um (+0.1 %) thick;
#  - every foil face has such a first cell (layer coverage 100 %: foil faces = plane foil edges
#    x spanwise layers below the tip + section triangles, as cgrid3d.py reports them);
#  - moved by fsiInverseDistance (libfsiMeshMotion.so of FSI_BUILD_DIR) to -12 deg of tip
#    twist and 30 mm of tip deflection, beam-like, checkMesh still says "Mesh OK".
# usage: test_cgrid_motion.sh WORKDIR   (environment: FSI_BUILD_DIR)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
work=${1:?usage: test_cgrid_motion.sh WORKDIR}
rm -rf "$work"
"$root/cases/hydrofoil/mesh.sh" --preset coarse --fluid-mesh cgrid --fluid-only --out "$work" > "$work.log" 2>&1 ||
    { tail -20 "$work.log"; echo "FAIL: mesh.sh --fluid-mesh cgrid"; exit 1; }
summary="$work/fluid/cgrid/cgrid3d-mesh.txt"
/usr/bin/python3 - "$summary" "$work/fluid/log.checkMesh" <<'EOP'
import re, sys
s = dict(kv.split("=", 1) for kv in open(sys.argv[1]).read().split())
side_max = float(s["first_cell_sides_m"].split("..")[1])
tip = float(s["first_cell_tip_m"])
assert side_max <= 5.0e-6 * 1.001, "first cell on the sides %g m > 5 um" % side_max
assert tip <= 5.0e-6 * 1.001, "first cell over the tip %g m > 5 um" % tip
log = open(sys.argv[2]).read()
foil = int(re.search(r"^\s*foil\s+(\d+)", log, re.M).group(1))
assert foil == int(s["foil_faces"]), "checkMesh foil faces %d != cgrid3d's %s" % (foil, s["foil_faces"])
print("cgrid: first cell sides <= %.3g m, tip %.3g m, %d foil faces, all with a first cell" % (side_max, tip, foil))
EOP
"$root/cases/hydrofoil/tools/motionCheck.sh" --mesh "$work/fluid" --out "$work/motion" \
    --tip-twist-deg -12 --tip-deflection 0.030 --bending beam
