"""Charts of a foam-erosion output folder: the dam surface after each coupling step
(profiles.csv) and the discharge through the inlet, crest, toe and outlet sections over time
(discharge.csv), with the eroded volume per step (erosion.csv) when there is one, beside the
breach model's outflow and eroded volume on the same dam (breach_model/hydrograph.csv) when the
run made that comparison.

    /usr/bin/python3 solvers/foam_erosion_fem/plot/plot_foam_erosion.py OUT_DIR

writes OUT_DIR/profiles.png and OUT_DIR/discharge.png."""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main(out):
    profiles = os.path.join(out, "profiles.csv")
    if os.path.exists(profiles):
        rows = read(profiles)
        steps = sorted({int(r["step"]) for r in rows})
        cmap = plt.get_cmap("viridis")
        fig, ax = plt.subplots(figsize=(8, 3.6))
        for i, s in enumerate(steps):
            pts = [r for r in rows if int(r["step"]) == s]
            ax.plot([float(r["x_m"]) for r in pts], [float(r["y_m"]) for r in pts],
                    color=cmap(i / max(1, len(steps) - 1)), lw=1.2,
                    label=f"t = {float(pts[0]['time_s']):g} s" if s in (steps[0], steps[-1]) else None)
        ax.set_xlabel("x (m, downstream)")
        ax.set_ylabel("level (m)")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_title("dam surface after each coupling step")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "profiles.png"), dpi=130)
    discharge = os.path.join(out, "discharge.csv")
    if os.path.exists(discharge):
        rows = read(discharge)
        t = [float(r["time_s"]) for r in rows]
        fig, ax = plt.subplots(figsize=(8, 3.6))
        for name in ("inlet", "crest", "toe", "outlet"):
            ax.plot(t, [float(r[f"{name}_Q_m3_s"]) for r in rows], lw=1, label=name)
        breach = os.path.join(out, "breach_model", "hydrograph.csv")
        b = read(breach) if os.path.exists(breach) else None
        if b:
            ax.plot([float(r["time [s]"]) for r in b], [float(r["outflow [m^3/s]"]) for r in b], "k:", lw=1.5,
                    label="breach model: outflow")
        erosion = os.path.join(out, "erosion.csv")
        if os.path.exists(erosion) or b:
            ax2 = ax.twinx()
            if os.path.exists(erosion):
                e = read(erosion)
                ax2.step([0.0] + [float(r["time_s"]) for r in e], [0.0] + [float(r["total_eroded_volume_m3"]) for r in e],
                         "k--", where="post", lw=1, label="eroded volume")
            if b:
                ax2.plot([float(r["time [s]"]) for r in b], [float(r["eroded_volume [m^3]"]) for r in b], "-.",
                         color="0.4", lw=1, label="breach model: eroded volume")
            ax2.set_ylabel("eroded volume (m^3)")
            ax2.legend(loc="lower right", fontsize=8)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("water discharge Q (m^3/s)")
        ax.set_title("discharge through the sections")
        ax.legend(loc="upper left", fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "discharge.png"), dpi=130)


if __name__ == "__main__":
    main(sys.argv[1])
