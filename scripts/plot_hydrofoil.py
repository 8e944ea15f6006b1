#!/usr/bin/python3
"""Plots and summary of a hydrofoil run (the paper's figures 5 and 6, and the tip AOA).

usage: plot_hydrofoil.py RESULTS [--span-axis 2 --lift-axis 1 --chord-axis 0]

RESULTS holds
  history.csv              viscoelastic run, one row per accepted level (solid-app's history)
  visco/interface/level_*.csv   wetted-node positions and displacements per level
  baseline/history.csv     elastic baseline with the instantaneous modulus (optional)
  baseline/interface/level_0000.csv
Writes RESULTS/tip_sections.png (Fig. 5: closed outlines of the tip section at --shape-times,
the elastic baseline and the undeformed section, equal axis scales), forces.png, tip_aoa.png
and summary.csv.
Conventions (cases/hydrofoil/README.md): x flow, y across the tunnel, lift = -F_y, z span.
"""
import argparse
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
import numpy as np  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        lines = [ln for ln in f if not ln.startswith("#")]
    rows = list(csv.DictReader(lines))
    return rows


def column(rows, name):
    return [float(r[name]) for r in rows]


def interface_levels(folder):
    """{level: (time, rows)} of interface/level_*.csv."""
    out = {}
    for path in sorted(glob.glob(os.path.join(folder, "interface", "level_*.csv"))):
        with open(path) as f:
            header = f.readline()  # "# level N time T s"
        parts = header.split()
        level, time = int(parts[2]), float(parts[4])
        out[level] = (time, read_csv(path))
    return out


def tip_face(rows, span_axis, tolerance=1e-6):
    """Wetted nodes in the tip plane (span coordinate within tolerance x span of the largest)."""
    keys = "xyz"
    s = [float(r[keys[span_axis]]) for r in rows]
    smin, smax = min(s), max(s)
    return [r for r, v in zip(rows, s) if v >= smax - tolerance * (smax - smin)]


def _circumradius(p):
    """Circumradius of the triangles p (m, 3, 2); inf for degenerate (collinear) ones."""
    a = np.linalg.norm(p[:, 1] - p[:, 2], axis=1)
    b = np.linalg.norm(p[:, 2] - p[:, 0], axis=1)
    c = np.linalg.norm(p[:, 0] - p[:, 1], axis=1)
    d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    area2 = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    with np.errstate(divide="ignore", invalid="ignore"):
        r = a * b * c / (2.0 * area2)
    return np.where(area2 > 1e-14 * (a * b + b * c + c * a), r, np.inf)


def section_outline(points, alpha=3.0):
    """Outline of a planar section given as all of its nodes, boundary and interior.

    points: (n, 2) reference positions (chord, lift) of the nodes of the section face.
    The Delaunay triangulation of the nodes covers their convex hull; triangles are peeled off
    from the hull inwards while their circumradius exceeds alpha x the median edge length (the
    triangles that bridge a concave stretch of the outline have the outline's radius of curvature;
    triangles of the face's own mesh have about the mesh size). The edges used by one remaining
    triangle form the outline.
    Returns (upper, lower): node indices of the two surfaces, each from the leading edge (smallest
    chord coordinate) to the trailing edge (largest), upper = larger lift coordinate; together they
    are the closed outline, ordered around the section."""
    pts = np.asarray(points, dtype=float)
    tri = mtri.Triangulation(pts[:, 0], pts[:, 1])
    triangles = tri.triangles
    edges = tri.edges
    limit = alpha * np.median(np.linalg.norm(pts[edges[:, 0]] - pts[edges[:, 1]], axis=1))
    radius = _circumradius(pts[triangles])
    # triangle adjacency through edges; -1 across the hull
    neighbours = tri.neighbors
    alive = np.ones(len(triangles), bool)
    exposed = [t for t in range(len(triangles)) if (neighbours[t] < 0).any()]
    while exposed:
        t = exposed.pop()
        if not alive[t] or radius[t] <= limit:
            continue
        alive[t] = False
        exposed.extend(n for n in neighbours[t] if n >= 0 and alive[n])
    count = {}
    for t in np.nonzero(alive)[0]:
        for k in range(3):
            e = tuple(sorted((triangles[t][k], triangles[t][(k + 1) % 3])))
            count[e] = count.get(e, 0) + 1
    adjacent = {}
    for (i, j), n in count.items():
        if n == 1:
            adjacent.setdefault(i, []).append(j)
            adjacent.setdefault(j, []).append(i)
    if not adjacent:
        raise ValueError("section_outline: no outline found (fewer than 3 nodes?)")
    start = min(adjacent, key=lambda i: (pts[i, 0], pts[i, 1]))
    loop, previous = [start], None
    while True:
        nxt = [j for j in adjacent[loop[-1]] if j != previous]
        if not nxt:
            raise ValueError("section_outline: the outline is not closed")
        previous = loop[-1]
        if nxt[0] == start:
            break
        if nxt[0] in loop:
            raise ValueError("section_outline: the outline crosses itself (lower alpha)")
        loop.append(nxt[0])
    x, y = pts[loop, 0], pts[loop, 1]
    if np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) < 0.0:  # make it counter-clockwise
        loop = [loop[0]] + loop[1:][::-1]
    te = max(range(len(loop)), key=lambda k: pts[loop[k], 0])
    lower = loop[: te + 1]  # counter-clockwise from the leading edge: lower surface first
    upper = [loop[0]] + loop[te:][::-1]
    return upper, lower


