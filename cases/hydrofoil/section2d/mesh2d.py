#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Structured C-grid of the 2-D section mode of the hydrofoil case (Gmsh MSH 2.2, hexahedra).

The foil section of geometry/naca66a08.py in the x-y plane of the water tunnel (the 3-D case's
frame: leading edge at x = 0.356 m, chord line y = 0, suction side towards -y), inside the
tunnel's test section L x W = 0.762 x 0.508 m, one cell thick in z (dz = 1 mm). The side walls
y = +-W/2 are slip walls (patch "sides", type symmetry: the tunnel's blockage without its wall
boundary layers, which a 2-D section cannot represent).

Topology: a C-block wraps the suction side, the leading edge and the pressure side and runs
along both sides of the wake to the outlet; a strip block behind the blunt trailing-edge face
(0.4 mm at t/c 0.12) fills the wake between the two wake cuts. Grid lines leave the foil along
its normals (straight for the first 10 % chord, then a cubic Hermite curve to the tunnel
boundary), so the wall cells are orthogonal; cell heights grow geometrically from the first-cell
height y1. Along the foil the stations are clustered at the leading and trailing edges.

Refinement: level k multiplies every cell count by r^k (r = sqrt 2, rounded) and divides the
first-cell height by r^k with the same distribution functions, i.e. a systematic refinement at a
constant ratio (GCI: representative size h = sqrt(area / cells)).

Usage: mesh2d.py --level K --out DIR [--tc 0.12 --cli 0.5 --meanline a08]
Writes DIR/section2d.msh (gmshToFoam input; physical groups inlet, outlet, sides, foil,
frontAndBack, fluid) and DIR/section2d-mesh.txt (the parameters, one line).
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "geometry"))
import naca66a08  # noqa: E402

CHORD = 0.050
X_LE = 0.356
TUNNEL_L = 0.762
TUNNEL_W = 0.508
DZ = 0.001
RATIO = math.sqrt(2.0)

# Level 0 (coarsest). First-cell height: y+ <= 1 at the suction peak of the turbulent flow
# (u_tau <= 0.2 m/s) needs y1 <= 5e-6 m.
Y1_0 = 5.0e-6
N_SIDE_0 = 80     # cells along each side of the foil, leading to trailing edge
N_TE_0 = 16       # cells across the trailing-edge face (and the wake strip), even
N_WAKE_0 = 40     # cells along the wake, trailing edge to outlet
N_NORMAL_0 = 56   # cells from the foil / wake cut to the tunnel boundary
STRAIGHT = 0.1 * CHORD  # grid lines are straight along the wall normal this far
WAKE_WIDTH_OUT = 0.01   # wake strip width at the outlet (m); 0.4 mm at the trailing edge
X_SPLIT = X_LE + 0.3 * CHORD  # foil lines behind this x run straight to the side wall
NORMAL_SMOOTHING = 0.004 * CHORD  # Gaussian width of the normal smoothing (m)
TE_BLEND = 0.15 * CHORD # foil lines turn to the wall normal over this length before the TE
WAKE_RAMP = 0.356        # the first-cell height at the wake cut grows from y1 over this length
# Trailing-edge spacing along the foil, in L/n (L the side's arc length, n its cells). The
# sharp trailing edge sets the circulation: at 0.57 (0.1 + 0.15 pi, the first meshes' value)
# the section's C_L rose 4 % when only the foil stations were doubled, and the level study
# showed order 0.3. At 0.2 the turbulent C_L converges monotonically with order 1.6 (levels
# 0-1-2, verification/hydrofoil-2d); at 0.1 levels 1-3 agree to 0.04 %, but level 0 does not
# settle (cases/hydrofoil/README.md, "2-D section mode"). 0.1 would equal the leading edge's
# spacing. The 3-D C-grid (tools/cgrid3d.py) uses the same value.
TE_SPACING = 0.2
# The rear lines' outer ends: a fraction OUTER_BLEND of their x is evenly spaced (by index)
# between the first rear line and the outlet, the rest is the x where their straight part ends;
# keeps the cells at the side wall behind a finely spaced trailing edge from aspect ratios
# beyond checkMesh's 1 000.
OUTER_BLEND = 0.5


