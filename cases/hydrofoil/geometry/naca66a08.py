#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Parametric NACA 66 (DTRC-modified) / a = 0.8 hydrofoil of the paper's water-tunnel case.

Section: NACA 66 (DTRC-modified) thickness (table of reference/naca66-a08.md, half-thickness
ratio t(x)/t_max) laid perpendicular to the NACA a = 0.8 mean line (Abbott & von Doenhoff
eqs. 4.26-4.27).

Thickness interpolation: a monotone piecewise cubic Hermite interpolant (Fritsch-Carlson /
PCHIP, with Fritsch-Butland harmonic-mean slopes) of the tabulated ratio in the variable
s = sqrt(x/c). In s the round nose (t ~ sqrt(x)) becomes a regular, nearly linear start, so
one interpolant covers nose and body with C1 continuity; the interpolant never overshoots the
table, its maximum is exactly the tabulated 1.0 at x/c = 0.45 (PCHIP puts a zero slope at a
local extremum of the data), and the trailing edge keeps its finite 0.0666 t_max.

Mean line: "a08" (default) is the formula of NACA report 824 for a = 0.8 (max camber
0.06794 c C_Li at x/c = 0.515). "a08mod" is the slope clamp of NACA report 903 approximated
as: the a08 ordinate continued with its x/c = 0.85 slope to the trailing edge, sheared back
to y_c(1) = 0 and scaled so that the maximum camber is the tabulated 0.06651 c C_Li.

Units: metres. Section frame (x, y_s): x from the leading edge along the chord, y_s positive on
the convex (suction) side of the camber. 3-D tunnel frame (X, Y, Z): X = x_LE + x (flow), Y =
y_0 - y_s (so the suction side faces -Y and lift = -F_Y, as in the paper), Z = span (root at
Z = z_root, tip at Z = z_root + span). Angle of attack rotates the section about the
quarter chord; positive AOA raises the nose towards +y_s (more lift).

