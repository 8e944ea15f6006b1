#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""How smooth is the displacement the coupling handed a fluid patch? Ratios along the patch edges.

    displacementJumps.py CASE TIME [--patch foil] [--split AXIS VALUE] [--top 10]

For every edge a-b of the patch's faces: |d_a - d_b| / |x_a - x_b|, d the point displacement
(TIME/pointDisplacement, all points) and x the undeformed points (constant/polyMesh/points). A
displacement of a solid is smooth: the ratio is of the order of its strains and rotations
(0.1 at most on the hydrofoil); a jump of the mapped field between neighbouring fluid points
shows as a ratio far above that, and thin layer cells there take it as shear
(cases/hydrofoil/README.md, "The first flow-model comparison": 0.54 along the cgrid tip edge
with the nearest-projection mapping). Prints the edge count, the median, the largest ratio on
either side of the plane AXIS = VALUE (--split z 0.0995: below / at the tip) and the --top
largest edges with their midpoints. A decomposed case (CASE/processor*) is read per processor
(an edge on a processor boundary counts once per processor).
The files must be ASCII, as foilMotion.py's: convert with writeFormat ascii in
system/controlDict and `foamFormatConvert [-parallel] -time TIME` (it converts constant/ too).
"""
import argparse
import os
import sys

import numpy as np

from foilMotion import caseParts, readFaces, readPatch, readPoints


def edgeJumps(points, displacement, faces):
    """Rows (ratio, |d_a - d_b|, |x_a - x_b|, midpoint x, y, z) over the unique edges of faces
    (lists of labels into points and displacement, both (n, 3) arrays)."""
    edges = set()
    for f in faces:
        for a, b in zip(f, f[1:] + f[:1]):
            edges.add((min(a, b), max(a, b)))
    a, b = np.array(sorted(edges)).T
    dx = np.linalg.norm(points[a] - points[b], axis=1)
    dd = np.linalg.norm(displacement[a] - displacement[b], axis=1)
    mid = 0.5 * (points[a] + points[b])
    return np.column_stack([dd / dx, dd, dx, mid])


def caseJumps(case, time, patch):
    """edgeJumps of the patch in a serial case or over its processor directories."""
    rows = []
    for part in caseParts(case):
        mesh = os.path.join(part, "constant", "polyMesh")
        start, count = readPatch(os.path.join(mesh, "boundary"), patch)
        if count == 0:
            continue
        faces = readFaces(os.path.join(mesh, "faces"), start, count)
        points = readPoints(os.path.join(mesh, "points"))
        displacement = readPoints(os.path.join(part, time, "pointDisplacement"))
        if len(displacement) != len(points):
            raise RuntimeError(f"displacementJumps.py: {part}/{time}/pointDisplacement has "
                               f"{len(displacement)} values for {len(points)} points")
        rows.append(edgeJumps(points, displacement, faces))
    if not rows:
        raise RuntimeError(f"displacementJumps.py: patch '{patch}' has no faces in {case}")
    return np.vstack(rows)


def main(argv):
    p = argparse.ArgumentParser(description="Displacement jumps along a fluid patch's edges.")
    p.add_argument("case")
    p.add_argument("time")
    p.add_argument("--patch", default="foil")
    p.add_argument("--split", nargs=2, metavar=("AXIS", "VALUE"))
    p.add_argument("--top", type=int, default=10)
    a = p.parse_args(argv)
    rows = caseJumps(a.case, a.time, a.patch)
    ratio = rows[:, 0]
    print(f"displacementJumps: {len(rows)} edges of patch {a.patch} at time {a.time}; "
          f"|d_a - d_b| / |x_a - x_b| median {np.median(ratio):.3g}, max {ratio.max():.3g}")
    if a.split:
        axis = "xyz".index(a.split[0])
        above = rows[:, 3 + axis] > float(a.split[1])
        for name, sel in (("below", ~above), ("above", above)):
            top = f"{ratio[sel].max():.3g}" if sel.any() else "-"
            print(f"  {a.split[0]} {name} {a.split[1]}: {sel.sum()} edges, max {top}")
    print("  ratio   |dd| [um]  |dx| [um]  midpoint x y z [mm]")
    for r in rows[np.argsort(-ratio)[:a.top]]:
        print(f"  {r[0]:6.3f} {1e6 * r[1]:10.2f} {1e6 * r[2]:10.2f}  "
              f"{1e3 * r[3]:8.2f} {1e3 * r[4]:7.2f} {1e3 * r[5]:7.2f}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except (RuntimeError, OSError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
