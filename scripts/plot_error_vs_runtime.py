#!/usr/bin/python3
"""Plot |relative error| against wall time, one line per quantity.

usage: plot_error_vs_runtime.py CSV PNG [TITLE]
CSV columns: level,size,cores,wall_s,quantity,value,reference,rel_error (further columns are
ignored, except model: a file with several models draws one line per quantity and model).
Rows with rel_error exactly 0 (a level that is its own reference) are not plotted.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) > 1 and sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return
    if len(sys.argv) < 3:
        sys.exit("usage: plot_error_vs_runtime.py CSV PNG [TITLE]")
    src, png = sys.argv[1], sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else src
    series = {}
    skipped = set()
    with open(src, newline="") as f:
        rows = list(csv.DictReader(f))
    models = sorted({row.get("model", "") for row in rows})
    for row in rows:
        tag = f" [{row['model']}]" if len(models) > 1 else ""
        if float(row["rel_error"]) == 0.0:
            skipped.add(row["level"] + tag)
            continue
        series.setdefault(row["quantity"] + tag, []).append(
            (float(row["wall_s"]), abs(float(row["rel_error"])), row["level"], row["size"]))
    if not series:
        sys.exit(f"error: {src} has no rows")
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for q, pts in sorted(series.items()):
        pts.sort()
        ax.loglog([p[0] for p in pts], [max(p[1], 1e-16) for p in pts], "o-", label=q)
        for p in pts:
            ax.annotate(f"{p[2]} ({p[3]})", (p[0], max(p[1], 1e-16)), fontsize=7,
                        textcoords="offset points", xytext=(4, 4))
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("|relative error|")
    ax.set_title(f"{title}: error against run time")
    if skipped:  # below the axes, clear of the legend
        fig.text(0.01, 0.01, "own reference, not shown: " + ", ".join(sorted(skipped)), fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7 if len(models) > 1 else None)
    fig.tight_layout(rect=(0, 0.03 if skipped else 0, 1, 1))
    fig.savefig(png, dpi=120)


if __name__ == "__main__":
    main()
