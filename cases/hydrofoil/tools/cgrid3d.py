#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Boundary-layer fluid mesh of the 3-D hydrofoil case: the 2-D section C-grid extruded along
the span, with the foil's interior filled above the tip (Gmsh MSH 2.2 for gmshToFoam).

Frame and tunnel as in system/blockMeshDict: x flow (inlet x = 0, outlet x = 0.762 m), y across
the width (+-0.254 m), z along the span (root wall z = 0, tip z = 0.100 m, tunnel wall z = 0.114 m).

Construction
- The x-y plane is section2d/mesh2d.py's C-grid (grid lines leave the foil along its normals,
  first-cell height y1, geometric growth; the wake cut runs to the outlet), with this preset's
  cell counts. Its outer boundary is the inlet and the side walls y = +-0.254 m.
- It is extruded along z through stations clustered at the root wall (z = 0), below and above
  the tip plane, and at the wall z = H. Below the tip the plane has the foil section as a hole:
  the foil's sides (and the blunt trailing-edge face) are walls, their first cell is y1 thick.
- Above the tip the hole is filled with a triangulation of the section (Gmsh, on the foil's own
  boundary nodes), extruded as prisms; the tip face is the plane z = 0.100 under them, and the
  first station above it is y1 away: the tip face has a y1-thick first cell too.
Every foil face therefore has a first cell of height y1 normal to it (sides and tip; a blunt
trailing-edge face has the strip's streamwise spacing), i.e. layer coverage 100 % by
construction; cgrid3d reports the first-cell heights per part of the foil.

Patches (physical groups): inlet, outlet, walls (the four tunnel walls), foil (sides, tip,
trailing-edge face: the FSI interface); volume group fluid.

Usage: cgrid3d.py --preset coarse|medium|fine --out DIR [--tc 0.12 --cli 0.5 --meanline a08]
                  [--te sharp|blunt]
Writes DIR/cgrid3d.msh and DIR/cgrid3d-mesh.txt (the parameters and counts, one line).
Needs the `gmsh` binary (the triangulation of the section above the tip) and numpy.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "section2d"))
import mesh2d  # noqa: E402

SPAN = 0.100      # root z = 0 to tip (m)
HEIGHT = 0.114    # tunnel height (m): wall z = H, tip gap 14 mm

# Presets: a systematic refinement of the coarse preset at the constant ratio RATIO per level
# (coarse 0, medium 1, fine 2): every cell count times RATIO^level, every size (y1 and the
# spanwise sizes) divided by it, every growth rate g replaced by 1 + (g - 1) / RATIO^level.
# Plane (coarse): cells along each foil side, across a blunt trailing edge, along the wake and
# from the foil to the tunnel boundary; first-cell height y1 (m; y+ <= 1 at 2 m/s needs
# <= 5e-6 at the turbulent suction peak). Span: cell size at the root wall and just below the
# tip, growth and largest size there; above the tip the first cell is y1, the size at the wall
# z = H is dz_top, growth and largest size in the gap.
RATIO = 1.3
COARSE = dict(n_side=40, n_te=4, n_wake=16, n_normal=36, y1=5.0e-6,
              dz_root=2.0e-3, dz_below_tip=1.0e-3, growth_span=1.25, dz_max=4.5e-3,
              dz_top=1.0e-3, growth_gap=1.4, dz_max_gap=2.5e-3)
LEVELS = {"coarse": 0, "medium": 1, "fine": 2}


def preset(name):
    """The cell counts and sizes of a preset (see COARSE)."""
    r = RATIO ** LEVELS[name]
    c = {}
    for key, v in COARSE.items():
        if key.startswith("n_"):
            c[key] = int(round(v * r))
        elif key.startswith("growth"):
            c[key] = 1.0 + (v - 1.0) / r
        else:
            c[key] = v / r
    return c


