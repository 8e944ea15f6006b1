#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Fault campaign on the viscoelastic Turek-Hron FSI1 case (coarse, real fluid-app + solid-app,
1 + 1 ranks), in both launch modes. Driven by scripts/verify faults (scripts/verify.d/faults.sh).

usage: campaign.py OUT_DIR [--only NAME,...] [--timeout S] [--seed N]

Scenarios (each in its own copy of cases/turek-hron-fsi1 under OUT_DIR/work/NAME):
  reference-MODE                 uninterrupted run: the reference history
  MODE-SIDE-SIG                  SIG (KILL, TERM, STOP) sent to SIDE (fluid-app | solid-app) at
                                 a random moment once the first level is checkpointed; then
                                 run.sh --restart must reach the reference history
  disk-full                      a tmpfs (a copy of results/ + 64 KiB) mounted over results/
                                 once level 1 is checkpointed (needs mount rights), --restart
  checkpoint-truncated           the newest checkpoint's solid_rank_0.bin cut in half, --restart
  checkpoint-altered             one byte of driver.bin flipped, --restart
  restart-2-solid-ranks          the reference set back to its older checkpoint, restarted with
                                 2 solid ranks instead of 1 (MPMD)
Per scenario one row of OUT_DIR/results.csv: fault, time to detect [s] (signal -> both launchers
ended), exit code, the survivor's message, the state left behind (latest checkpoint level, fluid
levels listed in accepted.csv, processes left), the restart result (max |u_A - u_A,ref| over the
levels) and pass/fail; OUT_DIR/table.md is the same as a Markdown table.
Pass = the run ended (no hang) within timeout + 60 s, with a non-zero exit and an error line, no
process left behind, no accepted level lost (the checkpoint level >= the last one listed before
the fault), and the restart (where one is made) reproduced the reference within 5e-8 m.
"""
import argparse
import csv
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from processes import comm_name, descendants, session_pids  # noqa: E402

root = os.environ.get("FSI_ROOT") or os.path.abspath(os.path.join(here, "..", "..", ".."))
case = os.path.join(root, "cases", "turek-hron-fsi1")
TIMES = "0,0.5,1,2,4,1e6"
TOL = 5e-8  # [m] restart vs reference, as tests/cases/fsi1/test_fault_restart.py


def env():
    e = dict(os.environ)
    e["FSI_ROOT"] = root
    e.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    e["FOAM_SIGFPE"] = "false"
    e.update(OMPI_MCA_btl_tcp_if_include="lo", OMPI_MCA_oob_tcp_if_include="lo",
             OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
             OMPI_MCA_rmaps_base_oversubscribe="1")
    return e


def start(d, args):
    log = open(os.path.join(d, "log.run"), "a")
    # own session: every process of this run (mpiruns, ompi-server, programs) is findable
    return subprocess.Popen(["./run.sh"] + args, cwd=d, env=env(), stdout=log,
                            stderr=subprocess.STDOUT, start_new_session=True)


def wait(p, bound):
    t0 = time.time()
    while p.poll() is None and time.time() - t0 < bound:
        time.sleep(0.2)
    if p.poll() is None:
        return None
    return p.returncode


def leftovers(p):
    """Processes of the run's session still alive 5 s after run.sh ended (then killed)."""
    left = []
    for _ in range(25):
        left = session_pids(p.pid)
        if not left:
            return ""
        time.sleep(0.2)
    names = sorted(set(comm_name(q) for q in left))
    for q in left:
        try:
            os.kill(q, signal.SIGKILL)
        except OSError:
            pass
    return " ".join(names)


def read(path):
    try:
        with open(path, errors="replace") as f:
            return f.read()
    except OSError:
        return ""


def error_lines(d):
    out = []
    for name in ("log.solid", "log.fluid", "log.mpirun", "log.run"):
        for line in read(os.path.join(d, name)).splitlines():
            if line.startswith("error:") or "exited on signal" in line or "MPI_ABORT was invoked" in line:
                out.append("%s: %s" % (name, line.strip()))
    return out


