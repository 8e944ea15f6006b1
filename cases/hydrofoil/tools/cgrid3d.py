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
- It is extruded along z through stations clustered at the root wall (z = 0), on both sides
  of the tip plane (first cell y1_tip) and at the wall z = H; near the foil only: away from it
  each node's stations blend into even ones (blendWeights: checkMesh's aspect-ratio limit).
  Below the tip the plane has the foil section as a hole: the foil's sides (and the blunt
  trailing-edge face) are walls, their first cell is y1 thick; within h_thin below the tip the
  front half's first cell is thinned (tip_thinning: the tip's leading-edge corner).
- Above the tip the hole is filled with a triangulation of the section (Gmsh, on the foil's own
  boundary nodes), extruded as prisms; the tip face is the plane z = 0.100 under them, and the
  first station above it is y1_tip away. There the plane's wall clustering, with no wall left,
  relaxes with height to an evenly graded spacing (relaxedPlane): its y1 cells next to the
  section's triangles diverged the solver.
Every foil face therefore has a first cell normal to it of at most y1 (sides and tip; a blunt
trailing-edge face has the strip's streamwise spacing), i.e. layer coverage 100 % by
construction; cgrid3d reports the first-cell heights per part of the foil.

Patches (physical groups): inlet, outlet, walls (the four tunnel walls), foil (sides, tip,
trailing-edge face: the FSI interface); volume group fluid.

Usage: cgrid3d.py --preset coarse|medium|fine|finer --out DIR [--tc 0.12 --cli 0.5 --meanline a08]
                  [--te sharp|blunt] [--full-span]
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
# <= 5e-6 at the turbulent suction peak). Span: cell size at the root wall (dz_root), growth
# and largest size along the foil (away from the foil the stations are even where the clustered
# ones close in on the tip plane, spacing under dz_blend); next to the tip plane (on both sides)
# the cells are y1 thick, growing by growth_gap; the size at the wall z = H is dz_top; largest
# size in the gap dz_max_gap. Above the tip the plane's nodes within gap_relax_length of the foil
# re-space within h_relax, growing by growth_relax from the foil (1: even; see relaxedPlane).
# Next to the tip plane: first cell y1_tip over the tip, and, within h_thin below it, the
# sides' first cell thinned by tip_thinning (nodes within thin_length of the wall): without,
# y+ reached 1.96 at the tip's leading-edge corner (SST, coarse; 0.76 elsewhere on the sides).
RATIO = 1.3
COARSE = dict(n_side=40, n_te=4, n_wake=16, n_normal=36, y1=5.0e-6,
              dz_root=2.0e-3, dz_blend=2.0e-3, growth_span=1.25, dz_max=4.5e-3,
              dz_top=1.0e-3, growth_gap=1.4, dz_max_gap=2.5e-3,
              gap_relax_length=1.5e-3, h_relax=1.0e-3, growth_relax=1.0, growth_relax_wake=1.1,
              y1_tip=3.5e-6, tip_thinning=0.35, thin_length=1.5e-3, h_thin=2.0e-3)
# finer: a fourth level for the mesh studies only (about 2.8 M cells; the rigid 3-D study's
# level beyond fine, scripts/verify.d/hydrofoil-3d-rigid.sh), not a case preset.
LEVELS = {"coarse": 0, "medium": 1, "fine": 2, "finer": 3}


def preset(name):
    """The cell counts and sizes of a preset (see COARSE)."""
    r = RATIO ** LEVELS[name]
    c = {}
    for key, v in COARSE.items():
        if key == "tip_thinning":        # a ratio
            c[key] = v
        elif key.startswith("n_"):
            c[key] = int(round(v * r))
        elif key.startswith("growth"):   # 1 + (g - 1)/r: even (1) stays even
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
    p.add_argument("--full-span", action="store_true",
                   help="diagnostic: the foil spans the tunnel from wall to wall (no tip, no gap)")
    p.add_argument("--te", default="sharp", choices=["sharp", "blunt"],
                   help="trailing edge of the fluid's foil: sharp (closed; default, the steady "
                        "model of the 2-D study) or blunt (the section's 0.4 mm face)")
    p.add_argument("--growth-relax", type=float, default=None,
                   help="diagnostic: growth of the re-spaced cells of the foil's grid lines above "
                        "the tip (default: the preset's growth_relax, 1: even)")
    a = p.parse_args(argv)
    if a.growth_relax is not None and not 1.0 <= a.growth_relax <= 2.0:
        p.error("--growth-relax %g: must be in [1, 2]" % a.growth_relax)
    return a


def stations(a, b, ha, hb, ga, gb, hmax):
    """Stations from a to b whose cell size grows from ha at a by the factor ga per cell and
    from hb at b by gb, capped at hmax: h(z) = min(hmax, ha + (ga-1)(z-a), hb + (gb-1)(b-z)).
    A geometric sequence of ratio g has one cell per ln(g)/(g-1) of integral dz/h; the
    stations are at equal increments of that measure (with the g of the branch that sets h),
    their number rounded up (no cell exceeds h)."""
    u = np.linspace(0.0, 1.0, 400001)
    z = a + (b - a) * u
    fromA, fromB = ha + (ga - 1.0) * (z - a), hb + (gb - 1.0) * (b - z)
    h = np.minimum(hmax, np.minimum(fromA, fromB))

    def perCell(g):
        return np.log(g) / (g - 1.0) if g > 1.0 else 1.0
    scale = np.where(h >= hmax, 1.0, np.where(fromA <= fromB, perCell(ga), perCell(gb)))
    f = 1.0 / (h * scale)
    xi = np.concatenate([[0.0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(z))])
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
    # gmsh node -> plane node (the nearest loop point, when closer than a millionth of the
    # shortest segment: gmsh's coordinates may differ from the .geo's in the last bits, so
    # rounding both to a grid can split a pair) or a new interior point
    tol = 1e-6 * seg.min()
    ids, extra = {}, []
    for tag, (x, y) in nodes.items():
        dist = np.hypot(p[:, 0] - x, p[:, 1] - y)
        k = int(np.argmin(dist))
        if dist[k] < tol:
            ids[tag] = int(loop[k])
        else:
            ids[tag] = len(xy) + len(extra)
            extra.append((x, y))
    tri = np.array([[ids[v] for v in t] for t in tris])
    missing = set(int(v) for v in loop) - set(tri.ravel().tolist())
    if missing:   # the prisms above the tip would not match the hexahedra around them
        sys.exit("cgrid3d: the section's triangulation misses %d of its %d boundary nodes"
                 % (len(missing), n))
    return np.array(extra).reshape(-1, 2), tri


def signedArea(pts, cells):
    p = pts[cells]
    return 0.5 * np.sum(p[:, :, 0] * np.roll(p[:, :, 1], -1, axis=1)
                        - np.roll(p[:, :, 0], -1, axis=1) * p[:, :, 1], axis=1)


def build(name, tc, cli, meanline, te, workdir, fullSpan=False, growthRelax=None):
    c = preset(name)
    if growthRelax is not None:
        c["growth_relax"] = growthRelax
    g = mesh2d.build(0, tc, cli, meanline, te, counts=c)  # mesh2d's TE_SPACING, OUTER_BLEND
    xy, quads, edges, _ = mesh2d.quads(g)
    loop = foilLoop(edges["foil"])
    if fullSpan:   # diagnostic: no tip; the foil's sides reach the wall z = H
        z = stations(0.0, HEIGHT, c["dz_root"], c["dz_root"], c["growth_span"], c["growth_span"],
                     c["dz_max"])
        return dict(xy=xy, xyAll=xy, quads=quads, tri=np.zeros((0, 3), dtype=int), edges=edges,
                    z=np.tile(z, (len(xy), 1)), kTip=len(z) - 1, g=g, c=c, xyAt=lambda k: xy,
                    ptsTip=g["pts"])
    extra, tri = triangulateSection(xy, loop, workdir)
    xyAll = np.vstack([xy, extra])
    area = signedArea(xyAll, tri)
    if np.any(np.abs(area) < 1e-16):
        sys.exit("cgrid3d: degenerate triangles in the section")
    tri[area < 0] = tri[area < 0][:, ::-1]
    z, kTip = spanStations(xyAll, quads, tri, loop, c)
    xyRelaxed, ptsRelaxed = relaxedPlane(g, c["gap_relax_length"], c["growth_relax"],
                                         c["growth_relax_wake"])
    xyAt, ptsThin = planeNodesAt(g, xy, extra, z, kTip, c, xyRelaxed)
    return dict(xy=xy, xyAll=xyAll, quads=quads, tri=tri, edges=edges, z=z,
                kTip=kTip, g=g, c=c, xyAt=xyAt, ptsTip=ptsThin, ptsRelaxed=ptsRelaxed)


def spanStations(xyAll, quads, tri, loop, c):
    """z of every node (rows: plane nodes, then the section's interior) at every station, and
    the index of the tip plane's station."""
    # Below the tip plane (root wall to tip) and above it (tip to wall z = H). On both sides
    # the cells next to the tip plane are y1_tip thick near the foil (the spanwise spacing is
    # continuous across the plane there: a 1 mm layer under a 5 um one diverged the solver at
    # the tip edge) and blend into even stations away from it (blendWeights).
    w = blendWeights(xyAll, quads, tri, loop, c["y1_tip"])
    fineBelow = stations(0.0, SPAN, c["dz_root"], c["y1_tip"], c["growth_span"], c["growth_gap"],
                         c["dz_max"])
    fineAbove = stations(SPAN, HEIGHT, c["y1_tip"], c["dz_top"], c["growth_gap"], c["growth_gap"],
                         c["dz_max_gap"])
    # away from the foil the stations below the tip are the clustered ones except where these
    # close in on the tip plane (spacing under dz_blend): there they are even
    k = int(np.flatnonzero(np.diff(fineBelow) >= c["dz_blend"])[-1])
    evenBelow = np.concatenate([fineBelow[:k], np.linspace(fineBelow[k], SPAN, len(fineBelow) - k)])
    below = blend(w, fineBelow, evenBelow)
    above = blend(w, fineAbove, np.linspace(SPAN, HEIGHT, len(fineAbove)))
    z = np.hstack([below, above[:, 1:]])
    kTip = len(fineBelow) - 1
    return z, kTip


def planeNodesAt(g, xy, extra, z, kTip, c, xyRelaxed):
    """xyAt(k): the node positions at station k (the plane's below the tip, the plane's and the
    section's from the tip plane up), and the plane's grid-line points at the tip plane.
    xyRelaxed: the plane re-spaced above the tip (relaxedPlane)."""
    # Above the tip the plane's wall clustering serves no wall: its y1-wide cells next to the
    # section's triangles (0.1-1.7 mm) made a 200:1 size jump, and the solver diverged there
    # (in the gap; the same mesh without a tip, --full-span, converges). So, with height h
    # above the tip plane, the plane's nodes within gap_relax_length of the foil move to an
    # evenly graded spacing (relaxedPlane) over h_relax; the far field keeps its nodes.
    # Below the tip, within h_thin of it, the front half's first cells thin towards the tip
    # plane (scaledPlane), which carries the thinned nodes.
    xyThin, ptsThin = scaledPlane(g, c["thin_length"],
                                  lambda u: c["tip_thinning"] + (1.0 - c["tip_thinning"]) * u)
    relax = np.vstack([xyRelaxed - xyThin, np.zeros_like(extra)])
    thin = xyThin - xy
    if not np.any(relax) or not np.any(thin):
        sys.exit("cgrid3d: no plane node moves next to the tip (relax/thin lengths too short?)")
    n2 = len(xy)

    def smooth(u):
        u = np.clip(u, 0.0, 1.0)
        return u * u * (3.0 - 2.0 * u)

    def xyAt(k):
        """Node positions at station k: the plane's nodes below the tip, the plane's and the
        section's from the tip plane up."""
        if k < kTip:
            return xy + (1.0 - smooth((SPAN - z[:n2, k]) / c["h_thin"]))[:, None] * thin
        return (np.vstack([xyThin, extra])
                + smooth((z[:, k] - SPAN) / c["h_relax"])[:, None] * relax)
    return xyAt, ptsThin


def relaxedPlane(g, length, growth, growthWake):
    """(xy, pts): the plane's nodes (mesh2d.quads numbering) and grid-line points with every
    foil grid line's nodes within `length` of the foil re-spaced: the same count J of cells
    over the same distance s_J, growing by `growth` (the preset's growth_relax, 1: even) from
    the foil. Nodes never come closer to the wall than before. The lines are straight there
    (mesh2d: the first 10 % of the chord), so the nodes move along them.
    The first re-spaced cell sits beside the section's triangles (as wide as the foil's
    boundary spacing); that size jump decides whether SIMPLEC converges in the tip gap. Growing
    by 1.1 (the presets until 2026-12-05) the first cell was 38 / 19 / 9 um on coarse / medium /
    fine (jumps 35 / 53 / 87:1: J grows while s_J shrinks), and SIMPLEC oscillated in those
    cells on medium and fine (the aft suction side, +-15 m/s) until the solve diverged or
    stalled; even (1) they are 92 / 59 / 39 um (15 / 17 / 21:1) and all three converge
    (cases/hydrofoil/README.md, "The tip gap's re-spaced cells"). The wake cut's lines border
    no triangle and keep growing (`growthWake`, the preset's growth_relax_wake): re-spaced
    evenly they tilted the cells where their move tapers off to 72 deg on coarse."""
    def respace(s, J, onFoil):
        k = np.arange(J + 1)
        rate = growth if onFoil else growthWake
        if rate == 1.0:
            return np.maximum(s[J] * k / J, s[:J + 1])
        return np.maximum(s[J] * (rate ** k - 1.0) / (rate ** J - 1.0), s[:J + 1])
    return movedAlongLines(g, length, respace)


def gapSizeJump(g, ptsRelaxed):
    """Above the tip: the median over the foil's grid lines of the foil's boundary spacing (the
    width of the section's triangle there) over the line's first re-spaced cell; ptsRelaxed:
    relaxedPlane's grid-line points."""
    iA, iB = g["iA"], g["iB"]
    first = np.hypot(*(ptsRelaxed[iA:iB, 1] - ptsRelaxed[iA:iB, 0]).T)
    along = np.hypot(*(ptsRelaxed[iA + 1:iB + 1, 0] - ptsRelaxed[iA:iB, 0]).T)
    return float(np.median(along / first))


def scaledPlane(g, length, factor):
    """The plane's nodes with each front foil grid line's node at distance s from the wall
    moved to s factor(smoothstep(s / length)) (factor(1) = 1: nodes from `length` on stay;
    monotone for an increasing factor). Only the front half of the foil (movedAlongLines
    foilOnly): y+ exceeded 1 only at the tip's leading-edge corner, and thinned cells at the
    sharp trailing edge's tip corner reached 86 deg of non-orthogonality at -12 deg / 30 mm."""
    def rescale(s, J, onFoil):
        u = np.clip(s[:J + 1] / length, 0.0, 1.0)
        return s[:J + 1] * factor(u * u * (3.0 - 2.0 * u))
    return movedAlongLines(g, length, rescale, foilOnly=True)


def movedAlongLines(g, length, newDistances, foilOnly=False, taper=0.025):
    """The plane's nodes (mesh2d.quads numbering) with the nodes of the grid lines within
    `length` of the foil or wake cut moved along their line towards newDistances(s, J, onFoil) (s:
    the line's node distances from its wall node, J: the first node at least `length` away).
    Weight of the move: 1 on the foil's lines; on the wake cut's lines falling linearly to 0 at
    `taper` (m) behind the trailing edge (moving the wake's long cells tilted them to 71 deg;
    stopping abruptly at the trailing edge folded cells there). foilOnly: only the front of
    the foil, weight 1 to x/c 0.3 falling to 0 at x/c 0.6 (smoothstep), nothing behind."""
    pts = g["pts"].copy()
    xTe = 0.5 * (pts[g["iA"], 0, 0] + pts[g["iB"], 0, 0])
    xLe = pts[g["iA"]:g["iB"] + 1, 0, 0].min()
    for i in range(pts.shape[0]):
        onFoil = g["iA"] <= i <= g["iB"]
        if foilOnly:
            u = np.clip((pts[i, 0, 0] - xLe) / (xTe - xLe) / 0.3 - 1.0, 0.0, 1.0)
            weight = (1.0 - u * u * (3.0 - 2.0 * u)) if onFoil else 0.0
        else:
            weight = 1.0 if onFoil else max(0.0, 1.0 - (pts[i, 0, 0] - xTe) / taper)
        s = np.hypot(*(pts[i] - pts[i, 0]).T)
        J = int(np.searchsorted(s, length))
        if weight == 0.0 or J < 3 or J >= len(s) - 1:
            continue
        sNew = s[:J + 1] + weight * (newDistances(s, J, onFoil) - s[:J + 1])
        pts[i, 1:J] = pts[i, 0] + (pts[i, 1:J] - pts[i, 0]) * (sNew[1:J] / s[1:J])[:, None]
    xy, _, _, _ = mesh2d.quads(dict(g, pts=pts))
    return xy, pts


def blend(w, fine, even):
    """Stations per node: w fine + (1 - w) even (monotone for any w in [0, 1])."""
    return w[:, None] * fine[None, :] + (1.0 - w[:, None]) * even[None, :]


def blendWeights(xyAll, quads, tri, loop, y1):
    """Weight w per node of the clustered spanwise stations (next to the tip plane: first cell
    y1) against even ones.

    A plane of y1-thick cells across the whole tunnel would make cells of y1 x (tens of mm),
    far beyond checkMesh's aspect-ratio limit (1000). So w = 1 where the node's in-plane cell
    size s (its longest edge) allows a first cell of y1 (s <= s0 = ASPECT y1: over the section
    and near the foil), w = 0 (even stations) from s1 = RAMP s0 on, a smoothstep in s between,
    smoothed over neighbours (never above the node's own value). The ramp is long because a
    thin blended layer over a stack of planar ones tilts the line between their cell centres:
    measured on coarse (clustering above the tip only), max non-orthogonality 87 / 80 / 66 /
    56 / 71 deg for RAMP 4 / 8 / 16 / 32 / 64 (56 deg is the plane's own maximum)."""
    ASPECT = 600.0
    RAMP = 32.0
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
    s0 = ASPECT * y1
    u = np.clip((size - s0) / (RAMP * s0 - s0), 0.0, 1.0)
    wMax = 1.0 - u * u * (3.0 - 2.0 * u)
    fixed = np.zeros(len(xyAll), dtype=bool)
    fixed[loop] = True
    fixed[np.unique(tri)] = True
    if np.any(size[fixed] > 900.0 * y1):   # these keep w = 1: a y1-thick first cell
        sys.exit("cgrid3d: section cells of %g m: with a %g m first cell over the tip they "
                 "exceed checkMesh's aspect-ratio limit (1000)" % (size[fixed].max(), y1))
    w = wMax.copy()
    for _ in range(20):
        w = np.minimum(wMax, np.array([np.mean(w[[i] + nbr[i]]) for i in range(len(w))]))
        w[fixed] = 1.0
    return w


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
            pts = m["xyAt"](k)
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
        m = build(a.preset, a.tc, a.cli, a.meanline, a.te, work, a.full_span, a.growth_relax)
    nCells, nPoints, nFoil = writeMsh(os.path.join(a.out, "cgrid3d.msh"), m)
    c, kTip = m["c"], m["kTip"]
    z = m["z"][m["tri"][0, 0] if len(m["tri"]) else 0]   # a node of the section: the tip's stations
    pts = m["g"]["pts"]
    iA, iB = m["g"]["iA"], m["g"]["iB"]
    side = np.hypot(*(pts[iA:iB + 1, 1] - pts[iA:iB + 1, 0]).T)
    ptsTip = m["ptsTip"][iA:iB + 1]     # the plane at the tip (first cells thinned in front)
    sideTip = np.hypot(*(ptsTip[:, 1] - ptsTip[:, 0]).T)
    gapJump = float("nan") if a.full_span else gapSizeJump(m["g"], m["ptsRelaxed"])
    summary = ("preset=%s te=%s cells=%d points=%d foil_faces=%d plane_cells=%d section_triangles=%d "
               "span_cells=%d below_tip=%d above_tip=%d first_cell_sides_m=%.3e..%.3e "
               "first_cell_sides_at_tip_m=%.3e..%.3e first_cell_tip_m=%.3e n_side=%d n_wake=%d "
               "n_normal=%d growth_relax=%g gap_size_jump=%.1f"
               % (a.preset, a.te, nCells, nPoints, nFoil, len(m["quads"]), len(m["tri"]),
                  len(z) - 1, kTip, len(z) - 1 - kTip, side.min(), side.max(), sideTip.min(),
                  sideTip.max(), (z[kTip + 1] - z[kTip]) if kTip + 1 < len(z) else float("nan"),
                  c["n_side"], c["n_wake"], c["n_normal"], c["growth_relax"], gapJump))
    with open(os.path.join(a.out, "cgrid3d-mesh.txt"), "w") as f:
        f.write(summary + "\n")
    print(summary)


if __name__ == "__main__":
    main()
