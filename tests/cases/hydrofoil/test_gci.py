#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""scripts/gci.py and scripts/history_gci.py against sequences with a known answer."""
import math
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "scripts"))
from gci import gci  # noqa: E402


class GciTest(unittest.TestCase):
    def test_exact_power_law_constant_ratio(self):
        # phi = 2 + 0.3 h^2 on h = 4, 2, 1: p = 2 and phi_ext = 2 exactly
        h = [4.0, 2.0, 1.0]
        r = gci(h, [2 + 0.3 * v * v for v in h])
        self.assertEqual(r["convergence"], "monotone")
        self.assertAlmostEqual(r["observed_order"], 2.0, places=10)
        self.assertAlmostEqual(r["extrapolated"], 2.0, places=10)
        # GCI_fine = 1.25 |e21/phi1| / (r^p - 1) = 1.25 * 0.9 / 2.3 / 3
        self.assertAlmostEqual(r["gci_fine_pct"], 100 * 1.25 * 0.9 / 2.3 / 3, places=8)
        self.assertAlmostEqual(r["asymptotic_ratio"], 1.0, places=10)

    def test_exact_power_law_varying_ratio(self):
        # non-constant ratios (r21 = 1.3, r32 = 1.7): the iteration recovers p = 1.5
        h = [1.0 * 1.3 * 1.7, 1.3, 1.0]
        r = gci(h, [5 - 0.8 * v ** 1.5 for v in h])
        self.assertAlmostEqual(r["observed_order"], 1.5, places=8)
        self.assertAlmostEqual(r["extrapolated"], 5.0, places=8)

    def test_oscillatory_and_diverging_are_flagged(self):
        self.assertEqual(gci([4, 2, 1], [1.0, 1.2, 1.1])["convergence"], "oscillatory")
        self.assertEqual(gci([4, 2, 1], [1.0, 1.1, 1.3])["convergence"], "diverging")
        self.assertTrue(math.isnan(gci([4, 2, 1], [1.0, 1.1, 1.3])["observed_order"]))

    def test_range_uncertainty(self):
        # half the range over |fine|: (1.2 - 1.0) / 2 / 1.1 for the oscillatory sequence, and
        # the same rule for any other (here monotone: 6.8, 3.2, 2.3, range 4.5 about phi1 2.3)
        r = gci([4, 2, 1], [1.0, 1.2, 1.1])
        self.assertEqual(r["convergence"], "oscillatory")
        self.assertAlmostEqual(r["range_uncertainty_pct"], 100 * 0.1 / 1.1, places=10)
        self.assertAlmostEqual(gci([4, 2, 1], [2 + 0.3 * v * v for v in (4, 2, 1)])
                               ["range_uncertainty_pct"], 100 * 0.5 * 4.5 / 2.3, places=10)
        self.assertAlmostEqual(gci([4, 2, 1], [-1.0, -1.2, -1.1])["range_uncertainty_pct"],
                               100 * 0.1 / 1.1, places=10)

    def test_bad_input(self):
        with self.assertRaises(ValueError):
            gci([1, 2, 4], [1, 2, 3])


