#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks of the hydrofoil geometry generator (run: /usr/bin/python3 test_naca66a08.py)."""
import os
import re
import sys
import tempfile
import unittest

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import naca66a08 as geo  # noqa: E402

CHORD, SPAN, TC, CLI = 0.050, 0.100, 0.12, 0.5


def referenceArea(tc, cli, chord, meanline="a08"):
    """Exact section area of a perpendicular thickness offset: chord^2 * int 2 y_t ds (camber arc
    length), by the trapezoid rule in s = sqrt(x) on 400k intervals (converged to ~1e-9)."""
    s = np.linspace(0.0, 1.0, 400001)
    x = s * s
    _, dyc = geo.meanLine(x, cli, meanline)
    dyc[0] = 0.0  # integrand is 0 at the nose (y_t = 0, slope log-singular but integrable)
    f = tc * geo.thicknessRatio(x) * np.sqrt(1.0 + dyc * dyc) * 2.0 * s
    return np.trapz(f, s) * chord * chord


NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")


def geoDifferences(expected, actual, rtol=1e-9, atol=1e-12):
    """Differences between two .geo texts: the text between numbers must be equal, the numbers
    equal within |a - b| <= atol + rtol |a| (atol in m: coordinates are in metres). The generator
    prints 13 significant digits, whose last ones differ between machines (libm, numpy builds), so
    the text itself is not compared. Returns a list of human-readable differences (empty: same)."""
    diffs = []
    a, b = NUMBER.split(expected), NUMBER.split(actual)
    if a != b:
        for i, (x, y) in enumerate(zip(a, b)):
            if x != y:
                diffs.append("text differs: %r vs %r" % (x.strip()[:60], y.strip()[:60]))
                break
        else:
            diffs.append("the texts have %d and %d parts" % (len(a), len(b)))
        return diffs
    for x, y in zip(NUMBER.findall(expected), NUMBER.findall(actual)):
        if abs(float(x) - float(y)) > atol + rtol * abs(float(x)):
            diffs.append("number %s vs %s" % (x, y))
    return diffs


def readAsciiStl(path):
    pts = []
    with open(path) as f:
        for line in f:
            w = line.split()
            if w and w[0] == "vertex":
                pts.append([float(v) for v in w[1:4]])
    pts = np.array(pts)
    verts, idx = np.unique(pts, axis=0, return_inverse=True)
    return verts, idx.reshape(-1, 3)


class Thickness(unittest.TestCase):
    def test_interpolant_reproduces_table(self):
        t = geo.thicknessRatio(geo.THICKNESS_X)
        self.assertLess(np.max(np.abs(t - geo.THICKNESS_T)), 1e-15)

    def test_max_thickness_is_tc_at_045(self):
        x = np.linspace(0.0, 1.0, 200001)
        t = 2.0 * 0.5 * TC * geo.thicknessRatio(x) * CHORD
        self.assertAlmostEqual(float(t.max()), TC * CHORD, delta=1e-12)
        self.assertAlmostEqual(float(x[np.argmax(t)]), 0.45, delta=1e-9)
        # on the generated section: the perpendicular distance upper-lower at the x = 0.45 station
        up, lo = geo.section(TC, CLI, CHORD)
        k = int(np.flatnonzero(geo.chordStations(len(up)) == 0.45)[0])
        self.assertAlmostEqual(float(np.linalg.norm(up[k] - lo[k])), TC * CHORD, delta=1e-12)

    def test_monotone_no_overshoot(self):
        x = np.linspace(0.0, 1.0, 100001)
        t = geo.thicknessRatio(x)
        d = np.diff(t)
        self.assertTrue(np.all(d[x[1:] <= 0.45] >= -1e-15))
        self.assertTrue(np.all(d[x[:-1] >= 0.45] <= 1e-15))
        self.assertLessEqual(t.max(), 1.0)


class MeanLine(unittest.TestCase):
    def test_max_camber_formula(self):
        x = np.linspace(0.0, 1.0, 200001)
        yc, _ = geo.meanLine(x, CLI, "a08")
        k = int(np.argmax(yc))
        self.assertAlmostEqual(float(yc[k]) * CHORD, 0.06794 * CLI * CHORD, delta=1e-4 * CHORD)
        self.assertAlmostEqual(float(yc[k]) / CLI, 0.06794, delta=5e-6)  # tighter: table digits
        self.assertAlmostEqual(float(x[k]), 0.515, delta=0.005)
        self.assertAlmostEqual(float(yc[0]), 0.0, delta=1e-15)
        self.assertAlmostEqual(float(yc[-1]), 0.0, delta=1e-15)

    def test_slope_matches_finite_difference(self):
        x = np.array([0.05, 0.3, 0.6, 0.79, 0.81, 0.95])
        _, d = geo.meanLine(x, 1.0)
        e = 1e-6
        fd = (geo.meanLine(x + e, 1.0)[0] - geo.meanLine(x - e, 1.0)[0]) / (2 * e)
        self.assertLess(np.max(np.abs(fd - d)), 1e-8)

    def test_modified_line(self):
        x = np.linspace(0.0, 1.0, 200001)
        yc, d = geo.meanLine(x, 1.0, "a08mod")
        self.assertAlmostEqual(float(yc.max()), 0.06651, delta=1e-9)
        self.assertAlmostEqual(float(yc[-1]), 0.0, delta=1e-14)
        self.assertLess(np.ptp(d[x > 0.85]), 1e-14)  # constant slope aft of 0.85c


