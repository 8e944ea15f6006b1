#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The Prony rule's time-step error on a schedule, in a one-variable model of the hydrofoil.

Not the toolkit's solver: a model that shows how large the error of the Prony recursion's
strain interpolation (prony.integration linear | quadratic, material/Viscoelastic.hpp) is on a
given schedule of levels (cases/hydrofoil/README.md, "The Prony rule on long steps").

One twist variable e (the tip twist, deg) with the case's Prony series (gamma 0.1484 0.2115
0.1993, tau 4.130 81.95 1610 s, long-term modulus 1) under a load that grows with the twist,
    G0-weighted stress = m0 + m1 e,
m1 and m0 chosen so that the instantaneous and the fully relaxed elastic states are the case's
t = 0 and relaxed tip twists (3.20 and 7.77 deg: baseline and relaxed.yaml), and a lift linear
in e through the t = 0 and relaxed lifts (2.37 and 0.42 N). Each level solves the model
implicitly with the chosen rule; the error is against the same model on 44 000 steps.

CLI: prony-step-model.py HISTORY.csv [HISTORY.csv ...]  (a results/visco/history.csv: its
     `time` column is the schedule) -> the lift error [%] at each level for both rules.
     prony-step-model.py --max-step S  -> the case's 19-level schedule and one with late steps
     of at most S seconds instead.
"""
import csv
import sys

import numpy as np

GAMMA = np.array([0.1484, 0.2115, 0.1993])
TAU = np.array([4.130, 81.95, 1610.0])
G0 = 1.0 + GAMMA.sum()  # instantaneous / long-term
TWIST0, TWIST_INF = 3.20, 7.77  # deg
LIFT0, LIFT_INF = 2.37, 0.42  # N
# e0 = m0 / (G0 - m1), e_inf = m0 / (1 - m1)
M1 = (TWIST_INF - G0 * TWIST0) / (TWIST_INF - TWIST0)
M0 = TWIST0 * (G0 - M1)
CASE_SCHEDULE = [0, 0.5, 2, 6.04327, 16.5037, 28.9474, 50, 92.648, 195.278, 277.639, 360,
                 471.563, 632.113, 885.009, 1381.85, 1851.13, 2473.54, 3038.69, 3600]


def lift(twist):
    return LIFT0 + (LIFT_INF - LIFT0) * (twist - TWIST0) / (TWIST_INF - TWIST0)


def solve(times, quadratic):
    """Twist at each level of `times` (from 0) with the linear or the quadratic strain rule."""
    e = M0 / (G0 - M1)
    h = GAMMA * e  # the terms' stresses after the instantaneous level
    twist, rate, previous_dt = [e], 0.0, 0.0
    for n in range(1, len(times)):
        dt = times[n] - times[n - 1]
        xi = dt / TAU
        phi = -np.expm1(-xi) / xi
        psi = 2.0 * (1.0 - phi) / xi - phi
        w = dt / (previous_dt + dt) if quadratic and previous_dt > 0 else 0.0
        a = GAMMA * (phi + w * psi)  # coefficient of the change D of the base stress
        b = -GAMMA * w * psi * dt * rate  # the previous rate's part
        # e_new + sum(exp(-xi) h + a (e_new - e) + b) = m0 + m1 e_new
        en = twist[-1]
        e_new = (M0 - np.sum(np.exp(-xi) * h - a * en + b)) / (1.0 + a.sum() - M1)
        h = np.exp(-xi) * h + a * (e_new - en) + b
        rate, previous_dt = (e_new - en) / dt, dt
        twist.append(e_new)
    return np.array(twist)


def errors(times):
    fine = np.concatenate([np.linspace(0, 10, 4001), np.linspace(10, times[-1], 40000)[1:]])
    exact = np.interp(times, fine, lift(solve(fine, False)))
    return {rule: 100 * (lift(solve(times, rule == "quadratic")) - exact) / exact
            for rule in ("linear", "quadratic")}


def report(name, times):
    err = errors(np.array(times, dtype=float))
    for rule, e in err.items():
        print(f"{name} ({len(times)} levels), {rule:9s}: lift error at {times[-1]:g} s "
              f"{e[-1]:+.3f} %, largest over the levels {np.abs(e).max():.3f} %")


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv else 2
    if argv[0] == "--max-step":
        cap = float(argv[1])
        report("the case's schedule", CASE_SCHEDULE)
        capped = [t for t in CASE_SCHEDULE if t <= 100] + \
            [t for t in np.arange(100 + cap, 3600, cap)] + [3600]
        report(f"late steps of at most {cap:g} s", sorted(set(capped)))
        return 0
    for path in argv:
        times = [float(r["time"]) for r in csv.DictReader(open(path))]
        report(path, times)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
