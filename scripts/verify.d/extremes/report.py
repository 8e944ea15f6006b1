#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Helper of scripts/verify.d/extremes.sh (the extremes stress suite).

usage: report.py patch CASE_DIR CONFIG KEY=VALUE
         patch a copy of cases/turek-hron-fsi1: E, nu (material), gamma, tau (the one Prony
         term of solid-visco.yaml) in CONFIG; gravity=G adds density 1000 and a body load
         (0, -G, 0) m/s^2; U=FACTOR scales the inlet profile of CASE_DIR/fluid/0.orig/U (the
         polynomial coefficients, i.e. the mean inflow speed).
       report.py report WORK OUT [--mode full|quick]
         classify every case listed in WORK/cases.list (run folders WORK/NAME with case.meta)
         and write OUT/results.csv, OUT/README.md and OUT/error_vs_runtime.csv; exit 1 when
         a case is FAILED or misses its expectation.
Outcomes: converged (exit 0, finite results, checks pass) | diagnosed (non-zero exit with an
`error:` line, nothing non-finite accepted) | FAILED (hang, NaN/inf accepted, a check violated
after exit 0, or a crash without an `error:` line).
"""
import csv
import datetime
import math
import os
import re
import subprocess
import sys

NOTES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "notes.md")


# ----------------------------------------------------------------------------------- patch
def patch(case_dir, config, assignment):
    key, _, value = assignment.partition("=")
    try:
        float(value)
    except ValueError:
        sys.exit(f"error: report.py patch: '{assignment}' needs a number after '='")
    if key == "U":
        path = os.path.join(case_dir, "fluid", "0.orig", "U")
        text = open(path).read()
        # polynomial ((a 0 0) (1 0 0)) ((b 0 0) (2 0 0)): u(y) = a y + b y^2
        pat = re.compile(r"\(\((-?[0-9.eE+-]+) 0 0\) \(([12]) 0 0\)\)")
        hits = pat.findall(text)
        if len(hits) != 2:
            sys.exit(f"error: report.py patch: {path}: expected the 2-term inlet polynomial, found {len(hits)} terms")
        text = pat.sub(lambda m: f"(({float(m.group(1)) * float(value):.15g} 0 0) ({m.group(2)} 0 0))", text)
        open(path, "w").write(text)
        return
    if key == "gravity":
        # body load on the beam (rho = 1000 kg/m^3, the benchmark's), downwards (-y) [m/s^2]
        text = open(config).read()
        text, n1 = re.subn(r"^(    nu: .*)$", r"\1\n    density: 1000", text, count=1, flags=re.M)
        text, n2 = re.subn(r"^(  loads:)$", rf"\1\n    gravity: [0.0, -{value}, 0.0]", text, count=1, flags=re.M)
        if n1 != 1 or n2 != 1:
            sys.exit(f"error: report.py patch: {config}: no '    nu:' or '  loads:' line for the gravity load")
        open(config, "w").write(text)
        return
    lines = {"E": r"^(    E: ).*$", "nu": r"^(    nu: ).*$",
             "gamma": r"^(      coefficients: ).*$", "tau": r"^(      times: ).*$"}
    if key not in lines:
        sys.exit(f"error: report.py patch: unknown key '{key}' (E, nu, gamma, tau, gravity, U)")
    text = open(config).read()
    repl = f"[{value}]" if key in ("gamma", "tau") else value
    new, n = re.subn(lines[key], lambda m: m.group(1) + repl, text, flags=re.M)
    if n != 1:
        sys.exit(f"error: report.py patch: {config}: {n} lines match '{key}', expected 1")
    open(config, "w").write(new)


# ---------------------------------------------------------------------------------- report
def read_meta(d):
    meta = {}
    with open(os.path.join(d, "case.meta")) as f:
        for line in f:
            k, _, v = line.rstrip("\n").partition("=")
            meta[k] = v
    return meta


def read_text(path):
    try:
        with open(path, errors="replace") as f:
            return f.read()
    except OSError:
        return ""


def read_rows(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError:
        return None


def non_finite(rows):
    """(row index, column) of the first NaN/inf field of accepted rows, or None."""
    for i, row in enumerate(rows or []):
        for k, v in row.items():
            if v is None or k is None:
                continue
            try:
                if not math.isfinite(float(v)):
                    return i, k
            except ValueError:
                if v.strip().lower() in ("nan", "-nan", "inf", "-inf"):
                    return i, k
    return None


def first_error(text, skip=()):
    for line in text.splitlines():
        s = line.strip()
        i = s.find("error:")
        if i >= 0 and not any(x in s for x in skip):
            return s[i:]
    return ""


def creep_check(meta, rows):
    """Bounds, monotonicity and the analytic SLS creep value; returns (ok, text, value, ref)."""
    K, G0, g, sigma = 10.0e6, 1.0e6, 0.5, 1.0e4
    tau = float(meta["creep"])
    Ginf = G0 * (1 - g)
    inst = sigma * (1 / (9 * K) + 1 / (3 * G0))
    longterm = sigma * (1 / (9 * K) + 1 / (3 * Ginf))
    eps = [float(r["probe_ux"]) for r in rows]
    times = [float(r["time"]) for r in rows]
    lo, hi = inst * (1 - 1e-6), longterm * (1 + 1e-6)
    t, e = times[-1], eps[-1]
    J = 1 / Ginf - (1 / Ginf - 1 / G0) * math.exp(-t * Ginf / (G0 * tau))
    ref = sigma * (1 / (9 * K) + J / 3)
    bad = [k for k, x in enumerate(eps) if not lo <= x <= hi]
    if bad:
        k = bad[0]
        return False, (f"creep bound violated at t = {times[k]:g} s: eps_xx = {eps[k]:.6e} outside "
                       f"[{inst:.6e}, {longterm:.6e}] (instantaneous, long-term)"), e, ref
    drop = [k for k in range(1, len(eps)) if eps[k] < eps[k - 1] * (1 - 1e-9)]
    if drop:
        k = drop[0]
        return False, (f"creep not monotone at t = {times[k]:g} s: eps_xx {eps[k - 1]:.6e} -> "
                       f"{eps[k]:.6e} under a constant load"), e, ref
    text = (f"eps_xx(t={t:g} s) = {e:.6e} in [{inst:.4e}, {longterm:.4e}], analytic {ref:.6e} "
            f"({(e - ref) / ref:+.2e})")
    return True, text, e, ref


def classify(d):
    meta = read_meta(d)
    r = {"case": meta["name"], "program": "solid alone" if meta["program"] == "solid" else "coupled",
         "parameters": meta.get("params", ""), "expected": meta.get("expect", "any"),
         "wall_s": meta.get("wall_s", ""), "outcome": "", "levels": "", "newton_iterations": "",
         "coupling_iterations": "", "cures": "", "result": "", "check": "", "meets_expectation": ""}
    rc = int(meta.get("rc", "-1"))
    limit = meta.get("limit_s", "?")
    planned = int(meta.get("levels_planned", "1"))
    extra = {}
    if meta["program"] == "solid":
        log = read_text(os.path.join(d, "log.solid-app"))
        hist = read_rows(os.path.join(d, "output", "history.csv"))
        accepted = read_rows(os.path.join(d, "output", "levels.csv"))
        r["newton_iterations"] = len(re.findall(r"^\s*newton\s+\d+\s+\|R\|", log, re.M))
        subs = re.findall(r"retrying in (\d+) load sub-steps", log)
        cut_levels = sum(1 for row in accepted or [] if int(row.get("load_cuts", "0") or 0) > 0)
        r["cures"] = (f"{len(subs)} (load sub-stepping up to x{max(int(s) for s in subs)}"
                      f"{f'; {cut_levels} level(s) converged after it' if cut_levels else ''})" if subs else "0")
        error = first_error(log)
        nlev = len(accepted or [])
        m = re.search(r"(\d+) free dofs", log)
        extra["dofs"] = m.group(1) if m else ""
        nan_files = [(n, non_finite(rows)) for n, rows in (("history.csv", hist), ("levels.csv", accepted))]
        exited_ok_text = "solid-app: done" in log
    else:
        logs = {n: read_text(os.path.join(d, n)) for n in ("log.solid", "log.fluid", "log.mpirun", "log.run")}
        hist = read_rows(os.path.join(d, "results", "history.csv"))
        coupling = read_rows(os.path.join(d, "results", "coupling.csv")) or []
        r["coupling_iterations"] = len(re.findall(r"^\s*\[level \d+ it\s+\d+\]", logs["log.solid"], re.M))
        r["newton_iterations"] = sum(int(float(row.get("newton_iterations") or 0)) for row in coupling)
        retries = len(re.findall(r"\[cure \d+/\d+\]", logs["log.solid"]))
        subs = re.findall(r"\[cure\] solid load sub-stepping x(\d+)", logs["log.solid"])
        kinds = []
        if retries:
            relax = len(re.findall(r"\[cure \d+/\d+\].*initial relaxation", logs["log.solid"]))
            dts = len(re.findall(r"\[cure \d+/\d+\].*redoing the level with dt", logs["log.solid"]))
            kinds.append(f"{retries} level retr{'y' if retries == 1 else 'ies'}"
                         + (f": {relax} stronger relaxation" if relax else "")
                         + (f"{', ' if relax else ': '}{dts} smaller dt" if dts else ""))
        if subs:
            kinds.append(f"{len(subs)} solid load sub-stepping (up to x{max(int(s) for s in subs)})")
        r["cures"] = f"{retries + len(subs)} ({'; '.join(kinds)})" if kinds else "0"
        solid_err = first_error(logs["log.solid"])
        fluid_err = first_error(logs["log.fluid"])
        error = solid_err or fluid_err or first_error(logs["log.mpirun"]) or \
            first_error(logs["log.run"], skip=("the coupled run failed",))
        core = lambda e: e[len("error:"):].strip()[:80]  # noqa: E731
        if fluid_err and solid_err and core(solid_err) not in fluid_err and core(fluid_err) not in solid_err:
            error += " || fluid: " + fluid_err
        nlev = len(hist or [])
        nan_files = [("results/history.csv", non_finite(hist))]
        exited_ok_text = "solid-app: done" in logs["log.solid"]
    r["levels"] = f"{nlev}/{planned}"

    # the result quantity (last accepted level)
    watch = meta.get("watch", "")
    value = None
    if hist:
        last = hist[-1]
        comp = "ux" if meta.get("creep") else "uy"
        key = f"{watch}_{comp}" if f"{watch}_{comp}" in last else None
        if key:
            try:
                value = float(last[key])
            except ValueError:
                value = float("nan")
            r["result"] = f"{'eps_xx' if meta.get('creep') else key} = {value:.4e}"
            if "retries" in last and last["retries"] not in ("", "0"):
                r["result"] += f" (level retries {last['retries']})"

    # outcome
    nan = [(f, where) for f, where in nan_files if where]
    checks_ok, check_text = True, ""
    if rc in (124, 137):
        outcome = "FAILED"
        check_text = f"hang: no end within the {limit} s wall-clock limit (killed, exit {rc})"
    elif nan:
        f, (row, col) = nan[0]
        outcome = "FAILED"
        check_text = (f"non-finite value accepted: {f} row {row + 1} column {col}"
                      + (f" (exit {rc}" + (f", {error})" if error else ")")))
    elif rc == 0:
        if nlev < planned:
            outcome, check_text = "FAILED", f"exit 0 but only {nlev} of {planned} levels accepted"
        elif not exited_ok_text:
            outcome, check_text = "FAILED", "exit 0 without the final 'solid-app: done' line"
        elif meta.get("creep"):
            checks_ok, check_text, val, ref = creep_check(meta, hist)
            outcome = "converged" if checks_ok else "FAILED"
            extra["reference"], extra["value"] = ref, val
        else:
            outcome = "converged"
            if value is not None and not math.isfinite(value):
                outcome, check_text = "FAILED", "exit 0 with a non-finite result"
    elif error:
        outcome, check_text = "diagnosed", error
    else:
        sig = f" (signal {rc - 128})" if rc > 128 else ""
        outcome, check_text = "FAILED", f"crash without an error: line: exit {rc}{sig}"
    if "strays" in meta:
        check_text += f"; processes left running after the limit were killed: {meta['strays'].strip()}"
    if outcome == "converged" and re.match(r"E1e(9|11)-cant-", r["case"]) and value is not None:
        extra["reference"], extra["value"] = float(meta["timoshenko"]), value
    r["outcome"] = outcome
    r["check"] = check_text
    exp = r["expected"]
    r["meets_expectation"] = "yes" if outcome != "FAILED" and (exp == "any" or exp == outcome) else "NO"
    return r, meta, extra


COLUMNS = ["case", "program", "parameters", "expected", "outcome", "meets_expectation", "levels",
           "newton_iterations", "coupling_iterations", "cures", "result", "check", "wall_s"]


def md(s):
    return str(s).replace("|", "\\|").replace("\n", " ")


def report(work, out, mode):
    names = [n.strip() for n in open(os.path.join(work, "cases.list")) if n.strip()]
    rows, evr = [], []
    for n in names:
        r, meta, extra = classify(os.path.join(work, n))
        rows.append(r)
        if "reference" in extra:
            ref, val = extra["reference"], extra["value"]
            q = "eps_xx(t_end)" if meta.get("creep") else "u_y(tip)"
            evr.append([n, extra.get("dofs", ""), 1, r["wall_s"], q, f"{val:.9e}", f"{ref:.9e}",
                        f"{(val - ref) / ref:.6e}"])
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "results.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([r[c] for c in COLUMNS])
    with open(os.path.join(out, "error_vs_runtime.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["level", "size", "cores", "wall_s", "quantity", "value", "reference", "rel_error"])
        w.writerows(evr)

    count = {k: sum(1 for r in rows if r["outcome"] == k) for k in ("converged", "diagnosed", "FAILED")}
    unmet = [r for r in rows if r["meets_expectation"] != "yes"]
    try:
        commit = subprocess.run(["git", "-C", os.path.dirname(os.path.abspath(__file__)), "rev-parse",
                                 "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    except OSError:
        commit = "?"
    load = open("/proc/loadavg").read().split()[:3] if os.path.exists("/proc/loadavg") else ["?"]
    now = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    L = ["<!-- SPDX-License-Identifier: GPL-3.0-or-later -->",
         "# Extremes stress suite (issue #8)",
         "",
         "Written by `scripts/verify extremes` (`scripts/verify.d/extremes.sh`; CTest `extremes_quick`,"
         " label `verification`, and `extremes_full`, label `long`). Do not edit the table by hand:"
         " re-run the suite.",
         "",
         f"Run: {now}, {mode} matrix, {len(rows)} cases, commit {commit}, load average at the end"
         f" {' '.join(load)} (2 shared cores: wall times are indicative only).",
         "",
         f"**{count['converged']} converged, {count['diagnosed']} diagnosed, {count['FAILED']} FAILED;"
         f" {len(unmet)} case(s) missing their expectation.**",
         "",
         "## What the outcomes mean",
         "",
         "| outcome | meaning |",
         "|---|---|",
         "| converged | exit 0, every planned level accepted, all accepted results finite; creep cases:"
         " eps_xx at every level between the instantaneous and the long-term elastic responses and"
         " non-decreasing |",
         "| diagnosed | non-zero exit with an `error:` line naming the failed check (Newton stall,"
         " divergence, inverted cells, mesh quality, coupling cap, peer abort); nothing non-finite"
         " accepted. The table shows that line |",
         "| FAILED | a hang (killed at the wall-clock limit), NaN/inf in an accepted result"
         " (`history.csv`, `levels.csv`), exit 0 with a violated check or missing levels, or a crash"
         " without an `error:` line |",
         "",
         "`expected`: `converged` = a fixed expectation (the physics has a solution well inside the"
         " solvers' range); `any` = converged or diagnosed are both acceptable, FAILED never is."
         " `levels` = accepted / planned levels. Iterations count every attempt (retries and load"
         " sub-steps included): Newton iterations of the solid (coupled: summed over"
         " `results/coupling.csv`), coupling iterations = `[level k it n]` lines of `log.solid`."
         " `cures` = automatic cures announced in the logs: `[cure k/max]` level retries of the"
         " coupling driver (stronger relaxation, smaller dt), `[cure] solid load sub-stepping` notes"
         " of coupling iterations, and standalone `retrying in N load sub-steps` lines.",
         "",
         "## Results",
         "",
         "| case | program | parameters | expected | outcome | levels | Newton it. | coupling it. |"
         " cures | result (last level) | check failed / diagnosis / check | wall [s] |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        oc = r["outcome"] if r["meets_expectation"] == "yes" else f"**{r['outcome']}** (expected {r['expected']})"
        if r["outcome"] == "FAILED":
            oc = "**FAILED**"
        L.append("| " + " | ".join(md(x) for x in [
            r["case"], r["program"], r["parameters"], r["expected"], oc, r["levels"],
            r["newton_iterations"], r["coupling_iterations"], r["cures"], r["result"], r["check"],
            r["wall_s"]]) + " |")
    L += ["", "## The matrix", "",
          "Solid alone (solid-app standalone, 1 rank; meshes by Gmsh, second order):",
          "",
          "- `nu*-cook-*`: Cook's membrane (plane strain slab, 8 x 8 cells), E = 250 Pa, small strain,"
          " total shear 1 N, nu = 0.49 / 0.499 / 0.4999, Tet10 and Hex20 (quadratic elements do not"
          " lock). `nu*-cookfs-*`: the same with neo-Hooke, total Lagrangian and 100 N"
          " (|u_C| about 8 on a 48 x 60 panel): nearly incompressible finite strain.",
          "- `E*-cant-*`: cantilever 2 x 0.1 x 0.1 m (Tet10: 20 x 1 x 1 boxes, Hex20: 40 x 2 x 2),"
          " St Venant-Kirchhoff, total Lagrangian, fixed tip force 100 N, E = 1e3 ... 1e11 Pa: from"
          " 3e-4 m deflection (E = 1e11, compared with Timoshenko in `error_vs_runtime.csv`) to a"
          " bar hanging from its clamp stretched about 3 times (E = 1e3). `E1e11-P0.1-tight-*`: the"
          " stiffest bar under 0.1 N (strains of 1e-8) with the Newton tolerances of"
          " `cases/turek-hron-fsi1` (1e-10 relative + 1e-12 N), small strain (a linear problem) and"
          " total Lagrangian. `E1e3-compress-*`: the"
          " softest bar pushed axially with 10 N (P/EA = 1): beyond St Venant-Kirchhoff's"
          " compressive limit point (P/EA = 0.19) and far beyond Euler buckling.",
          "- `creep-tau*-dt*`: creep of the unit cube under a 1e4 Pa step held: K = 10 MPa,"
          " G0 = 1 MPa, one Prony term g = 0.5, tau = 1e-6, 1e-2, 1e2, 1e8 s against"
          " dt = 1e-3, 1, 1e3 s (10 levels after t = 0): eps_xx must stay between the instantaneous"
          " and the long-term elastic values at every level and never decrease; its distance to the"
          " analytic standard-linear-solid creep is in `error_vs_runtime.csv`.",
          "- `jump-*`: the cantilever (E = 1e7 Pa) with levels t = 0 (load factor 0) and t = 1"
          " (factor 1): the whole load (100 N or 1e4 N) in one level.",
          "",
          "Coupled (Turek-Hron FSI1 coarse: 3 488 fluid cells, 18 x 2 Hex20 beam; fluid-app + solid-app,"
          " MPMD, 1 + 1 ranks, `--timeout 120`; each case in a copy of `cases/turek-hron-fsi1` whose"
          " `solid.yaml` / `solid-visco.yaml` / `fluid/0.orig/U` were patched):"
          " nominal; E x0.01, x0.1, x100; nu = 0.499; inflow x0.1 and x5 (both inlet polynomial"
          " coefficients scaled); gravity on the beam (density 1000 kg/m^3) switched on in the single"
          " level on top of the flow: 2 m/s^2 (CSM1's load) and 20 m/s^2 (the beam would reach the"
          " channel wall: the fluid mesh cannot follow, a diagnosis is expected);"
          " viscoelastic (gamma 0.5) with tau = 1e-6 s and 1e8 s on the levels"
          " 0, 1e-3, 1, 1e3 s; a jump: long-term E x0.1 with gamma = 99 (instantaneous modulus x100),"
          " levels 0 and 1e6 s, i.e. the beam softens 100 times in one level.",
          "",
          "Every case runs under a hard wall-clock limit (`timeout`; 300 s by default, coupled and"
          " solid); run folders: `runs/extremes/NAME` (or `--work`), with `case.meta`, the logs and"
          " the outputs.", ""]
    if os.path.exists(NOTES):
        L += [open(NOTES).read().rstrip(), ""]
    with open(os.path.join(out, "README.md"), "w") as f:
        f.write("\n".join(L))
    # console summary
    for r in rows:
        flag = "" if r["meets_expectation"] == "yes" else "   <-- " + ("FAILED" if r["outcome"] == "FAILED" else f"expected {r['expected']}")
        print(f"{r['case']:26s} {r['outcome']:9s} levels {r['levels']:5s} newton {str(r['newton_iterations']):>5s}"
              f" coupling {str(r['coupling_iterations']):>4s} cures {r['cures'][:40]:40s} {r['wall_s']:>7s} s{flag}")
        if r["outcome"] != "converged":
            print(f"    {r['check']}")
    print(f"extremes: {count['converged']} converged, {count['diagnosed']} diagnosed, "
          f"{count['FAILED']} FAILED, {len(unmet)} not as expected; {out}/README.md")
    return 1 if unmet else 0


def main():
    a = sys.argv[1:]
    if len(a) == 4 and a[0] == "patch":
        patch(a[1], a[2], a[3])
        return 0
    if len(a) >= 3 and a[0] == "report":
        mode = a[a.index("--mode") + 1] if "--mode" in a else "full"
        return report(a[1], a[2], mode)
    sys.exit(__doc__)


if __name__ == "__main__":
    sys.exit(main())
