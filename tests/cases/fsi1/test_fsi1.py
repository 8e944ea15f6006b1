#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Turek-Hron FSI1 coupled verification tests (real fluid-app + solid-app).

usage: test_fsi1.py elastic WORKDIR --launch mpmd|port --tol ux=A,uy=B,drag=C,lift=D
                     [--mapping TYPE]
       test_fsi1.py viscoelastic WORKDIR --launch mpmd|port --tol-match T

elastic:      runs cases/turek-hron-fsi1/run.sh --preset coarse in a copy of the case and
              asserts |rel_error| <= tol for ux(A), uy(A), drag, lift against the FSI1
              reference (results/benchmark.csv); --mapping replaces the case's mapping type
              (run.sh --mapping), e.g. nearest-projection.
viscoelastic: runs --material viscoelastic (levels t = 0, 1e6 s), --material instantaneous
              and --material elastic (coarse) and asserts that the t = 1e6 s level matches the
              elastic FSI1 run and the t = 0 level the instantaneous-modulus elastic run, each
              quantity within a relative difference T; and that the beam relaxed: uy(t = 1e6)
              / uy(t = 0) > 1.1 (instantaneous shear modulus 1.5 x the long-term one, K
              elastic: plane-strain bending stiffness x1.40; measured coarse ratio 1.203).
Needs fluid-app, solid-app, blockMesh, gmsh, mpirun on PATH; FSI_ROOT for port mode.
"""
import csv
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.environ.get("FSI_ROOT", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..")))
CASE = os.path.join(ROOT, "cases", "turek-hron-fsi1")
QUANTITIES = ("ux", "uy", "drag", "lift")


def run_case(workdir, name, launch, *options):
    run = os.path.join(workdir, name)
    shutil.rmtree(run, ignore_errors=True)
    shutil.copytree(CASE, run)
    cmd = ["./run.sh", "--preset", "coarse", "--launch", launch] + list(options)
    t0 = time.time()
    with open(os.path.join(run, "log.run"), "w") as log:
        rc = subprocess.call(cmd, cwd=run, stdout=log, stderr=subprocess.STDOUT)
    print("%s: %s -> exit %d in %.1f s" % (name, " ".join(cmd), rc, time.time() - t0))
    if rc != 0:
        with open(os.path.join(run, "log.run")) as f:
            sys.stdout.write(f.read()[-3000:])
        sys.exit("FAIL: %s: the coupled run failed (exit %d), logs in %s" % (name, rc, run))
    with open(os.path.join(run, "results", "summary.txt")) as f:
        sys.stdout.write(f.read())
    check_cpu_accounting(run)
    levels = {}
    with open(os.path.join(run, "results", "benchmark.csv")) as f:
        for row in csv.DictReader(f):
            levels.setdefault(int(row["level"]), {})[row["quantity"]] = (
                float(row["value"]), float(row["rel_error"]))
    return levels


def check_cpu_accounting(run):
    """The CPU time by program that scripts/bench-fsi splits a run's CPU by: solid-app's cpu_s in
    summary.csv and fluid-app's closing line, each positive and at most its program's wall time
    times the cores (every thread of a process counts; fluid-app starts before solid-app's
    clock, hence the 60 s margin)."""
    with open(os.path.join(run, "results", "summary.csv")) as f:
        s = next(csv.DictReader(f))
    solid, wall = float(s["cpu_s"]), float(s["wall_s"])
    with open(os.path.join(run, "log.fluid")) as f:
        m = re.findall(r"^fsi: CPU of the fluid ranks ([0-9.eE+-]+) s \(user \+ system, "
                       r"summed over (\d+) rank", f.read(), re.M)
    if not m:
        sys.exit("FAIL: %s/log.fluid has no 'fsi: CPU of the fluid ranks' line" % run)
    fluid, ranks = float(m[-1][0]), int(m[-1][1])
    cores = os.cpu_count() or 1
    print("CPU: solid-app %.2f s, fluid-app %.2f s (%d rank(s)); solid-app's wall %.2f s"
          % (solid, fluid, ranks, wall))
    if not (0 < solid <= 1.1 * wall * cores and 0 < fluid <= 1.1 * wall * cores + 60):
        sys.exit("FAIL: CPU times outside (0, wall x cores]")


def parse_tol(text):
    tol = {}
    for item in text.split(","):
        k, v = item.split("=")
        tol[k] = float(v)
    missing = [q for q in QUANTITIES if q not in tol]
    if missing:
        sys.exit("usage error: --tol lacks %s" % ",".join(missing))
    return tol


def main():
    if len(sys.argv) < 3 or sys.argv[1] not in ("elastic", "viscoelastic"):
        sys.exit(__doc__)
    mode, workdir = sys.argv[1], sys.argv[2]
    args = sys.argv[3:]
    launch = args[args.index("--launch") + 1] if "--launch" in args else "mpmd"
    os.makedirs(workdir, exist_ok=True)
    failures = []
    if mode == "elastic":
        tol = parse_tol(args[args.index("--tol") + 1])
        mapping = args[args.index("--mapping") + 1] if "--mapping" in args else ""
        levels = run_case(workdir, "coarse-" + launch + ("-" + mapping if mapping else ""), launch,
                          *(["--mapping", mapping] if mapping else []))
        for q in QUANTITIES:
            value, err = levels[0][q]
            ok = abs(err) <= tol[q]
            print("%-5s %.7e rel_error %+.3e  tolerance %.1e  %s" % (q, value, err, tol[q],
                                                                   "ok" if ok else "FAIL"))
            if not ok:
                failures.append(q)
    else:
        tol = float(args[args.index("--tol-match") + 1])
        visco = run_case(workdir, "viscoelastic-" + launch, launch, "--material", "viscoelastic")
        inst = run_case(workdir, "instantaneous-" + launch, launch, "--material", "instantaneous")
        elastic = run_case(workdir, "elastic-" + launch, launch, "--material", "elastic")
        if sorted(visco) != [0, 1]:
            sys.exit("FAIL: the viscoelastic run accepted levels %s, expected [0, 1]" % sorted(visco))
        for label, lv, other in (("t = 0 vs instantaneous", 0, inst[0]),
                                 ("t = 1e6 s vs elastic FSI1", 1, elastic[0])):
            for q in QUANTITIES:
                a, b = visco[lv][q][0], other[q][0]
                d = abs(a - b) / abs(b)
                ok = d <= tol
                print("%-28s %-5s %.7e vs %.7e  rel.diff %.2e  tolerance %.0e  %s" % (
                    label, q, a, b, d, tol, "ok" if ok else "FAIL"))
                if not ok:
                    failures.append("%s %s" % (label, q))
        ratio = visco[1]["uy"][0] / visco[0]["uy"][0]
        ok = ratio > 1.1
        print("relaxation: uy(t = 1e6 s) / uy(t = 0) = %.4f (> 1.1)  %s" % (ratio, "ok" if ok else "FAIL"))
        if not ok:
            failures.append("relaxation ratio")
    if failures:
        sys.exit("FAIL: " + ", ".join(failures))
    print("PASS")


if __name__ == "__main__":
    main()
