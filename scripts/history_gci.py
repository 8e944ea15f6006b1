#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Mesh study of the hydrofoil's viscoelastic history on three presets.

usage: history_gci.py [--model NAME] [--out GCI_CSV] [--table] COARSE MEDIUM FINE

COARSE, MEDIUM, FINE: run folders of the same case on three presets (a `run.sh` output folder,
or a bench-fsi work folder whose iqn-ils/ run is used), each with results/visco/history.csv and
mesh/mesh-summary.txt (the fluid cell count: h = cells^(-1/3), the fluid mesh's representative
size; the Tet10 foil is refined with it). For the tip AOA [deg], the lift -F_y [N] and the drag
F_x [N] at t = 0, 50, 360 and 3600 s (the times every schedule of the case hits) it applies
scripts/gci.py (Celik et al. 2008: observed order, extrapolated value, GCI_fine; NaN unless the
three values converge monotonically) and writes GCI_CSV with the columns
    quantity,model,levels,observed_order,extrapolated,gci_fine_pct,convergence,
    coarse,medium,fine,rel_diff_coarse_fine,rel_diff_medium_fine
(quantity: e.g. tip_aoa_deg@t=360). --table prints the same as a Markdown table. Exits 1 with a
one-line error when a folder lacks a file or a time.
"""
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gci  # noqa: E402

TIMES = (0.0, 50.0, 360.0, 3600.0)
QUANTITIES = (("tip_aoa_deg", lambda r: float(r["tip_aoa_deg"])),
              ("lift_N", lambda r: -float(r["Fy"])),
              ("drag_N", lambda r: float(r["Fx"])))


def fail(message):
    sys.exit("error: history_gci.py: " + message)


def run_files(folder):
    for base in (os.path.join(folder, "iqn-ils"), folder):
        history = os.path.join(base, "results", "visco", "history.csv")
        if os.path.isfile(history):
            break
    else:
        fail(f"{folder}: no results/visco/history.csv (nor iqn-ils/results/visco/history.csv); "
             "give a run.sh or bench-fsi --run folder")
    for summary in (os.path.join(folder, "mesh", "mesh-summary.txt"),
                    os.path.join(base, "mesh", "mesh-summary.txt")):
        if os.path.isfile(summary):
            return history, summary
    fail(f"{folder}: no mesh/mesh-summary.txt (the fluid cell count)")


def fluid_cells(summary):
    for line in open(summary):
        if line.startswith("fluid: cells "):
            return int(line.split()[2])
    fail(f"{summary}: no 'fluid: cells N' line")


def values_at_times(history):
    rows = list(csv.DictReader(open(history)))
    out = {}
    for t in TIMES:
        hit = [r for r in rows if abs(float(r["time"]) - t) <= 1e-9 * max(1.0, t)]
        if not hit:
            fail(f"{history}: no accepted level at t = {t:g} s (a run to 3600 s with the case's "
                 "hit times is needed)")
        out[t] = {name: get(hit[-1]) for name, get in QUANTITIES}
    return out


def main(argv):
    model, out, table, folders = "laminar-upwind", None, False, []
    i = 0
    while i < len(argv):
        if argv[i] == "--model":
            model, i = argv[i + 1], i + 2
        elif argv[i] == "--out":
            out, i = argv[i + 1], i + 2
        elif argv[i] == "--table":
            table, i = True, i + 1
        elif argv[i].startswith("--"):
            fail(f"unknown option {argv[i]} (--model NAME, --out FILE, --table)")
        else:
            folders.append(argv[i])
            i += 1
    if len(folders) != 3:
        fail("three run folders needed, coarsest first (COARSE MEDIUM FINE)")
    runs = [run_files(f) for f in folders]
    cells = [fluid_cells(s) for _, s in runs]
    if not cells[0] < cells[1] < cells[2]:
        fail(f"fluid cells {cells}: the folders must go from coarsest to finest")
    h = [c ** (-1.0 / 3.0) for c in cells]
    values = [values_at_times(hist) for hist, _ in runs]
    rows = []
    for t in TIMES:
        for name, _ in QUANTITIES:
            phi = [v[t][name] for v in values]
            g = gci.gci(h, phi)
            rows.append({
                "quantity": f"{name}@t={t:g}", "model": model,
                "levels": f"{cells[0]} {cells[1]} {cells[2]}",
                "observed_order": g["observed_order"], "extrapolated": g["extrapolated"],
                "gci_fine_pct": g["gci_fine_pct"], "convergence": g["convergence"],
                "coarse": phi[0], "medium": phi[1], "fine": phi[2],
                "rel_diff_coarse_fine": (phi[0] - phi[2]) / phi[2],
                "rel_diff_medium_fine": (phi[1] - phi[2]) / phi[2]})
    columns = list(rows[0].keys())
    if out:
        with open(out, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=columns)
            w.writeheader()
            for r in rows:
                w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    if table or not out:
        print("| quantity | coarse | medium | fine | coarse vs fine | medium vs fine | "
              "convergence | order | GCI_fine |")
        print("|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            def num(v, fmt):
                return fmt % v if not math.isnan(v) else "-"
            print(f"| {r['quantity']} | {r['coarse']:.4g} | {r['medium']:.4g} | {r['fine']:.4g} | "
                  f"{100 * r['rel_diff_coarse_fine']:+.1f} % | "
                  f"{100 * r['rel_diff_medium_fine']:+.1f} % | {r['convergence']} | "
                  f"{num(r['observed_order'], '%.2f')} | {num(r['gci_fine_pct'], '%.2f %%')} |")


if __name__ == "__main__":
    main(sys.argv[1:])