class SectionAndStl(unittest.TestCase):
    def setUp(self):
        self.up, self.lo = geo.section(TC, CLI, CHORD)

    def test_section_closed(self):
        self.assertTrue(np.array_equal(self.up[0], self.lo[0]))  # shared leading edge
        ring = geo.sectionPolygon(self.up, self.lo)
        self.assertEqual(len(np.unique(ring, axis=0)), len(ring))  # simple ring, no repeats
        # finite trailing edge closed by a flat face of 0.0666 t_max (perpendicular offset)
        te = np.linalg.norm(self.up[-1] - self.lo[-1])
        self.assertAlmostEqual(te, 0.0666 * TC * CHORD, delta=1e-12)
        self.assertGreater(geo.polygonArea(ring), 0.0)
        # suction side: upper surface above the lower one at every station
        self.assertTrue(np.all(self.up[1:, 1] > self.lo[1:, 1]))

    def test_stl_watertight_and_volume(self):
        with tempfile.TemporaryDirectory() as tmp:
            geo.main(["--out", tmp, "--tc", str(TC), "--cli", str(CLI)])
            for name in ("section.csv", "foil.stl", "foil.geo"):
                self.assertTrue(os.path.getsize(os.path.join(tmp, name)) > 0)
            verts, tris = readAsciiStl(os.path.join(tmp, "foil.stl"))
            with open(os.path.join(tmp, "foil.geo")) as f:
                geoText = f.read()
        _, counts = geo.edgeUseCounts(tris)
        self.assertTrue(np.all(counts == 2), "an edge not shared by exactly two triangles")
        # consistent orientation: every directed edge appears once
        de = np.vstack([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
        self.assertEqual(len(np.unique(de, axis=0)), len(de))
        vol = geo.meshVolume(verts, tris)
        self.assertGreater(vol, 0.0)  # outward normals
        ring = geo.sectionPolygon(self.up, self.lo)
        self.assertAlmostEqual(vol / (geo.polygonArea(ring) * SPAN), 1.0, delta=1e-9)
        self.assertAlmostEqual(vol / (referenceArea(TC, CLI, CHORD) * SPAN), 1.0, delta=1e-3)
        # placement: root on Z = 0, tip at the span, LE at X = 0.356, suction side towards -Y
        self.assertAlmostEqual(verts[:, 2].min(), 0.0, delta=1e-15)
        self.assertAlmostEqual(verts[:, 2].max(), SPAN, delta=1e-15)
        self.assertAlmostEqual(verts[:, 0].min(), 0.356 - 0.0, delta=2e-4)
        self.assertGreater(-verts[:, 1].min(), verts[:, 1].max())  # camber bulges to -Y
        for group in ('"volume"', '"clamped"', '"wetted"'):
            self.assertIn(group, geoText)

    def test_committed_geo_is_current(self):
        """geometry/foil.geo (defaults, for users without python) matches the generator."""
        here = os.path.dirname(os.path.abspath(__file__))
        with tempfile.TemporaryDirectory() as tmp:
            from contextlib import redirect_stdout
            import io
            with redirect_stdout(io.StringIO()):
                geo.main(["--out", tmp])
            with open(os.path.join(tmp, "foil.geo")) as f:
                fresh = f.read()
        with open(os.path.join(here, "foil.geo")) as f:
            diffs = geoDifferences(f.read(), fresh)
        self.assertEqual(diffs[:5], [], "regenerate geometry/foil.geo with naca66a08.py")

    def test_geo_comparison_is_numeric(self):
        """last-digit noise passes, a changed coordinate, count or keyword does not."""
        base = "Point(2) = {3.559814036303e-01, -7.302101151309e-05, 0.0, lc};\nspan = 0.1;\n"
        noisy = "Point(2) = {3.559814036304e-01, -7.302101151311e-05, 0.0, lc};\nspan = 0.1;\n"
        self.assertEqual(geoDifferences(base, noisy), [])
        self.assertEqual(geoDifferences(base, base.replace("3.559814036303e-01", "3.56e-01")),
                         ["number 3.559814036303e-01 vs 3.56e-01"])
        self.assertNotEqual(geoDifferences(base, base.replace("Point(2)", "Point(3)")), [])
        self.assertNotEqual(geoDifferences(base, base.replace(", lc}", ", lcEdge}")), [])
        self.assertNotEqual(geoDifferences(base, base + "span = 0.1;\n"), [])

    def test_aoa_rotates_about_quarter_chord(self):
        up, lo = geo.section(TC, 0.0, CHORD, aoaDeg=5.0)
        # symmetric section: the nose goes up (+y_s) by 0.25 c sin(5 deg)
        self.assertAlmostEqual(up[0, 1], 0.25 * CHORD * np.sin(np.radians(5.0)), delta=1e-12)


if __name__ == "__main__":
    unittest.main(verbosity=2)
