#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The error_vs_runtime.csv of a three-level mesh study of steady loads.

usage: levels_error_csv.py LEVELS_CSV GCI_CSV OUT_CSV CORES MODEL [--extra COLUMN ...]

LEVELS_CSV: one row per level, coarse to fine, with the columns preset, cells, wall_s, cpu_s,
iterations, converged and one column per quantity of GCI_CSV's rows of MODEL
(scripts/history_gci.py --rigid: lift_N, drag_N, root_moment_z_Nm; the file may hold other
models' rows too). Writes OUT_CSV with the standard columns
level,size,cores,wall_s,quantity,value,reference,rel_error and then cpu_s, iterations,
converged and the --extra columns of LEVELS_CSV. The reference of a quantity is its extrapolated
value where gci.csv says the three levels are in the asymptotic range, else the finest level's
value (whose rows then have rel_error 0).
"""
import csv
import sys


def main(argv):
    if len(argv) < 6 or (len(argv) > 6 and argv[6] != "--extra"):
        sys.exit(__doc__.strip().splitlines()[2])
    levelsCsv, gciCsv, out, cores, model = argv[1:6]
    extra = argv[7:]
    levels = list(csv.DictReader(open(levelsCsv)))
    gci = [g for g in csv.DictReader(open(gciCsv)) if g["model"] == model]
    if not gci:
        sys.exit("error: levels_error_csv.py: %s has no rows of model %s" % (gciCsv, model))
    with open(out, "w") as f:
        f.write(",".join(["level", "size", "cores", "wall_s", "quantity", "value", "reference",
                          "rel_error", "cpu_s", "iterations", "converged"] + extra) + "\n")
        for g in gci:
            q = g["quantity"]
            ref = float(g["extrapolated"]) if g["asymptotic_range"] == "yes" else float(g["fine"])
            for l in levels:
                v = float(l[q])
                f.write(",".join([l["preset"], l["cells"], cores, l["wall_s"], q, "%.8g" % v,
                                  "%.8g" % ref, "%.6e" % (abs(v - ref) / abs(ref)), l["cpu_s"],
                                  l["iterations"], l["converged"]] + [l[c] for c in extra]) + "\n")


if __name__ == "__main__":
    main(sys.argv)
