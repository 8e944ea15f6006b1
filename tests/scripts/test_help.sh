#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# tests/scripts/test_help.sh WORK
#
# Every user-facing script answers -h / --help with its documentation: exit 0, at least three
# lines on stdout (stderr is not judged: a library may warn there, e.g. matplotlib about its
# cache folder), and nothing done: no file written in the working folder
# (WORK, empty), no setup, build or run. Covered: the executables in scripts/, the case scripts
# cases/*/*.sh, the case tools cases/*/tools/* and the 2-D section and geometry scripts (Python
# through Debian's /usr/bin/python3), scripts/gci.py; `scripts/verify --list` names every study
# of scripts/verify.d with its first header line, and `scripts/verify NAME --help` prints that
# study's header. A new script without --help fails here: give it one, or list it in `internal`
# below with the reason. Needs FSI_ROOT (the repository); no OpenFOAM run, no MPI.
set -uo pipefail
work=${1:?usage: test_help.sh WORK}
: "${FSI_ROOT:?set FSI_ROOT to the repository}"
# Not user-facing: logrun is mpirun's per-rank log wrapper (LOG FIRST_RANK CMD...); env.sh and
# model_csv.py are sourced / imported, not run.
internal=" cases/turek-hron-fsi1/tools/logrun scripts/env.sh scripts/model_csv.py "
fail=0 checked=0
rm -rf "$work"; mkdir -p "$work"

# checkHelp NAME CMD...: CMD --help in the empty WORK folder.
checkHelp() {
  local name=$1; shift
  local rc=0
  (cd "$work" && timeout 30 "$@" --help > "$work/.out" 2> "$work/.err") || rc=$?
  local lines; lines=$(wc -l < "$work/.out")
  local left; left=$(cd "$work" && ls -A | grep -v -x -e .out -e .err | tr '\n' ' ')
  checked=$((checked + 1))
  if [ "$rc" -ne 0 ] || [ "$lines" -lt 3 ] || [ -n "$left" ]; then
    echo "FAIL: $name --help: exit $rc, $lines lines on stdout, stderr: $(head -c 200 "$work/.err"), written: ${left:-nothing}"
    fail=1
    (cd "$work" && ls -A | grep -v -x -e .out -e .err | xargs -r rm -rf --)
  fi
}

cd "$FSI_ROOT" || exit 1
for f in scripts/* scripts/gci.py cases/*/*.sh cases/*/tools/* cases/hydrofoil/section2d/* \
         cases/hydrofoil/geometry/*.py; do
  [ -f "$f" ] || continue
  case "$internal" in *" $f "*) continue ;; esac
  case "$f" in *.md|*.geo|*/test_*.py) continue ;; esac
  if head -n 1 "$f" | grep -q python; then
    checkHelp "$f" /usr/bin/python3 "$FSI_ROOT/$f"
  elif head -n 1 "$f" | grep -q bash; then
    checkHelp "$f" bash "$FSI_ROOT/$f"
  fi
done

# scripts/verify: the list names every study with its description; each study's header.
list=$("$FSI_ROOT/scripts/verify" --list 2>&1) || { echo "FAIL: scripts/verify --list: exit $?"; fail=1; }
for study in "$FSI_ROOT"/scripts/verify.d/*.sh; do
  name=$(basename "$study" .sh)
  first=$(sed -n '3s/^# //p' "$study")
  if ! grep -q -F -- "$name" <<< "$list" || ! grep -q -F -- "$first" <<< "$list"; then
    echo "FAIL: scripts/verify --list lacks '$name  $first'"; fail=1
  fi
  checkHelp "scripts/verify $name" "$FSI_ROOT/scripts/verify" "$name"
  if ! head -n 1 "$work/.out" | grep -q -F -- "$first"; then
    echo "FAIL: scripts/verify $name --help does not start with the study's header ('$first')"; fail=1
  fi
done

echo "test_help: $checked scripts checked"
[ "$checked" -ge 40 ] || { echo "FAIL: only $checked scripts found (expected 40 or more)"; fail=1; }
exit $fail
