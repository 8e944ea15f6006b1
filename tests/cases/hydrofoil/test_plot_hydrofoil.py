#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks of scripts/plot_hydrofoil.py's tip-section outline (the paper's Fig. 5) and of its
summary's late lift change.
Run: /usr/bin/python3 tests/cases/hydrofoil/test_plot_hydrofoil.py"""
import os
import sys
import tempfile
import types
import unittest

import numpy as np
from matplotlib.path import Path

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import plot_hydrofoil as ph  # noqa: E402


def face_nodes(boundary, h, seed=1):
    """Boundary nodes (closed polygon, in order) plus jittered interior nodes about h apart,
    none closer than h/2 to the boundary polygon: the nodes of a meshed planar face."""
    rng = np.random.default_rng(seed)
    path = Path(boundary)
    lo, hi = boundary.min(axis=0), boundary.max(axis=0)
    gx, gy = np.meshgrid(np.arange(lo[0], hi[0], h), np.arange(lo[1], hi[1], h))
    inner = np.column_stack([gx.ravel(), gy.ravel()]) + rng.uniform(-0.2, 0.2, (gx.size, 2)) * h
    inner = inner[path.contains_points(inner)]
    a, b = boundary, np.roll(boundary, -1, axis=0)  # the boundary's segments a -> b
    w = np.clip(np.einsum("pij,ij->pi", inner[:, None, :] - a[None], b - a) /
                np.einsum("ij,ij->i", b - a, b - a), 0.0, 1.0)
    foot = a[None] + w[..., None] * (b - a)[None]
    inner = inner[np.min(np.linalg.norm(inner[:, None, :] - foot, axis=2), axis=1) > 0.5 * h]
    pts = np.vstack([boundary, inner])
    perm = rng.permutation(len(pts))  # node numbers in no particular order
    return pts[perm], np.argsort(perm)[: len(boundary)]


def segments_cross(p, q, r, s):
    def orient(a, b, c):
        return np.sign((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    return orient(p, q, r) * orient(p, q, s) < 0 and orient(r, s, p) * orient(r, s, q) < 0


class Outline(unittest.TestCase):
    def check(self, boundary, h):
        pts, boundary_ids = face_nodes(boundary, h)
        upper, lower = ph.section_outline(pts)
        loop = upper + lower[::-1][1:-1]
        # exactly the boundary nodes, each once, in the boundary's cyclic order
        self.assertEqual(sorted(loop), sorted(boundary_ids.tolist()))
        self.assertEqual(len(set(loop)), len(loop))
        position = {int(n): k for k, n in enumerate(boundary_ids)}
        steps = [(position[loop[(k + 1) % len(loop)]] - position[loop[k]]) % len(loop)
                 for k in range(len(loop))]
        self.assertTrue(all(s == steps[0] for s in steps) and steps[0] in (1, len(loop) - 1))
        # closed and not self-intersecting
        poly = pts[loop]
        n = len(poly)
        for i in range(n):
            for j in range(i + 2, n):
                if i == 0 and j == n - 1:
                    continue  # the closing segment shares node 0
                self.assertFalse(segments_cross(poly[i], poly[(i + 1) % n], poly[j],
                                                poly[(j + 1) % n]), (i, j))
        # surfaces: both from the leading edge to the trailing edge, upper above lower
        self.assertEqual(upper[0], lower[0])
        self.assertEqual(upper[-1], lower[-1])
        self.assertAlmostEqual(pts[upper[0], 0], pts[:, 0].min(), delta=1e-15)
        self.assertAlmostEqual(pts[upper[-1], 0], pts[:, 0].max(), delta=1e-15)
        self.assertGreater(np.mean(pts[upper, 1]), np.mean(pts[lower, 1]))
        return pts, upper, lower

    def test_ellipse(self):
        t = np.linspace(0.0, 2.0 * np.pi, 80, endpoint=False)
        self.check(np.column_stack([0.025 * np.cos(t), 0.006 * np.sin(t)]), 0.002)

    def test_cambered_section_with_concave_lower_surface(self):
        # thickness 12 %, camber 8 % (parabolic): the lower surface is concave
        c = 0.05
        x = c * 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, 60)))
        yt = 0.12 * c * 5.0 * (0.2969 * np.sqrt(x / c) - 0.126 * x / c - 0.3516 * (x / c) ** 2
                               + 0.2843 * (x / c) ** 3 - 0.1036 * (x / c) ** 4)
        yc = 0.08 * c * 4.0 * (x / c) * (1.0 - x / c)
        up = np.column_stack([x, yc + yt])
        lo = np.column_stack([x, yc - yt])
        boundary = np.vstack([lo, up[::-1][1:-1]])  # LE, lower to the TE, upper back
        pts, upper, lower = self.check(boundary, 0.0015)
        # the lower surface is concave: its middle nodes lie above the LE-TE chord line
        mid = pts[lower[len(lower) // 2]]
        self.assertGreater(mid[1], 0.0)


class Figure(unittest.TestCase):
    def test_tip_sections_equal_axis_scales(self):
        """draw_tip_sections on a synthetic run: closed curves and equal data scales on x, y."""
        import matplotlib.pyplot as plt
        t = np.linspace(0.0, 2.0 * np.pi, 40, endpoint=False)
        pts, _ = face_nodes(np.column_stack([0.356 + 0.025 * (1 + np.cos(t)), 0.004 * np.sin(t)]),
                            0.002)
        with tempfile.TemporaryDirectory() as res:
            os.makedirs(os.path.join(res, "visco", "interface"))
            for level, time in ((0, 0.0), (1, 50.0)):
                with open(os.path.join(res, "visco", "interface", "level_%04d.csv" % level),
                          "w") as f:
                    f.write("# level %d time %g s\nx,y,z,ux,uy,uz,fx,fy,fz\n" % (level, time))
                    for z in (0.09, 0.1):
                        for p in pts:
                            uy = 0.002 * level * (p[0] - 0.356) / 0.05  # a twist
                            f.write("%r,%r,%r,0,%r,0,0,0,0\n" % (p[0], p[1], z, uy))
            fig, ax = plt.subplots(figsize=(7.5, 3.6))
            a = types.SimpleNamespace(span_axis=2, shape_times="0,50")
            ph.draw_tip_sections(ax, res, a, "x", "y")
            fig.tight_layout()
            fig.canvas.draw()
            lines = ax.get_lines()
            self.assertEqual(len(lines), 3)  # undeformed, t = 0, t = 50
            for line in lines:
                xs, ys = line.get_data()
                self.assertEqual((xs[0], ys[0]), (xs[-1], ys[-1]))  # closed
                self.assertEqual(len(xs), 41)  # the 40 outline nodes of the tip face only
            (x0, y0), (x1, y1) = ax.transData.transform([(0.0, 0.0), (1.0, 1.0)])
            self.assertAlmostEqual((x1 - x0) / (y1 - y0), 1.0, delta=1e-9)
            plt.close(fig)


class LateChange(unittest.TestCase):
    def test_one_level_in_the_window_is_not_steady(self):
        # the case's last step 3 038 -> 3 600 s: only the final level lies in the last 10 %;
        # the lift at 3 240 s is interpolated: 0.70 - 0.01 * 202 / 562
        t, lift = [0.0, 3038.0, 3600.0], [2.0, 0.70, 0.69]
        expected = (0.70 - 0.01 * 202.0 / 562.0 - 0.69) / 0.69
        self.assertAlmostEqual(ph.late_change(t, lift), expected, delta=1e-12)

    def test_levels_inside_the_window_count(self):
        t, lift = [0.0, 3000.0, 3300.0, 3500.0, 3600.0], [2.0, 1.0, 1.3, 0.9, 1.0]
        # window from 3 240 s: interpolated 1.24, then 1.3, 0.9, 1.0
        self.assertAlmostEqual(ph.late_change(t, lift), (1.3 - 0.9) / 1.0, delta=1e-12)


if __name__ == "__main__":
    unittest.main(verbosity=2)
