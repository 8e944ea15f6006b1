#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""State of the boundary layers of a solved 2-D section case: laminar or turbulent, where.

    blstate.py CASE OUT_CSV

CASE is a run2d.sh case after its post-processing (ASCII fields in the latest time folder:
nut and the cell centres C; the foil's wall shear stress sampled as
postProcessing/foilSurface/<time>/wallShearStress_foil.raw). Writes OUT_CSV, one row per foil
face: side (pressure | suction: the suction side is the one with the lower mean wall pressure),
x_c (x/c from the leading edge), cf (|tau_w| / q, negative where the flow near the wall runs
upstream), cf_turb (flat-plate turbulent
0.0592 Re_x^-0.2), cf_lam (Blasius 0.664 Re_x^-0.5), nut_ratio_max (max nu_t/nu of the cells
within 2 mm of the wall whose nearest foil face is this face). Prints per side the first x/c
from which nu_t/nu stays above 1 in the boundary layer (the boundary layer turns turbulent
there; a laminar layer carries only the small free-stream value, limited by the shear) and
the mean |cf| / cf_turb over 0.2 <= x/c <= 0.8, and the first x/c > 0.1 with reversed flow
(separation); last line "blstate-onsets: TURB_SUCTION SEP_SUCTION TURB_PRESSURE SEP_PRESSURE".
Units SI; chord 0.05 m, leading edge at x = 0.356 m, U = 2 m/s, nu = 1.004e-6 m^2/s.
"""
import glob
import math
import os
import re
import sys

import numpy as np
from scipy.spatial import cKDTree

CHORD, X_LE, U, NU = 0.05, 0.356, 2.0, 1.004e-6
BAND = 2e-3          # m: cells this close to the wall count as boundary layer


def latestTime(case):
    times = [d for d in os.listdir(case) if re.fullmatch(r"[0-9.eE+-]+", d) and d != "0"]
    if not times:
        sys.exit("blstate.py: %s has no time folder besides 0" % case)
    return max(times, key=float)


def internalField(path):
    """ASCII OpenFOAM field: the internalField list as an array (scalars or vectors)."""
    s = open(path, errors="replace").read()
    if re.search(r"\bformat\s+binary\s*;", s[:2000]):
        sys.exit("blstate.py: %s is binary; run2d.sh sets writeFormat ascii (controlDict) for it" % path)
    m = re.search(r"internalField\s+nonuniform\s+List<(scalar|vector)>\s*(\d+)\s*\(", s)
    if not m:
        sys.exit("blstate.py: %s: no ASCII nonuniform internalField (writeFormat ascii needed)" % path)
    n = int(m.group(2))
    body = s[m.end():]
    if m.group(1) == "scalar":
        return np.array(body.split(None, n)[:n], dtype=float)
    nums = re.findall(r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?", body[:body.find("\n)\n")])
    return np.array(nums[:3 * n], dtype=float).reshape(n, 3)


def main(case, outCsv):
    t = latestTime(case)
    cc = internalField(os.path.join(case, t, "C"))[:, :2]
    nutPath = os.path.join(case, t, "nut")   # absent for the laminar model: nu_t = 0
    nut = internalField(nutPath) if os.path.exists(nutPath) else np.zeros(len(cc))
    raws = sorted(glob.glob(os.path.join(case, "postProcessing/foilSurface/*/wallShearStress_foil.raw")))
    praw = sorted(glob.glob(os.path.join(case, "postProcessing/foilSurface/*/p_foil.raw")))
    if not raws or not praw:
        sys.exit("blstate.py: %s: no postProcessing/foilSurface/*/{wallShearStress,p}_foil.raw" % case)
    tau = np.loadtxt(raws[-1], comments="#")
    pw = np.loadtxt(praw[-1], comments="#")
    xf, yf = tau[:, 0], tau[:, 1]
    # kinematic tau_w / (U^2/2), signed: negative where the near-wall flow runs against x
    # (OpenFOAM's wallShearStress points against the near-wall velocity)
    cf = -np.sign(tau[:, 3]) * np.hypot(tau[:, 3], tau[:, 4]) / (0.5 * U * U)
    # sides: split at the leading and trailing edge along the camber (faces ordered by x)
    xc = (xf - X_LE) / CHORD
    order = np.argsort(xf)
    # camber y at x: midpoint of the two faces' y nearest in x, via the mean y of the band
    side = np.empty(len(xf), dtype=object)
    for i in range(len(xf)):
        near = np.abs(xf - xf[i]) < 0.02 * CHORD
        side[i] = "upper" if yf[i] >= 0.5 * (yf[near].max() + yf[near].min()) else "lower"
    pmap = {tuple(np.round(r[:2], 9)): r[3] for r in pw}
    pf = np.array([pmap.get(tuple(np.round((x, y), 9)), np.nan) for x, y in zip(xf, yf)])
    pUpper, pLower = np.nanmean(pf[side == "upper"]), np.nanmean(pf[side == "lower"])
    suction = "upper" if pUpper < pLower else "lower"
    names = np.where(side == suction, "suction", "pressure")
    # boundary-layer cells: nearest foil face within BAND
    d, idx = cKDTree(np.column_stack([xf, yf])).query(cc, distance_upper_bound=BAND)
    inBand = np.isfinite(d)
    ratio = np.zeros(len(xf))
    np.maximum.at(ratio, idx[inBand], nut[inBand] / NU)
    rex = np.maximum(xc, 1e-6) * CHORD * U / NU
    cfT, cfL = 0.0592 * rex ** -0.2, 0.664 * rex ** -0.5
    with open(outCsv, "w") as f:
        f.write("side,x_c,cf,cf_turb,cf_lam,nut_ratio_max\n")
        for i in order:
            f.write("%s,%.5f,%.6g,%.6g,%.6g,%.5g\n" % (names[i], xc[i], cf[i], cfT[i], cfL[i], ratio[i]))
    onsets = {}
    for s in ("suction", "pressure"):
        sel = [i for i in order if names[i] == s]
        onset = float("nan")
        for j, i in enumerate(sel):
            if ratio[i] > 1.0 and all(ratio[k] > 1.0 for k in sel[j:] if xc[k] < 0.98):
                onset = xc[i]
                break
        mid = [i for i in sel if 0.2 <= xc[i] <= 0.8]
        sep = next((xc[i] for i in sel if xc[i] > 0.1 and cf[i] < 0), float("nan"))
        print("blstate: %s side: nu_t/nu > 1 in the boundary layer from x/c = %.3f; "
              "cf / cf_turb over x/c 0.2-0.8 = %.3f (laminar would be %.3f); nu_t/nu max %.1f; "
              "reversed flow (cf < 0) from x/c = %.3f"
              % (s, onset, np.mean(np.abs(cf[mid]) / cfT[mid]), np.mean(cfL[mid] / cfT[mid]),
                 ratio[sel].max(), sep))
        onsets[s] = (onset, sep)
    print("blstate-onsets: %.4f %.4f %.4f %.4f" % (onsets["suction"] + onsets["pressure"]))


if __name__ == "__main__":
    if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        sys.exit(0)
    if len(sys.argv) != 3:
        sys.exit("usage: blstate.py CASE OUT_CSV")
    main(*sys.argv[1:])
