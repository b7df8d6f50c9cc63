#!/usr/bin/python3
"""Bandwidth of an HDF5 output step and of a checkpoint against data size, one line per rank
count, from the CSV files of io_throughput. Usage: plot_io_throughput.py OUT.png CSV..."""
import csv
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(png, files):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    title = ""
    for path in files:
        with open(path) as f:
            first = f.readline().lstrip("# ").strip()
            rows = list(csv.DictReader(f))
        title = title or re.sub(r"^io_throughput: |, \d+ ranks|, medians.*$", "", first)
        ranks = rows[0]["ranks"]
        mb = [float(r["bytes_total"]) / 1e6 for r in rows]
        ax.plot(mb, [float(r["step_MBps"]) for r in rows], "o-", label=f"output step, {ranks} ranks")
        ax.plot(mb, [float(r["checkpoint_MBps"]) for r in rows], "s--", label=f"checkpoint (fsync), {ranks} ranks")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("data written per step [MB] (56 bytes per particle)")
    ax.set_ylabel("bandwidth [MB/s], median")
    ax.set_title(f"Collective HDF5 writes: {title}", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print(f"wrote {png}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
