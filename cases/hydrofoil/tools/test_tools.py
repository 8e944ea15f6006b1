#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks of tools/forceConvergence.py, tools/iterationBand.py, tools/mshinfo.py, tools/foilMotion.py,
tools/foilDisplacement.py, tools/displacementJumps.py, tools/solveRunTime.py, tools/sectionShape.py
and tools/spanwiseLift.py on small synthetic inputs, and of tools/mapInitialFields.sh's input
checks."""
import io
import math
import os
import re
import sys
import tempfile
import time
import unittest
from contextlib import redirect_stderr, redirect_stdout

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import displacementJumps  # noqa: E402
import foilDisplacement  # noqa: E402
import foilMotion  # noqa: E402
import forceConvergence as fc  # noqa: E402
import iterationBand  # noqa: E402
import mshinfo  # noqa: E402
import sectionShape  # noqa: E402
import solveRunTime  # noqa: E402
import spanwiseLift  # noqa: E402


def _foamList(rows, fmt):
    return f"{len(rows)}\n(\n" + "\n".join(fmt(r) for r in rows) + "\n)\n"


_HEADER = "FoamFile\n{\n    format ascii;\n}\n"


def _vec(r):
    return "(%r %r %r)" % tuple(float(v) for v in r)


def writeAsciiCase(case, points, patchFaces):
    """A minimal ASCII polyMesh in CASE: the points, one internal face, then patch foil."""
    mesh = os.path.join(case, "constant", "polyMesh")
    os.makedirs(mesh)
    with open(os.path.join(mesh, "points"), "w") as f:
        f.write(_HEADER + _foamList(points, _vec))
    faces = [[9, 9, 9]] + patchFaces  # one internal face before the patch
    with open(os.path.join(mesh, "faces"), "w") as f:
        f.write(_HEADER + _foamList(faces, lambda v: f"{len(v)}(" + " ".join(map(str, v)) + ")"))
    with open(os.path.join(mesh, "boundary"), "w") as f:
        f.write(_HEADER + "1\n(\n    foil\n    {\n        type wall;\n"
                f"        nFaces {len(patchFaces)};\n        startFace 1;\n    }}\n)\n")


def writeAsciiPointVectors(path, values, foilEntry=False):
    """A pointVectorField file with the given internalField (and an empty foil entry)."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(_HEADER + "dimensions [0 1 0 0 0 0 0];\n"
                "internalField nonuniform List<vector> " + _foamList(values, _vec) +
                ";\nboundaryField\n{\n" +
                ("    foil\n    {\n        type fixedValue;\n        value uniform (0 0 0);\n    }\n"
                 if foilEntry else "") + "}\n")


class ForceConvergence(unittest.TestCase):
    def test_criterion(self):
        it = np.arange(1, 201, dtype=float)
        # Fx, Fy decay to (0.3, -2.0) like exp(-i/10); Fz ~ 0 with tiny noise
        f = np.column_stack([0.3 + 0.5 * np.exp(-it / 10), -2.0 + 3 * np.exp(-it / 10),
                             1e-6 * np.sin(it)])
        n = fc.convergedAt(it, f, 20, 1e-3)
        # Fx: 0.5 e^{-(n-20)/10} (1 - e^{-2}) <= 3e-4 -> n - 20 >= 10 ln(0.5*0.8647/3e-4)
        nx = 20 + 10 * np.log(0.5 * (1 - np.exp(-2.0)) / 3e-4)
        ny = 20 + 10 * np.log(3 * (1 - np.exp(-2.0)) / 2e-3)
        self.assertEqual(int(it[n]), int(np.ceil(max(nx, ny))))
        self.assertIsNone(fc.convergedAt(it[:50], f[:50], 20, 1e-3))

    def test_reads_force_dat(self):
        with tempfile.TemporaryDirectory() as case:
            d = os.path.join(case, "postProcessing", "forces", "0")
            os.makedirs(d)
            with open(os.path.join(d, "force.dat"), "w") as fh:
                fh.write("# Force\n# Time total_x total_y total_z pressure_x ...\n")
                for i in range(1, 61):
                    fh.write(f"{i}\t(0.3 -2 0.01)\t(0.2 -2 0.01)\t(0.1 0 0)\n")
            it, tot, pres, visc = fc.readForces(case)
            self.assertEqual(len(it), 60)
            self.assertEqual(tuple(tot[-1]), (0.3, -2.0, 0.01))
            self.assertEqual(tuple(visc[0]), (0.1, 0.0, 0.0))
            buf = io.StringIO()
            with redirect_stdout(buf):
                fc.main([case])
            self.assertIn("converged_at=21", buf.getvalue())


