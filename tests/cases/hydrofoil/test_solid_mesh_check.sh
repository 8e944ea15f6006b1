#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# tests/cases/hydrofoil/test_solid_mesh_check.sh MESH_DIR WORK
#
# cases/hydrofoil/tools/solidMeshCheck.sh on the coarse meshes of MESH_DIR (hydrofoil_mesh_coarse's
# output): the clamped root carries the whole applied load (reaction_clamped_y = +1.16 N to 1e-7
# relative: equilibrium, both elements); the plain Tet10 and the Hex20 B-bar foils, two
# independent discretisations of the same structure, agree on the tip deflection within 0.5 %
# (measured 2026-12-07: 0.22 %); the tip deflects by 5-7 mm in -y. Bad options are refused in
# one line (exit 2) before anything is written. Needs solid-app on PATH.
set -uo pipefail
mesh=${1:?usage: test_solid_mesh_check.sh MESH_DIR WORK}
work=${2:?usage: test_solid_mesh_check.sh MESH_DIR WORK}
tool=$(cd "$(dirname "$0")/../../.." && pwd)/cases/hydrofoil/tools/solidMeshCheck.sh
fail=0
rm -rf "$work"
for bad in "--load 0" "--load abc" "--bogus 1"; do
    rc=0
    # shellcheck disable=SC2086  # $bad: two words on purpose
    "$tool" --out "$work" $bad "$mesh" > /dev/null 2> "$work.err" || rc=$?
    if [ "$rc" -ne 2 ] || [ "$(wc -l < "$work.err")" -ne 1 ] || [ -e "$work" ]; then
        echo "FAIL: solidMeshCheck.sh $bad: exit $rc, $(wc -l < "$work.err") lines, wrote: $(ls "$work" 2> /dev/null)"; fail=1
    else
        echo "ok: $bad refused: $(cat "$work.err")"
    fi
done
rm -f "$work.err"
"$tool" --out "$work" "$mesh" || { echo "FAIL: solidMeshCheck.sh on $mesh"; exit 1; }
/usr/bin/python3 - "$work" <<'PY' || fail=1
import csv, glob, os, sys
work = sys.argv[1]
rows = {r["element"]: r for r in csv.DictReader(open(os.path.join(work, "solid-mesh.csv")))}
ok = True
for el in ("tet10", "hex20"):
    hist = glob.glob(os.path.join(work, "*-" + el, "history.csv"))
    h = next(csv.DictReader(open(hist[0])))
    ry = float(h["reaction_clamped_y"])
    if abs(ry - 1.16) > 1e-7 * 1.16:  # the direct solve leaves ~2e-9 (Hex20)
        print(f"FAIL: {el}: reaction_clamped_y {ry!r}, expected 1.16 N (the applied load)"); ok = False
    if not rows[el]["nodes"].isdigit():
        print(f"FAIL: {el}: nodes '{rows[el]['nodes']}' (from mesh-summary.txt, which mesh.sh appends to)"); ok = False
    uy = float(rows[el]["tip_le_uy_m"])
    if not -7e-3 < uy < -5e-3:
        print(f"FAIL: {el}: tip deflection {uy} m outside -7..-5 mm"); ok = False
tet, hexa = float(rows["tet10"]["tip_le_uy_m"]), float(rows["hex20"]["tip_le_uy_m"])
diff = abs(tet - hexa) / abs(hexa)
print(f"tip deflection Tet10 {tet * 1e3:.5f} mm, Hex20 {hexa * 1e3:.5f} mm: {100 * diff:.3f} % apart (limit 0.5 %)")
if diff > 5e-3:
    print("FAIL: the two element families disagree by more than 0.5 %"); ok = False
sys.exit(0 if ok else 1)
PY
exit $fail
