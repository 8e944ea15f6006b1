#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Grid convergence index (Roache; ASME V&V 20-2009, Celik et al. J. Fluids Eng. 130, 2008).

For three solutions phi1 (finest) .. phi3 (coarsest) on meshes of representative sizes
h1 < h2 < h3 (h = (volume / cells)^(1/dim)):
    r21 = h2/h1, r32 = h3/h2, e21 = phi2 - phi1, e32 = phi3 - phi2
    observed order p: |ln|e32/e21| + q(p)| / ln r21 = p, q(p) = ln((r21^p - s)/(r32^p - s)),
    s = sign(e32/e21) (fixed-point iteration; q = 0 for a constant ratio)
    extrapolated phi_ext = (r21^p phi1 - phi2) / (r21^p - 1)
    GCI_fine = Fs |(phi1 - phi2)/phi1| / (r21^p - 1), Fs = 1.25 (three meshes)
Only monotone convergence (0 < e21/e32 < 1) gets an order: oscillatory (e32/e21 < 0) and
diverging (|e21| >= |e32|) sequences are flagged and get NaN. Every sequence also gets
    range_uncertainty_pct = 100 (max phi - min phi) / 2 / |phi1|,
the estimate for oscillatory convergence (Stern, Wilson, Coleman & Paterson, J. Fluids Eng. 123,
2001: U = (S_U - S_L) / 2, half the range of the solutions).

CLI: gci.py H3,PHI3 H2,PHI2 H1,PHI1  -> prints observed_order, extrapolated, gci_fine_pct.
"""
import math
import sys


def gci(h, phi, fs=1.25, maxIter=200):
    """h, phi: three values each, coarsest first. Returns a dict with observed_order,
    extrapolated, gci_fine_pct (percent of phi1), rel_diff_fine (|phi1 - phi2|/|phi1|),
    convergence ('monotone' | 'oscillatory' | 'diverging' | 'converged' | 'indeterminate'),
    asymptotic_ratio: the error estimate of the medium mesh |e32|/(r32^p - 1) over r21^p times
    that of the fine mesh |e21|/(r21^p - 1) (1 in the asymptotic range), and
    range_uncertainty_pct: half the range of the three values in percent of |phi1|."""
    if len(h) != 3 or len(phi) != 3:
        raise ValueError("gci: three levels needed (coarsest first)")
    h3, h2, h1 = (float(v) for v in h)
    p3, p2, p1 = (float(v) for v in phi)
    if not (h1 < h2 < h3):
        raise ValueError("gci: sizes must decrease from coarsest to finest, got %r" % (h,))
    r21, r32 = h2 / h1, h3 / h2
    e21, e32 = p2 - p1, p3 - p2
    out = dict(r21=r21, r32=r32, observed_order=float("nan"), extrapolated=float("nan"),
               gci_fine_pct=float("nan"), rel_diff_fine=abs(e21) / abs(p1) if p1 else float("nan"),
               asymptotic_ratio=float("nan"),
               range_uncertainty_pct=(100.0 * 0.5 * (max(p1, p2, p3) - min(p1, p2, p3)) / abs(p1)
                                      if p1 else float("nan")))
    if e21 == 0.0 and e32 == 0.0:
        out.update(convergence="converged", observed_order=float("inf"), extrapolated=p1,
                   gci_fine_pct=0.0)
        return out
    if e21 == 0.0 or e32 == 0.0:
        out["convergence"] = "indeterminate"
        return out
    ratio = e32 / e21
    if ratio < 0:
        out["convergence"] = "oscillatory"
        return out
    if abs(e21) >= abs(e32):
        out["convergence"] = "diverging"
        return out
    s = 1.0
    p = math.log(abs(ratio)) / math.log(r21)
    for _ in range(maxIter):
        q = math.log((r21 ** p - s) / (r32 ** p - s))
        pNew = abs(math.log(abs(ratio)) + q) / math.log(r21)
        if abs(pNew - p) < 1e-12:
            p = pNew
            break
        p = pNew
    rp = r21 ** p
    ext = (rp * p1 - p2) / (rp - 1.0)
    gciFine = fs * abs(e21 / p1) / (rp - 1.0)
    # asymptotic-range check on absolute errors: the medium error estimate over r21^p times
    # the fine one; exactly 1 for phi = phi_ext + C h^p
    errMedium = abs(e32) / (r32 ** p - 1.0)
    errFine = abs(e21) / (rp - 1.0)
    out.update(convergence="monotone", observed_order=p, extrapolated=ext,
               gci_fine_pct=100.0 * gciFine,
               asymptotic_ratio=errMedium / (rp * errFine) if errFine > 0 else float("nan"))
    return out


def main(argv):
    if argv and argv[0] in ("-h", "--help"):
        print(__doc__.strip())
        return
    if len(argv) != 3:
        sys.exit("usage: gci.py H3,PHI3 H2,PHI2 H1,PHI1 (coarsest first)")
    pairs = [tuple(float(v) for v in a.split(",")) for a in argv]
    r = gci([p[0] for p in pairs], [p[1] for p in pairs])
    print(" ".join("%s=%s" % (k, ("%.6g" % v) if isinstance(v, float) else v)
                   for k, v in r.items()))


if __name__ == "__main__":
    main(sys.argv[1:])