MSH22 = """$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
2 2 "clamped"
3 1 "volume"
$EndPhysicalNames
$Nodes
4
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
$EndNodes
$Elements
2
1 2 2 2 1 1 2 3
2 4 2 1 1 1 2 3 4
$EndElements
"""


class MshInfo(unittest.TestCase):
    def test_msh22(self):
        with tempfile.TemporaryDirectory() as tmp:
            p = os.path.join(tmp, "t.msh")
            with open(p, "w") as fh:
                fh.write(MSH22)
            version, nNodes, byType, byGroup = mshinfo.summarise(p)
            self.assertEqual((version, nNodes), ("2.2", 4))
            self.assertEqual(byGroup["volume"][4], 1)
            self.assertEqual(byGroup["clamped"][2], 1)
            with redirect_stdout(io.StringIO()):
                self.assertEqual(mshinfo.main(["--require", "volume,clamped", p]), 0)
                with open(os.devnull, "w") as null:
                    stderr, sys.stderr = sys.stderr, null
                    try:
                        self.assertEqual(mshinfo.main(["--require", "wetted", p]), 1)
                    finally:
                        sys.stderr = stderr


class FoilMotion(unittest.TestCase):
    def test_beam_and_shear_bending(self):
        # points of a section at the root, mid-span and tip; no twist
        pts = np.array([[0.3685, y, z] for z in (0.0, 0.05, 0.1) for y in (-0.003, 0.0, 0.002)])
        D = 0.03
        beam = foilMotion.displacement(pts, D, 0.0, "beam")
        shear = foilMotion.displacement(pts, D, 0.0, "shear")
        s = pts[:, 2] / foilMotion.SPAN
        # deflection w = -D (z/s)^2 for both; zero at the clamped root
        np.testing.assert_allclose(beam[:, 1], -D * s * s, atol=1e-15)
        np.testing.assert_allclose(shear[:, 1], -D * s * s, atol=1e-15)
        np.testing.assert_allclose(beam[:3], 0.0, atol=1e-15)
        # beam: the section turns with the slope w' = -2 D z / s^2: d_z = -y w'
        np.testing.assert_allclose(beam[:, 2], pts[:, 1] * 2 * D * s / foilMotion.SPAN, atol=1e-15)
        self.assertAlmostEqual(beam[8, 2], 0.002 * 0.6)   # y = 2 mm at the tip: 1.2 mm
        np.testing.assert_allclose(shear[:, 2], 0.0)

    def test_from_replays_a_given_field_in_patch_point_order(self):
        points = DisplacementJumps.POINTS
        faces = [[4, 5, 2, 1], [3, 4, 1, 0]]  # first appearance: 4 5 2 1 3 0
        given = 1e-3 * (np.arange(18.0).reshape(6, 3) + 1.0)
        with tempfile.TemporaryDirectory() as case:
            writeAsciiCase(case, points, faces)
            writeAsciiPointVectors(os.path.join(case, "0", "pointDisplacement"), 0 * points, True)
            source = os.path.join(case, "level.pointDisplacement")
            writeAsciiPointVectors(source, given)
            with redirect_stdout(io.StringIO()):
                self.assertEqual(foilMotion.main([case, "--from", source]), 0)
            with open(os.path.join(case, "0", "pointDisplacement")) as f:
                text = f.read()
            foil = text[text.index("List<vector>", text.index("foil")):]
            written = foilMotion.readPoints(os.path.join(case, "0", "pointDisplacement"))
            self.assertEqual(len(written), 6)  # the internalField is left alone
            values = np.array([[float(v) for v in r.split()]
                               for r in re.findall(r"\(([^()]*)\)", foil)[:6]])
            np.testing.assert_allclose(values, given[[4, 5, 2, 1, 3, 0]], rtol=1e-9)
            writeAsciiPointVectors(source, given[:5])
            with self.assertRaises(RuntimeError):
                foilMotion.main([case, "--from", source])

    @staticmethod
    def foilLikeSurface(n, seed):
        """n points on an elliptic cylinder (chord 50 mm, thickness 6 mm) over the 0.1 m span."""
        rng = np.random.default_rng(seed)
        t, z = rng.uniform(0, 2 * np.pi, n), rng.uniform(0.0, 0.1, n)
        return np.column_stack([0.3685 + 0.025 * np.cos(t), 0.003 * np.sin(t), z])

    def test_interface_fit_reproduces_linear_fields(self):
        rng = np.random.default_rng(3)
        B = np.array([[0.1, -0.2, 0.05], [0.3, 0.01, -0.02], [0.02, 0.04, 0.5]])
        a = np.array([1e-3, -2e-3, 5e-4])
        # nodes spanning three directions: exact
        nodes, targets = rng.uniform(0, 0.01, (4000, 3)), rng.uniform(0.002, 0.008, (300, 3))
        d, gap = foilMotion.interpolateLinear(nodes, a + nodes @ B, targets)
        np.testing.assert_allclose(d, a + targets @ B, rtol=0, atol=1e-15)
        self.assertLess(gap, 1e-3)
        # nodes and targets on one plane (the tip face z = 0.1): exact within the plane
        flat = np.column_stack([rng.uniform(0.36, 0.4, (3000, 2)), np.full(3000, 0.1)])
        flatTargets = np.column_stack([rng.uniform(0.365, 0.395, (200, 2)), np.full(200, 0.1)])
        d, _ = foilMotion.interpolateLinear(flat, a + flat @ B, flatTargets)
        np.testing.assert_allclose(d, a + flatTargets @ B, rtol=0, atol=1e-15)

    def test_interface_fit_of_a_beam_motion_is_close_and_has_no_jumps(self):
        nodes = self.foilLikeSurface(20000, 1)          # ~0.6 mm node spacing
        beam = lambda p: foilMotion.displacement(p, 0.005, -2.0, "beam")
        targets = self.foilLikeSurface(3000, 2)
        d, _ = foilMotion.interpolateLinear(nodes, beam(nodes), targets)
        # measured 1.7 um against 5 mm of deflection: the fit's error on the bending curvature
        self.assertLess(float(np.abs(d - beam(targets)).max()), 5e-6)
        # along a 2 mm spanwise line of targets 1 um apart, the values change smoothly: a jump
        # where a node enters or leaves a target's fit would show as a step far above the
        # field's own slope (< 0.1)
        line = np.column_stack([np.full(2000, 0.3685 + 0.025 * np.cos(1.0)),
                                np.full(2000, 0.003 * np.sin(1.0)), 0.05 + 1e-6 * np.arange(2000)])
        d, _ = foilMotion.interpolateLinear(nodes, beam(nodes), line)
        self.assertLess(float(np.abs(np.diff(d, axis=0)).max()) / 1e-6, 0.2)

    def test_interface_fit_carries_the_surface_value_along_the_normal(self):
        # nodes on a gently curved sheet y = x^2 (radius 0.5 m); a field with a strong normal
        # gradient; a target 0.2 mm off the sheet gets the value at its foot point, not an
        # extrapolation with a gradient the nodes cannot determine
        rng = np.random.default_rng(4)
        xz = rng.uniform(-0.01, 0.01, (5000, 2))
        nodes = np.column_stack([xz[:, 0], xz[:, 0] ** 2, xz[:, 1]])
        field = lambda p: np.column_stack([p[:, 1] * 10.0, p[:, 0], p[:, 2]])
        foot = np.array([[0.001, 1e-6, 0.002]])
        d, _ = foilMotion.interpolateLinear(nodes, field(nodes), foot + [0.0, 2e-4, 0.0])
        np.testing.assert_allclose(d, field(foot), rtol=0, atol=2e-6)

    def test_from_interface_writes_the_fitted_values_and_refuses_another_geometry(self):
        points = DisplacementJumps.POINTS * 1e-3       # a 2 mm x 1 mm patch
        faces = [[4, 5, 2, 1], [3, 4, 1, 0]]
        rng = np.random.default_rng(5)
        nodes = np.column_stack([rng.uniform(-5e-4, 2.5e-3, (400, 2)), rng.uniform(-1e-4, 1e-4, 400)])
        with tempfile.TemporaryDirectory() as case:
            writeAsciiCase(case, points, faces)
            writeAsciiPointVectors(os.path.join(case, "0", "pointDisplacement"), 0 * points, True)
            csvPath = os.path.join(case, "level_0000.csv")

            def writeCsv(shift):
                with open(csvPath, "w") as f:
                    f.write("# level 0 time 0 s\nx,y,z,ux,uy,uz,fx,fy,fz\n")
                    for x in nodes + shift:
                        f.write("%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,0,0,0\n"
                                % (tuple(x) + (0.01 * x[0], 0.02 * x[1] - 1e-4, 3e-5)))
            writeCsv(0.0)
            with redirect_stdout(io.StringIO()):
                self.assertEqual(foilMotion.main([case, "--from-interface", csvPath]), 0)
            with open(os.path.join(case, "0", "pointDisplacement")) as f:
                text = f.read()
            foil = text[text.index("List<vector>", text.index("foil")):]
            values = np.array([[float(v) for v in r.split()]
                               for r in re.findall(r"\(([^()]*)\)", foil)[:6]])
            p = points[[4, 5, 2, 1, 3, 0]]
            expected = np.column_stack([0.01 * p[:, 0], 0.02 * p[:, 1] - 1e-4, np.full(6, 3e-5)])
            np.testing.assert_allclose(values, expected, rtol=0, atol=1e-12)
            # --check-gap: the same check, nothing written
            with redirect_stdout(io.StringIO()):
                self.assertEqual(foilMotion.main([case, "--from-interface", csvPath, "--check-gap"]), 0)
            writeCsv(np.array([0.0, 0.0, 5e-3]))        # the nodes 5 mm away
            with self.assertRaisesRegex(RuntimeError, "not this foil's interface"):
                foilMotion.main([case, "--from-interface", csvPath])
            with self.assertRaisesRegex(RuntimeError, "not this foil's interface"):
                foilMotion.main([case, "--from-interface", csvPath, "--check-gap"])
            with open(os.path.join(case, "0", "pointDisplacement")) as f:
                self.assertEqual(f.read(), text)        # the refused calls wrote nothing
            with self.assertRaisesRegex(RuntimeError, "needs --from-interface"):
                foilMotion.main([case, "--check-gap"])
            with self.assertRaisesRegex(RuntimeError, "exclude each other"):
                foilMotion.main([case, "--from-interface", csvPath, "--from", csvPath])

    def test_twist_is_a_rotation_about_the_quarter_chord(self):
        pts = np.array([[0.356, 0.0, 0.1], [0.406, 0.0, 0.1], [0.3685, 0.0, 0.1]])
        d = foilMotion.displacement(pts, 0.0, -12.0, "beam")
        np.testing.assert_allclose(d[2], 0.0, atol=1e-15)       # the axis stays
        # lengths from the axis are kept (a rotation); a negative twist moves the nose towards -y
        # (foilMotion.py's docstring)
        moved = pts + d
        np.testing.assert_allclose(np.hypot(*(moved[:2, :2] - [0.3685, 0.0]).T),
                                   np.hypot(*(pts[:2, :2] - [0.3685, 0.0]).T), rtol=1e-12)
        self.assertLess(d[0, 1], 0.0)


