#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Force convergence of a steady (SIMPLE) run from the OpenFOAM `forces` function object.

    forceConvergence.py CASE [--window 20] [--tol 1e-3] [--log log.simpleFoam]

Criterion (README, "Flow model and discretisation"): the solve is force-converged at the first
iteration n at which, for every component c of the total force F (x, y, z),
    max_{n-W <= i <= n} |F_c(i) - F_c(n)|  <=  tol * max(|F_c(n)|, 0.05 |F(n)|)
with the window W = 20 iterations and tol = 1e-3: each component varied by less than 0.1 % of
itself over the last 20 iterations (the floor 5 % of |F| keeps the near-zero spanwise
component from demanding an absolute accuracy the others do not have).
Prints one line of key=value pairs; with --log also the wall time per iteration from the
solver log (ExecutionTime between iteration 10 and the last one, so start-up is excluded).
"""
import argparse
import glob
import os
import re
import sys

import numpy as np


def readForces(case):
    files = sorted(glob.glob(os.path.join(case, "postProcessing", "forces", "*", "force*.dat")))
    if not files:
        raise RuntimeError(f"forceConvergence.py: no postProcessing/forces/*/force.dat in {case}; "
                           "run the solver with the forces function object of system/controlDict")
    rows = {}
    for path in files:
        with open(path) as f:
            for line in f:
                if line.startswith("#") or not line.strip():
                    continue
                w = line.replace("(", " ").replace(")", " ").split()
                rows[float(w[0])] = [float(v) for v in w[1:10]]
    it = np.array(sorted(rows))
    data = np.array([rows[t] for t in it])
    return it, data[:, 0:3], data[:, 3:6], data[:, 6:9]  # total, pressure, viscous


def convergedAt(it, force, window=20, tol=1e-3):
    mag = np.linalg.norm(force, axis=1)
    for n in range(window, len(it)):
        ref = np.maximum(np.abs(force[n]), 0.05 * mag[n])
        dev = np.max(np.abs(force[n - window:n + 1] - force[n]), axis=0)
        if np.all(dev <= tol * ref):
            return n
    return None


def wallPerIteration(logPath, skip=10):
    """(CPU s, wall s) per iteration from 'ExecutionTime = a s  ClockTime = b s' lines."""
    cpu, wall = [], []
    with open(logPath) as f:
        for line in f:
            m = re.match(r"ExecutionTime = ([0-9.eE+-]+) s\s+ClockTime = ([0-9.eE+-]+) s", line)
            if m:
                cpu.append(float(m.group(1)))
                wall.append(float(m.group(2)))
    if len(cpu) <= skip + 1:
        return None, None
    k = len(cpu) - 1 - skip
    return (cpu[-1] - cpu[skip]) / k, (wall[-1] - wall[skip]) / k


def main(argv):
    p = argparse.ArgumentParser()
    p.add_argument("case")
    p.add_argument("--window", type=int, default=20)
    p.add_argument("--tol", type=float, default=1e-3)
    p.add_argument("--log", default=None)
    a = p.parse_args(argv)
    it, total, pres, visc = readForces(a.case)
    n = convergedAt(it, total, a.window, a.tol)
    last = total[-1]
    out = [f"iterations={int(it[-1])}"]
    if n is None:
        tail = total[-min(100, len(total)):]
        out.append("converged_at=none")
        out.append("last100_range_Fx=%.4g last100_range_Fy=%.4g last100_range_Fz=%.4g"
                   % tuple(np.ptp(tail, axis=0)))
    else:
        out.append(f"converged_at={int(it[n])}")
        out.append("Fx=%.5g Fy=%.5g Fz=%.5g" % tuple(total[n]))
    out.append("final_Fx=%.5g final_Fy=%.5g final_Fz=%.5g" % tuple(last))
    out.append("final_pressure=(%.4g %.4g %.4g) final_viscous=(%.4g %.4g %.4g)"
               % (tuple(pres[-1]) + tuple(visc[-1])))
    out.append("lift=-Fy=%.5g drag=Fx=%.5g" % (-last[1], last[0]))
    if a.log:
        cpu, clock = wallPerIteration(a.log)
        if cpu is not None:
            out.append(f"cpu_s_per_iteration={cpu:.4f} wall_s_per_iteration={clock:.4f}")
    print(" ".join(out))
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except RuntimeError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
