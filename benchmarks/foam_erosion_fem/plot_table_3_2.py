"""Chart and table of run_table_3_2.sh: interFoam wall time for 4 s of flow against the fixed
deltaT, per flow (f1, f2) and rank count, with the adaptive runs (maxCo values) of the same flow and ranks
as dashed lines, beside the dissertation's Table 3.2 wall times (other mesh, other machine: compare
the slopes and the ratios, not the levels). Prints the Markdown table (medians over repeats):
steps, wall time, how many times the adaptive (largest maxCo) run's, and the crest and toe outflow volumes
against the 1-rank deltaT = 1e-4 run of the same flow.
    /usr/bin/python3 plot_table_3_2.py table_3_2.csv dissertation_table_3_2.csv table_3_2.png"""
import csv
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
paper = list(csv.DictReader(line for line in open(sys.argv[2]) if not line.startswith("#")))
FIELDS = ("cells", "time_steps", "flow_wall_s", "crest_volume_m3", "toe_volume_m3")

groups = {}
for r in rows:
    groups.setdefault((r["flow"], r["dt_s"], int(r["ranks"])), []).append(r)
med = {k: {f: statistics.median(float(r[f]) for r in v) for f in FIELDS} for k, v in groups.items()}
flows = sorted({k[0] for k in med})
ranks = sorted({k[2] for k in med})
adaptive_runs = sorted({k[1] for k in med if k[1].startswith("adaptive")}, key=lambda a: -float(a.split("-")[1]))
fixed_dts = sorted({float(k[1]) for k in med if not k[1].startswith("adaptive")}, reverse=True)


def seconds(hms):
    h, m, s = (int(x) for x in hms.split(":"))
    return 3600 * h + 60 * m + s


def dt_key(dt):
    return next(k[1] for k in med if not k[1].startswith("adaptive") and float(k[1]) == dt)


fig, axes = plt.subplots(2, len(flows), figsize=(6.0 * len(flows), 9.0), squeeze=False)
for ax, flow in zip(axes[0], flows):
    for i, n in enumerate(ranks):
        color = f"C{i}"
        pts = [(dt, med[(flow, dt_key(dt), n)]["flow_wall_s"]) for dt in fixed_dts if (flow, dt_key(dt), n) in med]
        if pts:
            ax.loglog(*zip(*pts), "o-", color=color, label=f"this suite, fixed deltaT, {n} rank{'s' * (n > 1)}")
        for adaptive, ls in zip(adaptive_runs, ("--", "-.", ":", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 3)))):
            if (flow, adaptive, n) in med:
                a = med[(flow, adaptive, n)]
                ax.axhline(a["flow_wall_s"], color=color, ls=ls,
                           label=f"this suite, adaptive maxCo {adaptive.split('-')[1]} ({int(a['time_steps'])} steps), "
                                 f"{n} rank{'s' * (n > 1)}")
    for j, cores in enumerate(("1", "2", "4", "8")):
        pts = sorted((float(p["deltaT"]), seconds(p[f"cores_{cores}"])) for p in paper if p["flow"] == flow)
        ax.loglog(*zip(*pts), "s:", mfc="none", color=f"C{j + 3}", label=f"dissertation (v1712), {cores} core{'s' * (cores != '1')}")
    cells = int(next(m["cells"] for k, m in med.items() if k[0] == flow))
    ax.set_title(f"flow {flow}: 4 s of flow, {cells} cells here")
    ax.set_xlabel("fixed deltaT (s)")
    ax.set_ylabel("wall time (s)")
    ax.set_ylim(top=ax.get_ylim()[1] * 50)  # room for the legend above the data
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6.5, loc="upper right", ncol=2)
# Accuracy against cost: the crest outflow volume's error against the 1-rank deltaT = 1e-4 run.
for ax, flow in zip(axes[1], flows):
    ref = med.get((flow, dt_key(min(fixed_dts)), 1)) if fixed_dts else None
    if not ref:
        continue
    for i, n in enumerate(ranks):
        for family, keys, marker in (("fixed deltaT", [dt_key(dt) for dt in fixed_dts], "o-"),
                                     ("adaptive", adaptive_runs, "^--")):
            pts = [(k, med[(flow, k, n)]) for k in keys if (flow, k, n) in med and med[(flow, k, n)] is not ref]
            if not pts:
                continue
            x = [m["flow_wall_s"] for _, m in pts]
            y = [max(abs(m["crest_volume_m3"] / ref["crest_volume_m3"] - 1), 1e-5) for _, m in pts]
            ax.loglog(x, y, marker, color=f"C{i}", label=f"{family}, {n} rank{'s' * (n > 1)}")
            for (k, _), xi, yi in zip(pts, x, y):
                ax.annotate(k.replace("adaptive-", "maxCo "), (xi, yi), fontsize=6.5, textcoords="offset points",
                            xytext=(3, 3))
    ax.set_title(f"flow {flow}: crest outflow volume against deltaT = 1e-4 (1 rank)")
    ax.set_xlabel("interFoam wall time (s)")
    ax.set_ylabel("|volume / reference - 1| (floor 1e-5)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
fig.suptitle("Table 3.2 runtime study: fixed deltaT against adaptive steps (other meshes and machines: compare ratios)",
             fontsize=9)
fig.tight_layout()
fig.savefig(sys.argv[3], dpi=120)

print("| flow | deltaT (s) | ranks | steps | interFoam wall time (s) | x adaptive | crest volume vs deltaT 1e-4 | "
      "toe volume vs deltaT 1e-4 | dissertation, same cores |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for flow in flows:
    ref = med.get((flow, dt_key(min(fixed_dts)), 1)) if fixed_dts else None
    for n in ranks:
        adaptive = med.get((flow, adaptive_runs[0], n)) if adaptive_runs else None
        for dt in adaptive_runs + fixed_dts:
            key = (flow, dt if isinstance(dt, str) else dt_key(dt), n)
            if key not in med:
                continue
            m = med[key]
            times = f"{m['flow_wall_s'] / adaptive['flow_wall_s']:.1f}" if adaptive else ""
            rel = lambda f: ("reference" if m is ref else f"{m[f] / ref[f] - 1:+.2%}") if ref else ""
            theirs = next((p[f"cores_{n}"] for p in paper
                           if not isinstance(dt, str) and p["flow"] == flow and float(p["deltaT"]) == dt and f"cores_{n}" in p), "")
            print(f"| {flow} | {dt.replace('-', ', maxCo ') if isinstance(dt, str) else f'{dt:g}'} | {n} | {int(m['time_steps'])} | "
                  f"{m['flow_wall_s']:.1f} | {times} | {rel('crest_volume_m3')} | {rel('toe_volume_m3')} | {theirs} |")