class DisplacementJumps(unittest.TestCase):
    # two unit quads side by side in z = 0: points 0-5, x in {0, 1, 2}, y in {0, 1}
    POINTS = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0], [1, 1, 0], [2, 1, 0]], float)
    FACES = [[0, 1, 4, 3], [1, 2, 5, 4]]

    def test_a_uniform_stretch_gives_its_strain_on_every_edge(self):
        rows = displacementJumps.edgeJumps(self.POINTS, 0.03 * self.POINTS, self.FACES)
        self.assertEqual(len(rows), 7)  # the shared edge 1-4 once
        np.testing.assert_allclose(rows[:, 0], 0.03, rtol=1e-12)

    def test_a_jump_at_one_point_shows_on_its_edges_only(self):
        d = 0.03 * self.POINTS
        d[5] += [0.0, 0.5, 0.0]
        rows = displacementJumps.edgeJumps(self.POINTS, d, self.FACES)
        touching = np.linalg.norm(rows[:, 3:] - [2.0, 1.0, 0.0], axis=1) < 0.6  # edges 2-5, 4-5
        self.assertEqual(touching.sum(), 2)
        self.assertGreater(rows[touching, 0].min(), 0.4)
        np.testing.assert_allclose(rows[~touching, 0], 0.03, rtol=1e-12)

    def test_reads_an_ascii_case(self):
        with tempfile.TemporaryDirectory() as case:
            writeAsciiCase(case, self.POINTS, self.FACES)
            writeAsciiPointVectors(os.path.join(case, "7", "pointDisplacement"), 0.03 * self.POINTS)
            rows = displacementJumps.caseJumps(case, "7", "foil")
            self.assertEqual(len(rows), 7)
            np.testing.assert_allclose(rows[:, 0], 0.03, rtol=1e-12)
            out = io.StringIO()
            with redirect_stdout(out):
                self.assertEqual(displacementJumps.main([case, "7", "--split", "x", "1.25"]), 0)
            self.assertIn("x above 1.25: 3 edges, max 0.03", out.getvalue())
            with self.assertRaises(RuntimeError):
                displacementJumps.caseJumps(case, "7", "tip")


