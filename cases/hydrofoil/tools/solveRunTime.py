#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The run time of a rigid solve that took several runs (rigid.sh --resume).

    cases/hydrofoil/tools/solveRunTime.py CASE RANKS

prints `wall_s cpu_s runs` of CASE's earlier runs: every log.fluid-app.before-N that
rigid.sh --resume kept. A run's wall time goes from its log's start stamp (OpenFOAM's banner
lines `Date : Mon DD YYYY` and `Time : HH:MM:SS`, local time) to the log's last write; its CPU
time is its time record time.txt.before-N (`user sys`, written by /usr/bin/time when the run
ended by itself), or RANKS x wall for a run stopped from outside (no record). rigid.sh adds the
last run's own measured times. A log without a start stamp is an error (exit 2): its run time
cannot be counted.
"""
import glob
import os
import re
import sys
import time


def runStart(log):
    """Epoch seconds of the start stamp in the banner of the OpenFOAM log `log` (local time)."""
    with open(log, errors="replace") as f:
        head = f.read(20000)
    date = re.search(r"^Date\s*:\s*(\w+ \d+ \d+)\s*$", head, re.M)
    hms = re.search(r"^Time\s*:\s*(\d+:\d+:\d+)\s*$", head, re.M)
    if not (date and hms):
        raise ValueError("%s has no start stamp (Date/Time lines): its run time cannot be counted" % log)
    return time.mktime(time.strptime(date.group(1) + " " + hms.group(1), "%b %d %Y %H:%M:%S"))


def recordedCpu(record):
    """CPU seconds (user + sys) of a run's time record (`user sys`, /usr/bin/time -f "%U %S"),
    or None when the record is missing or empty (a run stopped from outside)."""
    if not os.path.isfile(record):
        return None
    with open(record) as f:
        words = f.read().split()
    return sum(map(float, words[:2])) if len(words) >= 2 else None


def earlierRuns(case, ranks):
    """(wall_s, cpu_s, runs) of CASE's earlier runs (the module's doc)."""
    wall = cpu = 0.0
    logs = sorted(glob.glob(os.path.join(case, "log.fluid-app.before-*")))
    for log in logs:
        w = max(0.0, os.path.getmtime(log) - runStart(log))
        recorded = recordedCpu(os.path.join(case, os.path.basename(log).replace("log.fluid-app", "time.txt")))
        wall += w
        cpu += recorded if recorded is not None else ranks * w
    return wall, cpu, len(logs)


def main(argv):
    if argv[:1] in (["-h"], ["--help"]):
        print(__doc__.strip())
        return 0
    if len(argv) != 2 or not re.fullmatch(r"[1-9][0-9]*", argv[1]):
        print("error: solveRunTime.py: usage: solveRunTime.py CASE RANKS (RANKS a positive integer)",
              file=sys.stderr)
        return 2
    try:
        wall, cpu, runs = earlierRuns(argv[0], int(argv[1]))
    except ValueError as e:
        print("error: solveRunTime.py: %s" % e, file=sys.stderr)
        return 2
    print("%.1f %.1f %d" % (wall, cpu, runs))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
