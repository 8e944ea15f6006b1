#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Turek-Hron FSI1 summary of a coupled run.

usage: summary.py RUN_DIR [--depth D] [--wall SECONDS]

Reads RUN_DIR/results/history.csv (solid-app: one row per accepted level, watched point A)
and RUN_DIR/log.fluid (after a restart also the earlier parts log.fluid.part1, 2, ...; a level
accepted twice counts with its last line) (fluid-app: "fsi: ACCEPT step N time T" followed by
"fsi: accepted force on ... total (Fx Fy Fz) N" on the force patches cylinder + beam).
Writes
  results/forces.csv     level,time,Fx,Fy,Fz [N] (whole one-cell-thick body),drag,lift [N/m]
  results/benchmark.csv  level,time,quantity,value,reference,rel_error (ux, uy [m]; drag, lift [N/m])
  results/summary.txt    the same as a table
Drag and lift are per unit depth: the force on cylinder + beam divided by the fluid mesh's
depth D (default 0.01 m, DEPTH of cases/turek-hron-cfd1/blockMesh.py), as the benchmark defines them.
"""
import csv
import os
import re
import sys

REFERENCE = {"ux": 2.270493e-5, "uy": 8.208773e-4, "drag": 14.29426, "lift": 0.7637460}
UNITS = {"ux": "m", "uy": "m", "drag": "N/m", "lift": "N/m"}


def fluid_forces(logs):
    """{step: (time, (Fx, Fy, Fz))} of the accepted levels in the logs (read in order)."""
    out, step, time = {}, None, None
    accept = re.compile(r"^fsi: ACCEPT step (\S+) time (\S+)")
    force = re.compile(r"^fsi: accepted force on .*?total \((\S+) (\S+) (\S+)\) N")
    for log in logs:
        with open(log, errors="replace") as f:
            for line in f:
                m = accept.match(line)
                if m:
                    step, time = int(m.group(1)), float(m.group(2))
                    continue
                m = force.match(line)
                if m and time is not None:
                    out[step] = (time, tuple(float(m.group(i)) for i in (1, 2, 3)))
                    time = None
    return out


def main():
    args = sys.argv[1:]
    if args and args[0] in ("-h", "--help"):
        print(__doc__.strip())
        return
    if not args:
        sys.exit(__doc__)
    run = args[0]
    depth, wall = 0.01, None
    if "--depth" in args:
        depth = float(args[args.index("--depth") + 1])
    if "--wall" in args:
        wall = float(args[args.index("--wall") + 1])
    res = os.path.join(run, "results")
    with open(os.path.join(res, "history.csv")) as f:
        history = list(csv.DictReader(f))
    if not history:
        sys.exit("summary.py: %s/history.csv has no accepted level" % res)
    parts = sorted((p for p in os.listdir(run) if re.fullmatch(r"log\.fluid\.part\d+", p)),
                   key=lambda p: int(p.rsplit("part", 1)[1]))
    by_step = fluid_forces([os.path.join(run, p) for p in parts + ["log.fluid"]])
    missing = [h["level"] for h in history if int(h["level"]) not in by_step]
    if missing:
        sys.exit("summary.py: accepted levels %s of history.csv have no accepted force line in "
                 "log.fluid" % ", ".join(missing))
    forces = [by_step[int(h["level"])] for h in history]

    rows = []
    with open(os.path.join(res, "forces.csv"), "w") as f:
        f.write("level,time,Fx,Fy,Fz,drag,lift\n")
        for h, (t, F) in zip(history, forces):
            f.write("%s,%s,%.10e,%.10e,%.10e,%.8f,%.8f\n" % (h["level"], h["time"], F[0], F[1], F[2],
                                                           F[0] / depth, F[1] / depth))
            values = {"ux": float(h["A_ux"]), "uy": float(h["A_uy"]),
                      "drag": F[0] / depth, "lift": F[1] / depth}
            for q in ("ux", "uy", "drag", "lift"):
                ref = REFERENCE[q]
                rows.append((h["level"], h["time"], q, values[q], ref, (values[q] - ref) / ref,
                             h["coupling_iterations"]))
    with open(os.path.join(res, "benchmark.csv"), "w") as f:
        f.write("level,time,quantity,value,reference,rel_error\n")
        for r in rows:
            f.write("%s,%s,%s,%.10e,%.10e,%.6e\n" % r[:6])
    lines = ["Turek-Hron FSI1: point A = (0.6, 0.2) (mid-depth); drag, lift on cylinder + beam "
             "per unit depth (force / %g m)" % depth,
             "%-6s %-10s %-5s %15s %15s %10s %9s" % ("level", "time [s]", "qty", "value", "reference",
                                                     "rel.err", "coupl.it")]
    for r in rows:
        lines.append("%-6s %-10s %-5s %15.7e %15.7e %+9.3f%% %9s" % (r[0], r[1], r[2], r[3], r[4],
                                                                    100 * r[5], r[6]))
    if wall is not None:
        lines.append("wall time: %.1f s" % wall)
    text = "\n".join(lines) + "\n"
    with open(os.path.join(res, "summary.txt"), "w") as f:
        f.write(text)
    sys.stdout.write(text)


if __name__ == "__main__":
    main()