class MapInitialFields(unittest.TestCase):
    """tools/mapInitialFields.sh refuses bad folders with one line and exit 2, before mapping
    (the mapping itself runs in the grid-sequenced studies: run2d.sh / rigid.sh --init-from)."""

    def run_tool(self, *args):
        import subprocess
        tool = os.path.join(os.path.dirname(os.path.abspath(__file__)), "mapInitialFields.sh")
        return subprocess.run(["bash", tool, *args], capture_output=True, text=True)

    def test_bad_folders(self):
        with tempfile.TemporaryDirectory() as root:
            dest, src = os.path.join(root, "dest"), os.path.join(root, "src")
            r = self.run_tool(dest)
            self.assertEqual(r.returncode, 2)
            self.assertIn("usage", r.stderr)
            r = self.run_tool(dest, src)
            self.assertEqual(r.returncode, 2)
            self.assertIn("'%s' is not a case with a mesh" % dest, r.stderr)
            os.makedirs(os.path.join(dest, "constant", "polyMesh"))
            r = self.run_tool(dest, src)
            self.assertEqual(r.returncode, 2)
            self.assertIn("'%s' is not a case" % src, r.stderr)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1)


class IterationBand(unittest.TestCase):
    def write(self, folder, name, header, rows):
        path = os.path.join(folder, name)
        with open(path, "w") as f:
            f.write(header + "\n")
            for r in rows:
                f.write(",".join(str(v) for v in r) + "\n")
        return path

    def test_rigid_cycle(self):
        # lift component -2 + 1e-3 sin(2 pi i / 6) after a decaying start: period 6, the band
        # from the sampled extremes, the mean and no drift over whole periods
        it = np.arange(1, 1201)
        fy = -2.0 + 1e-3 * np.sin(2 * np.pi * it / 6) + 0.5 * np.exp(-it / 20.0)
        with tempfile.TemporaryDirectory() as d:
            path = self.write(d, "rigidIterations.csv", "iteration,Fx,Fy,Fz,residualU,residualP",
                              [(i, 0.3, repr(v), 0.0, 1e-3, 1e-3) for i, v in zip(it, fy)])
            s = iterationBand.band_summary(iterationBand.read_series(path, "Fy"), 300)
            w = fy[-300:]
            self.assertEqual(s["period"], 6)
            self.assertEqual(s["iterations"], 1200)
            self.assertAlmostEqual(s["mean"], np.mean(w), places=12)
            self.assertAlmostEqual(s["band"], (w.max() - w.min()) / (2 * abs(np.mean(w))), places=12)
            self.assertLess(abs(s["drift"]), 1e-9)  # whole periods in each half, decay gone
            # a partial last line (a run still writing) is ignored
            with open(path, "a") as f:
                f.write("1201,0.3,")
            self.assertEqual(len(iterationBand.read_series(path, "Fy")), 1200)

    def test_solve_selection_and_errors(self):
        rows = [(0, 1, k, 0.3, -2.0 - 0.1 * 0.5 ** k, 0.0, 1e-3, 1e-3) for k in range(1, 41)]
        rows += [(0, 2, k, 0.3, -1.5 + 0.01 * (-1) ** k, 0.0, 1e-3, 1e-3) for k in range(1, 21)]
        with tempfile.TemporaryDirectory() as d:
            path = self.write(d, "solveIterations.csv",
                              "step,iteration,simpleIteration,Fx,Fy,Fz,residualU,residualP", rows)
            last = iterationBand.read_series(path, "Fy")  # default: the last SOLVE
            self.assertEqual(len(last), 20)
            s = iterationBand.band_summary(last, 20)
            self.assertEqual(s["period"], 2)
            self.assertAlmostEqual(s["band"], 0.01 / 1.5, places=12)
            self.assertEqual(len(iterationBand.read_series(path, "Fy", 0, 1)), 40)
            for args in (("Fq",), ("Fy", 3, 1)):
                with self.assertRaises(SystemExit) as e:
                    iterationBand.read_series(path, *args)
                self.assertIn("iterationBand.py", str(e.exception))
            with self.assertRaises(SystemExit) as e:
                iterationBand.band_summary(last, 30)
            self.assertIn("fewer than --last 30", str(e.exception))


