#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The fluid iteration error of a coupled run's accepted state: the flow of its last fluid solve,
# at the accepted shape, solved on to convergence (rigid.sh --shape-from), and the loads compared.
# A coupled level is accepted on fluid solves stopped by the force-error estimate; this says how
# far their loads lie from the converged flow at the same shape (cases/hydrofoil/README.md, "The
# coupled levels' fluid iteration error").
#
#   cases/hydrofoil/tools/shapeCheck.sh --run RUN [--material baseline] [--out DIR] [--resume]
#       [--] [rigid.sh options: --band-tolerance, --max-iterations, --np, ...]
#
#   --run RUN          a finished run.sh run folder: RUN/mesh/fluid, RUN/fluid-MATERIAL (the
#                      coupled fluid case with its written moved mesh) and
#                      RUN/results/MATERIAL/history.csv (its last row: the state compared)
#   --material M       the run's --material (default baseline: the t = 0 state; visco: the last
#                      level written)
#   --out DIR          rigid.sh's run folder (default RUN/shape-MATERIAL)
#   --resume           go on with a shape solve stopped from outside (e.g. at a session's end) from
#                      its latest restart point (rigid.sh --resume on DIR/case: its moved mesh and
#                      flow model kept; give the same stopping options). shape.csv's iterations
#                      and cost are then the resumed part's only
#   the rest           passed to rigid.sh: the shape solve's stopping test (--tolerance,
#                      --band-tolerance, --band-mean-tolerance, --max-iterations). The flow model
#                      is the run's own (rigid.sh --shape-from reads its fluid case's fluidModel;
#                      a run made before 2026-12-07 has none: then give its --flow, --scheme and,
#                      as it ran, --algorithm and --root-wall). --np: rigid.sh takes the run's
#                      fluid case's decomposition unless it is given
#
# Writes DIR (rigid.sh's case and rigid.csv) and DIR/shape.csv, one row: time_s (the state's
# time), coupled_lift_N, shape_lift_N, lift_change_pct, coupled_drag_N, shape_drag_N,
# drag_change_pct (shape against coupled), then rigid.sh's iterations, converged, in_the_mean,
# band, root_moment_z_Nm, cpu_s, wall_s. Exit 2 on bad options (one line; rigid.sh's own too),
# non-zero when the solve fails.
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^[^#]/{/SPDX-License-Identifier/d;s/^# \{0,1\}//p}' "$0"; exit 0 ;; esac
here=$(cd "$(dirname "$0")/.." && pwd)
die() { echo "error: shapeCheck.sh: $*" >&2; exit 2; }
run="" material=baseline out="" resume=0
while [ $# -gt 0 ]; do
    case "$1" in
        --run) [ $# -ge 2 ] || die "--run needs a run folder"; run=$2; shift 2 ;;
        --material) [ $# -ge 2 ] || die "--material needs a name"; material=$2; shift 2 ;;
        --out) [ $# -ge 2 ] || die "--out needs a folder"; out=$2; shift 2 ;;
        --resume) resume=1; shift ;;
        --) shift; break ;;
        *) break ;;
    esac
done
[ -n "$run" ] || die "give --run RUN (a finished run.sh run folder)"
[[ "$material" =~ ^[A-Za-z0-9_-]+$ ]] || die "--material '$material' is not a material name (e.g. baseline)"
history=$run/results/$material/history.csv fluidCase=$run/fluid-$material
[ -f "$history" ] || die "--run '$run' has no results/$material/history.csv (a finished run of --material $material?)"
[ -d "$fluidCase" ] || die "--run '$run' has no fluid-$material case"
[ -d "$run/mesh/fluid" ] || die "--run '$run' has no mesh/fluid"
out=${out:-$run/shape-$material}
case " $* " in *" --shape-from "*|*" --mesh "*|*" --out "*|*" --resume "*) die "--shape-from, --mesh, --out and --resume are this tool's to set" ;; esac

start=(--shape-from "$fluidCase"); [ "$resume" = 0 ] || start=(--resume)
"$here/rigid.sh" --mesh "$run/mesh/fluid" --out "$out" "${start[@]}" "$@" || exit $?
[ -f "$out/rigid.csv" ] || { echo "error: shapeCheck.sh: rigid.sh wrote no $out/rigid.csv" >&2; exit 1; }

/usr/bin/python3 - "$history" "$out/rigid.csv" "$out/shape.csv" <<'EOP'
import csv, sys
historyCsv, rigidCsv, outCsv = sys.argv[1:]
state = list(csv.DictReader(open(historyCsv)))[-1]
shape = next(csv.DictReader(open(rigidCsv)))
liftC, dragC = -float(state["Fy"]), float(state["Fx"])
liftS, dragS = float(shape["lift_N"]), float(shape["drag_N"])
res = dict(time_s=state["time"], coupled_lift_N="%.6g" % liftC, shape_lift_N="%.6g" % liftS,
           lift_change_pct="%.3f" % (100.0 * (liftS - liftC) / liftC),
           coupled_drag_N="%.6g" % dragC, shape_drag_N="%.6g" % dragS,
           drag_change_pct="%.3f" % (100.0 * (dragS - dragC) / dragC))
for key in ("iterations", "converged", "in_the_mean", "band", "root_moment_z_Nm", "cpu_s", "wall_s"):
    res[key] = shape[key]
with open(outCsv, "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(res))
    w.writeheader()
    w.writerow(res)
print("shape: " + " ".join("%s=%s" % kv for kv in res.items()))
EOP
