"""Chart of benchmarks/foam_erosion_fem/run_flow_speed.sh: crest outflow volume error against
interFoam wall time (medians over repeats), adaptive time steps over resolution and fixed steps
at the finest mesh; the error is against the finest adaptive run (a dotted line at its time).
    /usr/bin/python3 plot_flow_speed.py flow_speed.csv flow_speed.png"""
import csv
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
groups = {}
for r in rows:
    config = r["config"] + ("" if r.get("ranks", "1") == "1" else f"_np{r['ranks']}")
    groups.setdefault((config, float(r["cell_size_m"])), []).append(r)
med = {k: {f: statistics.median(float(r[f]) for r in v)
           for f in ("cells", "time_steps", "flow_wall_s", "wall_s_per_simulated_s", "crest_volume_m3")}
       for k, v in groups.items()}
finest = min(h for (c, h) in med if c == "adaptive")
ref = med[("adaptive", finest)]["crest_volume_m3"]
fig, ax = plt.subplots(figsize=(6.4, 4.4))
labels = {"adaptive": "adaptive (maxCo 0.5)", "fixed_1e-3": "fixed dt = 1e-3", "fixed_5e-4": "fixed dt = 5e-4",
          "adaptive_np2": "adaptive, 2 ranks"}
for config, marker in (("adaptive", "o-"), ("fixed_1e-3", "s"), ("fixed_5e-4", "^"), ("adaptive_np2", "D")):
    # The reference run itself has no error to show.
    pts = sorted((h, m) for (c, h), m in med.items() if c == config and not (c == "adaptive" and h == finest))
    if not pts:
        continue
    x = [m["flow_wall_s"] for h, m in pts]
    y = [max(abs(m["crest_volume_m3"] / ref - 1.0), 1e-6) for h, m in pts]
    ax.loglog(x, y, marker, label=labels[config])
    for (h, m), xi, yi in zip(pts, x, y):
        ax.annotate(f"h={h:g} m\n{int(m['cells'])} cells", (xi, yi), fontsize=7, textcoords="offset points",
                    xytext=(4, 4))
ax.set_xlabel("interFoam wall time for 2 s of flow (s, median)")
ax.set_ylabel("|crest outflow volume / finest adaptive - 1| (floor 1e-6)")
ax.axvline(med[("adaptive", finest)]["flow_wall_s"], color="0.5", ls=":", label=f"reference: adaptive h={finest:g} m")
ax.set_title("foam-erosion lab embankment: accuracy against wall time")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