class SolveRunTime(unittest.TestCase):
    """A resumed rigid solve's earlier runs: wall from the banner's start stamp to the log's last
    write; CPU from the run's time record, else ranks x wall."""

    def _log(self, case, name, start, end):
        path = os.path.join(case, name)
        stamp = time.localtime(start)
        with open(path, "w") as f:
            f.write("Build  : v1912\nExec   : fluid-app -rigid -parallel\n")
            f.write(time.strftime("Date   : %b %d %Y\n", stamp))
            f.write(time.strftime("Time   : %H:%M:%S\n", stamp))
            f.write("smoothSolver:  Solving for Ux\n")
        os.utime(path, (end, end))

    def test_sums_stopped_and_finished_runs(self):
        with tempfile.TemporaryDirectory() as case:
            t = float(int(time.time()) - 100000)
            self._log(case, "log.fluid-app.before-400", t, t + 2000)        # stopped: no record
            open(os.path.join(case, "time.txt.before-400"), "w").close()
            self._log(case, "log.fluid-app.before-2200", t + 3000, t + 10000)   # ended by itself
            with open(os.path.join(case, "time.txt.before-2200"), "w") as f:
                f.write("12000.5 300.25\n")
            self._log(case, "log.fluid-app", t + 11000, t + 12000)           # the last run: not counted
            wall, cpu, runs = solveRunTime.earlierRuns(case, 2)
            self.assertEqual(runs, 2)
            self.assertAlmostEqual(wall, 2000 + 7000, delta=1e-6)
            self.assertAlmostEqual(cpu, 2 * 2000 + 12300.75, delta=1e-6)

    def test_no_earlier_run(self):
        with tempfile.TemporaryDirectory() as case:
            self.assertEqual(solveRunTime.earlierRuns(case, 2), (0.0, 0.0, 0))

    def test_log_without_start_stamp_is_refused(self):
        with tempfile.TemporaryDirectory() as case:
            with open(os.path.join(case, "log.fluid-app.before-200"), "w") as f:
                f.write("no banner\n")
            with self.assertRaises(ValueError):
                solveRunTime.earlierRuns(case, 2)
            err = io.StringIO()
            with redirect_stderr(err):
                self.assertEqual(solveRunTime.main([case, "2"]), 2)
            self.assertEqual(len(err.getvalue().strip().splitlines()), 1)
            self.assertIn("log.fluid-app.before-200", err.getvalue())