def best_message(errs, survivor):
    """The survivor's own error line, else mpirun's report, else the launcher's."""
    for prefix in (survivor, "log.mpirun", "log.run"):
        mine = [e for e in errs if e.startswith(prefix)]
        if mine:
            return mine[-1]
    return (errs or ["(none)"])[-1]


def checkpoint_level(d):
    m = re.search(r"^level (\d+)", read(os.path.join(d, "results", "checkpoint", "latest")), re.M)
    return int(m.group(1)) if m else -1


def fluid_levels(d):
    rows = read(os.path.join(d, "fluid", "postProcessing", "fsi", "accepted.csv")).splitlines()[1:]
    return [r for r in rows if r.strip()]


def history(d):
    """uy of point A per accepted time [m] from results/history.csv."""
    path = os.path.join(d, "results", "history.csv")
    if not os.path.isfile(path):
        return {}
    out = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            col = [k for k in row if k.endswith("_uy")]
            if col:
                out[float(row["time"])] = float(row[col[0]])
    return out


def prepare(work, name, timeout):
    d = os.path.join(work, name)
    shutil.rmtree(d, ignore_errors=True)
    shutil.copytree(case, d, ignore=shutil.ignore_patterns("log.*", "results"))
    return d


def run_args(mode, timeout, restart=False):
    a = ["--launch", mode, "--material", "viscoelastic", "--times", TIMES, "--timeout", str(timeout)]
    return a + (["--restart"] if restart else [])


def compare(d, ref):
    h = history(d)
    if not h or not ref:
        return None, "no history"
    missing = [t for t in ref if t not in h]
    if missing:
        return None, "levels missing: %s" % missing
    return max(abs(h[t] - ref[t]) for t in ref), ""


def restart_and_compare(d, mode, timeout, ref, extra=None):
    p = start(d, run_args(mode, timeout, restart=True) + (extra or []))
    rc = wait(p, 20 * timeout)
    left = leftovers(p)
    if rc is None:
        return "restart hung", False
    if rc != 0:
        errs = error_lines(d)
        return "restart exit %d: %s" % (rc, errs[-1] if errs else ""), False
    dmax, why = compare(d, ref)
    if dmax is None:
        return "restart exit 0 but " + why, False
    ok = dmax <= TOL and not left
    return "exit 0, max |du_A| %.1e m vs reference%s" % (dmax, "; left: " + left if left else ""), ok


def signal_scenario(work, mode, side, sig, timeout, ref, rng):
    name = "%s-%s-%s" % (mode, side.replace("-app", ""), sig)
    d = prepare(work, name, timeout)
    p = start(d, run_args(mode, timeout))
    # a random moment once level >= 1 is checkpointed (or 600 s)
    t0 = time.time()
    while checkpoint_level(d) < 1 and p.poll() is None and time.time() - t0 < 900:
        time.sleep(0.2)
    time.sleep(rng.uniform(0.0, 4.0))
    target = [q for q in descendants(p.pid) if comm_name(q) == side]
    listed = len(fluid_levels(d))
    level_before = checkpoint_level(d)
    if p.poll() is not None or not target:
        return dict(fault=name, detect_s="", exit=p.poll(), message="run ended before the fault",
                    state="", restart="", ok=False)
    for q in target:
        os.kill(q, getattr(signal, "SIG" + sig))
    tk = time.time()
    rc = wait(p, timeout + 120)
    detect = time.time() - tk
    hang = rc is None
    if hang:
        for q in [p.pid] + session_pids(p.pid):
            try:
                os.kill(q, signal.SIGKILL)
            except OSError:
                pass
        p.wait()
        rc = p.returncode
    left = leftovers(p)
    errs = error_lines(d)
    message = best_message(errs, "log.solid" if side == "fluid-app" else "log.fluid")
    lvl = checkpoint_level(d)
    state = "checkpoint level %d (was %d at the fault), fluid accepted.csv %d levels (was %d)%s" % (
        lvl, level_before, len(fluid_levels(d)), listed, "; left: " + left if left else "")
    lost = lvl < level_before or len(fluid_levels(d)) < listed
    ok = not hang and rc != 0 and errs and not left and not lost
    restart, rok = restart_and_compare(d, mode, timeout, ref)
    return dict(fault="%s %s in %s mode" % (sig, side, mode), detect_s="%.1f" % detect,
                exit=("HANG (killed)" if hang else rc), message=message, state=state,
                restart=restart, ok=bool(ok and rok))


