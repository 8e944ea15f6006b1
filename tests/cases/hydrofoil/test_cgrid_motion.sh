#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The boundary-layer fluid mesh (mesh.sh --fluid-mesh cgrid, coarse) and its motion:
#  - mesh.sh fails unless checkMesh says "Mesh OK" (aspect ratio < 1000 included);
#  - the first cells on the foil's sides and over its tip are at most 5 um (+0.1 %) thick;
#  - every foil face has such a first cell (layer coverage 100 %: foil faces = plane foil edges
#    x spanwise layers below the tip + section triangles, as cgrid3d.py reports them);
#  - moved by fsiInverseDistance (libfsiMeshMotion.so of FSI_BUILD_DIR) to -12 deg of tip
#    twist and 30 mm of tip deflection, beam-like, checkMesh still says "Mesh OK"; also with
#    openingAngle 0.1 (far foil points by expansion), every point within 10 um of the exact;
#  - in parallel (2 ranks, decomposed as the coupled runs are: hierarchical 2 1 1), two motion
#    steps of a displacement with point-to-point roughness of 5 um (foilMotion.py --roughness:
#    root points off the root wall by different amounts; the second step's slip-wall normals
#    are those of the moved, tilted um-wide faces) complete, and every point shared by the two
#    ranks has the same position on both (written with 17 digits: exactly). Before the
#    shared-point synchronisation the second step stopped with "face 0 area does not match
#    neighbour" (the coupled run on this mesh: at level 0's third coupling iteration).
#  - tools/fluidCase.sh --root-wall slip moves exactly the root wall's faces (one per plane
#    cell) from `walls` to a patch `root` with slip / zero-gradient fields, decomposes and
#    records the model in effect in fluidModel; a
#    no-slip case refuses to start from such a case (--init-from), before writing anything.
# usage: test_cgrid_motion.sh WORKDIR   (environment: FSI_BUILD_DIR)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
source "$root/scripts/env.sh"   # MPI as root, oversubscribed, on loopback; OpenFOAM's tree
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
# The same motion with far clusters of foil points expanded (openingAngle 0.1): a valid mesh,
# every point within 10 um of the exact sums' position (measured 2.8 um on this mesh, 3.2 um on
# medium, against 30 mm of tip deflection)
"$root/cases/hydrofoil/tools/motionCheck.sh" --mesh "$work/fluid" --out "$work/motion-tree" \
    --tip-twist-deg -12 --tip-deflection 0.030 --bending beam --opening-angle 0.1
/usr/bin/python3 - "$work/motion/1/polyMesh/points" "$work/motion-tree/1/polyMesh/points" \
    "$root/cases/hydrofoil/tools" <<'EOP'
import sys
sys.path.insert(0, sys.argv[3])
from foilMotion import readPoints
exact, tree = readPoints(sys.argv[1]), readPoints(sys.argv[2])
assert len(exact) == len(tree)
worst = float(abs(exact - tree).max())
assert worst <= 1.0e-5, "openingAngle 0.1 moved a point %.3g m away from the exact sums" % worst
print("fsiInverseDistance openingAngle 0.1: every point within %.3g m of the exact sums" % worst)
EOP

# Parallel consistency of the motion at the processor boundary
par="$work/parallel"
rm -rf "$par"; mkdir -p "$par"
cp -r "$work/fluid/0" "$work/fluid/constant" "$work/fluid/system" "$par/"
(
  cd "$par"
  export LD_LIBRARY_PATH="$FSI_BUILD_DIR/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  foamDictionary system/controlDict -entry endTime -set 2 > /dev/null
  foamDictionary system/controlDict -entry writeInterval -set 2 > /dev/null
  foamDictionary system/controlDict -entry writeFormat -set ascii > /dev/null
  foamDictionary system/controlDict -entry writePrecision -set 17 > /dev/null
  foamDictionary system/controlDict -entry functions -remove > /dev/null
  foamFormatConvert -constant > log.foamFormatConvert 2>&1
  /usr/bin/python3 "$root/cases/hydrofoil/tools/foilMotion.py" . --tip-twist-deg -4 \
      --tip-deflection 0.01 --roughness 5e-6
  foamDictionary system/decomposeParDict -entry numberOfSubdomains -set 2 > /dev/null
  foamDictionary system/decomposeParDict -entry method -set hierarchical > /dev/null
  decomposePar -force > log.decomposePar 2>&1
  mpirun --oversubscribe -np 2 moveDynamicMesh -parallel > log.moveDynamicMesh 2>&1 ||
      { grep -m2 "FATAL ERROR" -A1 log.moveDynamicMesh; echo "FAIL: parallel motion (log: $par/log.moveDynamicMesh)"; exit 1; }
)
/usr/bin/python3 - "$par" "$root/cases/hydrofoil/tools" <<'EOP'
import os, sys
sys.path.insert(0, sys.argv[2])
from foilMotion import _listBody, readPoints   # the case's ASCII OpenFOAM list readers
case = sys.argv[1]
def labels(path):
    n, body = _listBody(open(path).read())
    return [int(v) for v in body.split(")")[0].split()[:n]]