class HistoryGciTest(unittest.TestCase):
    """scripts/history_gci.py on three synthetic run folders whose values follow
    phi = phi_ext + C h^2 with h = cells^(-1/3)."""

    def make_run(self, root, name, cells, extra_times=()):
        import csv
        folder = os.path.join(root, name)
        os.makedirs(os.path.join(folder, "results", "visco"))
        os.makedirs(os.path.join(folder, "mesh"))
        with open(os.path.join(folder, "mesh", "mesh-summary.txt"), "w") as f:
            f.write("hydrofoil meshes: preset=%s\nfluid: cells %d points 1 foil-faces 1\n" % (name, cells))
        h = cells ** (-1.0 / 3.0)
        with open(os.path.join(folder, "results", "visco", "history.csv"), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["level", "time", "Fx", "Fy", "tip_aoa_deg"])
            for k, t in enumerate(sorted((0, 50, 360, 3600) + tuple(extra_times))):
                w.writerow([k, t, 0.4 + 50.0 * h * h, -(2.0 - 30.0 * h * h), -3.0 + 400.0 * h * h])
        return folder

    def test_power_law_and_csv(self):
        import subprocess
        import tempfile
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                              "scripts", "history_gci.py")
        with tempfile.TemporaryDirectory() as root:
            runs = [self.make_run(root, "coarse", 67345, (0.5, 2000)),
                    self.make_run(root, "medium", 141886), self.make_run(root, "fine", 372386)]
            out = os.path.join(root, "gci.csv")
            subprocess.run([sys.executable, script, "--out", out] + runs, check=True)
            import csv
            rows = {r["quantity"]: r for r in csv.DictReader(open(out))}
            self.assertEqual(len(rows), 12)  # 3 quantities x 4 times
            for t in ("0", "50", "360", "3600"):
                aoa = rows["tip_aoa_deg@t=" + t]
                self.assertEqual(aoa["convergence"], "monotone")
                self.assertAlmostEqual(float(aoa["observed_order"]), 2.0, places=4)
                self.assertAlmostEqual(float(aoa["extrapolated"]), -3.0, places=4)
                self.assertAlmostEqual(float(rows["lift_N@t=" + t]["extrapolated"]), 2.0, places=4)
                self.assertAlmostEqual(float(rows["drag_N@t=" + t]["extrapolated"]), 0.4, places=4)
            # a folder without t = 50 s: one-line error, exit 1
            bad = os.path.join(root, "bad")
            os.makedirs(os.path.join(bad, "results", "visco"))
            os.makedirs(os.path.join(bad, "mesh"))
            with open(os.path.join(bad, "mesh", "mesh-summary.txt"), "w") as f:
                f.write("fluid: cells 900000 points 1\n")
            with open(os.path.join(bad, "results", "visco", "history.csv"), "w") as f:
                f.write("level,time,Fx,Fy,tip_aoa_deg\n0,0,1,1,1\n")
            r = subprocess.run([sys.executable, script] + runs[:2] + [bad],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 1)
            self.assertIn("t = 50 s", r.stderr)


class RigidGciTest(unittest.TestCase):
    """history_gci.py --rigid on three synthetic rigid.sh / blcheck.sh folders whose loads
    follow phi = phi_ext + C h^1.5 with h = cells^(-1/3) (the cgrid presets' counts)."""

    CELLS = (276336, 595390, 1277256)

    def make_run(self, root, name, cells, converged=1, nested=False):
        folder = os.path.join(root, name)
        target = os.path.join(folder, "rigid") if nested else folder
        os.makedirs(target)
        h = cells ** (-1.0 / 3.0)
        with open(os.path.join(target, "rigid.csv"), "w") as f:
            f.write("cells,flow,scheme,iterations,converged,lift_N,drag_N,root_moment_z_Nm\n")
            f.write("%d,turbulent,upwind,900,%d,%.15g,%.15g,%.15g\n"
                    % (cells, converged, 1.6 + 40.0 * h ** 1.5, 0.2 + 9.0 * h ** 1.5, -0.03 - 0.5 * h ** 1.5))
        return folder

    def test_first_order_sequence(self):
        import csv
        import subprocess
        import tempfile
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                              "scripts", "history_gci.py")
        with tempfile.TemporaryDirectory() as root:
            runs = [self.make_run(root, "coarse", self.CELLS[0], nested=True),
                    self.make_run(root, "medium", self.CELLS[1]),
                    self.make_run(root, "fine", self.CELLS[2], nested=True)]
            out = os.path.join(root, "gci.csv")
            subprocess.run([sys.executable, script, "--rigid", "--out", out] + runs, check=True)
            with open(out) as f:
                rows = {r["quantity"]: r for r in csv.DictReader(f)}
            self.assertEqual(sorted(rows), ["drag_N", "lift_N", "root_moment_z_Nm"])
            for q, ext in (("lift_N", 1.6), ("drag_N", 0.2), ("root_moment_z_Nm", -0.03)):
                self.assertEqual(rows[q]["convergence"], "monotone")
                self.assertAlmostEqual(float(rows[q]["observed_order"]), 1.5, places=4)
                self.assertAlmostEqual(float(rows[q]["extrapolated"]), ext, places=5)
                self.assertEqual(rows[q]["asymptotic_range"], "yes")
                self.assertEqual(rows[q]["model"], "turbulent-upwind-cgrid")
            # a level whose solve did not meet its stopping test: no asymptotic claim, a warning
            runs[1] = self.make_run(root, "medium-capped", self.CELLS[1], converged=0)
            r = subprocess.run([sys.executable, script, "--rigid", "--out", out] + runs,
                               capture_output=True, text=True, check=True)
            self.assertIn("not converged", r.stderr)
            with open(out) as f:
                rows = {r["quantity"]: r for r in csv.DictReader(f)}
            self.assertEqual(rows["lift_N"]["asymptotic_range"], "no")
            # a folder without rigid.csv: one-line error, exit 1
            r = subprocess.run([sys.executable, script, "--rigid"] + runs[:2] + [root],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 1)
            self.assertIn("no rigid.csv", r.stderr)