def parseArgs(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--preset", required=True, choices=sorted(LEVELS))
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--tc", type=float, default=0.12)
    p.add_argument("--cli", type=float, default=0.5)
    p.add_argument("--meanline", default="a08", choices=["a08", "a08mod"])
    p.add_argument("--te", default="sharp", choices=["sharp", "blunt"],
                   help="trailing edge of the fluid's foil: sharp (closed; default, the steady "
                        "model of the 2-D study) or blunt (the section's 0.4 mm face)")
    return p.parse_args(argv)


def stations(a, b, ha, hb, growth, hmax):
    """Stations from a to b whose cell size grows from ha at a and from hb at b by the factor
    `growth` per cell, capped at hmax: with h(z) = min(hmax, ha + (g-1)(z-a), hb + (g-1)(b-z))
    a geometric sequence has one cell per ln(g)/(g-1) of integral dz/h; the stations are at
    equal increments of that measure, their number rounded up (no cell exceeds h)."""
    u = np.linspace(0.0, 1.0, 400001)
    z = a + (b - a) * u
    h = np.minimum(hmax, np.minimum(ha + (growth - 1.0) * (z - a), hb + (growth - 1.0) * (b - z)))
    perCell = np.log(growth) / (growth - 1.0) if growth > 1.0 else 1.0
    xi = np.concatenate([[0.0], np.cumsum(0.5 * (1.0 / h[1:] + 1.0 / h[:-1]) * np.diff(z))]) / perCell
    n = int(np.ceil(xi[-1]))
    s = np.interp(np.linspace(0.0, xi[-1], n + 1), xi, z)
    s[0], s[-1] = a, b
    return s


def foilLoop(edges):
    """The foil's boundary edges chained into one closed loop of node ids."""
    nxt = {}
    for a, b in edges:
        nxt.setdefault(a, []).append(b)
        nxt.setdefault(b, []).append(a)
    start = edges[0][0]
    loop, prev, cur = [start], None, start
    while True:
        cand = [v for v in nxt[cur] if v != prev]
        if not cand:
            sys.exit("cgrid3d: the foil boundary is not a closed loop")
        prev, cur = cur, cand[0]
        if cur == start:
            break
        loop.append(cur)
    if len(loop) != len(edges):
        sys.exit("cgrid3d: the foil boundary has %d edges but a loop of %d" % (len(edges), len(loop)))
    return np.array(loop)


def triangulateSection(xy, loop, workdir):
    """Triangles filling the foil section, on the loop's nodes (Gmsh Frontal-Delaunay, one
    element per boundary segment). Returns (new interior points, triangles) where triangle
    node ids < len(xy) are the plane's nodes and larger ids index the new points."""
    p = xy[loop]
    seg = np.hypot(*(np.roll(p, -1, axis=0) - p).T)
    lc = 0.5 * (seg + np.roll(seg, 1))
    geo = os.path.join(workdir, "section.geo")
    msh = os.path.join(workdir, "section.msh")
    n = len(loop)
    with open(geo, "w") as f:
        for i, ((x, y), h) in enumerate(zip(p, lc)):
            f.write("Point(%d) = {%.15g, %.15g, 0, %.6g};\n" % (i + 1, x, y, h))
        for i in range(n):
            f.write("Line(%d) = {%d, %d};\n" % (i + 1, i + 1, (i + 1) % n + 1))
        f.write("Curve Loop(1) = {1:%d};\nPlane Surface(1) = {1};\n" % n)
        f.write("Transfinite Curve{1:%d} = 2;\nMesh.Algorithm = 6;\n" % n)
    r = subprocess.run(["gmsh", geo, "-2", "-format", "msh22", "-o", msh],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0 or not os.path.exists(msh):
        sys.exit("cgrid3d: gmsh failed to triangulate the section:\n" + r.stdout[-2000:])
    nodes, tris = {}, []
    with open(msh) as f:
        lines = f.read().split("\n")
    i = lines.index("$Nodes")
    for ln in lines[i + 2:i + 2 + int(lines[i + 1])]:
        t = ln.split()
        nodes[int(t[0])] = (float(t[1]), float(t[2]))
    i = lines.index("$Elements")
    for ln in lines[i + 2:i + 2 + int(lines[i + 1])]:
        t = ln.split()
        if t[1] == "2":
            tris.append([int(v) for v in t[3 + int(t[2]):]])
    # gmsh node -> plane node (loop points, by coordinates) or a new interior point
    key = {(round(x, 12), round(y, 12)): int(v) for v, (x, y) in zip(loop, p)}
    ids, extra = {}, []
    for tag, (x, y) in nodes.items():
        k = key.get((round(x, 12), round(y, 12)))
        if k is None:
            ids[tag] = len(xy) + len(extra)
            extra.append((x, y))
        else:
            ids[tag] = k
    tri = np.array([[ids[v] for v in t] for t in tris])
    return np.array(extra).reshape(-1, 2), tri


def signedArea(pts, cells):
    p = pts[cells]
    return 0.5 * np.sum(p[:, :, 0] * np.roll(p[:, :, 1], -1, axis=1)
                        - np.roll(p[:, :, 0], -1, axis=1) * p[:, :, 1], axis=1)


def build(name, tc, cli, meanline, te, workdir):
    c = preset(name)
    g = mesh2d.build(0, tc, cli, meanline, te, counts=c)
    xy, quads, edges, _ = mesh2d.quads(g)
    loop = foilLoop(edges["foil"])
    extra, tri = triangulateSection(xy, loop, workdir)
    xyAll = np.vstack([xy, extra])
    area = signedArea(xyAll, tri)
    if np.any(np.abs(area) < 1e-16):
        sys.exit("cgrid3d: degenerate triangles in the section")
    tri[area < 0] = tri[area < 0][:, ::-1]
    zBelow = stations(0.0, SPAN, c["dz_root"], c["dz_below_tip"], c["growth_span"], c["dz_max"])
    zAbove = gapStations(xyAll, quads, tri, loop, c)
    nAbove = zAbove.shape[1] - 1
    # z of every node (plane and section interior) at every station: below the tip planes,
    # above it the node's own stations
    z = np.empty((len(xyAll), len(zBelow) + nAbove))
    z[:, :len(zBelow)] = zBelow
    z[:, len(zBelow):] = zAbove[:, 1:]
    return dict(xy=xy, xyAll=xyAll, quads=quads, tri=tri, edges=edges, z=z,
                kTip=len(zBelow) - 1, g=g, c=c)


def gapStations(xyAll, quads, tri, loop, c):
    """Stations of every node between the tip plane and the wall z = H (rows: nodes).

    Over the tip and near the foil the first cell above the tip plane is y1 thick, growing by
    growth_gap (the tip's boundary layer); a plane of such cells across the whole tunnel would
    make cells of y1 x (tens of mm), far beyond checkMesh's aspect-ratio limit (1000). So each
    node's stations blend the clustered sequence f_k with an even one c_k (same count):
    z_k - S = w f_k + (1 - w) c_k (monotone for any w in [0, 1]). w = 1 where the node's
    in-plane cell size s allows a first cell of y1 (s <= s0 = ASPECT f_1: over the section and
    near the foil), w = 0 (even stations) from s1 = RAMP s0 on, a smoothstep in s between.
    The ramp is long because a thin blended layer over a stack of planar ones tilts the line
    between their cell centres: measured on coarse, max non-orthogonality 87 / 80 / 66 / 56 /
    71 deg for RAMP 4 / 8 / 16 / 32 / 64 (56 deg is the plane's own maximum)."""
    ASPECT = 500.0
    RAMP = 32.0
    fine = stations(SPAN, HEIGHT, c["y1"], c["dz_top"], c["growth_gap"], c["dz_max_gap"]) - SPAN
    n = len(fine) - 1
    even = np.linspace(0.0, HEIGHT - SPAN, n + 1)
    # in-plane size at a node: the longest edge of the quads and triangles around it
    size = np.zeros(len(xyAll))
    nbr = [[] for _ in range(len(xyAll))]
    for cells in (quads, tri):
        for a, b in zip(cells.T, np.roll(cells, -1, axis=1).T):
            L = np.hypot(*(xyAll[b] - xyAll[a]).T)
            np.maximum.at(size, a, L)
            np.maximum.at(size, b, L)
            for u, v in zip(a, b):
                nbr[u].append(v)
                nbr[v].append(u)
    s0 = ASPECT * fine[1]
    s1 = RAMP * s0
    u = np.clip((size - s0) / (s1 - s0), 0.0, 1.0)
    wMax = 1.0 - u * u * (3.0 - 2.0 * u)
    fixed = np.zeros(len(xyAll), dtype=bool)
    fixed[loop] = True
    fixed[np.unique(tri)] = True
    w = wMax.copy()
    w[fixed] = 1.0
    for _ in range(20):   # smooth, never above the node's limit
        w = np.minimum(wMax, np.array([np.mean(w[[i] + nbr[i]]) for i in range(len(w))]))
        w[fixed] = 1.0
    if np.any(size[fixed] > ASPECT * fine[1]):
        sys.exit("cgrid3d: foil cells longer than %g m: the tip's first cell would exceed the "
                 "aspect-ratio limit" % (ASPECT * fine[1]))
    return SPAN + w[:, None] * fine[None, :] + (1.0 - w[:, None]) * even[None, :]


def writeMsh(path, m):
    """MSH 2.2: nodes of every station (the section's interior only from the tip up), hexahedra
    and prisms, boundary quads and triangles oriented out of the fluid."""
    xy, xyAll, quads, tri, z, kTip = m["xy"], m["xyAll"], m["quads"], m["tri"], m["z"], m["kTip"]
    n2, nAll, nz = len(xy), len(xyAll), z.shape[1]
    # node ids per station: the plane's nodes always, the section's interior from the tip up
    offset = np.zeros(nz + 1, dtype=np.int64)
    for k in range(nz):
        offset[k + 1] = offset[k] + (nAll if k >= kTip else n2)
    nid = lambda k, i: offset[k] + i + 1  # noqa: E731  (1-based)
    names = ["inlet", "outlet", "walls", "foil", "fluid"]
    tag = {nm: i + 1 for i, nm in enumerate(names)}
    # boundary edges of the plane, each with the centroid of its quad (for the orientation)
    centroid = xy[quads].mean(axis=1)
    owner = {}
    for q, cell in enumerate(quads):
        for a, b in zip(cell, np.roll(cell, -1)):
            owner[(min(a, b), max(a, b))] = q
    els = []

    def sideFaces(name, e, k0, k1):
        for a, b in e:
            d = xy[b] - xy[a]
            out = 0.5 * (xy[a] + xy[b]) - centroid[owner[(min(a, b), max(a, b))]]
            if d[1] * out[0] - d[0] * out[1] < 0:
                a, b = b, a
            for k in range(k0, k1):
                els.append((3, tag[name], (nid(k, a), nid(k, b), nid(k + 1, b), nid(k + 1, a))))

    for name in ("inlet", "outlet"):
        sideFaces(name, m["edges"][name], 0, nz - 1)
    sideFaces("walls", m["edges"]["sides"], 0, nz - 1)
    sideFaces("foil", m["edges"]["foil"], 0, kTip)
    for q in quads:   # root wall (outward -z: reversed), wall z = H (+z)
        els.append((3, tag["walls"], tuple(nid(0, v) for v in q[::-1])))
        els.append((3, tag["walls"], tuple(nid(nz - 1, v) for v in q)))
    for t in tri:     # tip (the fluid lies above it: outward -z), wall z = H
        els.append((2, tag["foil"], tuple(nid(kTip, v) for v in t[::-1])))
        els.append((2, tag["walls"], tuple(nid(nz - 1, v) for v in t)))
    for k in range(nz - 1):
        for q in quads:
            els.append((5, tag["fluid"], tuple(nid(k, v) for v in q) + tuple(nid(k + 1, v) for v in q)))
        if k >= kTip:
            for t in tri:
                els.append((6, tag["fluid"], tuple(nid(k, v) for v in t) + tuple(nid(k + 1, v) for v in t)))
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n%d\n" % len(names))
        for nm in names:
            f.write('%d %d "%s"\n' % (3 if nm == "fluid" else 2, tag[nm], nm))
        f.write("$EndPhysicalNames\n$Nodes\n%d\n" % offset[-1])
        for k in range(nz):
            pts = xyAll if k >= kTip else xy
            f.write("".join("%d %.15g %.15g %.15g\n" % (offset[k] + i + 1, x, y, z[i, k])
                            for i, (x, y) in enumerate(pts)))
        f.write("$EndNodes\n$Elements\n%d\n" % len(els))
        f.write("".join("%d %d 2 %d %d %s\n" % (i + 1, t, g, g, " ".join(map(str, v)))
                        for i, (t, g, v) in enumerate(els)))
        f.write("$EndElements\n")
    nCells = (nz - 1) * len(quads) + (nz - 1 - kTip) * len(tri)
    nFoil = kTip * len(m["edges"]["foil"]) + len(tri)
    return nCells, int(offset[-1]), nFoil


def main(argv=None):
    a = parseArgs(argv)
    os.makedirs(a.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        m = build(a.preset, a.tc, a.cli, a.meanline, a.te, work)
    nCells, nPoints, nFoil = writeMsh(os.path.join(a.out, "cgrid3d.msh"), m)
    c, kTip = m["c"], m["kTip"]
    z = m["z"][m["tri"][0, 0]]   # a node of the section: the tip's stations
    pts = m["g"]["pts"]
    iA, iB = m["g"]["iA"], m["g"]["iB"]
    side = np.hypot(*(pts[iA:iB + 1, 1] - pts[iA:iB + 1, 0]).T)
    summary = ("preset=%s te=%s cells=%d points=%d foil_faces=%d plane_cells=%d section_triangles=%d "
               "span_cells=%d below_tip=%d above_tip=%d first_cell_sides_m=%.3e..%.3e "
               "first_cell_tip_m=%.3e n_side=%d n_wake=%d n_normal=%d"
               % (a.preset, a.te, nCells, nPoints, nFoil, len(m["quads"]), len(m["tri"]),
                  len(z) - 1, kTip, len(z) - 1 - kTip, side.min(), side.max(),
                  z[kTip + 1] - z[kTip], c["n_side"], c["n_wake"], c["n_normal"]))
    with open(os.path.join(a.out, "cgrid3d-mesh.txt"), "w") as f:
        f.write(summary + "\n")
    print(summary)


if __name__ == "__main__":
    main()
