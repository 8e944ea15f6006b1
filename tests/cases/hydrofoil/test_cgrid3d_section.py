#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""cases/hydrofoil/tools/cgrid3d.py: the Gmsh triangulation of the section above the tip
shares every boundary node with the C-grid around it, on every preset (a node matched by
rounded coordinates once split a pair on the fine preset: 152 unnamed faces), and fills the
foil polygon exactly (areas equal to round-off); above the tip the re-spaced first cells beside
the triangles keep the size jump to them small on every preset (relaxedPlane)."""
import os
import sys
import tempfile
import unittest

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "..", "cases", "hydrofoil", "tools"))
import cgrid3d  # noqa: E402
import mesh2d  # noqa: E402  (cgrid3d put section2d on the path)
import naca66a08  # noqa: E402  (mesh2d put geometry on the path)


class CgridSectionTest(unittest.TestCase):
    def test_triangulation_matches_the_plane(self):
        for name in ("coarse", "medium", "fine"):
            g = mesh2d.build(0, 0.12, 0.5, "a08", "sharp", counts=cgrid3d.preset(name))
            xy, _, edges, _ = mesh2d.quads(g)
            loop = cgrid3d.foilLoop(edges["foil"])
            with tempfile.TemporaryDirectory() as d:
                extra, tri = cgrid3d.triangulateSection(xy, loop, d)
            p = xy[loop]
            seg = np.hypot(*(np.roll(p, -1, axis=0) - p).T)
            # every loop node is a triangle node, and no new point duplicates one
            self.assertEqual(set(int(v) for v in loop) - set(tri.ravel().tolist()), set(), name)
            for e in extra:
                self.assertGreater(np.min(np.hypot(*(p - e).T)), 1e-3 * seg.min(), name)
            # the triangles (all one orientation) fill the polygon: areas agree to round-off
            pts = np.vstack([xy, extra])
            a = cgrid3d.signedArea(pts, tri)
            self.assertTrue(np.all(a > 0) or np.all(a < 0), name)
            poly = abs(naca66a08.polygonArea(p))
            self.assertAlmostEqual(abs(a.sum()), poly, delta=1e-9 * poly, msg=name)

    def test_gap_cells_beside_the_triangles(self):
        # Above the tip, the first re-spaced cell of each foil grid line sits beside a triangle
        # about as wide as the foil's boundary spacing there. SIMPLEC oscillated in those cells
        # (the tip gap's aft suction side) where that size jump was 47:1 or more (fine with
        # growth_relax 1.059, medium with the old fixed 1.1: 53:1) and converged at 21:1 (fine,
        # even re-spacing) and below; the presets' even re-spacing gives 15 / 17 / 21:1 on coarse
        # / medium / fine. Guard: at most 25:1 on every preset, growing by at most half from
        # coarse to fine (systematic refinement).
        jump = {}
        for name in ("coarse", "medium", "fine"):
            c = cgrid3d.preset(name)
            g = mesh2d.build(0, 0.12, 0.5, "a08", "sharp", counts=c)
            _, pts = cgrid3d.relaxedPlane(g, c["gap_relax_length"], c["growth_relax"],
                                          c["growth_relax_wake"])
            jump[name] = cgrid3d.gapSizeJump(g, pts)
            self.assertLess(jump[name], 25.0, (name, jump))
            # the re-spaced lines stay ordered: every cell of the first 20 has a positive width
            for i in range(g["iA"], g["iB"]):
                s = np.hypot(*(pts[i, :21] - pts[i, 0]).T)
                self.assertTrue(np.all(np.diff(s) > 0), (name, i))
        self.assertLess(jump["fine"], 1.5 * jump["coarse"], jump)

    def test_even_respacing(self):
        # growth 1: the re-spaced nodes of a foil line are evenly spaced up to s_J
        c = cgrid3d.preset("coarse")
        g = mesh2d.build(0, 0.12, 0.5, "a08", "sharp", counts=c)
        _, pts = cgrid3d.relaxedPlane(g, c["gap_relax_length"], 1.0, 1.0)
        i = (g["iA"] + g["iB"]) // 2
        s0 = np.hypot(*(g["pts"][i] - g["pts"][i, 0]).T)
        J = int(np.searchsorted(s0, c["gap_relax_length"]))
        s = np.hypot(*(pts[i, :J + 1] - pts[i, 0]).T)
        np.testing.assert_allclose(np.diff(s), s0[J] / J, rtol=1e-9)


if __name__ == "__main__":
    unittest.main()
