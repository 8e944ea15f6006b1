#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Fault campaign (issue 15) on the viscoelastic Turek-Hron FSI1 case, coarse, real fluid-app +
# solid-app (1 + 1 ranks), both launch modes: SIGKILL / SIGTERM / SIGSTOP of either side at a
# random moment after the first checkpoint and a restart against the reference history; a full
# disk (tmpfs over results/, needs mount rights); a truncated and an altered checkpoint; a
# restart with 2 solid ranks. See scripts/verify.d/faults/campaign.py for the pass criteria.
# Driven by scripts/verify faults; writes $FSI_VERIFY_DIR/results.csv, table.md (the table of
# verification/faults/README.md) and error_vs_runtime.csv (wall_s = time to detect [s],
# rel_error = time to detect / comm timeout). FAULTS_ONLY=name[,name...] runs a subset (names:
# reference, mpmd-fluid-KILL ... port-solid-STOP, checkpoint-truncated, checkpoint-altered,
# disk-full, restart-2-solid-ranks); FAULTS_TIMEOUT sets --comm-timeout (default 60 s).
# About 40 min on an idle 2-core machine for the full set.
set -euo pipefail
: "${FSI_VERIFY_DIR:?run through scripts/verify faults}"
root=${FSI_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
export FSI_ROOT=$root
export PATH=${FSI_BUILD_DIR:-$root/build}/bin:$PATH
for p in fluid-app solid-app blockMesh gmsh mpirun; do
  command -v "$p" > /dev/null || { echo "error: faults: $p not found (build with the fluid: cmake -S . -B build)" >&2; exit 1; }
done
timeout=${FAULTS_TIMEOUT:-60}
rc=0
/usr/bin/python3 "$root/scripts/verify.d/faults/campaign.py" "$FSI_VERIFY_DIR" \
  --only "${FAULTS_ONLY:-}" --timeout "$timeout" || rc=$?
/usr/bin/python3 - "$FSI_VERIFY_DIR" "$timeout" <<'PY'
import csv, os, re, sys
out, timeout = sys.argv[1], float(sys.argv[2])
with open(os.path.join(out, "results.csv")) as f:
    rows = list(csv.DictReader(f))
with open(os.path.join(out, "error_vs_runtime.csv"), "w") as f:
    f.write("level,size,cores,wall_s,quantity,value,reference,rel_error\n")
    for r in rows:
        m = re.match(r"[0-9.]+", r["detect_s"] or "")
        if not m:
            continue
        s = float(m.group(0))
        name = re.sub(r"[^A-Za-z0-9]+", "-", r["fault"]).strip("-")[:40]
        f.write("%s,0,2,%.1f,detect_over_timeout,%.1f,%g,%.4g\n" % (name, s, s, timeout, s / timeout))
PY
cat "$FSI_VERIFY_DIR/table.md"
exit $rc