class SectionShape(unittest.TestCase):
    """A beam's motion (heave, twist about the quarter chord, both varying along the span) is
    fitted exactly with zero camber; an added parabola in x is the camber, exactly."""

    def _surface(self, n=400, seed=3):
        rng = np.random.default_rng(seed)
        x = 0.356 + 0.05 * rng.random(n)
        y = 0.003 * (rng.random(n) - 0.5)
        z = 0.1 * rng.random(n)
        return np.stack([x, y, z], axis=1)

    def _beam(self, p, camber=0.0):
        x, y, z = p.T
        theta = -0.03 * z / 0.1                  # twist [rad], linear along the span
        w = -4e-3 * (z / 0.1) ** 2               # heave of the quarter chord [m]
        X = x - sectionShape.X_QC
        uy = w + theta * X + camber * (X / 0.025) ** 2
        return np.stack([-theta * y, uy, np.zeros_like(z)], axis=1)

    def test_beam_motion_exact(self):
        p = self._surface()
        s = sectionShape.section_shape(p, self._beam(p), 0.05, 2.5e-3)
        self.assertAlmostEqual(s["twist_deg"], math.degrees(-0.015), delta=1e-9)
        self.assertAlmostEqual(s["heave_mm"], -1.0, delta=1e-9)
        self.assertAlmostEqual(s["camber_mm"], 0.0, delta=1e-9)

    def test_camber_exact(self):
        p = self._surface()
        base = sectionShape.section_shape(p, self._beam(p), 0.07, 2.5e-3)
        bent = sectionShape.section_shape(p, self._beam(p, camber=5e-5), 0.07, 2.5e-3)
        self.assertAlmostEqual(bent["camber_mm"] - base["camber_mm"], 0.05, delta=1e-9)
        self.assertAlmostEqual(bent["twist_deg"], base["twist_deg"], delta=1e-9)

    def test_reads_interface_csv_and_refuses_a_thin_slab(self):
        p = self._surface()
        u = self._beam(p)
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "level_0000.csv")
            with open(path, "w") as f:
                f.write("# level 0 time 0 s\nx,y,z,ux,uy,uz,fx,fy,fz\n")
                for a, b in zip(p, u):
                    f.write(",".join("%.17g" % v for v in list(a) + list(b) + [0, 0, 0]) + "\n")
            points, disp = sectionShape.read_interface(path)
            np.testing.assert_allclose(disp, u, rtol=0, atol=1e-15)
            out = io.StringIO()
            with redirect_stdout(out):
                sectionShape.main([path, "--stations", "0.05"])
            fields = dict(kv.split("=") for kv in out.getvalue().split()[1:])
            self.assertAlmostEqual(float(fields["twist_deg"]), math.degrees(-0.015), delta=1e-5)
            self.assertAlmostEqual(float(fields["camber_mm"]), 0.0, delta=1e-5)
            err = io.StringIO()
            with self.assertRaises(SystemExit) as e, redirect_stderr(err):
                sectionShape.main([path, "--stations", "0.05", "--half-width", "1e-6"])
            self.assertEqual(e.exception.code, 2)
            self.assertEqual(len(err.getvalue().strip().splitlines()), 1)
            self.assertIn("--half-width", err.getvalue())


