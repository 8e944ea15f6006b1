#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Band, mean and period of a force over the last iterations of a steady solve.

    iterationBand.py CSV [--column Fy] [--last 300] [--step S --iteration I]

CSV: fluid-app's per-iteration force history, postProcessing/fsi/rigidIterations.csv (a rigid
solve: columns iteration,Fx,Fy,Fz,...) or postProcessing/fsi/solveIterations.csv (every SOLVE
of a coupled run: step,iteration,simpleIteration,Fx,...; choose one with --step and
--iteration, default the last). Over the last N iterations (--last, default 300) of the chosen
column (default Fy, the lift's component) it prints one line of key=value pairs:
    iterations  how many rows the solve has;  window  the N used
    mean        the plain mean over the window;  min max
    band        (max - min) / (2 |mean|): the half-width relative to the mean (fsiDict
                bandTolerance's measure)
    drift       (mean of the window's second half - mean of its first half) / |mean|
    period      the lag (>= 2 iterations) of the largest autocorrelation of the window's
                fluctuation, when that correlation is >= 0.5 (a clean cycle), else 0
So that the oscillations quoted in cases/hydrofoil/README.md (e.g. the medium cgrid rigid
solve's period-6 cycle) come from a script, not from inline numpy. Exits 2 with a one-line
error when the file, the column or the solve is missing or the window is too short.
"""
import argparse
import csv
import sys

import numpy as np


def fail(message):
    sys.exit("error: iterationBand.py: " + message)


def read_series(path, column, step=None, iteration=None):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        fail(f"cannot read {path} ({e.strerror})")
    if not rows:
        fail(f"{path}: no rows")
    if column not in rows[0]:
        fail(f"{path}: no column '{column}' (have {', '.join(rows[0])})")
    if "step" in rows[0]:  # solveIterations.csv: pick one SOLVE
        solves = [(int(r["step"]), int(r["iteration"])) for r in rows]
        chosen = (step if step is not None else solves[-1][0],
                  iteration if iteration is not None else
                  max(i for s, i in solves if s == (step if step is not None else solves[-1][0])))
        rows = [r for r, key in zip(rows, solves) if key == chosen]
        if not rows:
            fail(f"{path}: no SOLVE step {chosen[0]} iteration {chosen[1]}")
    elif step is not None or iteration is not None:
        fail(f"{path}: --step/--iteration need a solveIterations.csv (a rigid history has one solve)")
    # a run still writing may have a partial last line
    values = []
    for r in rows:
        try:
            values.append(float(r[column]))
        except (TypeError, ValueError):
            break
    return np.array(values)


def band_summary(values, last):
    """The key=value figures of the docstring for the last `last` values."""
    if last < 8:
        fail(f"--last {last}: at least 8 iterations are needed")
    if len(values) < last:
        fail(f"the solve has {len(values)} iterations, fewer than --last {last}")
    w = values[-last:]
    mean = float(np.mean(w))
    if mean == 0.0:
        fail("the window's mean is 0: no relative band")
    half = last // 2
    drift = (float(np.mean(w[half:])) - float(np.mean(w[:half]))) / abs(mean)
    x = w - mean
    period = 0
    if np.dot(x, x) > 0.0:
        corr = [np.dot(x[:-k], x[k:]) / np.dot(x, x) for k in range(2, last // 4 + 1)]
        k = int(np.argmax(corr))
        if corr[k] >= 0.5:
            period = k + 2
    return {"iterations": len(values), "window": last, "mean": mean, "min": float(w.min()),
            "max": float(w.max()), "band": (float(w.max()) - float(w.min())) / (2.0 * abs(mean)),
            "drift": drift, "period": period}


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("csv")
    p.add_argument("--column", default="Fy")
    p.add_argument("--last", type=int, default=300)
    p.add_argument("--step", type=int)
    p.add_argument("--iteration", type=int)
    a = p.parse_args(argv)
    s = band_summary(read_series(a.csv, a.column, a.step, a.iteration), a.last)
    print(" ".join(f"{k}={v:.8g}" if isinstance(v, float) else f"{k}={v}" for k, v in s.items()))


if __name__ == "__main__":
    main(sys.argv[1:])
