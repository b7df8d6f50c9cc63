#!/usr/bin/python3
"""Chart and summary of two_view_slices' CSV: the two-view model's volume error against the number
of slices N, plain and with neighbour averaging, per shape and pixel density. Lines are the mean
error over the sub-pixel positions, bands the smallest to largest.
usage: plot_two_view_slices.py CSV PNG MARKDOWN"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "wheat_ellipsoid": "wheat ellipsoid 7.2 x 3.6 x 2.9 mm",
    "ball_3.18mm": "ball 3.18 mm",
    "ball_6.35mm": "ball 6.35 mm",
    "kstate_wheat_hull": "real grain (its 36-view hull)",
    "milo_superellipsoid": "milo superellipsoid (not elliptic across)",
    "creased_grain": "creased grain (groove unseen)",
}
TABLE_N = [5, 10, 20, 30, 50, 100, 400]


def read(path):
    with open(path) as f:
        lines = f.readlines()
    notes = [ln[2:].strip() for ln in lines if ln.startswith("#")]
    return notes, list(csv.DictReader([ln for ln in lines if not ln.startswith("#")]))


def series(rows, shape, px, avg):
    pts = [r for r in rows if r["shape"] == shape and float(r["px_per_mm"]) == px and r["neighbour_average"] == avg]
    return sorted(pts, key=lambda r: int(r["slices"]))


def main(csv_path, png_path, md_path):
    notes, rows = read(csv_path)
    pxs = sorted({float(r["px_per_mm"]) for r in rows}, reverse=True)
    fig, axes = plt.subplots(1, len(pxs) + 1, figsize=(6 * (len(pxs) + 1), 5))
    for ax, px in zip(axes, pxs):
        for i, shape in enumerate(s for s in LABELS if s not in ("milo_superellipsoid", "creased_grain")):
            for avg, style in (("0", "-"), ("1", "--")):
                pts = series(rows, shape, px, avg)
                if not pts:
                    continue
                n = [int(r["slices"]) for r in pts]
                mean = [float(r["mean_error_pct"]) for r in pts]
                ax.plot(n, mean, style, color=f"C{i}", marker="o" if avg == "0" else "x", ms=4,
                        label=LABELS[shape] + (", averaged" if avg == "1" else ""))
                if avg == "0":
                    ax.fill_between(n, [float(r["min_error_pct"]) for r in pts],
                                    [float(r["max_error_pct"]) for r in pts], color=f"C{i}", alpha=0.12)
        n = sorted({int(r["slices"]) for r in rows})
        ax.plot(n, [50.0 / (k * k) for k in n], ":", color="k", label="midpoint rule, ellipsoid: +1/(2N^2)")
        ax.set_xscale("log")
        ax.set_ylim(-1.0, 1.5)
        ax.axhline(0, color="grey", lw=0.5)
        ax.set_xlabel("slices N")
        ax.set_ylabel("volume error, % (mean; band: min..max over positions, plain)")
        ax.set_title(f"exact silhouettes, {px:g} px/mm")
        ax.legend(fontsize=7)
    ax = axes[-1]
    px = pxs[0]
    for i, shape in enumerate(LABELS):
        for avg, style in (("0", "-"), ("1", "--")):
            pts = series(rows, shape, px, avg)
            if pts:
                ax.plot([int(r["slices"]) for r in pts], [float(r["sd_error_pct"]) for r in pts], style,
                        color=f"C{i}", label=LABELS[shape] + (", averaged" if avg == "1" else ""))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("slices N")
    ax.set_ylabel("spread over sub-pixel positions: standard deviation, %")
    ax.set_title(f"what averaging buys: spread at {px:g} px/mm")
    ax.legend(fontsize=7)
    fig.suptitle("two-view elliptic slices: volume error against the number of slices")
    fig.text(0.01, 0.005, notes[0] if notes else "", fontsize=6)
    fig.tight_layout(rect=(0, 0.02, 1, 0.96))
    fig.savefig(png_path, dpi=110)

    out = ["# Two-view slicing: what the slice count buys", "",
           "Made by `benchmarks/carving/run_two_view_slices.sh`; the run's provenance (the CSV's first line):", "",
           "    " + (notes[0] if notes else "(none)"), "",
           "Volume error (volume / true - 1, %) on exact silhouettes from parallel top and side cameras,",
           "mean over the sub-pixel positions [smallest, largest]; `avg` = `slicing.neighbour_average: true`.",
           "The real grain's reference is its own 36-view hull (the elliptic model's and the pixels' error,",
           "not the hull's). Chart: `two_view_slices.png`.", ""]
    for px in pxs:
        out += [f"## {px:g} px/mm", "", "| shape | " + " | ".join(f"N = {k}" for k in TABLE_N) + " |",
                "|---|" + "---|" * len(TABLE_N)]
        for shape in LABELS:
            for avg in ("0", "1"):
                pts = {int(r["slices"]): r for r in series(rows, shape, px, avg)}
                if not pts:
                    continue
                cells = []
                for k in TABLE_N:
                    r = pts.get(k)
                    cells.append("" if r is None else
                                 f"{float(r['mean_error_pct']):+.2f} [{float(r['min_error_pct']):+.2f}, "
                                 f"{float(r['max_error_pct']):+.2f}]")
                out.append(f"| {shape}{' avg' if avg == '1' else ''} | " + " | ".join(cells) + " |")
        out.append("")
    out += ["## Time of `measure_two_view` (masks given; median of repeats, microseconds)", "",
            "| px/mm | shape | N = 50 | N = 50 avg | N = 400 | N = 400 avg |", "|---|---|---|---|---|---|"]
    for px in pxs:
        for shape in ("wheat_ellipsoid", "kstate_wheat_hull"):
            t = {(int(r["slices"]), r["neighbour_average"]): float(r["slicing_us"])
                 for r in rows if r["shape"] == shape and float(r["px_per_mm"]) == px}
            if (50, "0") in t:
                out.append(f"| {px:g} | {shape} | {t[(50, '0')]:.1f} | {t[(50, '1')]:.1f} | {t[(400, '0')]:.1f} | "
                           f"{t[(400, '1')]:.1f} |")
    with open(md_path, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
