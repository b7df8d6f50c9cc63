#!/usr/bin/python3
"""Table and chart of run_dam_convergence.sh: the outflow water volume and the eroded soil volume
of Table 3.4 example 2 at a fixed simulated time, per resolution and drag scheme, against the
median wall time; errors against the finest lumped run (the drag's difference at the finest
resolution shows as the consistent run's error there). Prints Markdown.
    plot_dam_convergence.py dam_convergence.csv dam_convergence.png"""
import csv
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["status"] == "completed"]
groups = {}
for r in rows:
    groups.setdefault((float(r["spacing_m"]), r["drag"]), []).append(r)
med = lambda k, f: statistics.median(float(r[f]) for r in groups[k])
finest = min(h for h, _ in groups)
ref_key = (finest, "lumped") if (finest, "lumped") in groups else min(groups)
ref = {f: med(ref_key, f) for f in ("outflow_water_volume", "eroded_soil_volume")}


def err(k, f):
    return abs(med(k, f) - ref[f]) / abs(ref[f]) if ref[f] else float("nan")


end = rows[0]["end_time"]
print(f"Simulated time {float(end):g} s; reference: h = {ref_key[0]:g} m, {ref_key[1]} drag.")
print()
print("| h (m) | drag | repeats | particles start -> end | steps | wall time (s, median, min-max) | "
      "outflow water volume (m^2) | vs reference | eroded soil volume (m^2) | vs reference | KSP iterations (max) |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for k in sorted(groups, key=lambda k: (-k[0], k[1])):
    g = groups[k]
    w = [float(r["wall_s"]) for r in g]
    rel = lambda f: "reference" if k == ref_key else f"{100 * err(k, f):.1f}%"
    print(f"| {k[0]:g} | {k[1]} | {len(g)} | {int(med(k, 'particles_first'))} -> {int(med(k, 'particles_last'))} | "
          f"{g[0]['steps']} | {statistics.median(w):.1f} ({min(w):.1f}-{max(w):.1f}) | "
          f"{med(k, 'outflow_water_volume'):.3f} | {rel('outflow_water_volume')} | {med(k, 'eroded_soil_volume'):.4f} | "
          f"{rel('eroded_soil_volume')} | {g[0]['drag_ksp_max_iterations'] or '-'} |")
print()
for h in sorted({h for h, _ in groups}, reverse=True):
    if (h, "lumped") in groups and (h, "consistent") in groups:
        pairs = {}
        for r in rows:
            if float(r["spacing_m"]) == h:
                pairs.setdefault(r["repeat"], {})[r["drag"]] = float(r["wall_s"])
        q = [p["consistent"] / p["lumped"] for p in pairs.values() if len(p) == 2]
        print(f"- h = {h:g} m: consistent / lumped wall time {statistics.median(q):.2f}x (median of {len(q)} pairs)")

fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
for ax, f, name in ((axes[0], "outflow_water_volume", "outflow water volume"),
                    (axes[1], "eroded_soil_volume", "eroded soil volume")):
    for drag, marker in (("lumped", "o-"), ("consistent", "s--")):
        ks = sorted((k for k in groups if k[1] == drag and k != ref_key), key=lambda k: -k[0])
        if not ks:
            continue
        x = [med(k, "wall_s") for k in ks]
        y = [max(err(k, f), 1e-4) for k in ks]
        ax.loglog(x, y, marker, label=f"{drag} drag")
        for k, xi, yi in zip(ks, x, y):
            ax.annotate(f"h={k[0]:g}", (xi, yi), fontsize=7, textcoords="offset points", xytext=(4, 4))
    ax.axvline(med(ref_key, "wall_s"), color="0.5", ls=":", label=f"reference h={ref_key[0]:g} m {ref_key[1]}")
    ax.set_xlabel("wall time (s, median)")
    ax.set_ylabel(f"|{name} / reference - 1| (floor 1e-4)")
    ax.set_title(name, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
fig.suptitle(f"mpm2grid, Table 3.4 example 2 at t = {float(end):g} s: accuracy against wall time", fontsize=9)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
