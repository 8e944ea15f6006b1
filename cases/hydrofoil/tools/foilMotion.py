#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Impose a test displacement on the foil patch of a fluid case (ASCII mesh) for mesh-motion checks.

    foilMotion.py CASE [--tip-deflection 0.003] [--tip-twist-deg -8] [--time 0]
                       [--bending beam|shear] [--roughness AMP] [--from FILE]
                       [--from-interface CSV]

Writes CASE/TIME/pointDisplacement with the foil patch as `fixedValue` and a nonuniform value
list: a bending deflection w(z) = d_y = -tip_deflection (z / span)^2 (towards the suction side,
-y) with, for `--bending beam` (default), the sections turning with the slope as in a beam
(linear Euler-Bernoulli kinematics, d_z = -y w'(z): what the structural solver's displacement
does), or, for `shear`, without (d_z = 0: the sections shear, the tip face stays level; the
check's first version), and a twist about the quarter-chord line (x = 0.3685, y = 0) growing linearly from 0 at the root to
tip_twist at the tip (negative = nose towards -y... i.e. towards the suction side, lower AOA: the
paper's tip AOA reaches -8.1 deg). Zero at the clamped root, like the coupled displacement.
--roughness AMP (m, default 0) adds to every foil point its own offset of up to AMP per
component (AMP (sin 1.7 i, sin(2.3 i + 1), sin(0.9 i + 2)) for the i-th patch point): a rough
field, unlike any structural displacement, that moves the root points off the root wall by
different amounts (the parallel-consistency check of test_cgrid_motion.sh; a few um of it
inverts the um-thin first cells, so it is no mesh-quality check).
--from FILE takes the foil's displacement from FILE instead, the (ASCII, reconstructed)
pointDisplacement of a coupled run's level on the same mesh (its internalField at the foil
points): a coupled level's motion replayed on a fresh copy of the mesh, e.g. to see which part of
the mapped displacement a mesh-quality failure comes from (cases/hydrofoil/README.md, "The tip
cells and the mapped displacement's kink").
--from-interface CSV takes it from a CSV with the columns x,y,z,ux,uy,uz instead (a solid-app
interface CSV, RUN/results/MODEL/interface/level_NNNN.csv, or tools/foilDisplacement.py's), on
any fluid mesh of the same foil: each foil point gets the value of a moving-least-squares linear
fit to the nodes around it (interpolateLinear below: exact for a displacement linear in x, y, z;
a foil point farther than 2 mm from every node is refused as another geometry). One coupled
level's shape can so be imposed on the fluid mesh of another preset (rigid.sh
--shape-displacement).
Values are in the order of the patch's mesh points (points in order of first appearance in the
patch faces), which is OpenFOAM's PrimitivePatch::meshPoints order. The mesh may be ASCII or
binary; TIME/pointDisplacement must be ASCII (foamFormatConvert with writeFormat ascii converts
it).
"""
import argparse
import glob
import math
import os
import re
import sys

import numpy as np

X_QC, SPAN = 0.3685, 0.100
NEIGHBOURS = 12        # the fit's radius: 1.5 x the distance to this nearest node (--from-interface)
MAX_GAP = 2.0e-3       # m: a foil point farther than this from every node: another geometry


def _listBody(text):
    """Body of the first top-level OpenFOAM list after the FoamFile header: (count, text)."""
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    hdr = text.find("FoamFile")
    if hdr >= 0:
        text = text[text.index("}", hdr) + 1:]
    m = re.search(r"(\d+)\s*\(", text)
    if not m:
        raise RuntimeError("foilMotion.py: no list found (is the mesh binary? convert to ascii)")
    return int(m.group(1)), text[m.end():]


def _binaryHeader(raw):
    """(label dtype, end of the FoamFile header) of a binary OpenFOAM file, or None if ASCII."""
    head = raw[:4096]
    h = head.find(b"FoamFile")
    if h < 0 or not re.search(rb"format\s+binary", head):
        return None
    m = re.search(rb"label=(\d+)", head)
    label = np.dtype("<i8") if m and m.group(1) == b"64" else np.dtype("<i4")
    return label, raw.index(b"}", h) + 1


def _binaryList(raw, pos, dtype, width=1):
    """(array, position after the list) of the binary list N (...) at or after pos."""
    m = re.compile(rb"(\d+)\s*\(").search(raw, pos)
    n, start = int(m.group(1)), m.end()
    nbytes = n * width * dtype.itemsize
    a = np.frombuffer(raw[start:start + nbytes], dtype=dtype)
    return (a.reshape(n, width) if width > 1 else a), start + nbytes + 1


def readPoints(path):
    """The vectors of a points or pointVectorField file (its first list), ASCII or binary."""
    with open(path, "rb") as f:
        raw = f.read()
    binary = _binaryHeader(raw)
    if binary:
        return _binaryList(raw, binary[1], np.dtype("<f8"), 3)[0].copy()
    n, body = _listBody(raw.decode())
    vals = np.array(re.findall(r"\(([^()]*)\)", body)[:n], dtype=object)
    return np.array([[float(v) for v in s.split()] for s in vals])


def readFaces(path, start, count):
    """Faces start .. start + count - 1 of a faces file (faceList ASCII, or binary
    faceCompactList: the offsets, then the point labels)."""
    with open(path, "rb") as f:
        raw = f.read()
    binary = _binaryHeader(raw)
    if binary:
        offsets, pos = _binaryList(raw, binary[1], binary[0])
        labels, _ = _binaryList(raw, pos, binary[0])
        return [labels[offsets[i]:offsets[i + 1]].tolist() for i in range(start, start + count)]
    n, body = _listBody(raw.decode())
    faces = re.findall(r"\d+\s*\(([^()]*)\)", body)
    return [[int(v) for v in s.split()] for s in faces[start:start + count]]


def caseParts(case):
    """The folders holding CASE's mesh parts: its processorN folders (sorted), or CASE itself
    when it is not decomposed."""
    return sorted(glob.glob(os.path.join(case, "processor[0-9]*"))) or [case]


def readPatch(boundaryPath, name):
    with open(boundaryPath, "rb") as f:
        text = f.read().decode("latin-1")   # a binary-format boundary is text all the same
    m = re.search(r"\b" + re.escape(name) + r"\s*\{([^}]*)\}", text)
    if not m:
        raise RuntimeError(f"foilMotion.py: patch '{name}' not in {boundaryPath}")
    body = m.group(1)
    nFaces = int(re.search(r"nFaces\s+(\d+)", body).group(1))
    startFace = int(re.search(r"startFace\s+(\d+)", body).group(1))
    return startFace, nFaces


def meshPoints(faces):
    seen, order = set(), []
    for f in faces:
        for p in f:
            if p not in seen:
                seen.add(p)
                order.append(p)
    return order


def displacement(pts, tipDeflection, tipTwistDeg, bending="beam"):
    x, y, z = pts[:, 0], pts[:, 1], pts[:, 2]
    s = np.clip(z / SPAN, 0.0, None)
    th = math.radians(tipTwistDeg) * s
    # positive twist = positive AOA = nose towards +y_s = -y (suction side faces -y), so the
    # rotation about +z is by -th
    c, sn = np.cos(-th), np.sin(-th)
    dx = (x - X_QC) * (c - 1) - y * sn
    dy = (x - X_QC) * sn + y * (c - 1) - tipDeflection * s * s
    # beam: the section turns with the slope w' = -2 tip_deflection z / span^2, d_z = -y w'
    dz = y * 2.0 * tipDeflection * s / SPAN if bending == "beam" else np.zeros_like(dx)
    return np.column_stack([dx, dy, dz])


def interpolateLinear(nodes, values, targets, neighbours=NEIGHBOURS):
    """values (n, 3) given at nodes (n, 3), evaluated at targets (m, 3) by moving least squares:
    at each target the value of the linear field fitted to the nodes within R of it, weighted
    (1 - (r/R)^2)^2, where R is 1.5 times the distance to its NEIGHBOURS-th nearest node (a
    continuous function of the target's position, and a weight that vanishes where a node
    enters or leaves: the result has no jumps between neighbouring targets, which would fold
    the um-thin wall cells). The fit is about the nodes' weighted centre, coordinates scaled by
    R, and directions the nodes hardly span (singular values below 1e-2 of the largest: across
    a gently curved surface) are left out of the fit, so that the value is carried unchanged
    along the surface normal to a target off the nodes' surface (0.17 mm near the trailing
    edge, fluid against solid mesh), instead of being extrapolated with a gradient the nodes do
    not determine. Exact for values linear in
    x, y, z where the nodes span three directions, and within the nodes' plane where they span
    two. Returns (values at targets, largest nearest-node distance)."""
    from scipy.spatial import cKDTree
    if len(targets) == 0:
        return np.zeros((0, 3)), 0.0
    if len(nodes) < 4:
        raise RuntimeError(f"foilMotion.py: {len(nodes)} interface nodes: a linear fit needs 4")
    k = min(neighbours, len(nodes))
    kMax = min(4 * neighbours, len(nodes))
    dist, idx = cKDTree(nodes).query(targets, k=kMax)
    radius = np.minimum(1.5 * dist[:, k - 1], dist[:, -1] if kMax < len(nodes) else np.inf)
    radius = np.maximum(radius, 1e-300)
    w = np.clip(1.0 - (dist / radius[:, None]) ** 2, 0.0, None) ** 2            # (m, kMax)
    # the fit a + b (x - c) about the stencil's weighted centre c: the constant is then
    # orthogonal to the slopes, and a slope left out (b along the normal = 0) moves nothing
    centre = np.einsum("mk,mkc->mc", w, nodes[idx]) / w.sum(axis=1)[:, None]
    rel = (nodes[idx] - centre[:, None, :]) / radius[:, None, None]
    A = np.concatenate([np.ones(rel.shape[:2] + (1,)), rel], axis=2)            # (m, kMax, 4)
    sw = np.sqrt(w)[:, :, None]
    P = np.linalg.pinv(A * sw, rcond=1e-2)                                      # (m, 4, kMax)
    at = (targets - centre) / radius[:, None]                                   # (m, 3)
    row = (P[:, 0, :] + np.einsum("mc,mck->mk", at, P[:, 1:, :])) * sw[:, :, 0]
    return np.einsum("mk,mkc->mc", row, values[idx]), float(dist[:, 0].max())


def main(argv):
    p = argparse.ArgumentParser()
    p.add_argument("case")
    p.add_argument("--patch", default="foil")
    p.add_argument("--tip-deflection", type=float, default=0.003)
    p.add_argument("--tip-twist-deg", type=float, default=-8.0)
    p.add_argument("--time", default="0")
    p.add_argument("--bending", default="beam", choices=["beam", "shear"])
    p.add_argument("--roughness", type=float, default=0.0)
    p.add_argument("--from", dest="source", default="",
                   help="pointDisplacement (ASCII, same mesh) whose foil values to impose")
    p.add_argument("--from-interface", dest="interface", default="",
                   help="CSV x,y,z,ux,uy,uz (solid-app interface, foilDisplacement.py) fitted onto the foil")
    p.add_argument("--check-gap", action="store_true",
                   help="with --from-interface: only check that every foil point lies within "
                        f"{MAX_GAP * 1e3:g} mm of a node of the CSV (the same foil); writes nothing")
    a = p.parse_args(argv)
    if a.source and a.interface:
        raise RuntimeError("foilMotion.py: --from and --from-interface exclude each other")
    if a.check_gap and not a.interface:
        raise RuntimeError("foilMotion.py: --check-gap needs --from-interface CSV")
    mesh = os.path.join(a.case, "constant", "polyMesh")
    start, count = readPatch(os.path.join(mesh, "boundary"), a.patch)
    faces = readFaces(os.path.join(mesh, "faces"), start, count)
    order = meshPoints(faces)
    allPoints = readPoints(os.path.join(mesh, "points"))
    pts = allPoints[order]
    if a.source:
        given = readPoints(a.source)
        if len(given) != len(allPoints):
            raise RuntimeError(f"foilMotion.py: --from {a.source} has {len(given)} values for "
                               f"the {len(allPoints)} points of {mesh} (another mesh, or a "
                               f"decomposed part? reconstructPar it first)")
        d = given[order]
    elif a.interface:
        from sectionShape import read_interface
        nodes, values = read_interface(a.interface)
        if a.check_gap:
            from scipy.spatial import cKDTree
            gap = float(cKDTree(nodes).query(pts)[0].max()) if len(pts) else 0.0
        else:
            d, gap = interpolateLinear(nodes, values, pts)
        if gap > MAX_GAP:
            raise RuntimeError(f"foilMotion.py: --from-interface {a.interface}: a foil point of "
                               f"{a.case} is {gap * 1e3:.3g} mm from the nearest interface node "
                               f"(> {MAX_GAP * 1e3:g} mm): not this foil's interface")
        print(f"foilMotion: {len(nodes)} interface nodes of {a.interface}, nearest node within "
              f"{gap * 1e6:.1f} um of every foil point")
        if a.check_gap:
            return 0
    else:
        d = displacement(pts, a.tip_deflection, a.tip_twist_deg, a.bending)
    if a.roughness:
        i = np.arange(len(d), dtype=float)
        d += a.roughness * np.column_stack([np.sin(1.7 * i), np.sin(2.3 * i + 1), np.sin(0.9 * i + 2)])
    target = os.path.join(a.case, a.time, "pointDisplacement")
    with open(target) as f:
        text = f.read()
    i = re.search(r"\n\s*" + re.escape(a.patch) + r"\s*\n\s*\{", text)
    if not i:
        raise RuntimeError(f"foilMotion.py: no '{a.patch}' entry in {target}")
    j = text.index("}", i.end())
    values = "\n".join("(%.10e %.10e %.10e)" % tuple(v) for v in d)
    entry = (f"\n    {a.patch}\n    {{\n        type            fixedValue;\n"
             f"        value           nonuniform List<vector> {len(d)}\n(\n{values}\n);\n    }}")
    with open(target, "w") as f:
        f.write(text[:i.start()] + entry + text[j + 1:])
    largest = np.linalg.norm(d, axis=1).max() if len(d) else 0.0
    print(f"foilMotion: {len(d)} foil points, max |d| {largest:.4e} m "
          f"-> {target}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except RuntimeError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
