#!/usr/bin/python3
"""Table and chart of run_particle_step.sh: median ns per particle-step per configuration, the goals
(100 ns in 2D, 300 ns in 3D, lumped drag) and the consistent drag's overhead, the median of each
repeat's consistent/lumped ratio (the pair ran back to back). Prints Markdown.
    plot_particle_step.py particle_step.csv particle_step.png"""
import csv
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

GOAL = {"2d": 100.0, "3d": 300.0}
rows = list(csv.DictReader(open(sys.argv[1])))
groups = {}
for r in rows:
    groups.setdefault((r["dimension"], r["drag"]), []).append(r)
med = lambda rs, f: statistics.median(float(r[f]) for r in rs)
print("| dimension | drag | h | particles | steps | repeats | ns per particle-step (median, min-max) | "
      "ms per step | goal (lumped) | peak RSS (MB) | bytes per particle |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for (dim, drag), rs in sorted(groups.items()):
    ns = [float(r["ns_per_particle_step"]) for r in rs]
    rss = med(rs, "rss_max_kb") if all(r["rss_max_kb"] for r in rs) else float("nan")
    n = med(rs, "particles_mean")
    goal = f"{GOAL[dim]:.0f} ns" if drag == "lumped" else ""
    print(f"| {dim.upper()} | {drag} | {rs[0]['spacing']} | {n:.0f} | {rs[0]['steps']} | {len(rs)} | "
          f"{statistics.median(ns):.0f} ({min(ns):.0f}-{max(ns):.0f}) | {1e3 * med(rs, 's_per_step'):.1f} | {goal} | "
          f"{rss / 1024:.0f} | {rss * 1024 / n:.0f} |")
print()
print("Consistent drag overhead (median over repeats of consistent / lumped of the same repeat):")
print()
ratios = {}
for dim in sorted({d for d, _ in groups}):
    pairs = {}
    for r in rows:
        if r["dimension"] == dim:
            pairs.setdefault(r["repeat"], {})[r["drag"]] = float(r["ns_per_particle_step"])
    q = [p["consistent"] / p["lumped"] for p in pairs.values() if "consistent" in p and "lumped" in p]
    if q:
        ratios[dim] = statistics.median(q)
        print(f"- {dim.upper()}: {ratios[dim]:.2f}x (range {min(q):.2f}-{max(q):.2f} over {len(q)} repeats)")
print()
print("RSS: /usr/bin/time's maximum resident set size of the process (seeding and output buffers included).")

fig, ax = plt.subplots(figsize=(6.4, 4))
labels, values, errs = [], [], []
for (dim, drag), rs in sorted(groups.items()):
    ns = [float(r["ns_per_particle_step"]) for r in rs]
    labels.append(f"{dim.upper()}\n{drag}")
    values.append(statistics.median(ns))
    errs.append([[statistics.median(ns) - min(ns)], [max(ns) - statistics.median(ns)]])
bars = ax.bar(range(len(values)), values, color=["tab:blue" if "lumped" in l else "tab:orange" for l in labels])
for i, e in enumerate(errs):
    ax.errorbar(i, values[i], yerr=e, color="k", capsize=3)
for i, l in enumerate(labels):
    dim = l[:2].lower()
    ax.hlines(GOAL[dim], i - 0.4, i + 0.4, color="r", ls="--", label="goal (lumped)" if i == 0 else None)
ax.set_xticks(range(len(values)), labels)
ax.set_ylabel("ns per particle-step per core (median, min-max)")
ax.set_title("mpm2grid full two-species step, 1 rank", fontsize=9)
ax.legend(fontsize=8)
ax.grid(True, axis="y", alpha=0.3)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