class SpanwiseLift(unittest.TestCase):
    """A flat plate y = 0 from z = 0 to 0.1 m under a pressure linear in z: the lift outboard of
    each station and the centre of lift are known exactly, whatever the faces' spanwise rows."""

    def _plate(self, path, rows, p_of_z, rho):
        # quads (x 0..0.05) in uneven spanwise rows, normals -y (out of the fluid above, into
        # the plate), each face's p the exact mean of p_of_z over the face
        edges = np.concatenate([[0.0], np.sort(rows), [0.1]])
        pts, conn, offs, ps = [], [], [], []
        for z0, z1 in zip(edges[:-1], edges[1:]):
            k = len(pts)
            pts += [(0, 0, z0), (0.05, 0, z0), (0.05, 0, z1), (0, 0, z1)]
            conn += [k, k + 1, k + 2, k + 3]
            offs.append(len(conn))
            ps.append(p_of_z(0.5 * (z0 + z1)) / rho)   # kinematic, linear in z: its mean
        with open(path, "w") as f:
            f.write("<VTKFile type='PolyData'><PolyData><Piece>\n<CellData>\n")
            f.write("<DataArray type='Float32' Name='p' format='ascii'>%s</DataArray>\n"
                    % " ".join("%.17g" % v for v in ps))
            f.write("</CellData><Points>\n<DataArray type='Float32' Name='Points' "
                    "NumberOfComponents='3' format='ascii'>%s</DataArray>\n</Points><Polys>\n"
                    % " ".join("%.17g" % c for q in pts for c in q))
            f.write("<DataArray type='Int32' Name='connectivity' format='ascii'>%s</DataArray>\n"
                    % " ".join(map(str, conn)))
            f.write("<DataArray type='Int32' Name='offsets' format='ascii'>%s</DataArray>\n"
                    % " ".join(map(str, offs)))
            f.write("</Polys></Piece></PolyData></VTKFile>\n")

    def test_linear_pressure_exact(self):
        rho, p0, p1 = 998.2, 100.0, 300.0              # p [Pa] = p0 + (p1 - p0) z / 0.1
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "foil.vtp")
            self._plate(path, [0.013, 0.031, 0.0495, 0.077], lambda z: p0 + (p1 - p0) * z / 0.1, rho)
            fy, zlo, zhi = spanwiseLift.face_forces(*spanwiseLift.read_patch(path), rho)
            # area vectors (0, -A, 0) as the quads are ordered: F_y = -p A, lift = -F_y = p A
            self.assertAlmostEqual(-fy.sum(), 0.05 * 0.1 * 0.5 * (p0 + p1), delta=1e-9)
            lift = spanwiseLift.lift_outboard(fy, zlo, zhi, np.array([0.0, 0.05, 0.1]))
            # spreading a face's force evenly over its row is exact at the row edges and, within a
            # row, linear: outboard of 0.05 (inside the row 0.0495..0.077) the error is below
            # (p1 - p0) / 0.1 x 0.05 x 0.0275^2 / 8
            exact = lambda z: 0.05 * ((p0 * (0.1 - z)) + (p1 - p0) / 0.1 * (0.1 ** 2 - z ** 2) / 2)
            self.assertAlmostEqual(lift[0], exact(0.0), delta=1e-9)
            self.assertAlmostEqual(lift[1], exact(0.05), delta=(p1 - p0) / 0.1 * 0.05 * 0.0275 ** 2 / 8)
            self.assertAlmostEqual(lift[2], 0.0, delta=1e-12)
            out = io.StringIO()
            with redirect_stdout(out):
                spanwiseLift.main([path, "--step", "0.05"])
            total = re.search(r"pressure lift ([-0-9.e]+) N", out.getvalue()).group(1)
            self.assertAlmostEqual(float(total), exact(0.0), delta=1e-5)
            # a uniform pressure: the centre of lift is mid-span, whatever the rows
            self._plate(path, [0.013, 0.031, 0.0495, 0.077], lambda z: p0, rho)
            out = io.StringIO()
            with redirect_stdout(out):
                spanwiseLift.main([path])
            zc = re.search(r"centre z_c ([-0-9.e]+) m", out.getvalue()).group(1)
            self.assertAlmostEqual(float(zc), 0.05, delta=1e-5)

    def test_missing_pressure_is_refused(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "foil.vtp")
            with open(path, "w") as f:
                f.write("<VTKFile><PolyData><Piece></Piece></PolyData></VTKFile>\n")
            err = io.StringIO()
            with self.assertRaises(SystemExit) as e, redirect_stderr(err):
                spanwiseLift.read_patch(path)
            self.assertEqual(e.exception.code, 2)
            self.assertIn("spanwiseLift.py", err.getvalue())


