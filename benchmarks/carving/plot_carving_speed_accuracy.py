#!/usr/bin/python3
"""Chart of carving_speed_accuracy's CSVs: volume error against carve time over resolution (36
views) and over the number of views (256^3), the error against N beside the analytic visual-hull
bias of a sphere under parallel projection, and the creased grain's error by crease size.
Errors are |volume / true - 1|; hollow markers are volumes below the truth.
usage: plot_carving_speed_accuracy.py CSV CREASE_CSV PNG"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "sphere_parallel_r500px": "sphere, parallel, 500 px/radius",
    "sphere_parallel_r200px": "sphere, parallel, 200 px/radius",
    "sphere_pinhole_r500px": "sphere, pinhole (25 radii), 500 px/radius",
    "sphere_pinhole_r200px": "sphere, pinhole (25 radii), 200 px/radius",
    "wheat_ellipsoid": "wheat ellipsoid, pinhole, 60 px/mm",
    "creased_grain": "creased grain, no view along the crease",
}


def read(path):
    with open(path) as f:
        lines = f.readlines()
    notes = [ln[2:].strip() for ln in lines if ln.startswith("#")]
    return notes, list(csv.DictReader([ln for ln in lines if not ln.startswith("#")]))


def error_vs_time(ax, rows, sweep, key, title):
    for i, shape in enumerate(LABELS):
        pts = sorted((r for r in rows if r["sweep"] == sweep and r["shape"] == shape), key=lambda r: int(r[key]))
        if not pts:
            continue
        t = [float(r["median_s"]) for r in pts]
        e = [float(r["error_pct"]) for r in pts]
        colour = f"C{i}"
        ax.loglog(t, [max(abs(x), 1e-4) for x in e], "-", color=colour, label=LABELS[shape], lw=1)
        for ti, ei, r in zip(t, e, pts):
            ax.plot(ti, max(abs(ei), 1e-4), "o", color=colour, mfc=colour if ei >= 0 else "none", ms=4)
            if r is pts[0] or r is pts[-1] or shape == "wheat_ellipsoid":
                ax.annotate(r[key], (ti, max(abs(ei), 1e-4)), textcoords="offset points", xytext=(3, 2), fontsize=6,
                            color=colour)
    ax.set_xlabel("carve time per seed (s, one core)")
    ax.set_ylabel("|volume error| (%)")
    ax.set_title(title, fontsize=9)
    ax.grid(alpha=0.3, which="both")


def error_vs_views(ax, rows):
    n = list(range(4, 73, 2))
    ax.loglog(n, [100 * (k * math.tan(math.pi / k) / math.pi - 1) for k in n], "k-", lw=2, alpha=0.35,
              label="analytic hull bias, parallel: N tan(pi/N)/pi - 1")
    for i, shape in enumerate(LABELS):
        pts = sorted((r for r in rows if r["sweep"] == "views" and r["shape"] == shape), key=lambda r: int(r["views"]))
        e = [float(r["error_pct"]) for r in pts]
        ax.plot([int(r["views"]) for r in pts], [max(abs(x), 1e-3) for x in e], "-", color=f"C{i}", lw=1,
                label=LABELS[shape])
        for r, x in zip(pts, e):
            ax.plot(int(r["views"]), max(abs(x), 1e-3), "o", color=f"C{i}", mfc=f"C{i}" if x >= 0 else "none", ms=4)
    ax.set_xticks([4, 6, 8, 12, 18, 24, 36, 72])
    ax.set_xticklabels(["4", "6", "8", "12", "18", "24", "36", "72"])
    ax.set_xlabel("views N over a full turn (256^3)")
    ax.set_ylabel("|volume error| (%)")
    ax.set_title("error against the number of views, with the analytic visual-hull bias", fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=6)


def crease_panel(ax, rows):
    names = [f"r {float(r['crease_radius_mm']):.2f}\nd {float(r['crease_depth_mm']):.2f}" for r in rows
             if float(r["turn_deg"]) == 0]
    for k, (turn, label) in enumerate(((0.0, "a view along the crease (turn 0)"), (5.0, "none (turn 5 deg)"))):
        pts = [r for r in rows if float(r["turn_deg"]) == turn]
        x = [i + (k - 0.5) * 0.38 for i in range(len(pts))]
        ax.bar(x, [float(r["error_pct"]) for r in pts], width=0.38, label=label, color=f"C{k + 3}")
        for xi, r in zip(x, pts):
            ax.text(xi, max(float(r["error_pct"]), 0), f"{float(r['groove_missed_pct']):.0f}%", ha="center",
                    va="bottom", fontsize=6)
    ax.set_xticks(range(len(names)))
    ax.set_xticklabels(names, fontsize=7)
    ax.axhline(0, color="k", lw=0.6)
    ax.set_xlabel("crease radius r and depth d (mm) of the 7.2 x 3.6 x 2.9 mm grain")
    ax.set_ylabel("hull volume error (%), 36 views, 256^3")
    ax.set_title("creased grain: the hull cannot see into the crease\n(labels: share of the groove left in)",
                 fontsize=9)
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=7)


def main(csv_path, crease_csv, png):
    notes, rows = read(csv_path)
    _, crease = read(crease_csv)
    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    error_vs_time(axes[0][0], rows, "resolution", "resolution",
                  "error against time over resolution 32^3 .. 512^3 (36 views)")
    axes[0][0].legend(fontsize=6)
    error_vs_time(axes[0][1], rows, "views", "views", "error against time over N = 4 .. 72 views (256^3)")
    error_vs_views(axes[1][0], rows)
    crease_panel(axes[1][1], crease)
    fig.text(0.01, 0.005, "\n".join(notes[:2]), fontsize=6, va="bottom")
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(png, dpi=100)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
