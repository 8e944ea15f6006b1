#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Fault and restart test on viscoelastic Turek-Hron FSI1 (coarse, real fluid-app + solid-app,
port launch: two mpiruns, 1 + 1 ranks).

usage: test_fault_restart.py WORK_DIR [--times 0,0.5,1,2,4,1e6] [--timeout 20]

1. An uninterrupted run over the levels gives the reference history.
2. The same run again; once level 2 is checkpointed, the fluid-app process of this run is killed
   (SIGKILL, by its pid: a descendant of this test) in the middle of level 3. The solid side
   must stop within its comm timeout (+ margin) with a non-zero exit and a one-line message
   naming the fluid, and the checkpoint of level >= 2 must be intact (its files readable).
3. run.sh --restart continues from the checkpoint and must reach the reference: every level's
   point-A displacement within 1e-3 of the coupling tolerance-scaled value (|du| <= 5e-8 m;
   the coupling tolerance is 1e-8 m), and history.csv must hold each level exactly once.
"""
import csv
import os
import shutil
import signal
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.environ.get("FSI_ROOT") or os.path.abspath(os.path.join(here, "..", "..", ".."))
sys.path.insert(0, os.path.join(root, "scripts", "verify.d", "faults"))
from processes import comm_name, descendants  # noqa: E402


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def history(run):
    with open(os.path.join(run, "results", "history.csv")) as f:
        return list(csv.DictReader(f))


def fresh_copy(work, name):
    run = os.path.join(work, name)
    shutil.rmtree(run, ignore_errors=True)
    shutil.copytree(os.path.join(root, "cases", "turek-hron-fsi1"), run)
    return run


def main():
    args = sys.argv[1:]
    if not args or args[0] in ("-h", "--help"):
        sys.exit(__doc__)
    work = os.path.abspath(args[0])
    times = args[args.index("--times") + 1] if "--times" in args else "0,0.5,1,2,4,1e6"
    timeout = float(args[args.index("--timeout") + 1]) if "--timeout" in args else 20.0
    os.makedirs(work, exist_ok=True)
    opts = ["--material", "viscoelastic", "--times", times, "--launch", "port",
            "--timeout", "%g" % timeout]
    nlevels = len(times.split(","))

    # 1. reference
    ref = fresh_copy(work, "reference")
    r = subprocess.run(["./run.sh"] + opts, cwd=ref, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True)
    if r.returncode != 0:
        fail("the reference run failed:\n" + r.stdout[-3000:])
    reference = history(ref)
    if len(reference) != nlevels:
        fail("reference run has %d levels, expected %d" % (len(reference), nlevels))

    # 2. killed run
    run = fresh_copy(work, "killed")
    log = open(os.path.join(run, "out.killed"), "w")
    p = subprocess.Popen(["./run.sh"] + opts, cwd=run, stdout=log, stderr=subprocess.STDOUT,
                         start_new_session=True)
    latest = os.path.join(run, "results", "checkpoint", "latest")
    killed_at, victims = None, []
    t_start = time.time()
    while p.poll() is None and time.time() - t_start < 600:
        try:
            level = int(open(latest).read().split()[1])
        except (OSError, IndexError, ValueError):
            level = -1
        if level >= 2:
            victims = [c for c in descendants(p.pid) if comm_name(c) == "fluid-app"]
            if victims:
                for v in victims:
                    os.kill(v, signal.SIGKILL)
                killed_at = time.time()
                break
        time.sleep(0.02)
    if killed_at is None:
        p.kill()
        fail("never saw level 2 checkpointed with fluid-app running (run too fast or failed; see %s)" % run)
    try:
        rc = p.wait(timeout=timeout + 90)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        fail("the solid side did not stop within timeout + 90 s after the fluid was killed (hang)")
    stopped = time.time() - killed_at
    log.close()
    solid_log = open(os.path.join(run, "log.solid"), errors="replace").read()
    print("fluid-app pid(s) %s killed after checkpoint of level >= 2; run.sh exit %d after %.1f s"
          % (victims, rc, stopped))
    errors = [l for l in solid_log.splitlines() if l.startswith("error")]
    print("solid-app said: " + (errors[-1] if errors else "(nothing)"))
    if rc == 0:
        fail("run.sh returned 0 although the fluid was killed")
    if not errors or "fluid" not in errors[-1]:
        fail("log.solid has no one-line error naming the fluid:\n" + solid_log[-2000:])
    with open(latest) as f:
        saved = dict(line.split() for line in f if line.strip())
    level_dir = os.path.join(run, "results", "checkpoint", saved["folder"])
    for name in ["driver.bin", "solid_rank_0.bin"]:
        if not os.path.getsize(os.path.join(level_dir, name)) > 0:
            fail("checkpoint file %s is empty" % name)
    print("checkpoint intact: level %s, t = %s s" % (saved["level"], saved["time"]))

    # 3. restart
    r = subprocess.run(["./run.sh", "--restart"] + opts, cwd=run, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, universal_newlines=True)
    if r.returncode != 0:
        fail("the restart failed:\n" + r.stdout[-3000:])
    restarted = history(run)
    levels = [int(h["level"]) for h in restarted]
    if levels != list(range(nlevels)):
        fail("history.csv after the restart has levels %s, expected each of 0..%d once" % (levels, nlevels - 1))
    worst = 0.0
    for a, b in zip(reference, restarted):
        for k in ("A_ux", "A_uy"):
            d = abs(float(a[k]) - float(b[k]))
            worst = max(worst, d)
            print("level %s %s reference %.9e restarted %.9e |diff| %.2e m" % (a["level"], k, float(a[k]),
                                                                          float(b[k]), d))
    tol = 5e-8
    print("largest difference %.2e m (tolerance %.0e m)" % (worst, tol))
    if worst > tol:
        fail("the restarted run does not reproduce the uninterrupted one")
    print("PASS")


if __name__ == "__main__":
    main()
