#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""cases/hydrofoil/section2d/blstate.py on a synthetic solved case with a known answer: a thin
plate foil from x/c 0 to 1 (faces on both sides), the suction side (lower mean pressure) with
nu_t/nu 0.5 up to x/c 0.3 and 5 behind it, and reversed wall shear from x/c 0.85."""
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
BLSTATE = os.path.join(HERE, "..", "..", "..", "cases", "hydrofoil", "section2d", "blstate.py")
CHORD, X_LE, NU = 0.05, 0.356, 1.004e-6
N = 100  # faces per side


def writeField(path, kind, values):
    with open(path, "w") as f:
        f.write("FoamFile { version 2.0; format ascii; class vol%sField; object x; }\n"
                % ("Scalar" if kind == "scalar" else "Vector"))
        f.write("internalField   nonuniform List<%s> \n%d\n(\n" % (kind, len(values)))
        for v in values:
            f.write(("%.9g\n" % v) if kind == "scalar" else "(%.9g %.9g %.9g)\n" % v)
        f.write(")\n;\n\nboundaryField\n{\n}\n")


def makeCase(root, laminar=False):
    case = os.path.join(root, "case")
    os.makedirs(os.path.join(case, "0"))
    os.makedirs(os.path.join(case, "500"))
    surf = os.path.join(case, "postProcessing", "foilSurface", "500")
    os.makedirs(surf)
    faces, cells, nut = [], [], []
    for side, y0, sgn in (("upper", 1e-4, 1.0), ("lower", -1e-4, -1.0)):
        for i in range(N):
            xc = (i + 0.5) / N
            faces.append((X_LE + xc * CHORD, y0, side, xc))
            # two cells above the face, inside the 2 mm band
            for d in (2e-4, 6e-4):
                cells.append((X_LE + xc * CHORD, y0 + sgn * d, 0.0))
                suction = side == "lower"
                nut.append(0.0 if laminar else NU * ((0.5 if xc < 0.3 else 5.0) if suction else 2.0))
    with open(os.path.join(surf, "wallShearStress_foil.raw"), "w") as fw, \
            open(os.path.join(surf, "p_foil.raw"), "w") as fp:
        fw.write("#  x  y  z  wallShearStress_x  wallShearStress_y  wallShearStress_z\n")
        fp.write("#  x  y  z  p\n")
        for x, y, side, xc in faces:
            # OpenFOAM's wall shear stress points against the near-wall flow
            tauX = 0.002 if (side == "lower" and xc > 0.85) else -0.004
            fw.write("%.9g %.9g 0 %.9g 0 0\n" % (x, y, tauX))
            fp.write("%.9g %.9g 0 %.9g\n" % (x, y, -0.5 if side == "lower" else 0.2))
    writeField(os.path.join(case, "500", "nut"), "scalar", nut)
    writeField(os.path.join(case, "500", "C"), "vector", cells)
    return case


class BlStateTest(unittest.TestCase):
    def test_onset_and_separation(self):
        with tempfile.TemporaryDirectory() as root:
            case = makeCase(root)
            out = os.path.join(root, "bl.csv")
            res = subprocess.run([sys.executable, BLSTATE, case, out], capture_output=True,
                                 text=True, check=True)
            last = [l for l in res.stdout.splitlines() if l.startswith("blstate-onsets:")][0]
            turbS, sepS, turbP, sepP = (float(v) for v in last.split()[1:])
            self.assertAlmostEqual(turbS, 0.305, delta=1e-9)   # first face centre behind 0.3
            self.assertAlmostEqual(sepS, 0.855, delta=1e-9)    # first reversed face
            self.assertAlmostEqual(turbP, 0.005, delta=1e-9)   # nu_t/nu 2 everywhere
            self.assertNotEqual(sepP, sepP)                    # NaN: attached
            rows = open(out).read().splitlines()
            self.assertEqual(rows[0], "side,x_c,cf,cf_turb,cf_lam,nut_ratio_max")
            self.assertEqual(len(rows), 1 + 2 * N)
            cf = {(r.split(",")[0], round(float(r.split(",")[1]), 3)): float(r.split(",")[2])
                  for r in rows[1:]}
            self.assertAlmostEqual(cf[("suction", 0.505)], 0.004 / 2.0, delta=1e-12)  # tau/(U^2/2)
            self.assertAlmostEqual(cf[("suction", 0.905)], -0.002 / 2.0, delta=1e-12)

    def test_laminar_layer_has_no_onset(self):
        # nu_t = 0 everywhere (the laminar model): no x/c from which the layer is turbulent
        with tempfile.TemporaryDirectory() as root:
            case = makeCase(root, laminar=True)
            res = subprocess.run([sys.executable, BLSTATE, case, os.path.join(root, "bl.csv")],
                                 capture_output=True, text=True, check=True)
            last = [l for l in res.stdout.splitlines() if l.startswith("blstate-onsets:")][0]
            turbS, _, turbP, _ = (float(v) for v in last.split()[1:])
            self.assertNotEqual(turbS, turbS)
            self.assertNotEqual(turbP, turbP)

    def test_binary_fields_are_refused(self):
        with tempfile.TemporaryDirectory() as root:
            case = makeCase(root)
            with open(os.path.join(case, "500", "nut"), "w") as f:
                f.write("FoamFile { version 2.0; format binary; class volScalarField; }\n"
                        "internalField nonuniform List<scalar> 3(\x01\x02);\n")
            res = subprocess.run([sys.executable, BLSTATE, case, os.path.join(root, "bl.csv")],
                                 capture_output=True, text=True)
            self.assertNotEqual(res.returncode, 0)
            self.assertIn("writeFormat ascii", res.stderr)
            self.assertFalse(os.path.exists(os.path.join(root, "bl.csv")))


if __name__ == "__main__":
    unittest.main()
