#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Runs one verification study (scripts/verify NAME, with the solid-app of this build) and
# checks its CSV: for each quantity matching PATTERN, |rel_error| of the LAST row <= TOL and,
# with "falling", the first row's |rel_error| >= the last row's.
# usage: check_study.sh BUILD_DIR NAME PATTERN TOL [falling]
set -euo pipefail
build=$1; name=$2; pattern=$3; tol=$4; mode=${5:-}
root=$(cd "$(dirname "$0")/../.." && pwd)
FSI_BUILD_DIR=$build FSI_SKIP_BUILD=1 "$root/scripts/verify" "$name" > /dev/null
csv=$root/verification/$name/error_vs_runtime.csv
awk -F, -v p="$pattern" -v tol="$tol" -v mode="$mode" 'NR > 1 && $5 ~ p {
    e = $8 < 0 ? -$8 : $8; if (!($5 in first)) first[$5] = e; last[$5] = e; lastrow[$5] = $0 }
  END { bad = 0; n = 0
    for (q in last) { n++
      printf "%s: first |rel_error| %.3e, last %.3e (tolerance %s)\n", q, first[q], last[q], tol
      if (last[q] > tol) bad = 1
      if (mode == "falling" && first[q] < last[q]) bad = 1 }
    if (n == 0) { print "no quantity matches " p; exit 1 }
    exit bad }' "$csv"
