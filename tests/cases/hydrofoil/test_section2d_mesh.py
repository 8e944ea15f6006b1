#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""cases/hydrofoil/section2d/mesh2d.py: the C-grid levels are valid and a systematic refinement."""
import math
import os
import sys
import unittest

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "..", "cases", "hydrofoil", "section2d"))
sys.path.insert(0, os.path.join(here, "..", "..", "..", "cases", "hydrofoil", "geometry"))
import mesh2d  # noqa: E402
import naca66a08  # noqa: E402


def minAngleDeg(xy, cells):
    p = xy[cells]
    worst = 180.0
    for k in range(4):
        a = p[:, (k - 1) % 4] - p[:, k]
        b = p[:, (k + 1) % 4] - p[:, k]
        c = np.sum(a * b, axis=1) / np.hypot(a[:, 0], a[:, 1]) / np.hypot(b[:, 0], b[:, 1])
        worst = min(worst, float(np.degrees(np.arccos(np.clip(c, -1, 1))).min()))
    return worst


class Section2dMeshTest(unittest.TestCase):
    def check(self, level, te):
        g = mesh2d.build(level, 0.12, 0.5, "a08", te)
        xy, cells, edges, area = mesh2d.quads(g)
        # valid: every cell counter-clockwise with positive area, no sliver
        self.assertTrue(np.all(area > 0))
        self.assertGreater(minAngleDeg(xy, cells), 30.0)
        # the cells fill the tunnel minus the foil (the foil polygon of the mesh's own nodes)
        foilEdges = edges["foil"]
        nbr = {}
        for a, b in foilEdges:
            nbr.setdefault(a, []).append(b)
            nbr.setdefault(b, []).append(a)
        ring, prev = [foilEdges[0][0]], None
        while True:                       # walk the closed chain of foil edges
            nxt = [v for v in nbr[ring[-1]] if v != prev][0]
            if nxt == ring[0]:
                break
            prev = ring[-1]
            ring.append(nxt)
        self.assertEqual(len(ring), len(foilEdges))
        poly = xy[ring]
        foilArea = abs(0.5 * np.sum(poly[:, 0] * np.roll(poly[:, 1], -1)
                                    - np.roll(poly[:, 0], -1) * poly[:, 1]))
        tunnel = mesh2d.TUNNEL_L * mesh2d.TUNNEL_W
        self.assertAlmostEqual(area.sum() + foilArea, tunnel, delta=1e-9 * tunnel)
        # the foil area is the section's (the sharp trailing edge removes a sliver)
        up, lo = naca66a08.section(tc=0.12, cli=0.5, chord=mesh2d.CHORD, n=2001)
        exact = abs(naca66a08.polygonArea(naca66a08.sectionPolygon(up, lo)))
        if te == "sharp":
            # closing the trailing edge linearly in x/c removes the triangle 0.5 h_TE c
            exact -= 0.5 * float(np.hypot(*(up[-1] - lo[-1]))) * mesh2d.CHORD
        self.assertLess(abs(foilArea - exact) / exact, 2e-3)
        # every boundary edge is named, and the foil is closed (each node used twice)
        ids, counts = np.unique(np.array(foilEdges).ravel(), return_counts=True)
        self.assertTrue(np.all(counts == 2))
        # first-cell height on the foil's mid chord: y1 / sqrt(2)^level
        pts = g["pts"]
        iMid = g["iA"] + g["nSide"] // 2
        h1 = float(np.hypot(*(pts[iMid, 1] - pts[iMid, 0])))
        self.assertAlmostEqual(h1, mesh2d.Y1_0 / math.sqrt(2) ** level, delta=1e-3 * h1)
        return len(cells)

    def test_levels_are_valid_and_double_the_cells(self):
        for te in ("blunt", "sharp"):
            n0, n1, n2 = (self.check(k, te) for k in (0, 1, 2))
            for coarse, fine in ((n0, n1), (n1, n2)):
                self.assertAlmostEqual(fine / coarse, 2.0, delta=0.03)

    def test_station_spacing_at_the_edges(self):
        # f'(0) = 0.1 and f'(1) = teSpacing exactly (spacings in L/n). The end intervals times
        # n are f' + f''/(2n) + O(1/n^2); Richardson over n and 2n leaves O(1/n^2): 1e-4 at
        # n = 400.
        n = 400

        def ends(m, te):
            f = mesh2d.clustered(m, te)
            self.assertEqual(f[0], 0.0)
            self.assertAlmostEqual(f[-1], 1.0, delta=1e-14)
            self.assertTrue(np.all(np.diff(f) > 0))
            return (f[1] - f[0]) * m, (f[-1] - f[-2]) * m

        for te in (0.1, mesh2d.TE_SPACING, 0.1 + 0.15 * math.pi, 1.5):
            (le1, te1), (le2, te2) = ends(n, te), ends(2 * n, te)
            self.assertAlmostEqual(2 * le2 - le1, 0.1, delta=1e-4)
            self.assertAlmostEqual(2 * te2 - te1, te, delta=1e-4)
        with self.assertRaises(ValueError):
            mesh2d.clustered(n, 0.05)


if __name__ == "__main__":
    unittest.main()
