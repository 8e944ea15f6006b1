#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Impose a test displacement on the foil patch of a fluid case (ASCII mesh) for mesh-motion checks.

    foilMotion.py CASE [--tip-deflection 0.003] [--tip-twist-deg -8] [--time 0]
                       [--bending beam|shear] [--roughness AMP] [--from FILE]

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
Values are in the order of the patch's mesh points (points in order of first appearance in the
patch faces), which is OpenFOAM's PrimitivePatch::meshPoints order. The mesh must be ASCII
(foamFormatConvert with writeFormat ascii converts a binary one).
"""
import argparse
import math
import os
import re
import sys

import numpy as np

X_QC, SPAN = 0.3685, 0.100


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


def readPoints(path):
    with open(path) as f:
        n, body = _listBody(f.read())
    vals = np.array(re.findall(r"\(([^()]*)\)", body)[:n], dtype=object)
    return np.array([[float(v) for v in s.split()] for s in vals])


def readFaces(path, start, count):
    with open(path) as f:
        n, body = _listBody(f.read())
    faces = re.findall(r"\d+\s*\(([^()]*)\)", body)
    return [[int(v) for v in s.split()] for s in faces[start:start + count]]


def readPatch(boundaryPath, name):
    with open(boundaryPath) as f:
        text = f.read()
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
    a = p.parse_args(argv)
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
    print(f"foilMotion: {len(d)} foil points, max |d| {np.linalg.norm(d, axis=1).max():.4e} m "
          f"-> {target}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except RuntimeError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