def zero_crossing(times, values):
    """First time where values changes sign (linear interpolation), or None."""
    for i in range(1, len(values)):
        if values[i - 1] == 0.0:
            return times[i - 1]
        if values[i - 1] * values[i] < 0.0:
            t0, t1, v0, v1 = times[i - 1], times[i], values[i - 1], values[i]
            return t0 + (t1 - t0) * v0 / (v0 - v1)
    return None


def interpolate(times, values, t):
    if not times or t < times[0] or t > times[-1]:
        return None
    for i in range(1, len(times)):
        if times[i] >= t:
            w = (t - times[i - 1]) / (times[i] - times[i - 1]) if times[i] > times[i - 1] else 0.0
            return values[i - 1] + w * (values[i] - values[i - 1])
    return values[-1]


def late_change(times, values, fraction=0.1):
    """Relative range of `values` over the last `fraction` of the time, the value at the window's
    start interpolated between the levels around it (a window with one level is not 'steady')."""
    if len(times) < 2:
        return float("nan")
    start = (1.0 - fraction) * times[-1]
    window = [interpolate(times, values, start)] + [v for t, v in zip(times, values) if t > start]
    window = [v for v in window if v is not None]
    return (max(window) - min(window)) / max(abs(values[-1]), 1e-12)


def save(fig, ax, xlabel, ylabel, path, legend_size=8):
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=legend_size)
    fig.tight_layout()
    fig.savefig(path, dpi=130)


def outline_curve(rows, order, c, l, deformed=True):
    """Chord and lift coordinates of the nodes `order` of rows, closed (first node repeated)."""
    idx = list(order) + [order[0]]
    xs = [float(rows[i][c]) + (float(rows[i]["u" + c]) if deformed else 0.0) for i in idx]
    ys = [float(rows[i][l]) + (float(rows[i]["u" + l]) if deformed else 0.0) for i in idx]
    return xs, ys


def tip_outline(rows, span_axis, c, l):
    """The tip-face rows and their outline order (upper LE->TE, then lower TE->LE)."""
    tip = tip_face(rows, span_axis)
    upper, lower = section_outline([(float(r[c]), float(r[l])) for r in tip])
    return tip, upper + lower[::-1][1:-1]


