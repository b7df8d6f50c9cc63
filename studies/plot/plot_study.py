#!/usr/bin/python3
"""Charts of a study folder: plot_study.py DIR reads DIR/tabular.csv and DIR/analysis.json and
writes into DIR
  scatter_matrix.png          every input against every response (successful evaluations)
  surface_<response>.png      multidim designs with >= 2 variables: the response over the first
                              two variables, one surface per level of the third (the
                              dissertation's peak-outflow surfaces over Kd and Us per Scale)
  sobol_<response>.png        sobol_indices designs: first-order and total indices with their
                              bootstrap intervals
  morris_<response>.png       morris designs: mu* against sigma per input
"""
import csv
import json
import math
import sys
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.patches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def read_table(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return [r for r in rows if r["status"] == "ok"], list(rows[0].keys()) if rows else []


def number(text):
    return float(text) if text not in ("", None) else math.nan


def scatter_matrix(out, rows, inputs, responses):
    fig, axes = plt.subplots(len(responses), len(inputs), figsize=(3 * len(inputs), 2.6 * len(responses)),
                             squeeze=False)
    for i, r in enumerate(responses):
        for j, x in enumerate(inputs):
            ax = axes[i][j]
            ax.scatter([number(row[x]) for row in rows], [number(row[r]) for row in rows], s=6, alpha=0.6)
            if i == len(responses) - 1:
                ax.set_xlabel(x)
            if j == 0:
                ax.set_ylabel(r)
    fig.tight_layout()
    fig.savefig(out / "scatter_matrix.png", dpi=90)
    plt.close(fig)


def surfaces(out, rows, inputs, responses):
    x, y = inputs[0], inputs[1]
    by = inputs[2] if len(inputs) > 2 else None
    levels = sorted({number(row[by]) for row in rows}) if by else [None]
    for r in responses:
        fig = plt.figure(figsize=(8, 6))
        ax = fig.add_subplot(projection="3d")
        cmap = plt.get_cmap("viridis")
        for k, level in enumerate(levels):
            sub = [row for row in rows if by is None or number(row[by]) == level]
            xs = sorted({number(row[x]) for row in sub})
            ys = sorted({number(row[y]) for row in sub})
            grid = {(number(row[x]), number(row[y])): number(row[r]) for row in sub}
            if len(xs) < 2 or len(ys) < 2:
                continue
            Z = [[grid.get((a, b), math.nan) for a in xs] for b in ys]
            X = [xs for _ in ys]
            Y = [[b] * len(xs) for b in ys]
            color = cmap(k / max(1, len(levels) - 1))
            ax.plot_surface(np.array(X), np.array(Y), np.array(Z), color=color, alpha=0.55)
        ax.set_xlabel(x)
        ax.set_ylabel(y)
        ax.set_zlabel(r)
        if by:
            ax.set_title(f"{r} over {x} and {y}, one surface per {by}", fontsize=10)
            handles = [matplotlib.patches.Patch(color=cmap(k / max(1, len(levels) - 1)), label=f"{by} = {lv:g}")
                       for k, lv in enumerate(levels)]
            ax.legend(handles=handles, fontsize=7, loc="upper left")
        fig.tight_layout()
        fig.savefig(out / f"surface_{r}.png", dpi=90)
        plt.close(fig)


def sobol_bars(out, analysis):
    for r, s in analysis.get("sobol_indices", {}).items():
        if "first" not in s:
            continue
        names = s["variables"]
        idx = range(len(names))
        fig, ax = plt.subplots(figsize=(1.6 * len(names) + 3, 4))
        for shift, key, label in ((-0.18, "first", "first order"), (0.18, "total", "total")):
            vals = [v if v is not None else math.nan for v in s[key]]
            lo = [v - (l if l is not None else v) for v, l in zip(vals, s[key + "_low"])]
            hi = [(h if h is not None else v) - v for v, h in zip(vals, s[key + "_high"])]
            ax.bar([i + shift for i in idx], vals, width=0.34, yerr=[lo, hi], capsize=3, label=label)
        ax.set_xticks(list(idx))
        ax.set_xticklabels(names)
        ax.set_ylabel(f"Sobol index of {r}")
        ax.legend()
        ax.grid(alpha=0.3, axis="y")
        fig.tight_layout()
        fig.savefig(out / f"sobol_{r}.png", dpi=90)
        plt.close(fig)


def morris_plane(out, analysis):
    for r, m in analysis.get("morris", {}).items():
        fig, ax = plt.subplots(figsize=(5.5, 4.5))
        for name, ms, sg in zip(m["variables"], m["mu_star"], m["sigma"]):
            if ms is None or sg is None:
                continue
            ax.scatter([ms], [sg])
            ax.annotate(name, (ms, sg), textcoords="offset points", xytext=(4, 3))
        ax.set_xlabel("mu* (mean |elementary effect|)")
        ax.set_ylabel("sigma (spread of the effects)")
        ax.set_title(f"Morris screening of {r}", fontsize=10)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(out / f"morris_{r}.png", dpi=90)
        plt.close(fig)


def main(out):
    analysis = json.loads((out / "analysis.json").read_text())
    rows, header = read_table(out / "tabular.csv")
    names = [h for h in header if h not in ("eval_id", "status", "reason")]
    inputs = [n for n in names if n in analysis.get("variables", [])]
    responses = [n for n in names if n not in inputs]
    if rows and inputs and responses:
        scatter_matrix(out, rows, inputs, responses)
        if analysis["method"] == "multidim" and len(inputs) >= 2:
            surfaces(out, rows, inputs, responses)
    sobol_bars(out, analysis)
    morris_plane(out, analysis)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(Path(sys.argv[1]))
