"""Chart and table of run_coupling_interval.sh: the eroded area and the crest outflow volume of
the coupled lab-embankment run against its wall time (medians over repeats), over the coupling
interval at the finest mesh (errors against the smallest interval) and over the mesh at the
default interval (errors against the finest mesh at that interval). Prints the Markdown table.
    /usr/bin/python3 plot_coupling_interval.py coupling_interval.csv coupling_interval.png"""
import csv
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

FIELDS = ("cells", "run_wall_s", "flow_wall_s", "erosion_steps", "remeshes", "eroded_area_m2", "crest_volume_m3",
          "toe_volume_m3")
groups = {}
for r in csv.DictReader(open(sys.argv[1])):
    groups.setdefault((float(r["cell_size_m"]), float(r["interval_s"])), []).append(r)
med = {k: {f: statistics.median(float(r[f]) for r in v) for f in FIELDS} for k, v in groups.items()}
finest_h = min(h for h, _ in med)
ref_key = (finest_h, min(i for h, i in med if h == finest_h))
ref = med[ref_key]


def reference_of(k):
    """The finest run for the coupling-interval series; for the mesh series, the finest mesh at the
    same interval, so that each series shows one error only."""
    return ref_key if k[0] == finest_h else (finest_h, k[1])


def error(k, field):
    return abs(med[k][field] / med[reference_of(k)][field] - 1.0)


fig, axes = plt.subplots(1, 2, figsize=(11, 4.4))
for ax, field, name in ((axes[0], "eroded_area_m2", "eroded area"), (axes[1], "crest_volume_m3", "crest outflow volume")):
    for label, pts, marker in (
            (f"coupling interval, h = {finest_h:g} m", sorted((k, m) for k, m in med.items() if k[0] == finest_h and k != ref_key), "o-"),
            (f"mesh, interval 0.5 s, against h = {finest_h:g} m", sorted((k, m) for k, m in med.items() if k[0] != finest_h), "s-")):
        if not pts:
            continue
        x = [m["run_wall_s"] for _, m in pts]
        y = [max(error(k, field), 1e-5) for k, _ in pts]
        ax.loglog(x, y, marker, label=label)
        for (k, m), xi, yi in zip(pts, x, y):
            ax.annotate(f"h={k[0]:g}, {k[1]:g} s", (xi, yi), fontsize=7, textcoords="offset points", xytext=(4, 4))
    ax.axvline(ref["run_wall_s"], color="0.5", ls=":", label=f"reference: h={ref_key[0]:g} m, {ref_key[1]:g} s")
    ax.set_xlabel("wall time of the coupled run (s, median)")
    ax.set_ylabel(f"|{name} / reference - 1| (floor 1e-5)")
    ax.set_title(name)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
fig.suptitle("foam-erosion lab embankment, 4 s of flow x morphological factor 100: accuracy against wall time", fontsize=9)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)

print("| h (m) | coupling interval (s) | cells | erosion steps | re-meshes | wall time (s) | interFoam (s) | "
      "eroded area (m^2/m) | vs reference | crest volume vs reference | toe volume vs reference |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for k in sorted(med, key=lambda k: (-k[0], -k[1])):
    m = med[k]
    r = med[reference_of(k)]
    rel = lambda f: "reference" if k == reference_of(k) else f"{m[f] / r[f] - 1:+.1%}"
    print(f"| {k[0]:g} | {k[1]:g} | {int(m['cells'])} | {int(m['erosion_steps'])} | {int(m['remeshes'])} | "
          f"{m['run_wall_s']:.1f} | {m['flow_wall_s']:.1f} | {m['eroded_area_m2']:.3g} | {rel('eroded_area_m2')} | "
          f"{rel('crest_volume_m3')} | {rel('toe_volume_m3')} |")
