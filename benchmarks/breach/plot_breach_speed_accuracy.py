#!/usr/bin/python3
"""Chart of breach_speed_accuracy's CSV: peak-outflow error against time per run, adaptive
tolerances and fixed steps on one log-log plot.  usage: plot_breach_speed_accuracy.py CSV PNG"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png):
    with open(csv_path) as f:
        lines = f.readlines()
    notes = [ln[2:].strip() for ln in lines if ln.startswith("#")]
    rows = list(csv.DictReader([ln for ln in lines if not ln.startswith("#")]))
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for method, marker, label in (("adaptive", "o", "adaptive (tolerance)"), ("fixed", "s", "fixed step (dt, s)")):
        pts = [r for r in rows if r["method"] == method]
        x = [float(r["seconds_per_run"]) * 1e3 for r in pts]
        y = [max(float(r["peak_relative_error"]), 1e-12) for r in pts]
        ax.loglog(x, y, marker=marker, label=label)
        for r, xi, yi in zip(pts, x, y):
            ax.annotate(f"{float(r['parameter']):g}", (xi, yi), textcoords="offset points", xytext=(4, 3), fontsize=7)
    ax.set_xlabel("time per run (ms, one core)")
    ax.set_ylabel("relative error of the peak outflow")
    ax.set_title("breach model, default scene, 20-hour event", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    fig.text(0.01, 0.01, "\n".join(notes[:2]), fontsize=6, va="bottom")
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