seen, shared, worst = {}, 0, 0.0
for proc in ("processor0", "processor1"):
    addr = labels(os.path.join(case, proc, "constant", "polyMesh", "pointProcAddressing"))
    pts = readPoints(os.path.join(case, proc, "2", "polyMesh", "points"))
    assert len(addr) == len(pts), (proc, len(addr), len(pts))
    for g, p in zip(addr, pts):
        if g in seen:
            shared += 1
            worst = max(worst, float(abs(seen[g] - p).max()))
        else:
            seen[g] = p
assert shared > 0, "no point shared by the two ranks"
assert worst == 0.0, "a point shared by the ranks moved to two positions, %.3g m apart" % worst
print("parallel motion: 2 steps on 2 ranks, %d shared points at the same position on both" % shared)
EOP
# The slip root wall (tools/rootWall.sh through tools/fluidCase.sh --root-wall slip): the root
# wall's faces (the plane mesh's cells, one face each on z = 0) leave `walls` for a patch `root`,
# which the fields give slip / zero-gradient conditions; the case still decomposes.
slip=$work-rootwall
"$root/cases/hydrofoil/tools/fluidCase.sh" "$slip" "$work/fluid" 2 --flow turbulent --root-wall slip > "$slip.log" 2>&1 ||
    { tail -5 "$slip.log"; echo "FAIL: fluidCase.sh --root-wall slip"; exit 1; }
/usr/bin/python3 - "$work/fluid" "$slip" "$summary" <<'EOP'
import re, sys
plain, slip, summary = sys.argv[1:]
def patches(case):
    text = open(case + "/constant/polyMesh/boundary").read()
    return {m.group(1): int(m.group(2)) for m in
            re.finditer(r"\n\s*(\w+)\s*\{[^}]*?nFaces\s+(\d+);", text)}
plane = int(dict(kv.split("=", 1) for kv in open(summary).read().split())["plane_cells"])
a, b = patches(plain), patches(slip)
assert "root" not in a and b.get("root") == plane, ("root faces", b.get("root"), "plane cells", plane)
assert b["walls"] == a["walls"] - plane, ("walls", a["walls"], b["walls"])
assert all(b[p] == a[p] for p in a if p != "walls"), (a, b)
for field, kind in (("U", "slip"), ("p", "zeroGradient"), ("k", "zeroGradient"),
                    ("omega", "zeroGradient"), ("pointDisplacement", "slip")):
    text = open(slip + "/0/" + field, errors="replace").read()
    m = re.search(r"\n\s*root\s*\{\s*type\s+(\w+);", text)
    assert m and m.group(1) == kind, (field, m and m.group(1))
print("slip root wall: %d faces from walls to root, fields set, decomposed" % plane)
EOP
[ -d "$slip/processor1" ] || { echo "FAIL: fluidCase.sh --root-wall slip did not decompose"; exit 1; }
# ... and records the model in effect (the scheme and algorithm left out: the case's upwind and
# SIMPLEC), which rigid.sh --shape-from takes
model=$(grep -v '^#' "$slip/fluidModel" | tr '\n' ' ')
[ "$model" = "flow turbulent scheme upwind algorithm simplec root_wall slip " ] ||
    { echo "FAIL: fluidCase.sh recorded fluidModel '$model'"; exit 1; }
echo "fluidModel: $model"
# A no-slip case cannot start from a slip-root-wall run's flow (mapFields -consistent needs the
# same patches): refused in one line, before anything is written.
refused=$work-refused
rm -rf "$refused"; rc=0
"$root/cases/hydrofoil/tools/fluidCase.sh" "$refused" "$work/fluid" 2 --init-from "$slip" > /dev/null 2> "$refused.err" || rc=$?
if [ "$rc" != 2 ] || [ "$(wc -l < "$refused.err")" != 1 ] || ! grep -q -- "--root-wall slip" "$refused.err" || [ -e "$refused" ]; then
    echo "FAIL: --init-from a slip-root-wall case into a no-slip one: exit $rc, $(cat "$refused.err")"; exit 1
fi
echo "refused: $(cat "$refused.err")"