Outputs (file names below --out): section.csv, foil.stl (closed, ASCII), foil.geo (Gmsh).
"""
import argparse
import math
import os
import sys

import numpy as np

# Table of reference/naca66-a08.md: x/c and half-thickness ratio t/t_max.
THICKNESS_X = np.array([0.0, 0.0125, 0.025, 0.05, 0.075, 0.1, 0.15, 0.2, 0.3, 0.4, 0.45,
                        0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 1.0])
THICKNESS_T = np.array([0.0, 0.2088, 0.2932, 0.4132, 0.5050, 0.5814, 0.7042, 0.8000, 0.9274,
                        0.9904, 1.0000, 0.9924, 0.9306, 0.8070, 0.6220, 0.3754, 0.2286,
                        0.0666])
X_TMAX = 0.45


def pchipSlopes(xs, ys):
    """Fritsch-Carlson slopes of a monotone cubic Hermite interpolant (as in PCHIP)."""
    h = np.diff(xs)
    delta = np.diff(ys) / h
    n = len(xs)
    d = np.zeros(n)
    for k in range(1, n - 1):
        if delta[k - 1] * delta[k] <= 0.0:
            d[k] = 0.0  # local extremum (or flat): zero slope, no overshoot
        else:
            w1 = 2.0 * h[k] + h[k - 1]
            w2 = h[k] + 2.0 * h[k - 1]
            d[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k])

    def endSlope(h0, h1, del0, del1):
        s = ((2.0 * h0 + h1) * del0 - h0 * del1) / (h0 + h1)
        if np.sign(s) != np.sign(del0):
            s = 0.0
        elif np.sign(del0) != np.sign(del1) and abs(s) > abs(3.0 * del0):
            s = 3.0 * del0
        return s

    d[0] = endSlope(h[0], h[1], delta[0], delta[1])
    d[-1] = endSlope(h[-1], h[-2], delta[-1], delta[-2])
    return d


_S_NODES = np.sqrt(THICKNESS_X)
_S_SLOPES = pchipSlopes(_S_NODES, THICKNESS_T)


def thicknessRatio(x):
    """Half-thickness / max half-thickness at chord fraction x in [0, 1] (vectorised)."""
    x = np.clip(np.asarray(x, dtype=float), 0.0, 1.0)
    s = np.sqrt(x)
    k = np.clip(np.searchsorted(_S_NODES, s, side="right") - 1, 0, len(_S_NODES) - 2)
    h = _S_NODES[k + 1] - _S_NODES[k]
    u = (s - _S_NODES[k]) / h
    h00 = (1 + 2 * u) * (1 - u) ** 2
    h10 = u * (1 - u) ** 2
    h01 = u * u * (3 - 2 * u)
    h11 = u * u * (u - 1)
    return (h00 * THICKNESS_T[k] + h10 * h * _S_SLOPES[k] + h01 * THICKNESS_T[k + 1]
            + h11 * h * _S_SLOPES[k + 1])


def _xlogx(v):
    v = np.asarray(v, dtype=float)
    out = np.zeros_like(v)
    m = v > 0
    out[m] = v[m] * np.log(v[m])
    return out


def _sqlog(v):
    """v^2 ln|v| with the limit 0 at v = 0."""
    v = np.abs(np.asarray(v, dtype=float))
    out = np.zeros_like(v)
    m = v > 0
    out[m] = v[m] ** 2 * np.log(v[m])
    return out


def meanLineA08(x, cli, a=0.8):
    """NACA a-series mean line ordinate y_c/c and slope dy_c/dx (report 824, eq. 4.26-4.27)."""
    x = np.asarray(x, dtype=float)
    g = -(a * a * (0.5 * math.log(a) - 0.25) + 0.25) / (1.0 - a)
    h = (0.5 * (1 - a) ** 2 * math.log(1 - a) - 0.25 * (1 - a) ** 2) / (1 - a) + g
    k = cli / (2.0 * math.pi * (a + 1.0))
    yc = k * ((0.5 * _sqlog(a - x) - 0.5 * _sqlog(1 - x) + 0.25 * (1 - x) ** 2
               - 0.25 * (a - x) ** 2) / (1 - a) - _xlogx(x) + g - h * x)
    # derivative: d/dx[1/2 v^2 ln|v|] = -(v ln|v| + v/2) for v = a - x or 1 - x
    def dterm(v):
        v = np.asarray(v, dtype=float)
        out = np.zeros_like(v)
        m = np.abs(v) > 0
        out[m] = v[m] * np.log(np.abs(v[m]))
        return out
    lnx = np.log(np.maximum(x, 1e-300))  # slope -> +inf at the nose: finite but huge at x = 0
    dyc = k * ((-dterm(a - x) - 0.5 * (a - x) + dterm(1 - x) + 0.5 * (1 - x)
                - 0.5 * (1 - x) + 0.5 * (a - x)) / (1 - a) - lnx - 1.0 - h)
    return yc, dyc


def meanLine(x, cli, kind="a08"):
    """Mean line y_c/c and slope for kind 'a08' (formula) or 'a08mod' (slope clamp, see top)."""
    if kind == "a08":
        return meanLineA08(x, cli)
    if kind != "a08mod":
        raise ValueError(f"naca66a08.py: unknown --meanline '{kind}'; use a08 or a08mod")
    x = np.asarray(x, dtype=float)
    xc = 0.85
    yc, dyc = meanLineA08(x, 1.0)
    y85, d85 = meanLineA08(np.array([xc]), 1.0)
    aft = x > xc
    yc = np.where(aft, y85[0] + d85[0] * (x - xc), yc)
    dyc = np.where(aft, d85[0], dyc)
    y1 = y85[0] + d85[0] * (1.0 - xc)
    yc = yc - y1 * x
    dyc = dyc - y1
    # scale to the tabulated maximum camber of the modified line (0.06651 c at C_Li = 1)
    xf = np.linspace(0.0, 1.0, 20001)
    yf, _ = meanLineA08(xf, 1.0)
    yf = np.where(xf > xc, y85[0] + d85[0] * (xf - xc), yf) - y1 * xf
    scale = 0.06651 / yf.max()
    return cli * scale * yc, cli * scale * dyc


def chordStations(n):
    """n chord fractions in [0, 1], cosine-clustered at both ends, containing x = 0.45 exactly."""
    beta = np.linspace(0.0, math.pi, n)
    x = 0.5 * (1.0 - np.cos(beta))
    x[np.argmin(np.abs(x - X_TMAX))] = X_TMAX
    return x


def section(tc=0.12, cli=0.5, chord=0.05, n=121, meanline="a08", aoaDeg=0.0):
    """Upper and lower surface points (each n x 2, LE -> TE, metres) in the section frame.

    Thickness is laid perpendicular to the mean line; upper[0] == lower[0] is the leading edge,
    upper[-1] / lower[-1] the two trailing-edge corners (finite trailing edge).
    """
    x = chordStations(n)
    yc, dyc = meanLine(x, cli, meanline)
    yt = 0.5 * tc * thicknessRatio(x)
    theta = np.arctan(dyc)
    # at x = 0 the slope is infinite in the formula (log); the normal there is along -x
    theta[0] = 0.5 * math.pi if dyc[0] > 0 or not np.isfinite(dyc[0]) else theta[0]
    xu = x - yt * np.sin(theta)
    yu = yc + yt * np.cos(theta)
    xl = x + yt * np.sin(theta)
    yl = yc - yt * np.cos(theta)
    xu[0] = xl[0] = 0.0
    yu[0] = yl[0] = 0.0
    upper = np.column_stack([xu, yu]) * chord
    lower = np.column_stack([xl, yl]) * chord
    if aoaDeg != 0.0:
        a = math.radians(aoaDeg)
        rot = np.array([[math.cos(a), math.sin(a)], [-math.sin(a), math.cos(a)]])
        pivot = np.array([0.25 * chord, 0.0])
        upper = (upper - pivot) @ rot.T + pivot
        lower = (lower - pivot) @ rot.T + pivot
    return upper, lower


def sectionPolygon(upper, lower):
    """Closed ring (counter-clockwise in (x, y_s)): lower LE->TE, then upper TE->LE (no repeat)."""
    return np.vstack([lower, upper[::-1][:-1]])


def polygonArea(ring):
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def toTunnel(xs, ys, z, xLe, y0):
    """Section frame -> tunnel frame: X = xLe + x, Y = y0 - y_s, Z = z."""
    return np.column_stack([xLe + xs, y0 - ys, np.full_like(xs, z)])


def foilTriangles(upper, lower, span, nSpan, xLe=0.0, y0=0.0, zRoot=0.0):
    """Closed triangulation of the straight foil: vertices (N x 3) and triangles (M x 3, outward).

    Side surface: ring x nSpan+1 stations; caps: strips between upper[i] and lower[i] (valid for
    any camber since both are offsets of the same mean-line point); the finite trailing edge is
    the flat quad strip between upper[-1] and lower[-1] which is part of the ring.
    """
    ring = sectionPolygon(upper, lower)  # CCW in (x, y_s) => CW in (X, Y) because Y = -y_s
    m = len(ring)
    zs = zRoot + np.linspace(0.0, span, nSpan + 1)
    verts = np.vstack([toTunnel(ring[:, 0], ring[:, 1], z, xLe, y0) for z in zs])
    tris = []
    for j in range(nSpan):
        b0, b1 = j * m, (j + 1) * m
        for i in range(m):
            i1 = (i + 1) % m
            # ring runs clockwise seen from +Z; outward normal: (p1-p0) x (+Z) points out
            tris.append((b0 + i, b1 + i, b0 + i1))
            tris.append((b0 + i1, b1 + i, b1 + i1))
    n = len(upper)
    # ring index of lower[i] is i, of upper[i] is (2n-1 - i) for i >= 1, upper[0] is 0 (LE)
    def ui(i):
        return 0 if i == 0 else 2 * n - 1 - i
    # quad (lower i, lower i+1, upper i+1, upper i) runs in the ring's sense, i.e. clockwise
    # seen from +Z: as is it is outward on the root cap (-Z), reversed on the tip cap (+Z)
    for base, flip in ((0, False), (nSpan * m, True)):
        for i in range(n - 1):
            q = [base + i, base + i + 1, base + ui(i + 1), base + ui(i)]
            cand = [(q[0], q[1], q[2])]
            if i > 0:
                cand.append((q[0], q[2], q[3]))
            for t in cand:
                tris.append((t[0], t[2], t[1]) if flip else t)
    return verts, np.array(tris, dtype=np.int64)


def meshVolume(verts, tris):
    p0, p1, p2 = verts[tris[:, 0]], verts[tris[:, 1]], verts[tris[:, 2]]
    return float(np.sum(np.einsum("ij,ij->i", p0, np.cross(p1, p2)))) / 6.0


def edgeUseCounts(tris):
    """Map undirected edge -> number of triangles using it."""
    e = np.vstack([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    e.sort(axis=1)
    uniq, counts = np.unique(e, axis=0, return_counts=True)
    return uniq, counts


def writeStl(path, verts, tris, name="foil"):
    with open(path, "w") as f:
        f.write(f"solid {name}\n")
        for t in tris:
            p = verts[t]
            nrm = np.cross(p[1] - p[0], p[2] - p[0])
            ln = np.linalg.norm(nrm)
            nrm = nrm / ln if ln > 0 else nrm
            f.write(f"  facet normal {nrm[0]:.9e} {nrm[1]:.9e} {nrm[2]:.9e}\n    outer loop\n")
            for q in p:
                f.write(f"      vertex {q[0]:.12e} {q[1]:.12e} {q[2]:.12e}\n")
            f.write("    endloop\n  endfacet\n")
        f.write(f"endsolid {name}\n")


def writeCsv(path, upper, lower, args):
    with open(path, "w") as f:
        f.write(f"# NACA 66 (DTRC-mod) t/c={args.tc} + {args.meanline} mean line C_Li={args.cli}, "
                f"chord={args.chord} m, AOA={args.aoa} deg; section frame, metres\n")
        f.write("surface,i,x,y\n")
        for name, pts in (("upper", upper), ("lower", lower)):
            for i, (x, y) in enumerate(pts):
                f.write(f"{name},{i},{x:.12e},{y:.12e}\n")


def writeGeo(path, upper, lower, args):
    """Gmsh .geo of the foil in the tunnel frame, root face at Z = z_root, extruded to the tip.

    Numbers settable with `gmsh -setnumber NAME VALUE`: hex (0 Tet, 1 structured Hex),
    lc (tet size, m), edgeRatio (size at LE/TE points / lc),
    curved (0, default: straight-sided second-order elements, always valid; 1: mid-nodes on the
    curved surfaces, then use hoOpt 2 = Mesh.HighOrderOptimize to repair negative Jacobians;
    the structured hex variant is valid only straight-sided), nChord / nThick / nSpan (hex
    divisions along the chord, through the thickness, along the span). Physical groups:
    "volume" (3-D), "clamped" (root face), "wetted" (all other faces).
    """
    n = len(upper)
    xLe, y0, zr = args.x_le, args.y0, args.z_root
    # nose split points for the structured variant: first station with x/c >= xNose
    xs = chordStations(n)
    kNose = int(np.searchsorted(xs, args.hex_nose))
    L = []
    L.append("// Generated by cases/hydrofoil/geometry/naca66a08.py (GPL-3.0-or-later); do not edit.")
    L.append("// NACA 66 (DTRC-mod) t/c=%g, %s mean line C_Li=%g, chord=%g m, span=%g m, AOA=%g deg,"
             % (args.tc, args.meanline, args.cli, args.chord, args.span, args.aoa))
    L.append("// %d points per side; tunnel frame: LE at x=%g, chord line y=%g, root z=%g;"
             % (args.n, args.x_le, args.y0, args.z_root))
    L.append("// suction side towards -y. Usage: gmsh foil.geo -3 -order 2 [-setnumber NAME VALUE]")
    L.append("// (hex 0|1, lc, edgeRatio, nChord, nThick, nSpan, curved, hoOpt; see naca66a08.py).")
    L.append('SetFactory("Built-in");')
    L.append("DefineConstant[ hex = {0, Name \"hex\"}, lc = {%g, Name \"lc\"}," % (args.chord / 12))
    L.append("  nChord = {40, Name \"nChord\"}, nThick = {6, Name \"nThick\"},")
    L.append("  nSpan = {20, Name \"nSpan\"},")
    L.append("  edgeRatio = {0.25, Name \"edgeRatio\"}, hoOpt = {0, Name \"hoOpt\"},")
    L.append("  curved = {0, Name \"curved\"} ];")
    L.append("lcEdge = edgeRatio * lc; // size at the leading and trailing edge points")
    L.append("span = %.12g;" % args.span)
    # points: upper 0..n-1 ids 1..n ; lower 1..n-1 ids n+1..2n-1 (LE shared)
    def pid(surf, i):
        if i == 0:
            return 1
        return 1 + i if surf == "u" else n + i
    for i in range(n):
        X, Y = xLe + upper[i, 0], y0 - upper[i, 1]
        size = "lcEdge" if i in (0, n - 1) else "lc"
        L.append("Point(%d) = {%.12e, %.12e, %.12e, %s};" % (pid("u", i), X, Y, zr, size))
    for i in range(1, n):
        X, Y = xLe + lower[i, 0], y0 - lower[i, 1]
        size = "lcEdge" if i == n - 1 else "lc"
        L.append("Point(%d) = {%.12e, %.12e, %.12e, %s};" % (pid("l", i), X, Y, zr, size))

    def seq(surf, a, b):
        return ", ".join(str(pid(surf, i)) for i in range(a, b + 1))
    L.append("If (hex == 0)")
    L.append("  Spline(1) = {%s};" % seq("u", 0, n - 1))
    L.append("  Spline(2) = {%s};" % seq("l", 0, n - 1))
    L.append("  Line(3) = {%d, %d};" % (pid("u", n - 1), pid("l", n - 1)))
    L.append("  Curve Loop(1) = {1, 3, -2};")
    L.append("  Plane Surface(1) = {1};")
    L.append("  ex[] = Extrude {0, 0, span} { Surface{1}; };")
    L.append("Else")
    # structured: nose curve lower[k] -> LE -> upper[k], upper k..TE, TE line, lower TE..k
    nose = [pid("l", i) for i in range(kNose, 0, -1)] + [1] + [pid("u", i) for i in range(1, kNose + 1)]
    L.append("  Spline(1) = {%s};" % ", ".join(map(str, nose)))
    L.append("  Spline(2) = {%s};" % seq("u", kNose, n - 1))
    L.append("  Line(3) = {%d, %d};" % (pid("u", n - 1), pid("l", n - 1)))
    L.append("  Spline(4) = {%s};" % ", ".join(str(pid("l", i)) for i in range(n - 1, kNose - 1, -1)))
    L.append("  Curve Loop(1) = {1, 2, 3, 4};")
    L.append("  Plane Surface(1) = {1};")
    L.append("  Transfinite Curve{1, 3} = nThick + 1;")
    L.append("  Transfinite Curve{2, 4} = nChord + 1 Using Bump 0.4;")
    L.append("  Transfinite Surface{1} = {%d, %d, %d, %d};"
             % (pid("l", kNose), pid("u", kNose), pid("u", n - 1), pid("l", n - 1)))
    L.append("  Recombine Surface{1};")
    L.append("  ex[] = Extrude {0, 0, span} { Surface{1}; Layers{nSpan}; Recombine; };")
    L.append("EndIf")
    L.append('Physical Volume("volume") = {ex[1]};')
    L.append('Physical Surface("clamped") = {1};')
    L.append('Physical Surface("wetted") = {ex[0], ex[{2 : #ex[]-1}]};')
    L.append("Mesh.ElementOrder = 2;")
    L.append("Mesh.SecondOrderLinear = 1 - curved; // curved 0: straight-sided second order")
    L.append("Mesh.HighOrderOptimize = hoOpt;      // 2: optimise curved elements")
    with open(path, "w") as f:
        f.write("\n".join(L) + "\n")


def parseArgs(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--tc", type=float, default=0.12, help="thickness ratio t/c (0.12)")
    p.add_argument("--cli", type=float, default=0.5, help="design lift coefficient C_Li (0.5)")
    p.add_argument("--meanline", default="a08", choices=["a08", "a08mod"],
                   help="a08: formula (default); a08mod: slope clamp from 0.85c")
    p.add_argument("--chord", type=float, default=0.050, help="chord, m (0.050)")
    p.add_argument("--span", type=float, default=0.100, help="span, m (0.100)")
    p.add_argument("--aoa", type=float, default=0.0, help="angle of attack, deg (0)")
    p.add_argument("--n", type=int, default=121, help="points per surface LE->TE (121)")
    p.add_argument("--n-span", type=int, default=20, help="STL spanwise divisions (20)")
    p.add_argument("--x-le", type=float, default=0.356, help="leading edge X in tunnel, m")
    p.add_argument("--y0", type=float, default=0.0, help="chord line Y in tunnel, m")
    p.add_argument("--z-root", type=float, default=0.0, help="root Z (tunnel wall), m")
    p.add_argument("--stl-root-extension", type=float, default=0.0,
                   help="extend the STL below the root by this much (for snappyHexMesh), m")
    p.add_argument("--hex-nose", type=float, default=0.02,
                   help="x/c where the structured hex variant splits the nose block (0.02)")
    p.add_argument("--out", default=".", help="output folder")
    return p.parse_args(argv)


def main(argv=None):
    args = parseArgs(argv)
    os.makedirs(args.out, exist_ok=True)
    upper, lower = section(args.tc, args.cli, args.chord, args.n, args.meanline, args.aoa)
    writeCsv(os.path.join(args.out, "section.csv"), upper, lower, args)
    ext = args.stl_root_extension
    verts, tris = foilTriangles(upper, lower, args.span + ext, args.n_span, args.x_le, args.y0,
                                args.z_root - ext)
    writeStl(os.path.join(args.out, "foil.stl"), verts, tris)
    writeGeo(os.path.join(args.out, "foil.geo"), upper, lower, args)
    area = polygonArea(sectionPolygon(upper, lower))
    print(f"naca66a08: t/c={args.tc} C_Li={args.cli} ({args.meanline}) chord={args.chord} "
          f"span={args.span}: section area {area:.6e} m2, STL {len(tris)} triangles, "
          f"volume {meshVolume(verts, tris):.6e} m3 -> {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
