#!/usr/bin/python3
"""Hydrographs of one breach run: plot_breach.py OUT_DIR reads OUT_DIR/hydrograph.csv and
OUT_DIR/summary.json and writes OUT_DIR/hydrographs.png (inflow and outflow hydrographs on top,
reservoir level and breach geometry below)."""
import csv
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_series(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    names = [h.split(" [")[0] for h in rows[0]]
    cols = {n: [] for n in names}
    for r in rows[1:]:
        for n, v in zip(names, r):
            cols[n].append(float(v))
    return cols


def main(out):
    s = read_series(out / "hydrograph.csv")
    summary = json.loads((out / "summary.json").read_text())
    hours = [t / 3600.0 for t in s["time"]]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    ax1.plot(hours, s["inflow"], label="inflow", color="tab:blue")
    ax1.plot(hours, s["outflow"], label="total outflow", color="tab:red")
    ax1.plot(hours, s["breach_outflow"], label="through the breach", color="tab:orange", ls="--")
    title = f"peak outflow {summary['peak_outflow']:.4g} m$^3$/s at {summary['time_to_peak'] / 3600:.2f} h"
    if summary.get("breach_initiation_time") is not None:
        ti = summary["breach_initiation_time"] / 3600
        ax1.axvline(ti, color="gray", lw=0.8, ls=":")
        title += f"; breach initiation {ti:.2f} h"
    else:
        title += "; no breach"
    ax1.set_title(title, fontsize=10)
    ax1.set_ylabel("discharge (m$^3$/s)")
    ax1.legend()
    ax1.grid(alpha=0.3)
    ax2.plot(hours, s["level"], label="reservoir level", color="tab:blue")
    ax2.plot(hours, s["invert"], label="breach invert", color="tab:brown")
    ax2.set_ylabel("level (m)")
    ax2.set_xlabel("time (h)")
    ax2.grid(alpha=0.3)
    ax3 = ax2.twinx()
    ax3.plot(hours, s["bottom_width"], label="breach bottom width", color="tab:green", ls="--")
    ax3.set_ylabel("width (m)")
    lines = ax2.get_lines() + ax3.get_lines()
    ax2.legend(lines, [ln.get_label() for ln in lines], loc="center right")
    fig.tight_layout()
    fig.savefig(out / "hydrographs.png", dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: plot_breach.py OUT_DIR")
    main(Path(sys.argv[1]))
