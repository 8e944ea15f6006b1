#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Twist, heave and camber of the foil's sections from a coupled run's interface displacement.

    sectionShape.py CSV [CSV ...] [--stations 0.03,0.05,0.07,0.09] [--half-width 2.5e-3]

CSV: an interface file of solid-app (results/RUN/interface/level_NNNN.csv: the wetted nodes'
x,y,z,ux,uy,uz[,fx,fy,fz], a comment line first). For each spanwise station z_s [m] it fits, by
least squares over the wetted nodes with |z - z_s| <= half-width,
    u_y = a + b X + c X^2 + d dz + e X dz + f dz^2,   X = x - 0.3685 (the quarter chord),
                                                        dz = z - z_s
and prints one line per file and station:
    twist_deg   b in degrees: the section's rotation about z (nose towards -y negative, the sign
                of the case's tip AOA);
    heave_mm    a: the quarter chord's deflection in y [mm];
    camber_mm   c (chord/2)^2: how far the leading and trailing edges move in y against
                mid-chord, the section's own bending [mm] (0 for a rigid section motion);
    points      nodes in the slab;  rms_um  the fit's rms residual [um].
A beam's motion (sections that turn and deflect, the twist linear and the deflection
quadratic in z across the slab) gives camber 0 and the twist and heave exactly. So that the section-shape figures of cases/hydrofoil/README.md ("The
structure's share of the coupled mesh study") come from a script. Exits 2 with a one-line error
when a file cannot be read, lacks a column, or a slab has fewer than 8 nodes.
"""
import argparse
import csv
import math
import sys

import numpy as np

X_QC, CHORD = 0.3685, 0.05


def fail(message):
    print("error: sectionShape.py: " + message, file=sys.stderr)
    sys.exit(2)


def read_interface(path):
    """(points, displacements) of an interface CSV: two (n, 3) arrays."""
    try:
        with open(path, newline="") as f:
            lines = [line for line in f if not line.startswith("#")]
    except OSError as e:
        fail(f"cannot read {path} ({e.strerror})")
    rows = list(csv.DictReader(lines))
    need = ["x", "y", "z", "ux", "uy", "uz"]
    if not rows or any(k not in rows[0] for k in need):
        fail(f"{path}: needs the columns {','.join(need)} (an interface/level_NNNN.csv of solid-app)")
    try:
        a = np.array([[float(r[k]) for k in need] for r in rows])
    except (TypeError, ValueError) as e:
        fail(f"{path}: a row of {','.join(need)} is not all numbers ({e})")
    return a[:, :3], a[:, 3:]


def section_shape(points, disp, z_station, half_width):
    """The station's fit: dict twist_deg, heave_mm, camber_mm, points, rms_um."""
    x, z = points[:, 0], points[:, 2]
    m = np.abs(z - z_station) <= half_width
    if m.sum() < 8:
        raise ValueError(f"station z = {z_station} m has {int(m.sum())} nodes within "
                         f"{half_width} m (give a larger --half-width)")
    X, dz, uy = x[m] - X_QC, z[m] - z_station, disp[m, 1]
    A = np.stack([np.ones_like(X), X, X ** 2, dz, X * dz, dz ** 2], axis=1)
    coef, *_ = np.linalg.lstsq(A, uy, rcond=None)
    residual = uy - A @ coef
    return {"twist_deg": math.degrees(coef[1]), "heave_mm": 1e3 * coef[0],
            "camber_mm": 1e3 * coef[2] * (CHORD / 2) ** 2, "points": int(m.sum()),
            "rms_um": 1e6 * float(np.sqrt(np.mean(residual ** 2)))}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("csv", nargs="+")
    p.add_argument("--stations", default="0.03,0.05,0.07,0.09",
                   help="spanwise stations z [m], comma-separated")
    p.add_argument("--half-width", type=float, default=2.5e-3,
                   help="half-width of each station's slab [m] (default 2.5e-3)")
    a = p.parse_args(argv)
    try:
        stations = [float(s) for s in a.stations.split(",")]
    except ValueError:
        fail(f"--stations '{a.stations}' must be numbers in m separated by commas, e.g. 0.05,0.09")
    if not a.half_width > 0:
        fail(f"--half-width {a.half_width} must be > 0, e.g. 2.5e-3")
    for path in a.csv:
        points, disp = read_interface(path)
        for zs in stations:
            try:
                s = section_shape(points, disp, zs, a.half_width)
            except ValueError as e:
                fail(f"{path}: {e}")
            print(f"{path} z={zs:g} twist_deg={s['twist_deg']:.5f} heave_mm={s['heave_mm']:.5f} "
                  f"camber_mm={s['camber_mm']:.5f} points={s['points']} rms_um={s['rms_um']:.3g}")


if __name__ == "__main__":
    main()
