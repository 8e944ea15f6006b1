#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Mesh study of the hydrofoil on three presets: the viscoelastic history, or the rigid foil.

usage: history_gci.py [--rigid | --steady] [--model NAME] [--out GCI_CSV] [--table] COARSE MEDIUM FINE

COARSE, MEDIUM, FINE: run folders of the same case on three presets (a `run.sh` output folder,
or a bench-fsi work folder whose iqn-ils/ run is used), each with results/visco/history.csv and
mesh/mesh-summary.txt (the fluid cell count: h = cells^(-1/3), the fluid mesh's representative
size; the Tet10 foil is refined with it). For the tip AOA [deg], the lift -F_y [N] and the drag
F_x [N] at t = 0, 50, 360 and 3600 s (the times every schedule of the case hits) it applies
scripts/gci.py (Celik et al. 2008: observed order, extrapolated value, GCI_fine; NaN unless the
three values converge monotonically) and writes GCI_CSV with the columns
    quantity,model,levels,observed_order,extrapolated,gci_fine_pct,convergence,
    coarse,medium,fine,rel_diff_coarse_fine,rel_diff_medium_fine
(quantity: e.g. tip_aoa_deg@t=360), then asymptotic_ratio (gci.py: 1 in the asymptotic range),
asymptotic_range (yes when the sequence is monotone with an observed order between 1 and 3 and
every level's solve met its stopping test) and range_uncertainty_pct (below). --table prints
the same as a Markdown table.

--rigid: COARSE, MEDIUM, FINE are rigid-foil runs (cases/hydrofoil/rigid.sh folders with
rigid.csv, or blcheck.sh folders with rigid/rigid.csv; the cell count is rigid.csv's); the
quantities are the lift -F_y [N], the drag F_x [N] and the root pitching moment M_z [N m]
(quantity names lift_N, drag_N, root_moment_z_Nm), and a level counts as settled when its
rigid.csv says converged = 1.

--steady: COARSE, MEDIUM, FINE are run.sh folders of the coupled elastic t = 0 state
(`run.sh --material baseline`: results/baseline/history.csv, one accepted level, and
mesh/mesh-summary.txt); the quantities are the tip AOA [deg], the tip deflection [m] (along the
lift direction -y, the mean of the tip leading and trailing edge points) and the lift -F_y and
drag F_x [N], all with the suffix @t=0; a level counts as settled when history.csv says
converged = 1. When all three folders hold a shape check (shape-baseline/shape.csv of
cases/hydrofoil/tools/shapeCheck.sh: the accepted shape solved on to convergence), its lift and
drag are two more quantities, shape_lift_N@t=0 and shape_drag_N@t=0 (settled when shape.csv
says converged = 1): the coupled loads without the coupled solves' fluid iteration error.
When all three folders hold the accepted level's interface displacement
(results/baseline/interface/level_0000.csv), the twist of the section at z = 0.09 m fitted to it
(cases/hydrofoil/tools/sectionShape.py) is one more quantity, section_twist_deg@t=0: the tip
AOA of the two tip watch points carries the local deformation of the mesh's tip corners (2 %
between the Tet10 and Hex20 foils at the same section twist: cases/hydrofoil/README.md, "The
structure's share of the coupled mesh study").

Every row also gets range_uncertainty_pct: half the spread of the three values over |fine|, in
percent, the uncertainty estimate for oscillatory convergence (Stern et al., J. Fluids Eng. 123,
2001: U = (max - min) / 2), where no order and hence no GCI exists.

With --out, rows of GCI_CSV with another model are kept (one file holds several studies, one
block per model); rows of this model are replaced.

Exits 1 with a one-line error when a folder lacks a file or a time.
"""
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(1, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cases",
                                "hydrofoil", "tools"))
import gci  # noqa: E402
import sectionShape  # noqa: E402
from model_csv import write_model_rows  # noqa: E402

TIMES = (0.0, 50.0, 360.0, 3600.0)
RIGID_QUANTITIES = ("lift_N", "drag_N", "root_moment_z_Nm")
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


def steady_run(folder):
    """cells, {quantity@t=0: value} and converged of a run.sh --material baseline folder."""
    history = os.path.join(folder, "results", "baseline", "history.csv")
    summary = os.path.join(folder, "mesh", "mesh-summary.txt")
    for path in (history, summary):
        if not os.path.isfile(path):
            fail(f"{folder}: no {os.path.relpath(path, folder)}; give a run.sh --material "
                 "baseline folder")
    rows = list(csv.DictReader(open(history)))
    if len(rows) != 1:
        fail(f"{history}: one accepted level expected, found {len(rows)}")
    r = rows[0]
    try:
        values = {"tip_aoa_deg@t=0": float(r["tip_aoa_deg"]),
                  "tip_deflection_m@t=0": -0.5 * (float(r["tip_le_uy"]) + float(r["tip_te_uy"])),
                  "lift_N@t=0": -float(r["Fy"]),
                  "drag_N@t=0": float(r["Fx"])}
    except (KeyError, ValueError) as e:
        fail(f"{history}: column tip_aoa_deg, tip_le_uy, tip_te_uy, Fy or Fx missing or not a "
             f"number ({e})")
    return fluid_cells(summary), values, r.get("converged") == "1"


SECTION_STATION, SECTION_HALF_WIDTH = 0.09, 2.5e-3   # [m]


def section_twist(folder):
    """{section_twist_deg@t=0} of FOLDER's accepted interface displacement, or None when it has
    no results/baseline/interface/level_0000.csv."""
    path = os.path.join(folder, "results", "baseline", "interface", "level_0000.csv")
    if not os.path.isfile(path):
        return None
    points, disp = sectionShape.read_interface(path)
    try:
        fit = sectionShape.section_shape(points, disp, SECTION_STATION, SECTION_HALF_WIDTH)
    except ValueError as e:
        fail(f"{path}: {e}")
    return {"section_twist_deg@t=0": fit["twist_deg"]}


def shape_check(folder):
    """({shape_lift_N@t=0, shape_drag_N@t=0}, converged) of FOLDER's shape check, or None when
    it has none (shape-baseline/shape.csv)."""
    path = os.path.join(folder, "shape-baseline", "shape.csv")
    if not os.path.isfile(path):
        return None
    rows = list(csv.DictReader(open(path)))
    try:
        r = rows[-1]
        return ({"shape_lift_N@t=0": float(r["shape_lift_N"]),
                 "shape_drag_N@t=0": float(r["shape_drag_N"])}, r.get("converged") == "1")
    except (IndexError, KeyError, ValueError) as e:
        fail(f"{path}: no row with numbers in shape_lift_N and shape_drag_N ({e})")


def rigid_run(folder):
    """cells, {quantity: value} and converged (bool) of a rigid.sh / blcheck.sh folder."""
    for path in (os.path.join(folder, "rigid.csv"), os.path.join(folder, "rigid", "rigid.csv")):
        if os.path.isfile(path):
            break
    else:
        fail(f"{folder}: no rigid.csv (nor rigid/rigid.csv); give a rigid.sh or blcheck.sh folder")
    rows = list(csv.DictReader(open(path)))
    if len(rows) != 1:
        fail(f"{path}: one row expected, found {len(rows)}")
    try:
        return (int(rows[0]["cells"]), {q: float(rows[0][q]) for q in RIGID_QUANTITIES},
                rows[0]["converged"] == "1")
    except (KeyError, ValueError) as e:
        fail(f"{path}: column cells, converged or {'/'.join(RIGID_QUANTITIES)} missing or not a "
             f"number ({e})")


def history_runs(folders):
    """cells, {quantity@t: value} and converged per folder (a history's accepted levels are
    converged by the driver's acceptance rule)."""
    out = []
    for folder in folders:
        history, summary = run_files(folder)
        values = values_at_times(history)
        out.append((fluid_cells(summary),
                    {f"{name}@t={t:g}": values[t][name] for t in TIMES for name, _ in QUANTITIES},
                    True))
    return out


def main(argv):
    model, out, table, rigid, steady, folders = None, None, False, False, False, []
    i = 0
    while i < len(argv):
        if argv[i] in ("-h", "--help"):
            print(__doc__.strip())
            sys.exit(0)
        elif argv[i] == "--rigid":
            rigid, i = True, i + 1
        elif argv[i] == "--steady":
            steady, i = True, i + 1
        elif argv[i] == "--model":
            model, i = argv[i + 1], i + 2
        elif argv[i] == "--out":
            out, i = argv[i + 1], i + 2
        elif argv[i] == "--table":
            table, i = True, i + 1
        elif argv[i].startswith("--"):
            fail(f"unknown option {argv[i]} (--rigid, --steady, --model NAME, --out FILE, --table)")
        else:
            folders.append(argv[i])
            i += 1
    if rigid and steady:
        fail("--rigid and --steady exclude each other")
    if len(folders) != 3:
        fail("three run folders needed, coarsest first (COARSE MEDIUM FINE)")
    if model is None:
        model = "turbulent-upwind-cgrid" if rigid else "laminar-upwind"
    shape_settled = False
    if rigid:
        runs = [rigid_run(f) for f in folders]
    elif steady:
        runs = [steady_run(f) for f in folders]
        twists = [section_twist(f) for f in folders]
        if all(twists):
            for (_, values, _), twist in zip(runs, twists):
                values.update(twist)
        shapes = [shape_check(f) for f in folders]
        if all(shapes):
            for (_, values, _), (shape_values, _) in zip(runs, shapes):
                values.update(shape_values)
            shape_settled = all(ok for _, ok in shapes)
    else:
        runs = history_runs(folders)
    cells = [c for c, _, _ in runs]
    if not cells[0] < cells[1] < cells[2]:
        fail(f"fluid cells {cells}: the folders must go from coarsest to finest")
    settled = all(ok for _, _, ok in runs)
    if not settled:
        print("history_gci.py: warning: levels not converged: "
              + " ".join(f for f, (_, _, ok) in zip(folders, runs) if not ok), file=sys.stderr)
    h = [c ** (-1.0 / 3.0) for c in cells]
    rows = []
    for quantity in runs[0][1]:
        phi = [values[quantity] for _, values, _ in runs]
        g = gci.gci(h, phi)
        settled_here = shape_settled if quantity.startswith("shape_") else settled
        asymptotic = (settled_here and g["convergence"] == "monotone"
                      and 1.0 <= g["observed_order"] <= 3.0)
        rows.append({
            "quantity": quantity, "model": model,
            "levels": f"{cells[0]} {cells[1]} {cells[2]}",
            "observed_order": g["observed_order"], "extrapolated": g["extrapolated"],
            "gci_fine_pct": g["gci_fine_pct"], "convergence": g["convergence"],
            "coarse": phi[0], "medium": phi[1], "fine": phi[2],
            "rel_diff_coarse_fine": (phi[0] - phi[2]) / phi[2],
            "rel_diff_medium_fine": (phi[1] - phi[2]) / phi[2],
            "asymptotic_ratio": g["asymptotic_ratio"],
            "asymptotic_range": "yes" if asymptotic else "no",
            "range_uncertainty_pct": g["range_uncertainty_pct"]})
    columns = list(rows[0].keys())
    if out:
        write_model_rows(out, columns, model, [{k: (f"{v:.6g}" if isinstance(v, float) else v)
                                                for k, v in r.items()} for r in rows])
    if table or not out:
        print("| quantity | coarse | medium | fine | coarse vs fine | medium vs fine | "
              "convergence | order | GCI_fine | range / 2 |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            def num(v, fmt):
                return fmt % v if not math.isnan(v) else "-"
            print(f"| {r['quantity']} | {r['coarse']:.4g} | {r['medium']:.4g} | {r['fine']:.4g} | "
                  f"{100 * r['rel_diff_coarse_fine']:+.1f} % | "
                  f"{100 * r['rel_diff_medium_fine']:+.1f} % | {r['convergence']} | "
                  f"{num(r['observed_order'], '%.2f')} | {num(r['gci_fine_pct'], '%.2f %%')} | "
                  f"{num(r['range_uncertainty_pct'], '%.2f %%')} |")


if __name__ == "__main__":
    main(sys.argv[1:])