def _binaryHeader(cls):
    return (b"FoamFile\n{\n    version 2.0;\n    format binary;\n    class " + cls +
            b";\n    arch \"LSB;label=32;scalar=64\";\n}\n// * * //\n\n")


def writeBinaryPoints(path, points):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(_binaryHeader(b"vectorField") + b"%d\n(" % len(points) +
                np.asarray(points, "<f8").tobytes() + b")\n")


def writeBinaryFaces(path, faces):
    offsets = np.cumsum([0] + [len(f) for f in faces]).astype("<i4")
    labels = np.array([v for f in faces for v in f], "<i4")
    with open(path, "wb") as f:
        f.write(_binaryHeader(b"faceCompactList") + b"%d\n(" % len(offsets) + offsets.tobytes() +
                b")\n%d\n(" % len(labels) + labels.tobytes() + b")\n")


class FoilDisplacement(unittest.TestCase):
    def test_binary_readers_match_the_ascii_ones(self):
        points = DisplacementJumps.POINTS * 0.1 + 1e-3
        faces = [[4, 5, 2, 1], [3, 4, 1, 0]]
        with tempfile.TemporaryDirectory() as case:
            writeAsciiCase(case, points, faces)
            mesh = os.path.join(case, "constant", "polyMesh")
            asciiFaces = foilMotion.readFaces(os.path.join(mesh, "faces"), 1, 2)
            writeBinaryPoints(os.path.join(mesh, "points"), points)
            writeBinaryFaces(os.path.join(mesh, "faces"), [[9, 9, 9]] + faces)
            np.testing.assert_array_equal(foilMotion.readPoints(os.path.join(mesh, "points")), points)
            self.assertEqual(foilMotion.readFaces(os.path.join(mesh, "faces"), 1, 2), asciiFaces)
            self.assertEqual(asciiFaces, faces)

    def test_moved_case_gives_each_foil_point_once_with_its_displacement(self):
        points = DisplacementJumps.POINTS * 1e-3
        faces = [[4, 5, 2, 1], [3, 4, 1, 0]]
        move = lambda p: np.column_stack([0.01 * p[:, 1], -2e-4 + 0.0 * p[:, 0], 0.02 * p[:, 0]])
        with tempfile.TemporaryDirectory() as case:
            # two "processors" sharing the points 1 and 4 (one face each), the second binary
            for rank, face in enumerate(faces):
                part = os.path.join(case, "processor%d" % rank)
                writeAsciiCase(part, points, [face])
                moved = os.path.join(part, "0", "polyMesh", "points")
                if rank:
                    writeBinaryPoints(os.path.join(part, "constant", "polyMesh", "points"), points)
                    writeBinaryPoints(moved, points + move(points))
                else:
                    os.makedirs(os.path.dirname(moved))
                    with open(moved, "w") as f:
                        f.write(_HEADER + _foamList(points + move(points), _vec))
            ref, disp = foilDisplacement.foilDisplacement(case, "0", "foil")
            self.assertEqual(len(ref), 6)                    # 8 patch points, 2 shared
            np.testing.assert_allclose(disp, move(ref), rtol=0, atol=1e-15)
            out = os.path.join(case, "foil.csv")
            with redirect_stdout(io.StringIO()):
                self.assertEqual(foilDisplacement.main([case, out]), 0)
            nodes, values = sectionShape.read_interface(out)   # the interface CSV columns
            np.testing.assert_allclose(values, move(nodes), rtol=0, atol=1e-12)
            err = io.StringIO()
            with redirect_stderr(err), self.assertRaises(SystemExit) as e:
                foilDisplacement.main([case, out, "--time", "5"])
            self.assertEqual(e.exception.code, 2)
            self.assertIn("no moved mesh 5/polyMesh/points", err.getvalue())


if __name__ == "__main__":
    unittest.main(verbosity=2)
