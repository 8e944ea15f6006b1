#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Aitken relaxation (paper eq. 10) on non-normal linear interface maps u -> H u + b.

Compares the two policies of coupling.acceleration.aitken.negative_factor on random problems
H = Q diag(lambda) Q^-1 (Q = I + s G, G Gaussian, s in [0.1, 1]: non-normal), every eigenvalue
below 1, with relative noise on each evaluation (an inexact fluid):
  keep     the literal eq. 10: the factor's sign is kept (|omega| clamped to [1e-3, 1])
  restart  a factor <= 0 restarts from omega_0 (the solver's default)
Prints one line per spectrum: problems that did not reach |r| < tol |u*| within the cap, and
the mean iterations of those that did. Figures only; run: python3 aitken_model.py [--seed N]
"""
import argparse

import numpy as np


def aitken_level(h, b, policy, noise, tol, max_iterations, rng, omega0=0.5):
    """Iterations to |r| < tol |u*|, or None when not converged within max_iterations."""
    n = len(b)
    exact = np.linalg.solve(np.eye(n) - h, b)
    scale = np.linalg.norm(exact)
    u, omega, previous = np.zeros(n), omega0, None
    for iteration in range(1, max_iterations + 1):
        output = h @ u + b + noise * scale * rng.standard_normal(n) / np.sqrt(n)
        r = output - u
        if np.linalg.norm(r) < tol * scale:
            return iteration
        if previous is not None:
            change = r - previous
            factor = -omega * previous.dot(change) / change.dot(change)
            if factor <= 0.0 and policy == "restart":
                omega = omega0
            else:
                omega = np.copysign(min(max(abs(factor), 1e-3), 1.0), factor)
        u, previous = u + omega * r, r
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--problems", type=int, default=60)
    parser.add_argument("--size", type=int, default=30)
    args = parser.parse_args()
    for low, high, noise in ((-0.3, 0.7, 1e-5), (-0.5, 0.9, 1e-5), (0.0, 0.95, 1e-6),
                             (-0.9, 0.5, 1e-5)):
        rng = np.random.default_rng(args.seed)
        results = {"keep": [], "restart": []}
        for _ in range(args.problems):
            q = np.eye(args.size) + rng.standard_normal((args.size, args.size)) * rng.uniform(0.1, 1.0)
            h = q @ np.diag(rng.uniform(low, high, args.size)) @ np.linalg.inv(q)
            b = rng.standard_normal(args.size)
            for policy in results:
                results[policy].append(aitken_level(h, b, policy, noise, 1e-3, 400, rng))
        line = [f"aitken-model: lambda=[{low},{high}] noise={noise:g} problems={args.problems}"]
        for policy, its in results.items():
            done = [k for k in its if k is not None]
            mean = np.mean(done) if done else float("nan")
            line.append(f"{policy}_failed={len(its) - len(done)} {policy}_mean_iterations={mean:.1f}")
        print(" ".join(line))


if __name__ == "__main__":
    main()