def full_run(d, mode, timeout, extra=None):
    p = start(d, run_args(mode, timeout) + (extra or []))
    rc = wait(p, 40 * timeout)
    left = leftovers(p)
    return rc, left


def checkpoint_scenario(work, kind, timeout, ref, base):
    name = "checkpoint-" + kind
    d = os.path.join(work, name)
    shutil.rmtree(d, ignore_errors=True)
    shutil.copytree(base, d, symlinks=True)
    for f in ("log.solid", "log.fluid", "log.mpirun", "log.run"):
        if os.path.exists(os.path.join(d, f)):
            os.remove(os.path.join(d, f))
    latest = read(os.path.join(d, "results", "checkpoint", "latest"))
    folder = re.search(r"^folder (\S+)", latest, re.M).group(1)
    lvl = os.path.join(d, "results", "checkpoint", folder)
    if kind == "truncated":
        path = os.path.join(lvl, "solid_rank_0.bin")
        size = os.path.getsize(path)
        with open(path, "r+b") as f:
            f.truncate(size // 2)
        what = "%s cut from %d to %d bytes" % (os.path.relpath(path, d), size, size // 2)
    else:
        path = os.path.join(lvl, "driver.bin")
        with open(path, "r+b") as f:
            data = bytearray(f.read())
            data[len(data) // 2] ^= 0x40
            f.seek(0)
            f.write(data)
        what = "one byte of %s flipped" % os.path.relpath(path, d)
    t0 = time.time()
    p = start(d, run_args("mpmd", timeout, restart=True))
    rc = wait(p, 10 * timeout)
    detect = time.time() - t0
    left = leftovers(p)
    errs = error_lines(d)
    message = errs[-1] if errs else "(none)"
    named = folder in message or "checkpoint" in message
    ok = rc not in (None, 0) and named and not left
    return dict(fault="checkpoint %s: %s; run.sh --restart" % (kind, what),
                detect_s="%.1f" % detect, exit=rc, message=message,
                state="files left as they were%s" % ("; left: " + left if left else ""),
                restart="refused (as it must)" if ok else "NOT refused", ok=ok)


def disk_full_scenario(work, timeout, ref):
    """Once level 1 is checkpointed, a tmpfs holding a copy of results/ and 64 KiB to spare
    is mounted over results/: the next checkpoint, VTU or CSV write fills it. The run must stop with a message; after the unmount
    the checkpoint written before is intact and --restart must reach the reference."""
    d = prepare(work, "disk-full", timeout)
    p = start(d, run_args("mpmd", timeout))
    t0 = time.time()
    while checkpoint_level(d) < 1 and p.poll() is None and time.time() - t0 < 900:
        time.sleep(0.2)
    mnt = os.path.join(d, "results")
    before = checkpoint_level(d)
    # The tmpfs gets a copy of results/ (the run continues in it) and 64 KiB to spare: the
    # next level's VTU (60 KiB) or checkpoint (45 KiB) fills it.
    used = int(subprocess.run(["du", "-sk", mnt], capture_output=True, text=True).stdout.split()[0])
    copy = os.path.join(work, "disk-full.copy")
    shutil.rmtree(copy, ignore_errors=True)
    shutil.copytree(mnt, copy)
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=%dk" % (used + 64), "tmpfs", mnt],
                       capture_output=True, text=True)
    if r.returncode == 0:
        subprocess.run(["cp", "-a", copy + "/.", mnt])
    if r.returncode != 0:
        p.kill()
        wait(p, 60)
        leftovers(p)
        return dict(fault="disk full (tmpfs over results/)", detect_s="", exit="",
                    message="not run: mount not permitted (%s)" % r.stderr.strip(), state="",
                    restart="", ok=True)
    tm = time.time()
    rc = wait(p, 20 * timeout)
    detect = time.time() - tm
    hang = rc is None
    if hang:
        for q in [p.pid] + session_pids(p.pid):
            try:
                os.kill(q, signal.SIGKILL)
            except OSError:
                pass
        p.wait()
        rc = p.returncode
    left = leftovers(p)
    errs = error_lines(d)
    message = errs[-1] if errs else "(none)"
    usage = subprocess.run(["df", "-k", mnt], capture_output=True, text=True).stdout.split("\n")[1]
    subprocess.run(["umount", "-l", mnt])
    lvl = checkpoint_level(d)
    state = "tmpfs %s KiB used of %s; after unmount: checkpoint level %d (level %d at the mount)%s" % (
        usage.split()[2], usage.split()[1], lvl, before, "; left: " + left if left else "")
    ok = not hang and rc != 0 and bool(errs) and not left and lvl >= before
    restart, rok = restart_and_compare(d, "mpmd", timeout, ref)
    return dict(fault="disk full: tmpfs (results/ + 64 KiB) mounted over results/ after level %d" % before,
                detect_s="%.1f (mount -> end)" % detect, exit="HANG (killed)" if hang else rc,
                message=message, state=state, restart=restart, ok=bool(ok and rok))


def rank_change_scenario(work, timeout, ref, base):
    """A copy of the finished reference run is set back to its older kept checkpoint (latest ->
    that level, fluid fields of that level), then restarted in MPMD with 2 solid ranks instead
    of 1: the committed state of 1 rank is redistributed (restoreCommittedState)."""
    d = os.path.join(work, "restart-2-solid-ranks")
    shutil.rmtree(d, ignore_errors=True)
    shutil.copytree(base, d, symlinks=True)
    for f in ("log.solid", "log.fluid", "log.mpirun", "log.run"):
        if os.path.exists(os.path.join(d, f)):
            os.remove(os.path.join(d, f))
    ck = os.path.join(d, "results", "checkpoint")
    folders = sorted(x for x in os.listdir(ck) if x.startswith("level_"))
    newest = re.search(r"^folder (\S+)", read(os.path.join(ck, "latest")), re.M).group(1)
    older = [x for x in folders if x != newest]
    if not older:
        return dict(fault="restart with 2 solid ranks", detect_s="", exit="",
                    message="only one checkpoint kept", state="", restart="not run", ok=False)
    folder = older[-1]
    level = int(folder.split("_")[1])
    t = sorted(history(base).keys())[level]
    with open(os.path.join(ck, "latest"), "w") as f:
        f.write("level %d\ntime %r\nfolder %s\n" % (level, t, folder))
    subprocess.check_call([os.path.join(root, "scripts", "fsi-restart-fluid"), "fluid", "results"],
                          cwd=d, env=env(), stdout=subprocess.DEVNULL)
    logrun = os.path.join(d, "tools", "logrun")
    cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "--mca", "btl", "self,vader,tcp",
           "-x", "WM_PROJECT_DIR", "-x", "FOAM_SIGFPE", "-np", "1", logrun, "log.fluid", "0",
           "fluid-app", "-case", "fluid", "-restart", "--launch", "mpmd", "--comm-timeout",
           str(timeout), ":", "-np", "2", logrun, "log.solid", "1", "solid-app", "run.yaml",
           "--restart", "--launch", "mpmd", "--comm-timeout", str(timeout)]
    with open(os.path.join(d, "log.mpirun"), "w") as log:
        p = subprocess.Popen(cmd, cwd=d, env=env(), stdout=log, stderr=subprocess.STDOUT,
                             start_new_session=True)
        rc = wait(p, 40 * timeout)
    left = leftovers(p)
    dmax, why = compare(d, ref)
    ok = rc == 0 and dmax is not None and dmax <= TOL and not left
    return dict(fault="restart from level %d with 2 solid ranks (the run had 1), MPMD" % level,
                detect_s="", exit=rc, message=(error_lines(d) or ["(none)"])[-1], state="",
                restart=("exit %s, max |du_A| %s m vs reference" %
                         (rc, "%.1e" % dmax if dmax is not None else why)), ok=ok)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--only", default="")
    ap.add_argument("--timeout", type=float, default=60.0)
    ap.add_argument("--seed", type=int, default=15)
    a = ap.parse_args()
    timeout = int(a.timeout)
    rng = random.Random(a.seed)
    work = os.path.join(a.out, "work")
    os.makedirs(work, exist_ok=True)
    only = set(x for x in a.only.split(",") if x)
    want = lambda n: not only or n in only or any(n.startswith(o) for o in only)

    rows = []
    ref = {}
    ref_dir = os.path.join(work, "reference-mpmd")
    if not os.path.isfile(os.path.join(ref_dir, "results", "history.csv")):
        d = prepare(work, "reference-mpmd", timeout)
        t0 = time.time()
        rc, left = full_run(d, "mpmd", timeout)
        print("faults: reference run exit %s in %.0f s" % (rc, time.time() - t0), flush=True)
        if rc != 0:
            sys.exit("error: faults: the reference run failed, see %s/log.run" % d)
    ref = history(ref_dir)

    scenarios = []
    for mode in ("mpmd", "port"):
        for side in ("fluid-app", "solid-app"):
            for sig in ("KILL", "TERM", "STOP"):
                n = "%s-%s-%s" % (mode, side.replace("-app", ""), sig)
                if want(n):
                    scenarios.append((n, lambda m=mode, s=side, g=sig:
                                      signal_scenario(work, m, s, g, timeout, ref, rng)))
    for kind in ("truncated", "altered"):
        if want("checkpoint-" + kind):
            scenarios.append(("checkpoint-" + kind, lambda k=kind: checkpoint_scenario(
                work, k, timeout, ref, ref_dir)))
    if want("disk-full"):
        scenarios.append(("disk-full", lambda: disk_full_scenario(work, timeout, ref)))
    if want("restart-2-solid-ranks"):
        scenarios.append(("restart-2-solid-ranks", lambda: rank_change_scenario(work, timeout, ref, ref_dir)))

    out_csv = os.path.join(a.out, "results.csv")
    keys = ["fault", "detect_s", "exit", "message", "state", "restart", "ok"]
    old = []
    if os.path.isfile(out_csv) and only:
        with open(out_csv) as f:
            old = [r for r in csv.DictReader(f)]
    for n, fn in scenarios:
        t0 = time.time()
        r = fn()
        print("faults: %-28s %s (%.0f s): %s | %s | %s" % (n, "pass" if r["ok"] else "FAIL",
              time.time() - t0, r["message"], r["state"], r["restart"]), flush=True)
        r["ok"] = "pass" if r["ok"] else "FAIL"
        rows.append(r)
    names = set(r["fault"] for r in rows)
    rows = [r for r in old if r["fault"] not in names] + rows
    with open(out_csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(a.out, "table.md"), "w") as f:
        f.write("| fault | time to detect [s] | exit | message | state left behind | restart | result |\n")
        f.write("|---|---|---|---|---|---|---|\n")
        for r in rows:
            f.write("| " + " | ".join(str(r[k]).replace("|", "/") for k in keys) + " |\n")
    failed = [r for r in rows if r["ok"] != "pass"]
    print("faults: %d scenario(s), %d failed; %s" % (len(rows), len(failed), out_csv))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