def draw_tip_sections(ax, res, a, c, l):
    """The paper's Fig. 5: tip-section outlines at the chosen times, the elastic baseline and the
    undeformed section, on equal axis scales. The outline is found once in the reference
    configuration (section_outline) and drawn at each time with the nodes' displacements."""
    levels = interface_levels(os.path.join(res, "visco"))
    if levels:
        _, rows0 = levels[min(levels)]
        tip0, order = tip_outline(rows0, a.span_axis, c, l)
        xs, ys = outline_curve(tip0, order, c, l, deformed=False)
        ax.plot(xs, ys, "-", color="0.6", lw=0.8, label="undeformed")
        wanted = [float(x) for x in a.shape_times.split(",")]
        chosen = []
        for w in wanted:
            lv = min(levels, key=lambda k: abs(levels[k][0] - w))
            if lv not in chosen:
                chosen.append(lv)
        for lv in chosen:
            time, rows = levels[lv]
            tip, order = tip_outline(rows, a.span_axis, c, l)
            xs, ys = outline_curve(tip, order, c, l)
            ax.plot(xs, ys, "-", lw=1.2, label=f"t = {time:g} s")
        blevels = interface_levels(os.path.join(res, "baseline"))
        if blevels:
            _, rows = blevels[max(blevels)]
            tip, order = tip_outline(rows, a.span_axis, c, l)
            xs, ys = outline_curve(tip, order, c, l)
            ax.plot(xs, ys, "k--", lw=1.0, label="baseline (elastic)")
    ax.set_xlabel(f"{c} [m]")
    ax.set_ylabel(f"{l} [m]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title("Tip section (paper Fig. 5)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("results")
    ap.add_argument("--span-axis", type=int, default=2)
    ap.add_argument("--lift-axis", type=int, default=1)
    ap.add_argument("--chord-axis", type=int, default=0)
    ap.add_argument("--shape-times", default="0,10,50,360,3600",
                    help="times [s] whose tip sections are drawn (nearest level)")
    a = ap.parse_args()
    res = a.results
    hist_path = os.path.join(res, "history.csv")
    if not os.path.exists(hist_path):
        sys.exit(f"error: {hist_path} not found (run the case first)")
    visco = read_csv(hist_path)
    t = column(visco, "time")
    fx, fy, fz = column(visco, "Fx"), column(visco, "Fy"), column(visco, "Fz")
    lift = [-v for v in fy]
    aoa_key = next((k for k in visco[0] if k.endswith("_deg")), None)
    aoa = column(visco, aoa_key) if aoa_key else None
    base = None
    bpath = os.path.join(res, "baseline", "history.csv")
    if os.path.exists(bpath):
        base = read_csv(bpath)[-1]

    keys = "xyz"
    c, l = keys[a.chord_axis], keys[a.lift_axis]

    # Figure 5: tip-section outlines (closed curves, equal axis scales).
    fig, ax = plt.subplots(figsize=(7.5, 3.6))
    draw_tip_sections(ax, res, a, c, l)
    fig.tight_layout()
    fig.savefig(os.path.join(res, "tip_sections.png"), dpi=130)

    # Figure 6: net forces, baseline vs viscoelastic.
    fig, ax = plt.subplots(figsize=(6.8, 4.2))
    for vals, name, col in ((fx, "Fx", "C0"), (fy, "Fy", "C1"), (fz, "Fz", "C2")):
        ax.plot(t, vals, "o-", ms=3, color=col, label=f"{name} viscoelastic")
        if base:
            ax.axhline(float(base[name]), color=col, ls="--", label=f"{name} baseline")
    ax.set_title("Net foil forces (paper Fig. 6; lift = -Fy)")
    save(fig, ax, "t [s]", "force on the foil [N]", os.path.join(res, "forces.png"), 7)

    if aoa:
        fig, ax = plt.subplots(figsize=(6.4, 4.0))
        ax.plot(t, aoa, "o-", ms=3, label="viscoelastic")
        if base and aoa_key in base:
            ax.axhline(float(base[aoa_key]), color="k", ls="--", label="baseline")
        ax.axhline(-8.1, color="C3", ls=":", label="paper: -8.1 deg at 360 s")
        ax.axvline(360.0, color="C3", ls=":")
        save(fig, ax, "t [s]", "tip AOA [deg]", os.path.join(res, "tip_aoa.png"))

    # Summary against the paper's landmarks.
    rows = [("quantity", "value", "paper")]
    zc = zero_crossing(t, lift)
    rows.append(("lift_zero_crossing_s", "" if zc is None else f"{zc:.4g}", "about 50"))
    if aoa:
        a360 = interpolate(t, aoa, 360.0)
        rows.append(("tip_aoa_360s_deg", "" if a360 is None else f"{a360:.4g}", "-8.1"))
        rows.append(("tip_aoa_final_deg", f"{aoa[-1]:.4g}", ""))
    rows.append(("lift_t0_N", f"{lift[0]:.4g}", ""))
    rows.append(("lift_final_N", f"{lift[-1]:.4g}", ""))
    rows.append(("drag_t0_N", f"{fx[0]:.4g}", ""))
    rows.append(("drag_final_N", f"{fx[-1]:.4g}", ""))
    if len(t) > 2:
        # approach to steady state: relative change of the lift over the last 10 % of the time
        rows.append(("lift_change_last_10pct_time", f"{late_change(t, lift):.3g}",
                     "nearly steady after ~1 h"))
    if base:
        rows.append(("baseline_lift_N", f"{-float(base['Fy']):.4g}", ""))
        rows.append(("baseline_drag_N", f"{float(base['Fx']):.4g}", ""))
        if aoa_key in base:
            rows.append(("baseline_tip_aoa_deg", f"{float(base[aoa_key]):.4g}", ""))
    rows.append(("levels", str(len(t)), ""))
    rows.append(("coupling_iterations", str(int(sum(column(visco, "coupling_iterations")))), ""))
    rows.append(("fluid_iterations", str(int(sum(column(visco, "fluid_iterations")))), ""))
    rows.append(("wall_s", f"{float(visco[-1]['wall_s']):.1f}", ""))
    with open(os.path.join(res, "summary.csv"), "w", newline="") as f:
        csv.writer(f).writerows(rows)
    for r in rows[1:]:
        print(f"  {r[0]:32s} {r[1]:>12s}   {('paper: ' + r[2]) if r[2] else ''}")


if __name__ == "__main__":
    main()
