#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The fluid accuracy of a coupled run in one number: set both keys of a solid config's
# coupling.fluid_accuracy block that bound a fluid solve's force error, relative to |F|:
#   final: {force_tolerance: F}   the accuracy a level is accepted with
#   max_force_tolerance: F        the loosest an inexact solve early in a level may stop at
# (config/coupled.example.yaml documents both). The one place that knows these two lines:
# run.sh --fluid-tolerance and scripts/bench-fsi --fluid-tolerance use it.
#
#   cases/hydrofoil/tools/setFluidTolerance.sh YAML F     set both to F (0 < F < 1)
#   cases/hydrofoil/tools/setFluidTolerance.sh --check YAML...
#                                                         only check that every YAML has both lines
# Exit 2 with a one-line error naming the file and the missing line; YAML is not changed then.
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^[^#]/{/SPDX-License-Identifier/d;s/^# \{0,1\}//p}' "$0"; exit 0 ;; esac
die() { echo "error: setFluidTolerance.sh: $*" >&2; exit 2; }
finalLine='^    final: {force_tolerance: '
maxLine='^    max_force_tolerance: '
check() {
  [ -f "$1" ] || die "no solid config '$1'"
  grep -q "$finalLine" "$1" ||
    die "$1: no 'final: {force_tolerance: ...}' line under coupling.fluid_accuracy (restore it from cases/hydrofoil/solid)"
  grep -q "$maxLine" "$1" ||
    die "$1: no 'max_force_tolerance:' line under coupling.fluid_accuracy (restore it from cases/hydrofoil/solid)"
}
if [ "${1:-}" = --check ]; then
  shift
  [ $# -ge 1 ] || die "usage: setFluidTolerance.sh --check YAML..."
  for y in "$@"; do check "$y"; done
  exit 0
fi
[ $# = 2 ] || die "usage: setFluidTolerance.sh YAML F  |  setFluidTolerance.sh --check YAML..."
yaml=$1 f=$2
awk -v f="$f" 'BEGIN{exit !(f ~ /^[0-9.]+([eE][+-]?[0-9]+)?$/ && f + 0 > 0 && f + 0 < 1)}' ||
  die "fluid tolerance '$f' must be a number in (0, 1), e.g. 5e-5"
check "$yaml"
sed -i "s/\($finalLine\)[^}]*}/\1$f}/; s/\($maxLine\)[0-9.eE+-]*/\1$f/" "$yaml"