def parseArgs(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--level", type=int, required=True, help="refinement level 0..6")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--tc", type=float, default=0.12)
    p.add_argument("--cli", type=float, default=0.5)
    p.add_argument("--meanline", default="a08", choices=["a08", "a08mod"])
    p.add_argument("--te", default="blunt", choices=["blunt", "sharp"],
                   help="trailing edge: blunt (the section's 0.4 mm face) or sharp (closed)")
    p.add_argument("--level-along", type=int, default=None,
                   help="refinement level of the counts along the foil and the wake (n_side, "
                        "n_te, n_wake) alone; default --level (separate-refinement studies)")
    p.add_argument("--level-across", type=int, default=None,
                   help="refinement level across the layers (n_normal, y1) alone; default --level")
    a = p.parse_args(argv)
    for name in ("level", "level_along", "level_across"):
        v = getattr(a, name)
        if v is not None and not 0 <= v <= 6:
            p.error("--%s must be 0..6" % name.replace("_", "-"))
    return a


def geometricRatio(first, total, n):
    """q with first * (q^n - 1)/(q - 1) = total (q >= 1), by bisection."""
    if first * n >= total:
        return 1.0
    lo, hi = 1.0, 2.0
    while first * (hi ** n - 1) / (hi - 1) < total:
        hi *= 2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if first * (mid ** n - 1) / (mid - 1) < total:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def geometric(first, total, n):
    """n + 1 increasing stations from 0 to total, first spacing `first`, constant growth."""
    q = geometricRatio(first, total, n)
    d = first * q ** np.arange(n) if q > 1.0 else np.full(n, total / n)
    s = np.concatenate([[0.0], np.cumsum(d)])
    return s * (total / s[-1])


def arcLength(poly):
    return np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(poly, axis=0).T))])


def resample(poly, t):
    """Points at arc-length fractions t (0..1) of the polyline."""
    s = arcLength(poly)
    u = t * s[-1]
    return np.column_stack([np.interp(u, s, poly[:, 0]), np.interp(u, s, poly[:, 1])])


def clustered(n, teSpacing=TE_SPACING):
    """n + 1 fractions 0..1 from the leading edge (t = 0) to the trailing edge, clustered at the
    leading edge (spacing 0.1 L/n) and at the trailing edge (spacing teSpacing L/n, 0.1..1.5):
    f = 0.1 t + a (1 - cos(pi t))/2 + b (1 - cos(pi t / 2)), b = 2 (teSpacing - 0.1)/pi,
    a = 0.9 - b."""
    if not 0.1 <= teSpacing <= 1.5:
        raise ValueError("mesh2d: trailing-edge spacing %g L/n outside 0.1..1.5" % teSpacing)
    b = 2.0 * (teSpacing - 0.1) / math.pi
    t = np.linspace(0.0, 1.0, n + 1)
    return (0.1 * t + (0.9 - b) * 0.5 * (1.0 - np.cos(math.pi * t))
            + b * (1.0 - np.cos(0.5 * math.pi * t)))


def normals(poly):
    """Unit normals of a polyline (central differences), rotated tangent (t_y, -t_x)."""
    t = np.gradient(poly, axis=0)
    t /= np.hypot(t[:, 0], t[:, 1])[:, None]
    return np.column_stack([t[:, 1], -t[:, 0]])


