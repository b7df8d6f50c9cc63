#!/usr/bin/python3
"""Chart of the carving speed benchmarks: time per seed of the hierarchical carve and the plain
voxel loop against resolution (both inputs), their ratio, and the batch throughput by image format
on 1, 2 and 3 MPI ranks with the two-view slicing rate.  Prints the medians it plots.
usage: plot_carving_speed.py SPEED_CSV BATCH_CSV PNG"""
import csv
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        lines = f.readlines()
    notes = [ln[2:].strip() for ln in lines if ln.startswith("#")]
    return notes, list(csv.DictReader([ln for ln in lines if not ln.startswith("#")]))


def carve_times(rows, name, method):
    """{resolution: median seconds} of the carves of `name` by `method` that ran."""
    return {int(r["resolution"]): float(r["median_s"]) for r in rows
            if r["benchmark"] == "carve" and r["input"] == name and r["method"] == method and int(r["repeats"]) > 0}


def carve_panels(rows, ax_time, ax_ratio):
    styles = {"real_grain": ("C0", "real K-State grain (10 mm cube)"),
              "wheat_ellipsoid": ("C1", "rendered wheat ellipsoid (8 mm cube)")}
    for name, (colour, label) in styles.items():
        for method, ls, marker in (("hierarchical", "-", "o"), ("plain", "--", "s")):
            t = carve_times(rows, name, method)
            ax_time.loglog(sorted(t), [t[k] for k in sorted(t)], ls, marker=marker, color=colour,
                           label=f"{label}, {method}")
        hull = [r for r in rows
                if r["benchmark"] == "measure_hull" and r["input"] == name and r["method"].endswith("s=0")]
        ax_time.plot([256 for _ in hull], [float(r["median_s"]) for r in hull], "*", color=colour, markersize=12,
                     label=f"{label}, measure_hull (search + 256 + mesh 128)")
        h, p = carve_times(rows, name, "hierarchical"), carve_times(rows, name, "plain")
        n = sorted(set(h) & set(p))
        ax_ratio.plot(n, [p[k] / h[k] for k in n], "-o", color=colour, label=label)
        for k in n:
            print(f"{name:16s} {k:4d}^3: hierarchical {h[k]:.4f} s, plain {p[k]:.4f} s, "
                  f"plain / hierarchical {p[k] / h[k]:.1f}")
    ax_time.axhline(0.1, color="k", lw=0.8, ls=":")
    ax_time.text(97, 0.107, "goal: 512^3 in 0.1 s", fontsize=7)
    for ax in (ax_time, ax_ratio):
        ax.set_xscale("log")
        ax.set_xticks([100, 128, 256, 512, 625])
        ax.set_xticklabels(["100", "128", "256", "512", "625"])
        ax.minorticks_off()
    ax_time.set_xlabel("voxels per side of the cube (36 views)")
    ax_time.set_ylabel("time per seed (s, one core)")
    ax_time.set_title("carve time per seed", fontsize=10)
    ax_time.grid(alpha=0.3, which="both")
    ax_time.set_ylim(3e-4, 20)  # room for the legend below the curves
    ax_time.legend(fontsize=6, loc="lower right")
    ax_ratio.set_xlabel("voxels per side of the cube")
    ax_ratio.set_yscale("log")
    ax_ratio.set_ylabel("plain loop time / hierarchical time")
    ax_ratio.set_title("speed-up over the plain voxel loop (same run)", fontsize=10)
    ax_ratio.grid(alpha=0.3, which="both")
    ax_ratio.legend(fontsize=7)


def batch_panel(rows, speed_rows, ax):
    """Seeds per second by image format (groups) and rank count (bars), with the per-seed phases
    of the one-rank runs printed."""
    formats = list(dict.fromkeys(r.get("format", "png") for r in rows))
    ranks = sorted({int(r["ranks"]) for r in rows})
    width = 0.8 / len(ranks)
    for k, n in enumerate(ranks):
        rates = []
        for f in formats:
            pts = [r for r in rows if int(r["ranks"]) == n and r.get("format", "png") == f]
            rate = statistics.median(float(r["seeds_per_s"]) for r in pts)
            rates.append(rate)
            phases = {c: statistics.median(float(r[c]) for r in pts)
                      for c in ("median_seed_s", "median_read_s", "median_segment_s", "median_measure_s",
                                "median_outputs_s") if c in pts[0]}
            print(f"batch {f} {n} ranks ({pts[0]['workers']} measuring): {rate:.2f} seeds/s (median of {len(pts)}); "
                  + ", ".join(f"{c[7:-2]} {v:.3f} s" for c, v in phases.items()))
        xs = [i + (k - (len(ranks) - 1) / 2) * width for i in range(len(formats))]
        workers = n - 1 if n > 1 else 1
        label = "1 rank on one core" if n == 1 else f"{n} ranks ({workers} measuring)"
        ax.bar(xs, rates, width, label=label, color=f"C{k + 2}")
        for x, v in zip(xs, rates):
            ax.text(x, v, f"{v:.1f}", ha="center", va="bottom", fontsize=7)
    ax.set_xticks(range(len(formats)), [f"36 x {f.upper()}" for f in formats])
    pair = [r for r in speed_rows if r["benchmark"] == "two_view" and r["method"].startswith("segment x2")]
    if pair:
        rate = 2 / float(pair[0]["median_s"])
        print(f"two-view slicing: {rate:.0f} images/s per core (segmentation included)")
        ax.text(0.02, 0.97, f"two-view slicing: {rate:.0f} images/s per core\n"
                "(segmentation included; dissertation: 15)", transform=ax.transAxes, fontsize=7, va="top")
    ax.axhline(5, color="grey", lw=0.8, ls="--")
    ax.text(-0.45, 5, "a turntable rig: 5 seeds/s", fontsize=7, ha="left", va="bottom", color="grey")
    ax.set_ylim(0, max(7.5, 1.3 * max(float(r["seeds_per_s"]) for r in rows)))
    ax.set_ylabel("seeds per second (whole batch, 2-core machine)")
    ax.set_title("seedcarve batch, 36-view seeds of 640 x 480 px", fontsize=10)
    ax.legend(fontsize=7, loc="upper right")
    ax.grid(alpha=0.3, axis="y")


def main(speed_csv, batch_csv, png):
    notes, rows = read(speed_csv)
    batch_notes, batch = read(batch_csv)
    fig, axes = plt.subplots(1, 3, figsize=(15, 5))
    carve_panels(rows, axes[0], axes[1])
    batch_panel(batch, rows, axes[2])
    fig.text(0.01, 0.01, "\n".join(n if len(n) < 230 else n[:227] + "..." for n in notes[:1] + batch_notes[:1]),
             fontsize=6, va="bottom")
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
