#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""scripts/gci.py against sequences with a known answer."""
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

    def test_bad_input(self):
        with self.assertRaises(ValueError):
            gci([1, 2, 4], [1, 2, 3])


if __name__ == "__main__":
    unittest.main()
