#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# 2-D section of the hydrofoil (cases/hydrofoil/section2d): mesh study of C_L, C_D and C_M on the
# structured C-grid levels (every length refined by sqrt 2 per level), rigid steady flow with
# fluid-app -rigid, second-order bounded convection (linearUpwind, cell-limited gradients).
# Per flow model: observed order, Richardson extrapolation and GCI_fine (Celik et al. 2008 /
# ASME V&V 20) from the three finest levels -> gci.csv (quantity,model,levels,observed_order,
# extrapolated,gci_fine_pct, then convergence,asymptotic_ratio,rel_diff_fine,asymptotic_range:
# yes when the three levels are settled (below) and converge monotonically with an observed
# order between 1 and 3, otherwise the order and GCI are no error bound; settled: yes when
# all three levels are; range_uncertainty_pct: half the three levels' range over the finest,
# scripts/gci.py, the estimate for oscillatory convergence).
# error_vs_runtime.csv: the standard columns; reference = the extrapolated value where the
# three finest levels are in the asymptotic range, else the finest level (its rows then have
# rel_error 0); extra columns cpu_s, iterations, converged, model, te.
# Steadiness evidence (steadiness.csv): level-0/1 solves of the models and trailing edges that
# have no steady state (1500 iterations); their C_L range over 300 further SIMPLE iterations.
# A level of the mesh study counts as converged when its solve met the stopping test, or when
# it reached the iteration cap but C_L moved by less than 1e-4 relative over those 300
# further iterations.
# Environment:
#   H2D_LEVELS     levels, coarse to fine (default "0 1 2 3 4")
#   H2D_MODELS     flow models of the mesh study (default "turbulent")
#   H2D_TE         trailing edge of the mesh study: sharp | blunt (default sharp: see README)
#   H2D_TOLERANCE  estimated force error at which a solve stops (run2d.sh --tolerance; default
#                  1e-5, held for 100 iterations: well below the level-to-level differences)
#   H2D_EVIDENCE   1 (default): also the steadiness runs (laminar, transition, blunt turbulent)
#   H2D_MAX_ITERATIONS  SIMPLE iteration cap per level (default 8000)
#   H2D_SEQUENCE   1 (default): every level of the mesh study starts from the solution of the
#                  next coarser level (run2d.sh --init-from; grid sequencing, fewer iterations)
#   H2D_INLET      "TU L": inlet turbulence intensity and length scale (m) for every solve
#                  (run2d.sh --tu --length-scale; default: those of cases/hydrofoil/fluid/0.orig)
#   H2D_ALGORITHM  simplec (default: the case's SIMPLEC) | simple (classic SIMPLE, run2d.sh
#                  --algorithm; its run folders end in -simple)
#   H2D_BAND       run2d.sh --band-tolerance (default 0: off). Classic SIMPLE on level 0 kept a
#                  period-8 oscillation of +-3.4e-4 in C_L (case README, "Flow models"), so a
#                  band below that never fires there
#   H2D_BAND_WINDOW  run2d.sh --band-window: the band rule's block length (default 100); a
#                  space-separated list gives one per level of H2D_LEVELS (e.g. "100 100 100
#                  1000": level 3's SIMPLEC cycle has a period of ~420 iterations)
#   H2D_RUNS       run folders (default $FSI_VERIFY_DIR/runs, not tracked)
#   H2D_REUSE=1    keep finished runs (RUN/section2d.csv) instead of redoing them
# gci.csv has one row per quantity for every three consecutive levels (coarse to fine), so
# that the approach to the asymptotic range shows; the finest three give the result.
set -euo pipefail
: "${FSI_VERIFY_DIR:?run through scripts/verify hydrofoil-2d}"
root=${FSI_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
export PATH=${FSI_BUILD_DIR:-$root/build}/bin:$PATH
run2d=$root/cases/hydrofoil/section2d/run2d.sh
levels=${H2D_LEVELS:-"0 1 2 3 4"}
models=${H2D_MODELS:-turbulent}
te=${H2D_TE:-sharp}
runs=${H2D_RUNS:-$FSI_VERIFY_DIR/runs}
reuse=${H2D_REUSE:-0}
algorithm=${H2D_ALGORITHM:-simplec}
case "$algorithm" in simple|simplec) ;; *) echo "error: hydrofoil-2d: H2D_ALGORITHM='$algorithm' must be simple or simplec" >&2; exit 2 ;; esac
solverArgs=(--band-tolerance "${H2D_BAND:-0}") suffix=""
bandWindows=(${H2D_BAND_WINDOW:-100})
nLevels=$(echo $levels | wc -w)
[ ${#bandWindows[@]} = 1 ] || [ ${#bandWindows[@]} = "$nLevels" ] ||
    { echo "error: hydrofoil-2d: H2D_BAND_WINDOW='${H2D_BAND_WINDOW}' needs one value or one per level of H2D_LEVELS ($nLevels)" >&2; exit 2; }
[ "$algorithm" = simplec ] || { solverArgs+=(--algorithm "$algorithm"); suffix=-$algorithm; }
mkdir -p "$runs"

inlet=()
if [ -n "${H2D_INLET:-}" ]; then
    set -- $H2D_INLET
    [ $# = 2 ] || { echo "error: hydrofoil-2d: H2D_INLET='$H2D_INLET' must be \"TU L\" (e.g. \"0.01 0.001\")" >&2; exit 2; }
    inlet=(--tu "$1" --length-scale "$2")
fi

# the band window of a level: the list's entry at the level's position in H2D_LEVELS (one
# entry: every level; the evidence runs, not in the list: the first entry)
bandWindowOf() {
    local i=0 l
    [ ${#bandWindows[@]} = 1 ] && { echo "${bandWindows[0]}"; return; }
    for l in $levels; do
        [ "$l" = "$1" ] && { echo "${bandWindows[$i]:-${bandWindows[0]}}"; return; }
        i=$((i + 1))
    done
    echo "${bandWindows[0]}"
}

# one solve: run2d.sh into RUN unless reusable; echo its CSV row prefixed by te and h
solve() {  # model level te maxIterations [initFromRun]
    local r=$runs/$1-$3-L$2$suffix init=()
    [ -z "${5:-}" ] || init=(--init-from "$5")
    if [ "$reuse" = 1 ] && [ -f "$r/section2d.csv" ]; then
        echo "hydrofoil-2d: reusing $r" >&2
    else
        echo "hydrofoil-2d: $1 level $2 te $3 ($(date +%H:%M:%S), load $(cut -d' ' -f1 /proc/loadavg))" >&2
        "$run2d" --out "$r" --level "$2" --flow "$1" --te "$3" --max-iterations "$4" \
            --tolerance "${H2D_TOLERANCE:-1e-5}" "${solverArgs[@]}" --band-window "$(bandWindowOf "$2")" \
            ${inlet[@]+"${inlet[@]}"} \
            ${init[@]+"${init[@]}"} > "$r.log" 2>&1 ||
            { tail -5 "$r.log" >&2; echo "error: hydrofoil-2d: $1 level $2 failed (see $r.log)" >&2; exit 1; }
    fi
    local h; h=$(sed -n 's/.* h_m=\([^ ]*\).*/\1/p' "$r/mesh/section2d-mesh.txt")
    echo "$3,$h,$(sed -n 2p "$r/section2d.csv"),$(cut -d' ' -f1 /proc/loadavg)"
}

raw=$FSI_VERIFY_DIR/levels.csv
echo "te,h_m,level,cells,flow,scheme,iterations,converged,C_L,C_D,C_M,yplus_max,yplus_mean,cpu_s,wall_s,cl_min,cl_max,turb_from_suction,sep_suction,turb_from_pressure,sep_pressure,in_the_mean,band,load1" > "$raw"
for model in $models; do
    previous=""
    for level in $levels; do
        solve "$model" "$level" "$te" "${H2D_MAX_ITERATIONS:-8000}" "$previous" >> "$raw"
        tail -n 1 "$raw"
        [ "${H2D_SEQUENCE:-1}" != 1 ] || previous=$runs/$model-$te-L$level$suffix
    done
done
if [ "${H2D_EVIDENCE:-1}" = 1 ]; then
    steady=$FSI_VERIFY_DIR/steadiness.csv
    head -n 1 "$raw" > "$steady"
    for spec in "laminar 0 sharp" "transition 0 sharp" "turbulent 0 blunt" "turbulent 1 blunt"; do
        set -- $spec
        solve "$1" "$2" "$3" 1500 >> "$steady"
        tail -n 1 "$steady"
    done
fi

"$FSI_PYTHON" - "$raw" "$FSI_VERIFY_DIR" "$root/scripts" <<'PY'
import csv, math, os, sys
raw, outDir, scripts = sys.argv[1:]
sys.path.insert(0, scripts)
from gci import gci
rows = list(csv.DictReader(open(raw)))
gciRows, err = [], []
for model in sorted({r["flow"] for r in rows}):
    rs = sorted((r for r in rows if r["flow"] == model), key=lambda r: float(r["h_m"]), reverse=True)
    for q in ("C_L", "C_D", "C_M"):
        ref, res = None, None
        def settled(r):
            if r["converged"] == "1":
                return True
            lo, hi = float(r["cl_min"]), float(r["cl_max"])
            return math.isfinite(lo) and abs(hi - lo) < 1e-4 * abs(float(r["C_L"]))
        for i in range(len(rs) - 2):
            tri = rs[i:i + 3]
            allSettled = all(settled(r) for r in tri)
            res = gci([float(r["h_m"]) for r in tri], [float(r[q]) for r in tri])
            asymptotic = (allSettled and res["convergence"] == "monotone"
                          and 1.0 <= res["observed_order"] <= 3.0)
            gciRows.append([q, model, " ".join(r["level"] for r in tri),
                            "%.4g" % res["observed_order"], "%.8g" % res["extrapolated"],
                            "%.4g" % res["gci_fine_pct"], res["convergence"],
                            "%.4g" % res["asymptotic_ratio"], "%.4g" % res["rel_diff_fine"],
                            "yes" if asymptotic else "no", "yes" if allSettled else "no",
                            "%.4g" % res["range_uncertainty_pct"]])
            if i == len(rs) - 3 and asymptotic:
                ref = res["extrapolated"]
        if ref is None:
            ref = float(rs[-1][q])
        for r in rs:
            v = float(r[q])
            err.append([r["level"], r["cells"], 1, r["wall_s"], q, "%.8g" % v, "%.8g" % ref,
                        "%.6e" % (abs(v - ref) / abs(ref)), r["cpu_s"], r["iterations"],
                        r["converged"], model, r["te"]])
with open(os.path.join(outDir, "gci.csv"), "w") as f:
    f.write("quantity,model,levels,observed_order,extrapolated,gci_fine_pct,convergence,"
            "asymptotic_ratio,rel_diff_fine,asymptotic_range,settled,range_uncertainty_pct\n")
    for g in gciRows:
        f.write(",".join(g) + "\n")
with open(os.path.join(outDir, "error_vs_runtime.csv"), "w") as f:
    f.write("level,size,cores,wall_s,quantity,value,reference,rel_error,cpu_s,iterations,"
            "converged,model,te\n")
    for e in err:
        f.write(",".join(str(v) for v in e) + "\n")
for g in gciRows:
    print("hydrofoil-2d: %s %s levels %s: order %s, extrapolated %s, GCI_fine %s %% (%s, "
          "asymptotic ratio %s, in the asymptotic range (order 1-3): %s, levels settled: %s)"
          % tuple(g[:8] + g[9:11]))
PY