def build(level, tc, cli, meanline, te="blunt", counts=None, levelAlong=None, levelAcross=None,
          teSpacing=TE_SPACING, outerBlend=OUTER_BLEND):
    """The C-grid of refinement level `level`; `counts` (a dict with n_side, n_te, n_wake,
    n_normal, y1) replaces the level's cell counts and first-cell height (the 3-D mesher).
    levelAlong / levelAcross (default `level`) refine the counts along the foil and wake
    (n_side, n_te, n_wake) and across the layers (n_normal, y1) separately. teSpacing,
    outerBlend: see TE_SPACING, OUTER_BLEND."""
    kAlong = RATIO ** (level if levelAlong is None else levelAlong)
    kAcross = RATIO ** (level if levelAcross is None else levelAcross)
    nSide, nTe = round(N_SIDE_0 * kAlong), 2 * round(N_TE_0 * kAlong / 2)
    nWake, nNormal = round(N_WAKE_0 * kAlong), round(N_NORMAL_0 * kAcross)
    y1 = Y1_0 / kAcross
    if counts is not None:
        nSide, nTe, nWake = counts["n_side"], 2 * round(counts["n_te"] / 2), counts["n_wake"]
        nNormal, y1 = counts["n_normal"], counts["y1"]

    upper, lower = naca66a08.section(tc=tc, cli=cli, chord=CHORD, n=2001, meanline=meanline)
    # tunnel frame: suction side (section "upper") towards -y
    suction = np.column_stack([X_LE + upper[:, 0], -upper[:, 1]])
    pressure = np.column_stack([X_LE + lower[:, 0], -lower[:, 1]])
    if te == "sharp":
        # close the 0.4 mm trailing edge: each side moves by its offset from the trailing-edge
        # midpoint, linearly in x/c (the leading edge stays; <= 0.2 mm change at the TE)
        mid = 0.5 * (suction[-1] + pressure[-1])
        for side in (suction, pressure):
            side += np.outer((side[:, 0] - X_LE) / CHORD, mid - side[-1])
        suction[-1] = pressure[-1] = mid
    t = clustered(nSide, teSpacing)
    sideA = resample(suction, t)[::-1]   # suction side, trailing edge -> leading edge
    sideB = resample(pressure, t)[1:]    # pressure side, after the leading edge -> TE
    foil = np.vstack([sideA, sideB])     # corner A ... LE ... corner B
    cornerA, cornerB = foil[0], foil[-1]
    xTe = 0.5 * (cornerA[0] + cornerB[0])

    # wake stations behind the trailing edge: first spacing = the foil spacing at the TE
    dsTe = float(np.hypot(*(sideA[0] - sideA[1])))
    wakeLen = TUNNEL_L - xTe
    d = geometric(dsTe, wakeLen, nWake)          # distance behind the trailing edge
    frac = d / wakeLen
    width = (cornerB[1] - cornerA[1]) + (WAKE_WIDTH_OUT - (cornerB[1] - cornerA[1])) * frac
    cellAcross = width / nTe              # strip cell width (the wake cut's first-cell target)
    if te == "sharp":
        width = np.zeros_like(frac)       # one wake cut, shared by both sides
    yMid = 0.5 * (cornerA[1] + cornerB[1]) * (1.0 - frac)
    wakeA = np.column_stack([xTe + d, yMid - 0.5 * width])
    wakeB = np.column_stack([xTe + d, yMid + 0.5 * width])
    wakeA[0], wakeB[0] = cornerA, cornerB

    # C-line: wake A (outlet -> corner A), foil (corner A -> corner B), wake B (-> outlet)
    inner = np.vstack([wakeA[::-1][:-1], foil, wakeB[1:]])
    nI = len(inner)
    iA, iB = nWake, nWake + len(foil) - 1        # indices of the two corners
    # line directions: the foil's outward normals; over the last TE_BLEND of the chord they turn
    # to the wall normal (0, -+1) (the trailing-edge cells are non-orthogonal by the surface
    # slope there, about 17 deg); the wake's lines are straight across the tunnel
    # normals smoothed along the arc length (Gaussian, NORMAL_SMOOTHING): the leading edge of
    # the a = 0.8 mean line has a slope singularity, and the finest levels resolve it
    mf = normals(foil)
    sf = arcLength(foil)
    w = np.exp(-0.5 * ((sf[:, None] - sf[None, :]) / NORMAL_SMOOTHING) ** 2)
    mf = w @ mf
    mf /= np.hypot(mf[:, 0], mf[:, 1])[:, None]
    centre = np.array([X_LE + 0.5 * CHORD, 0.0])
    if np.dot(mf[nSide], foil[nSide] - centre) < 0:
        mf = -mf
    gamma = np.clip((foil[:, 0] - (xTe - TE_BLEND)) / TE_BLEND, 0.0, 1.0)[:, None]
    wallNormal = np.where(np.arange(len(foil))[:, None] < nSide, [[0.0, -1.0]], [[0.0, 1.0]])
    mf = (1.0 - gamma) * mf + gamma * wallNormal
    mf /= np.hypot(mf[:, 0], mf[:, 1])[:, None]
    m = np.zeros_like(inner)
    m[iA:iB + 1] = mf
    m[:iA] = [0.0, -1.0]
    m[iB + 1:] = [0.0, 1.0]

    # outer boundary targets: the wake's and the rear foil's lines (x >= X_SPLIT) run to the
    # side wall at the x where their straight part ends; the front foil's lines spread evenly (by index) over the wall ahead
    # of X_SPLIT and the inlet, the leading edge's to the inlet centre
    outer = np.zeros_like(inner)
    iLe = iA + nSide
    for lo, hi, sign in ((0, iLe, -1.0), (iLe, nI - 1, 1.0)):
        idx = np.arange(lo, hi + 1)
        rear = inner[idx, 0] >= X_SPLIT
        if sign < 0:
            rear[-1] = False                    # the leading edge itself
        x = inner[idx, 0] + STRAIGHT * m[idx, 0]   # where the straight part ends
        tgt = np.column_stack([x, np.full(len(idx), sign * TUNNEL_W / 2)])
        rearIdx = np.flatnonzero(rear)
        if outerBlend > 0 and len(rearIdx) > 1:
            even = np.linspace(x[rearIdx[0]], x[rearIdx[-1]], len(rearIdx))
            tgt[rearIdx, 0] = (1.0 - outerBlend) * x[rearIdx] + outerBlend * even
        front = np.flatnonzero(~rear)
        # path from the wall at X_SPLIT to the inlet centre (index order of this half)
        path = np.array([[X_SPLIT, sign * TUNNEL_W / 2], [0.0, sign * TUNNEL_W / 2], [0.0, 0.0]])
        f = np.linspace(0.0, 1.0, len(front) + 1)[1:] if sign < 0 else \
            np.linspace(0.0, 1.0, len(front) + 1)[:-1]
        if sign < 0:
            tgt[front] = resample(path, f)          # from X_SPLIT towards the LE
        else:
            tgt[front] = resample(path, 1.0 - f)    # from the LE towards X_SPLIT
        # the inlet corner is a node (the boundary must not cut the tunnel's corner)
        corner = np.array([0.0, sign * TUNNEL_W / 2])
        tgt[np.argmin(np.hypot(*(tgt - corner).T))] = corner
        outer[idx] = tgt

    # first-cell height along the C-line: y1 on the foil; along the wake cut it grows from y1
    # to the mean strip cell width over WAKE_RAMP
    first = np.full(nI, y1)
    ramp = np.minimum(1.0, d / WAKE_RAMP)
    wakeFirst = y1 + (cellAcross - y1) * ramp
    first[:iA + 1] = wakeFirst[::-1]
    first[iB:] = wakeFirst

    # grid lines: straight along m for STRAIGHT, then a cubic Hermite to the outer point
    nSample = 600
    u = np.linspace(0.0, 1.0, nSample)[:, None]
    pts = np.zeros((nI, nNormal + 1, 2))
    for i in range(nI):
        p0 = inner[i]
        p1 = p0 + STRAIGHT * m[i]
        r = outer[i]
        L = np.hypot(*(r - p1))
        e = (r - p1) / L
        h00, h10 = 2 * u ** 3 - 3 * u ** 2 + 1, u ** 3 - 2 * u ** 2 + u
        h01, h11 = -2 * u ** 3 + 3 * u ** 2, u ** 3 - u ** 2
        curve = h00 * p1 + h10 * (min(L, 4 * STRAIGHT) * m[i]) + h01 * r + h11 * (L * e)
        line = np.vstack([p0, curve])
        s = arcLength(line)
        sj = geometric(first[i], s[-1], nNormal)
        pts[i] = np.column_stack([np.interp(sj, s, line[:, 0]), np.interp(sj, s, line[:, 1])])
    # strip behind the trailing-edge face: straight across between the two wake cuts, clustered
    # towards both cuts with the C-block's first-cell height there (continuous spacing)
    strip = np.zeros((nWake + 1, nTe + 1, 2))
    for kk in range(nWake + 1 if te == "blunt" else 0):
        a, b = pts[iA - kk, 0], pts[iB + kk, 0]
        w = np.hypot(*(b - a))
        half = geometric(min(wakeFirst[kk], 0.5 * w / (nTe // 2)), 0.5 * w, nTe // 2)
        f = np.concatenate([half, w - half[::-1][1:]]) / w
        strip[kk] = a + f[:, None] * (b - a)
    return dict(sharp=(te == "sharp"), pts=pts, strip=strip, iA=iA, iB=iB, nI=nI, nNormal=nNormal, nTe=nTe,
                nWake=nWake, nSide=nSide, y1=y1)


def quads(g, check=True):
    """2-D nodes (n x 2) and quads (node ids, counter-clockwise) with boundary edges."""
    pts, strip, iA, iB = g["pts"], g["strip"], g["iA"], g["iB"]
    nI, nJ, nTe, nWake = g["nI"], g["nNormal"] + 1, g["nTe"], g["nWake"]
    cId = np.arange(nI * nJ).reshape(nI, nJ)
    nodes = [pts.reshape(-1, 2)]
    sId = np.zeros((nWake + 1, nTe + 1), dtype=int)
    nextId = nI * nJ
    for kk in range(nWake + 1):
        sId[kk, 0], sId[kk, nTe] = cId[iA - kk, 0], cId[iB + kk, 0]
        for mm in range(1, nTe):
            sId[kk, mm] = nextId
            nextId += 1
        nodes.append(strip[kk, 1:nTe])
    xy = np.vstack(nodes)
    cells = []
    for i in range(nI - 1):
        for j in range(nJ - 1):
            cells.append([cId[i, j], cId[i + 1, j], cId[i + 1, j + 1], cId[i, j + 1]])
    if not g["sharp"]:
        for kk in range(nWake):
            for mm in range(nTe):
                cells.append([sId[kk, mm], sId[kk + 1, mm], sId[kk + 1, mm + 1], sId[kk, mm + 1]])
    cells = np.array(cells)
    edges = {"foil": [], "inlet": [], "outlet": [], "sides": []}
    for i in range(iA, iB):
        edges["foil"].append((cId[i, 0], cId[i + 1, 0]))
    if not g["sharp"]:
        for mm in range(nTe):
            edges["foil"].append((sId[0, mm], sId[0, mm + 1]))
    for i in range(nI - 1):
        a, b = cId[i, nJ - 1], cId[i + 1, nJ - 1]
        mid = 0.5 * (xy[a] + xy[b])
        edges["inlet" if mid[0] < 1e-9 else "sides"].append((a, b))
    for j in range(nJ - 1):
        edges["outlet"].append((cId[0, j], cId[0, j + 1]))
        edges["outlet"].append((cId[nI - 1, j], cId[nI - 1, j + 1]))
    if not g["sharp"]:
        for mm in range(nTe):
            edges["outlet"].append((sId[nWake, mm], sId[nWake, mm + 1]))
    else:
        # sharp trailing edge: the two sides of the wake cut share their nodes (a C-grid);
        # the strip's nodes and the duplicates go, the rest is renumbered
        remap = np.arange(len(xy))
        for kk in range(nWake + 1):
            remap[cId[iB + kk, 0]] = cId[iA - kk, 0]
        cells = remap[cells]
        edges = {nm: [(remap[a], remap[b]) for a, b in e] for nm, e in edges.items()}
        used = np.unique(cells)
        newId = np.full(len(xy), -1)
        newId[used] = np.arange(len(used))
        xy = xy[used]
        cells = newId[cells]
        edges = {nm: [(newId[a], newId[b]) for a, b in e] for nm, e in edges.items()}
    # counter-clockwise; a mixed orientation would mean folded (inverted) cells
    p = xy[cells]
    area = 0.5 * np.sum(p[:, :, 0] * np.roll(p[:, :, 1], -1, axis=1)
                        - np.roll(p[:, :, 0], -1, axis=1) * p[:, :, 1], axis=1)
    if np.all(area < 0):
        cells = cells[:, ::-1]
        area = -area
    if check and np.any(area <= 0):
        sys.exit("mesh2d: %d folded cells; the grid lines cross" % int(np.sum(area <= 0)))
    return xy, cells, edges, area


def writeMsh(path, xy, cells, edges):
    n = len(xy)
    names = ["inlet", "outlet", "sides", "foil", "frontAndBack", "fluid"]
    tag = {nm: i + 1 for i, nm in enumerate(names)}
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n%d\n" % len(names))
        for nm in names:
            f.write('%d %d "%s"\n' % (3 if nm == "fluid" else 2, tag[nm], nm))
        f.write("$EndPhysicalNames\n$Nodes\n%d\n" % (2 * n))
        for z, off in ((0.0, 0), (DZ, n)):
            for i, (x, y) in enumerate(xy):
                f.write("%d %.15g %.15g %.15g\n" % (off + i + 1, x, y, z))
        f.write("$EndNodes\n")
        lines = []
        for nm in ("inlet", "outlet", "sides", "foil"):
            for a, b in edges[nm]:
                lines.append("3 2 %d %d %d %d %d %d" % (tag[nm], tag[nm], a + 1, b + 1, b + 1 + n, a + 1 + n))
        for c in cells:
            lines.append("3 2 %d %d %s" % (tag["frontAndBack"], tag["frontAndBack"], " ".join(str(v + 1) for v in c[::-1])))
            lines.append("3 2 %d %d %s" % (tag["frontAndBack"], tag["frontAndBack"], " ".join(str(v + 1 + n) for v in c)))
        for c in cells:
            lines.append("5 2 %d %d %s %s" % (tag["fluid"], tag["fluid"], " ".join(str(v + 1) for v in c), " ".join(str(v + 1 + n) for v in c)))
        f.write("$Elements\n%d\n" % len(lines))
        for i, l in enumerate(lines):
            f.write("%d %s\n" % (i + 1, l))
        f.write("$EndElements\n")


def main(argv=None):
    a = parseArgs(argv)
    g = build(a.level, a.tc, a.cli, a.meanline, a.te, levelAlong=a.level_along,
              levelAcross=a.level_across)
    xy, cells, edges, area = quads(g)
    os.makedirs(a.out, exist_ok=True)
    writeMsh(os.path.join(a.out, "section2d.msh"), xy, cells, edges)
    summary = ("te=%s level=%d ratio=%.6f cells=%d area_m2=%.8e h_m=%.6e y1_m=%.4e n_side=%d n_te=%d "
               "n_wake=%d n_normal=%d dz_m=%g" % (a.te, a.level, RATIO, len(cells), area.sum(),
                                                  math.sqrt(area.sum() / len(cells)), g["y1"],
                                                  g["nSide"], g["nTe"], g["nWake"],
                                                  g["nNormal"], DZ))
    with open(os.path.join(a.out, "section2d-mesh.txt"), "w") as f:
        f.write(summary + "\n")
    print(summary)


if __name__ == "__main__":
    main()
