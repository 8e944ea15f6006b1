#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The error_vs_runtime.csv of a three-level mesh study of steady loads.

usage: levels_error_csv.py LEVELS_CSV GCI_CSV OUT_CSV CORES MODEL [--extra COLUMN ...]

LEVELS_CSV: one row per level, coarse to fine, with the columns preset, cells, wall_s, cpu_s,
iterations, converged and one column per quantity of GCI_CSV's rows of MODEL
(scripts/history_gci.py --rigid: lift_N, drag_N, root_moment_z_Nm; the file may hold other
models' rows too). A LEVELS_CSV with a column model holds several studies: only its rows of
MODEL are read. Writes OUT_CSV with the standard columns
level,size,cores,wall_s,quantity,value,reference,rel_error and then model, cpu_s, iterations,
converged and the --extra columns of LEVELS_CSV; rows of another model already in OUT_CSV are
kept, this model's are replaced (model_csv.write_model_rows). The reference of a quantity is its
extrapolated value where gci.csv says the three levels are in the asymptotic range, else the
finest level's value (whose rows then have rel_error 0).
"""
import csv
import sys

from model_csv import write_model_rows


def fail(message):
    sys.exit("error: levels_error_csv.py: " + message)


def main(argv):
    if len(argv) > 1 and argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return
    if len(argv) < 6 or (len(argv) > 6 and argv[6] != "--extra"):
        sys.exit(__doc__.strip().splitlines()[2])
    levelsCsv, gciCsv, out, cores, model = argv[1:6]
    extra = argv[7:]
    levels = [l for l in csv.DictReader(open(levelsCsv)) if l.get("model", model) == model]
    if len(levels) != 3:
        fail("%s has %d levels of model %s (three needed)" % (levelsCsv, len(levels), model))
    gci = [g for g in csv.DictReader(open(gciCsv)) if g["model"] == model]
    if not gci:
        fail("%s has no rows of model %s" % (gciCsv, model))
    columns = ["level", "size", "cores", "wall_s", "quantity", "value", "reference", "rel_error",
               "model", "cpu_s", "iterations", "converged"] + extra
    rows = []
    for g in gci:
        q = g["quantity"]
        ref = float(g["extrapolated"]) if g["asymptotic_range"] == "yes" else float(g["fine"])
        for l in levels:
            v = float(l[q])
            rows.append(dict(zip(columns, [l["preset"], l["cells"], cores, l["wall_s"], q, "%.8g" % v,
                                           "%.8g" % ref, "%.6e" % (abs(v - ref) / abs(ref)), model,
                                           l["cpu_s"], l["iterations"], l["converged"]]
                                 + [l[c] for c in extra])))
    write_model_rows(out, columns, model, rows)


if __name__ == "__main__":
    main(sys.argv)
