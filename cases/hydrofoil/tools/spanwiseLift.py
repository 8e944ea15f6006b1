#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Spanwise distribution of the foil's pressure lift, from the foil patch of a fluid case.

    spanwiseLift.py VTP [VTP ...] [--rho 998.2] [--step 5e-3] [--span 0.1]

VTP: the foil patch written by OpenFOAM's foamToVTK in ASCII with the kinematic pressure as
face data, e.g. for a coupled run's accepted flow (the mesh moved):
    mpirun -np 2 foamToVTK -parallel -case RUN/fluid-baseline -latestTime -no-internal \\
        -no-point-data -patches foil -fields '(p)' -ascii
    -> RUN/fluid-baseline/VTK/fluid-baseline_N/boundary/foil.vtp
For every station z = 0, step, 2 step, ..., span it prints the pressure lift -F_y [N] carried
outboard of z (rho p times each face's area vector, OpenFOAM's boundary orientation, a face's force spread evenly over its
spanwise extent, so that the curve does not jump where a row of faces crosses a station), one
column per file, and, for each file after the first, its ratio to the previous file minus 1:
where along the span two meshes' loads part. The last line gives each file's total and its
spanwise centre of lift, z_c = sum(z F) / sum(F) [m]. Only the pressure part (the viscous part is
0.6 % of the lift here). Exits 2 with a one-line error when a file cannot be read or has no
Points, connectivity, offsets or p.
"""
import argparse
import re
import sys

import numpy as np


def fail(message):
    print("error: spanwiseLift.py: " + message, file=sys.stderr)
    sys.exit(2)


def read_patch(path):
    """points (n, 3), connectivity, offsets (VTK polys) and the face pressure p of an ASCII vtp."""
    try:
        text = open(path).read()
    except OSError as e:
        fail(f"cannot read {path} ({e.strerror})")

    def array(name, dtype):
        m = re.search(r"<DataArray[^>]*Name=['\"]%s['\"][^>]*format=['\"]ascii['\"][^>]*>([^<]*)<" % name, text)
        if not m:
            fail(f"{path}: no ASCII array '{name}' (write it with foamToVTK -ascii -fields '(p)')")
        return np.array(m.group(1).split(), dtype=dtype)

    return (array("Points", float).reshape(-1, 3), array("connectivity", int),
            array("offsets", int), array("p", float))


def face_forces(points, connectivity, offsets, p, rho):
    """Per face: the force on the foil F_y = rho p A_y (A: the face's area vector as OpenFOAM
    orients a boundary face, out of the fluid, i.e. into the foil) and its spanwise extent."""
    starts = np.concatenate([[0], offsets[:-1]])
    fy, zlo, zhi = np.empty(len(offsets)), np.empty(len(offsets)), np.empty(len(offsets))
    for f, (a, b) in enumerate(zip(starts, offsets)):
        q = points[connectivity[a:b]]
        c = q.mean(axis=0)
        area = 0.5 * np.cross(q - c, np.roll(q, -1, axis=0) - c).sum(axis=0)
        fy[f] = rho * p[f] * area[1]
        zlo[f], zhi[f] = q[:, 2].min(), q[:, 2].max()
    return fy, zlo, zhi


def lift_outboard(fy, zlo, zhi, stations):
    """-F_y carried outboard of each station, every face's force spread evenly over [zlo, zhi]."""
    width = zhi - zlo
    out = np.empty(len(stations))
    for i, z in enumerate(stations):
        share = np.where(width > 0, np.clip((zhi - z) / np.where(width > 0, width, 1), 0, 1),
                         (0.5 * (zlo + zhi) >= z).astype(float))
        out[i] = -(fy * share).sum()
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("vtp", nargs="+")
    ap.add_argument("--rho", type=float, default=998.2, help="density [kg/m^3] (default 998.2)")
    ap.add_argument("--step", type=float, default=5e-3, help="station spacing [m] (default 5e-3)")
    ap.add_argument("--span", type=float, default=0.1, help="last station [m] (default 0.1)")
    a = ap.parse_args(argv)
    if not (a.rho > 0 and a.step > 0 and a.span > 0 and a.span / a.step <= 10000):
        fail("--rho, --step and --span must be > 0 (and span / step <= 10000)")
    stations = np.arange(0.0, a.span + 0.5 * a.step, a.step)
    curves, totals = [], []
    for path in a.vtp:
        fy, zlo, zhi = face_forces(*read_patch(path), a.rho)
        curves.append(lift_outboard(fy, zlo, zhi, stations))
        totals.append((-fy.sum(), (-fy * 0.5 * (zlo + zhi)).sum() / -fy.sum()))
    print("z [m]  " + " ".join(f"lift>z[{i}]" for i in range(len(a.vtp))) +
          "".join(f"  [{i}]/[{i - 1}]-1" for i in range(1, len(a.vtp))))
    for k, z in enumerate(stations):
        ratios = "".join(f"  {c[k] / prev[k] - 1:+10.4f}" if prev[k] != 0 else "         nan"
                         for prev, c in zip(curves, curves[1:]))
        print(f"{z:6.4f} " + " ".join(f"{c[k]:10.5f}" for c in curves) + ratios)
    for i, (path, (total, zc)) in enumerate(zip(a.vtp, totals)):
        print(f"[{i}] {path}: pressure lift {total:.5f} N, centre z_c {zc:.5f} m")


if __name__ == "__main__":
    main()