class SteadyGciTest(unittest.TestCase):
    """history_gci.py --steady on three synthetic run.sh --material baseline folders whose
    coupled t = 0 state follows phi = phi_ext + C h^2 (h = cells^(-1/3)); --out keeps the rows
    of other models in the same file."""

    CELLS = (276336, 595390, 1277256)

    def make_run(self, root, name, cells, converged=1, shape_converged=None, interface=False):
        """shape_converged 0 or 1: also a shape check (shape-baseline/shape.csv) whose lift
        follows 1.25 + 50 h^2 and drag 0.35 + 10 h^2; interface: also the accepted interface
        displacement, a beam's motion whose twist at z = 0.09 m is -2.1 - 80 h^2 deg."""
        folder = os.path.join(root, name)
        os.makedirs(os.path.join(folder, "results", "baseline"))
        os.makedirs(os.path.join(folder, "mesh"))
        with open(os.path.join(folder, "mesh", "mesh-summary.txt"), "w") as f:
            f.write("fluid: cells %d points 1 foil-faces 1\n" % cells)
        h2 = cells ** (-2.0 / 3.0)
        # tip deflection = -(uy_le + uy_te)/2 = 0.009 + 0.4 h^2 (le and te differ by 2e-3 m)
        defl = 0.009 + 0.4 * h2
        with open(os.path.join(folder, "results", "baseline", "history.csv"), "w") as f:
            f.write("level,time,converged,Fx,Fy,tip_le_uy,tip_te_uy,tip_aoa_deg\n")
            f.write("0,0,%d,%.15g,%.15g,%.15g,%.15g,%.15g\n"
                    % (converged, 0.36 + 20.0 * h2, -(1.3 + 60.0 * h2), -defl + 1e-3, -defl - 1e-3,
                       -2.6 - 100.0 * h2))
        if interface:
            import math
            twist = math.radians(-2.1 - 80.0 * h2) / 0.09       # rate [rad/m], linear in z
            os.makedirs(os.path.join(folder, "results", "baseline", "interface"))
            with open(os.path.join(folder, "results", "baseline", "interface",
                                   "level_0000.csv"), "w") as f:
                f.write("# level 0 time 0 s\nx,y,z,ux,uy,uz,fx,fy,fz\n")
                for i in range(600):   # points on the foil's box, spread in x, y and z
                    x, y, z = 0.356 + 0.05 * ((i * 0.618) % 1), 0.006 * ((i * 0.414) % 1) - 0.003, \
                        0.1 * ((i * 0.3819) % 1)
                    theta = twist * z
                    f.write("%.17g,%.17g,%.17g,%.17g,%.17g,0,0,0,0\n"
                            % (x, y, z, -theta * y, -0.004 * (z / 0.1) ** 2 + theta * (x - 0.3685)))
        if shape_converged is not None:
            os.makedirs(os.path.join(folder, "shape-baseline"))
            with open(os.path.join(folder, "shape-baseline", "shape.csv"), "w") as f:
                f.write("time_s,coupled_lift_N,shape_lift_N,coupled_drag_N,shape_drag_N,converged\n"
                        "0,%.15g,%.15g,%.15g,%.15g,%d\n"
                        % (1.3 + 60.0 * h2, 1.25 + 50.0 * h2, 0.36 + 20.0 * h2, 0.35 + 10.0 * h2,
                           shape_converged))
        return folder

    def test_shape_check_quantities(self):
        import csv
        import subprocess
        import tempfile
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                              "scripts", "history_gci.py")
        names = ("coarse", "medium", "fine")
        with tempfile.TemporaryDirectory() as root:
            out = os.path.join(root, "gci.csv")
            runs = [self.make_run(root, n, c, shape_converged=1) for n, c in zip(names, self.CELLS)]
            subprocess.run([sys.executable, script, "--steady", "--model", "m", "--out", out] + runs,
                           check=True, capture_output=True)
            rows = {r["quantity"]: r for r in csv.DictReader(open(out))}
            self.assertEqual(len(rows), 6)
            for q, ext in (("shape_lift_N@t=0", 1.25), ("shape_drag_N@t=0", 0.35)):
                self.assertAlmostEqual(float(rows[q]["observed_order"]), 2.0, places=4)
                self.assertAlmostEqual(float(rows[q]["extrapolated"]), ext, places=5)
                self.assertEqual(rows[q]["asymptotic_range"], "yes")
                phi = [float(rows[q][n]) for n in names]
                self.assertAlmostEqual(float(rows[q]["range_uncertainty_pct"]),
                                       100 * 0.5 * (max(phi) - min(phi)) / phi[2], places=3)
            # a shape solve that did not converge: its quantities leave the asymptotic range,
            # the coupled ones keep it
            runs[1] = self.make_run(root, "medium-unsettled", self.CELLS[1], shape_converged=0)
            subprocess.run([sys.executable, script, "--steady", "--model", "m", "--out", out] + runs,
                           check=True, capture_output=True)
            rows = {r["quantity"]: r for r in csv.DictReader(open(out))}
            self.assertEqual(rows["shape_lift_N@t=0"]["asymptotic_range"], "no")
            self.assertEqual(rows["lift_N@t=0"]["asymptotic_range"], "yes")
            # one level without a shape check: no shape quantities
            runs[1] = self.make_run(root, "medium-plain", self.CELLS[1])
            subprocess.run([sys.executable, script, "--steady", "--model", "m", "--out", out] + runs,
                           check=True, capture_output=True)
            self.assertEqual(len(list(csv.DictReader(open(out)))), 4)

    def test_section_twist_quantity(self):
        import csv
        import subprocess
        import tempfile
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                              "scripts", "history_gci.py")
        with tempfile.TemporaryDirectory() as root:
            runs = [self.make_run(root, n, c, interface=True)
                    for n, c in zip(("coarse", "medium", "fine"), self.CELLS)]
            out = os.path.join(root, "gci.csv")
            subprocess.run([sys.executable, script, "--steady", "--model", "m", "--out", out] + runs,
                           check=True, capture_output=True)
            rows = {r["quantity"]: r for r in csv.DictReader(open(out))}
            q = rows["section_twist_deg@t=0"]
            for level, cells in zip(("coarse", "medium", "fine"), self.CELLS):
                self.assertAlmostEqual(float(q[level]), -2.1 - 80.0 * cells ** (-2.0 / 3.0), places=5)
            self.assertAlmostEqual(float(q["observed_order"]), 2.0, places=3)
            self.assertAlmostEqual(float(q["extrapolated"]), -2.1, places=4)
            # one level without its interface file: no section twist
            runs[0] = self.make_run(root, "coarse-plain", self.CELLS[0])
            subprocess.run([sys.executable, script, "--steady", "--model", "m", "--out", out] + runs,
                           check=True, capture_output=True)
            self.assertNotIn("section_twist_deg@t=0",
                             {r["quantity"] for r in csv.DictReader(open(out))})

    def test_second_order_sequence_and_merge(self):
        import csv
        import subprocess
        import tempfile
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                              "scripts", "history_gci.py")
        with tempfile.TemporaryDirectory() as root:
            runs = [self.make_run(root, n, c) for n, c in zip(("coarse", "medium", "fine"), self.CELLS)]
            out = os.path.join(root, "gci.csv")
            with open(out, "w") as f:  # an earlier study of another model in the same file
                f.write("quantity,model,levels,observed_order,extrapolated,gci_fine_pct\n"
                        "lift_N@t=50,laminar-upwind-snappy,1 2 3,2,1.8,0.5\n")
            subprocess.run([sys.executable, script, "--steady", "--model", "sst-cgrid", "--out", out]
                           + runs, check=True, capture_output=True)
            with open(out) as f:
                rows = list(csv.DictReader(f))
            self.assertEqual([r["model"] for r in rows].count("laminar-upwind-snappy"), 1)
            mine = {r["quantity"]: r for r in rows if r["model"] == "sst-cgrid"}
            self.assertEqual(sorted(mine), ["drag_N@t=0", "lift_N@t=0", "tip_aoa_deg@t=0",
                                            "tip_deflection_m@t=0"])
            for q, ext in (("tip_aoa_deg@t=0", -2.6), ("tip_deflection_m@t=0", 0.009),
                           ("lift_N@t=0", 1.3), ("drag_N@t=0", 0.36)):
                self.assertAlmostEqual(float(mine[q]["observed_order"]), 2.0, places=4)
                self.assertAlmostEqual(float(mine[q]["extrapolated"]), ext, places=5)
                self.assertEqual(mine[q]["asymptotic_range"], "yes")
            # rerun of the same model replaces its rows, a level that did not converge is flagged
            runs[2] = self.make_run(root, "fine-unconverged", self.CELLS[2], converged=0)
            r = subprocess.run([sys.executable, script, "--steady", "--model", "sst-cgrid", "--out", out]
                               + runs, capture_output=True, text=True, check=True)
            self.assertIn("not converged", r.stderr)
            with open(out) as f:
                rows = list(csv.DictReader(f))
            self.assertEqual(len(rows), 5)
            self.assertTrue(all(r["asymptotic_range"] == "no" for r in rows if r["model"] == "sst-cgrid"))
            # a rigid folder given to --steady: one-line error, exit 1
            r = subprocess.run([sys.executable, script, "--steady"] + runs[:2] + [root],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 1)
            self.assertIn("results/baseline/history.csv", r.stderr)


