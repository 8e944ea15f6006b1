#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The structure's own discretisation error on the foil: the same fixed load on the solid meshes
# of several presets, no fluid. Separates the solid's share of a coupled mesh study's changes
# (the coupled study refines the Tet10 foil with the fluid mesh) from the flow's.
#
#   cases/hydrofoil/tools/solidMeshCheck.sh --out DIR [--load N] MESH_DIR [MESH_DIR ...]
#
# MESH_DIR: mesh.sh output folders (solid/foil-tet10.msh, solid/foil-hex20.msh; coarsest
# first). Each mesh is solved by solid-app standalone (1 rank) with the baseline material
# (solid/baseline.yaml: linear elastic, E = 47.40 MPa, nu = 0.49, small strain, root clamped)
# under a total force (0, -N, 0) spread uniformly over the wetted surface (default N = 1.16, the
# coupled t = 0 lift), as Tet10 (plain) and as Hex20 (projected dilatation, B-bar: a second
# element family). Writes DIR/solid-mesh.csv (preset, element, nodes, tip_le_uy_m, tip_te_uy_m,
# tip_twist_deg = atan((uy_te - uy_le) / chord), wall_s) and prints it; with three meshes also
# the observed order and GCI_fine of the tip deflection per element (scripts/gci.py, h =
# nodes^(-1/3)). Needs solid-app on PATH. Cost: coarse 3 s, medium 20 s, fine 100 s and 5.6 GB
# (Tet10, 496 k dofs).
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^[^#]/{/SPDX-License-Identifier/d;s/^# \{0,1\}//p}' "$0"; exit 0 ;; esac
here=$(cd "$(dirname "$0")/.." && pwd)
die() { echo "error: solidMeshCheck.sh: $*" >&2; exit 2; }
out="" load=1.16 meshes=()
while [ $# -gt 0 ]; do
    case "$1" in
        --out) [ $# -ge 2 ] || die "--out needs a folder"; out=$2; shift 2 ;;
        --load) [ $# -ge 2 ] || die "--load needs a force [N]"; load=$2; shift 2 ;;
        -*) die "unknown option '$1' (see --help)" ;;
        *) meshes+=("$1"); shift ;;
    esac
done
[ -n "$out" ] || die "give --out DIR"
[[ "$load" =~ ^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$ ]] && awk -v l="$load" 'BEGIN{exit !(l > 0)}' ||
    die "--load '$load' must be a positive force in N (e.g. 1.16)"
[ "${#meshes[@]}" -ge 1 ] || die "give at least one MESH_DIR (a mesh.sh output folder)"
for m in "${meshes[@]}"; do
    for el in tet10 hex20; do
        [ -f "$m/solid/foil-$el.msh" ] || die "$m has no solid/foil-$el.msh (a mesh.sh output folder, not --fluid-only)"
    done
done
command -v solid-app > /dev/null || die "solid-app not on PATH (build first)"
mkdir -p "$out"
csv=$out/solid-mesh.csv
echo "preset,element,nodes,tip_le_uy_m,tip_te_uy_m,tip_twist_deg,wall_s" > "$csv.tmp"
for m in "${meshes[@]}"; do
    m=$(cd "$m" && pwd)
    # the latest entries of mesh-summary.txt (mesh.sh appends to it)
    preset=$(sed -n 's/.*preset=\([a-z]*\).*/\1/p' "$m/mesh-summary.txt" | tail -n 1)
    preset=${preset:-$(basename "$m")}
    for el in tet10 hex20; do
        name=$preset-$el
        type=displacement; [ "$el" = tet10 ] || type=projected-dilatation
        # baseline.yaml's solid block, with this mesh, element, load and output folder
        sed -n '/^solid:/,/^coupling:/p' "$here/solid/baseline.yaml" | sed '$d' |
            sed -e "s|@MESH@|$m/solid/foil-$el.msh|" -e "s|folder: baseline|folder: $name|" \
                -e "s|^  loads: {}|  element: {type: $type}\n  loads:\n    forces:\n      - surface: wetted\n        total: [0.0, -$load, 0.0]|" \
            > "$out/$name.yaml"
        t0=$(date +%s.%N)
        (cd "$out" && solid-app "$name.yaml" > "log.$name" 2>&1) || die "solid-app failed on $name (see $out/log.$name)"
        t1=$(date +%s.%N)
        nodes=$(grep "^foil-$el.msh: msh" "$m/mesh-summary.txt" | tail -n 1 | sed 's/.*nodes \([0-9]*\).*/\1/')
        /usr/bin/python3 - "$out/$name/history.csv" "$preset" "$el" "$nodes" "$t0" "$t1" >> "$csv.tmp" <<'PY'
import csv, math, sys
hist, preset, el, nodes, t0, t1 = sys.argv[1:]
r = next(csv.DictReader(open(hist)))
le, te = float(r["tip_le_uy"]), float(r["tip_te_uy"])
twist = math.degrees(math.atan((te - le) / 0.05))
print(f"{preset},{el},{nodes},{le:.9g},{te:.9g},{twist:.6g},{float(t1) - float(t0):.1f}")
PY
    done
done
mv "$csv.tmp" "$csv"
column -s, -t < "$csv"
[ "${#meshes[@]}" = 3 ] || exit 0
for el in tet10 hex20; do
    args=$(awk -F, -v e="$el" '$2 == e {printf "%.9g,%s ", $3 ^ (-1 / 3), $4}' "$csv")
    # shellcheck disable=SC2086  # three H,PHI words
    echo "$el tip deflection (tip_le_uy): $(/usr/bin/python3 "${FSI_ROOT:-$here/../..}/scripts/gci.py" $args)"
done
