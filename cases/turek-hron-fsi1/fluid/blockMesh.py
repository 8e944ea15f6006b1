#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Write system/blockMeshDict for the Turek-Hron FSI1 channel: the rigid
cylinder (patch 'cylinder') and the elastic beam (patch 'beam', the moving
fluid-structure interface); 19 fluid blocks, one cell thick (2-D,
frontAndBack empty, depth DEPTH in z from 0 to DEPTH).
Adapted from cases/turek-hron-cfd1/blockMesh.py (same topology and grading).

usage: blockMesh.py LEVEL OUT_FILE
  LEVEL: coarse | medium | fine | veryfine (each doubles the cells per direction)

Geometry (Turek & Hron 2006): channel 2.5 x 0.41 m, cylinder centre
(0.2, 0.2), radius 0.05; beam 0.35 x 0.02 m behind the cylinder, tip at x 0.6.
An O-grid of five blocks surrounds the cylinder inside the box
[0.1, 0.3]^2; the beam leaves the box through its right side.
"""
import math
import sys

DEPTH = 0.01  # [m] one cell thick; forces per unit depth = force / DEPTH
LEVELS = {"coarse": 1, "medium": 2, "fine": 4, "veryfine": 8}


def main():
    if len(sys.argv) < 3 or sys.argv[1] not in LEVELS:
        sys.exit("usage: blockMesh.py coarse|medium|fine|veryfine OUT_FILE")
    k = LEVELS[sys.argv[1]]
    out = sys.argv[2]

    # Cell counts (coarse) scaled by k
    nT = 16 * k    # per quarter of the cylinder (top, left, bottom blocks)
    nRu = 8 * k    # right blocks, along the cylinder between beam and 45 deg
    nR = 12 * k    # radial, box -> cylinder
    nL = 8 * k     # inlet column, x 0 .. 0.1
    nB = 8 * k     # bottom row, y 0 .. 0.1
    nTp = 8 * k    # top row, y 0.3 .. 0.41
    nBx = 24 * k   # along the beam, x 0.3 .. 0.6
    nBt = 4 * k    # across the beam tip, y 0.19 .. 0.21
    nD = 40 * k    # downstream, x 0.6 .. 2.5
    gr = 4.0       # radial expansion (cell at box / cell at cylinder)
    gt = 4.0       # right blocks: cell at 45 deg / cell at the beam
    gd = 10.0      # downstream expansion

    xc, yc, r = 0.2, 0.2, 0.05
    yb0, yb1 = 0.19, 0.21
    xa = xc + math.sqrt(r * r - (yb1 - yc) ** 2)

    def cyl(deg):
        t = math.radians(deg)
        return (xc + r * math.cos(t), yc + r * math.sin(t))

    V = {}
    order = []

    def vert(name, xy):
        V[name] = xy
        order.append(name)

    X = [0.0, 0.1, 0.3, 0.6, 2.5]
    Y = [0.0, 0.1, 0.19, 0.21, 0.3, 0.41]
    for i, x in enumerate(X):
        for j, y in enumerate(Y):
            vert("P%d%d" % (i, j), (x, y))
    vert("C45", cyl(45))
    vert("C135", cyl(135))
    vert("C225", cyl(225))
    vert("C315", cyl(315))
    vert("A1", (xa, yb1))
    vert("A2", (xa, yb0))
    idx = {n: i for i, n in enumerate(order)}
    N = len(order)

    B225, B315, B45, B135 = "P11", "P21", "P24", "P14"
    BA2, BA1 = "P22", "P23"

    blocks = []  # (v0, v1, v2, v3), (n1, n2), (g1, g2)

    def block(vs, n, g):
        # CCW check (shoelace)
        pts = [V[v] for v in vs]
        a = sum(pts[i][0] * pts[(i + 1) % 4][1] - pts[(i + 1) % 4][0] * pts[i][1] for i in range(4))
        assert a > 0, ("block not counter-clockwise", vs)
        blocks.append((vs, n, g))

    # O-grid around the cylinder; direction 2 goes from the box to the cylinder
    block((B225, B315, "C315", "C225"), (nT, nR), (1, 1 / gr))      # bottom
    block((B315, BA2, "A2", "C315"), (nRu, nR), (1 / gt, 1 / gr))   # right, below the beam
    block((BA1, B45, "C45", "A1"), (nRu, nR), (gt, 1 / gr))         # right, above the beam
    block((B45, B135, "C135", "C45"), (nT, nR), (1, 1 / gr))        # top
    block((B135, B225, "C225", "C135"), (nT, nR), (1, 1 / gr))      # left
    # Inlet column
    block(("P00", "P10", "P11", "P01"), (nL, nB), (1, 1))
    block(("P01", "P11", "P14", "P04"), (nL, nT), (1, 1))
    block(("P04", "P14", "P15", "P05"), (nL, nTp), (1, 1))
    # Cylinder column, below and above the box
    block(("P10", "P20", "P21", "P11"), (nT, nB), (1, 1))
    block(("P14", "P24", "P25", "P15"), (nT, nTp), (1, 1))
    # Beam column (no block in the beam itself)
    block(("P20", "P30", "P31", "P21"), (nBx, nB), (1, 1))
    block(("P21", "P31", "P32", "P22"), (nBx, nRu), (1, 1 / gt))
    block(("P23", "P33", "P34", "P24"), (nBx, nRu), (1, gt))
    block(("P24", "P34", "P35", "P25"), (nBx, nTp), (1, 1))
    # Downstream column
    block(("P30", "P40", "P41", "P31"), (nD, nB), (gd, 1))
    block(("P31", "P41", "P42", "P32"), (nD, nRu), (gd, 1 / gt))
    block(("P32", "P42", "P43", "P33"), (nD, nBt), (gd, 1))
    block(("P33", "P43", "P44", "P34"), (nD, nRu), (gd, gt))
    block(("P34", "P44", "P45", "P35"), (nD, nTp), (gd, 1))

    arcs = [("C225", "C315", 270), ("C315", "A2", -(45 + math.degrees(math.asin(0.2))) / 2),
            ("A1", "C45", (45 + math.degrees(math.asin(0.2))) / 2), ("C45", "C135", 90),
            ("C135", "C225", 180)]

    def face(a, b):
        return "(%d %d %d %d)" % (idx[a], idx[b], idx[b] + N, idx[a] + N)

    cylinder = [face(a, b) for a, b, _ in arcs]
    beam = [face(BA2, "A2"), face("A1", BA1), face("P22", "P32"), face("P23", "P33"),
            face("P32", "P33")]
    inlet = [face("P00", "P01"), face("P01", "P04"), face("P04", "P05")]
    outlet = [face("P40", "P41"), face("P41", "P42"), face("P42", "P43"), face("P43", "P44"),
              face("P44", "P45")]
    walls = [face("P%d0" % i, "P%d0" % (i + 1)) for i in range(4)] + \
            [face("P%d5" % i, "P%d5" % (i + 1)) for i in range(4)]

    L = []
    w = L.append
    w("// Generated by cases/turek-hron-fsi1/fluid/blockMesh.py %s -- do not edit" % sys.argv[1])
    w("FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }")
    w("convertToMeters 1;")
    w("vertices\n(")
    for z in (0.0, DEPTH):
        for n in order:
            w("    (%.12g %.12g %.12g)" % (V[n][0], V[n][1], z))
    w(");")
    w("blocks\n(")
    for vs, n, g in blocks:
        ids = [idx[v] for v in vs]
        w("    hex (%s) (%d %d 1) simpleGrading (%.12g %.12g 1)" %
          (" ".join(str(i) for i in ids + [i + N for i in ids]), n[0], n[1], g[0], g[1]))
    w(");")
    w("edges\n(")
    for a, b, deg in arcs:
        m = cyl(deg)
        for z, off in ((0.0, 0), (DEPTH, N)):
            w("    arc %d %d (%.12g %.12g %.12g)" % (idx[a] + off, idx[b] + off, m[0], m[1], z))
    w(");")

    def patch(name, ptype, faces):
        w("    %s\n    {\n        type %s;\n        faces\n        (" % (name, ptype))
        for f in faces:
            w("            " + f)
        w("        );\n    }")

    w("boundary\n(")
    patch("inlet", "patch", inlet)
    patch("outlet", "patch", outlet)
    patch("walls", "wall", walls)
    patch("cylinder", "wall", cylinder)
    patch("beam", "wall", beam)
    w("    frontAndBack\n    {\n        type empty;\n        faces\n        (")
    for vs, _, _ in blocks:
        ids = [idx[v] for v in vs]
        w("            (%d %d %d %d)" % (ids[0], ids[3], ids[2], ids[1]))
        w("            (%s)" % " ".join(str(i + N) for i in ids))
    w("        );\n    }")
    w(");")
    w("mergePatchPairs ();")
    with open(out, "w") as f:
        f.write("\n".join(L) + "\n")


if __name__ == "__main__":
    main()