class LevelsErrorCsvTest(unittest.TestCase):
    """scripts/levels_error_csv.py: one model's levels against its gci.csv reference, the rows of
    other models kept in levels.csv and error_vs_runtime.csv."""

    def test_reference_and_merge(self):
        import csv
        import subprocess
        import tempfile
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                              "scripts", "levels_error_csv.py")
        with tempfile.TemporaryDirectory() as root:
            levels, gciCsv, out = (os.path.join(root, n) for n in ("levels.csv", "gci.csv", "evr.csv"))
            with open(levels, "w") as f:
                f.write("model,preset,cells,iterations,converged,lift_N,cpu_s,wall_s,yplus_max\n")
                for m, lifts in (("first", (2.2, 2.1, 2.0)), ("second", (1.75, 1.78, 1.80))):
                    for p, c, lift in zip(("coarse", "medium", "fine"), (1, 2, 4), lifts):
                        f.write("%s,%s,%d,500,1,%g,%d,%d,0.9\n" % (m, p, c, lift, 10 * c, 5 * c))
            with open(gciCsv, "w") as f:
                f.write("quantity,model,extrapolated,fine,asymptotic_range\n"
                        "lift_N,first,1.9,2.0,yes\nlift_N,second,1.85,1.80,no\n")
            for m in ("first", "second", "first"):  # a rerun replaces its own rows only
                subprocess.run([sys.executable, script, levels, gciCsv, out, "2", m,
                                "--extra", "yplus_max"], check=True)
            with open(out) as f:
                rows = list(csv.DictReader(f))
            self.assertEqual(len(rows), 6)
            self.assertEqual([r["model"] for r in rows], ["second"] * 3 + ["first"] * 3)
            first = {r["level"]: r for r in rows if r["model"] == "first"}
            # asymptotic: the extrapolated value is the reference
            self.assertAlmostEqual(float(first["coarse"]["reference"]), 1.9, places=12)
            self.assertAlmostEqual(float(first["coarse"]["rel_error"]), 0.3 / 1.9, places=6)
            self.assertEqual(first["fine"]["wall_s"], "20")
            self.assertEqual(first["fine"]["yplus_max"], "0.9")
            # not asymptotic: the finest level is the reference and its own error is 0
            second = {r["level"]: r for r in rows if r["model"] == "second"}
            self.assertEqual(float(second["fine"]["rel_error"]), 0.0)
            self.assertAlmostEqual(float(second["coarse"]["rel_error"]), 0.05 / 1.8, places=6)
            # a model without gci rows: one-line error, exit 1, the output untouched
            r = subprocess.run([sys.executable, script, levels, gciCsv, out, "2", "third"],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 1)
            self.assertIn("levels of model third", r.stderr)
            with open(out) as f:
                self.assertEqual(len(list(csv.DictReader(f))), 6)


if __name__ == "__main__":
    unittest.main()
