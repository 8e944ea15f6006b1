#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Coupled elastic t = 0 state of the hydrofoil on the boundary-layer (cgrid) presets coarse /
# medium / fine: the study of scripts/verify.d/hydrofoil.sh (run.sh --material baseline, fluid 2
# ranks + solid 1 rank, the preset's Tet10 foil) with k-omega SST, first-order upwind and the
# rigid study's pressure-velocity algorithm (H3D_ALGORITHM, default simplec, the case's; simple:
# classic SIMPLE, the study of 2026-12-04 on the older meshes), on the same systematic cgrid
# refinement. Each level's fluid starts from that study's converged rigid flow
# of the same preset (run.sh --init-from): level 0's first solve then only confirms the rigid
# state, and a level costs its coupling iterations instead of a solve from rest (thousands of
# classic SIMPLE iterations on medium and fine). Run scripts/verify hydrofoil-3d-rigid first.
# Writes, besides hydrofoil.sh's levels.csv / error_vs_runtime.csv / richardson.csv here:
# the observed order, extrapolated value and GCI_fine of the tip AOA, tip deflection, lift and
# drag (scripts/history_gci.py --steady) into this folder's gci.csv and into
# verification/hydrofoil/gci.csv (model turbulent-upwind-ALGORITHM-cgrid-baseline; that file's
# rows of other studies are kept).
# Environment: HYDROFOIL_LEVELS, HYDROFOIL_RUNS, HYDROFOIL_REUSE, HYDROFOIL_TIMEOUT as
# hydrofoil.sh; H3D_RUNS: the rigid study's run folders (default
# verification/hydrofoil-3d-rigid/runs, that study's default); H3D_ALGORITHM as that study.
set -euo pipefail
: "${FSI_VERIFY_DIR:?run through scripts/verify hydrofoil-cgrid}"
root=${FSI_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
rigidRuns=${H3D_RUNS:-$root/verification/hydrofoil-3d-rigid/runs}
algorithm=${H3D_ALGORITHM:-simplec}
case "$algorithm" in simple|simplec) ;; *) echo "error: hydrofoil-cgrid: H3D_ALGORITHM='$algorithm' must be simple or simplec" >&2; exit 2 ;; esac
export HYDROFOIL_FLUID_MESH=cgrid HYDROFOIL_FLOW=turbulent HYDROFOIL_SCHEME=upwind HYDROFOIL_ALGORITHM=$algorithm
export HYDROFOIL_INIT_FROM=$rigidRuns/turbulent-upwind-$algorithm-LEVEL/rigid/case
export HYDROFOIL_GCI_MODEL=turbulent-upwind-$algorithm-cgrid-baseline
export HYDROFOIL_GCI_OUT=$FSI_VERIFY_DIR/gci.csv
bash "$(dirname "$0")/hydrofoil.sh" "$@"
set -- ${HYDROFOIL_LEVELS:-coarse medium fine}
if [ $# = 3 ]; then
  "$FSI_PYTHON" "$root/scripts/history_gci.py" --steady --model "$HYDROFOIL_GCI_MODEL" \
      --out "$root/verification/hydrofoil/gci.csv" \
      "${HYDROFOIL_RUNS:-$FSI_VERIFY_DIR}/run-$1" "${HYDROFOIL_RUNS:-$FSI_VERIFY_DIR}/run-$2" \
      "${HYDROFOIL_RUNS:-$FSI_VERIFY_DIR}/run-$3" > /dev/null
fi
