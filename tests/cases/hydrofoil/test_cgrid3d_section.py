#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""cases/hydrofoil/tools/cgrid3d.py: the Gmsh triangulation of the section above the tip
shares every boundary node with the C-grid around it, on every preset (a node matched by
rounded coordinates once split a pair on the fine preset: 152 unnamed faces), and fills the
foil polygon exactly (areas equal to round-off)."""
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


if __name__ == "__main__":
    unittest.main()
