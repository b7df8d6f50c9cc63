#!/usr/bin/python3
"""Table and chart of run_dam_convergence.sh: the outflow water volume, the peak outflow discharge
and the eroded soil volume of Table 3.4 example 2 at a fixed simulated time, per resolution and
drag scheme, against the median wall time; in the table, errors against the finest lumped run
(the drag's difference at the finest resolution shows as the consistent run's error there) and
the bed-shear closure's share of the step where the runs have one. The chart: eroded volume and
peak outflow against wall time, each point labelled with h and the closure's share. Prints
Markdown.
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
ref = {f: med(ref_key, f) for f in ("outflow_water_volume", "eroded_soil_volume", "outflow_discharge_max")
       if all(r.get(f) for r in groups[ref_key])}


def err(k, f):
    return abs(med(k, f) - ref[f]) / abs(ref[f]) if ref[f] else float("nan")


end = rows[0]["end_time"]
print(f"Simulated time {float(end):g} s; reference: h = {ref_key[0]:g} m, {ref_key[1]} drag.")
print()
has = lambda f: all(r.get(f) for r in rows)
peak, closure = has("outflow_discharge_max"), has("ph_bed_shear_mean")


def share(k):
    """The bed-shear closure's share of the step (median over the repeats)."""
    return statistics.median(float(r["ph_bed_shear_mean"]) / float(r["step_mean_s"]) for r in groups[k])


print("| h (m) | drag | repeats | particles start -> end | steps | wall time (s, median, min-max) | "
      "outflow water volume (m^2) | vs reference | eroded soil volume (m^2) | vs reference | "
      + ("peak outflow (m^2/s) | vs reference | " if peak else "") + ("closure's share of the step | " if closure else "")
      + "KSP iterations (max) |")
print("| --- " * (11 + 2 * peak + closure) + "|")
for k in sorted(groups, key=lambda k: (-k[0], k[1])):
    g = groups[k]
    w = [float(r["wall_s"]) for r in g]
    rel = lambda f: "reference" if k == ref_key else f"{100 * err(k, f):.1f}%"
    print(f"| {k[0]:g} | {k[1]} | {len(g)} | {int(med(k, 'particles_first'))} -> {int(med(k, 'particles_last'))} | "
          f"{g[0]['steps']} | {statistics.median(w):.1f} ({min(w):.1f}-{max(w):.1f}) | "
          f"{med(k, 'outflow_water_volume'):.3f} | {rel('outflow_water_volume')} | {med(k, 'eroded_soil_volume'):.4f} | "
          f"{rel('eroded_soil_volume')} | "
          + (f"{med(k, 'outflow_discharge_max'):.3f} | {rel('outflow_discharge_max')} | " if peak else "")
          + (f"{100 * share(k):.1f}% | " if closure else "") + f"{g[0]['drag_ksp_max_iterations'] or '-'} |")
print()
for h in sorted({h for h, _ in groups}, reverse=True):
    if (h, "lumped") in groups and (h, "consistent") in groups:
        pairs = {}
        for r in rows:
            if float(r["spacing_m"]) == h:
                pairs.setdefault(r["repeat"], {})[r["drag"]] = float(r["wall_s"])
        q = [p["consistent"] / p["lumped"] for p in pairs.values() if len(p) == 2]
        print(f"- h = {h:g} m: consistent / lumped wall time {statistics.median(q):.2f}x (median of {len(q)} pairs)")

panels = [("eroded_soil_volume", "eroded soil volume (m^2)")]
panels.append(("outflow_discharge_max", "peak outflow discharge (m^2/s)") if peak
              else ("outflow_water_volume", "outflow water volume (m^2)"))
fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
for ax, (f, name) in zip(axes, panels):
    for drag, marker in (("lumped", "o-"), ("consistent", "s--")):
        ks = sorted((k for k in groups if k[1] == drag), key=lambda k: -k[0])
        if not ks:
            continue
        x = [med(k, "wall_s") for k in ks]
        y = [med(k, f) for k in ks]
        ax.semilogx(x, y, marker, label=f"{drag} drag")
        for k, xi, yi in zip(ks, x, y):
            label = f"h={k[0]:g}" + (f", closure {100 * share(k):.1f}%" if closure else "")
            ax.annotate(label, (xi, yi), fontsize=7, textcoords="offset points", xytext=(4, 4))
    ax.set_xlabel("wall time (s, median)")
    ax.set_ylabel(name)
    ax.set_ylim(0, 1.15 * max(med(k, f) for k in groups))
    ax.set_title(name.split(" (")[0] + " against wall time over h", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
fig.suptitle(f"mpm2grid, Table 3.4 example 2 at t = {float(end):g} s: results against wall time"
             + (" (labels: the bed-shear closure's share of the step)" if closure else ""), fontsize=9)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
