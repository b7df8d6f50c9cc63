#!/usr/bin/env python3
"""One dam through three solvers (run_three_solvers.sh): the outflow hydrograph, the crest (breach
invert) and the eroded volume of mpm2grid and foam-erosion runs, and of the breach model run
beside each foam-erosion run, on one chart; prints a Markdown table and writes a CSV.

  plot_three_solvers.py --title TITLE --out CHART.png --csv TABLE.csv [--foam DIR]... [--mpm DIR]...

Per metre of crest (the 2D section; every run here has a 1 m crest):
  outflow   mpm2grid: water through the outlet (10.25 m below the downstream toe);
            foam-erosion: the outlet section (the same place); breach: the outflow at the dam
  crest     mpm2grid: the highest soil surface (detached soil left out); foam-erosion: the
            highest node of the eroded dam curve; breach: the breach invert
  eroded    what the excess-stress law kd (tau - tau_c) took from the bed. mpm2grid:
            law_eroded_volume (the columns' dt kd (tau - tau_c) sec h over the run, gross of
            deposits, as the other two erode), or in runs older than that column
            shear_eroded_volume; foam-erosion: the area between the initial and the eroded curve;
            breach: its eroded volume over the 1 m crest
  net       mpm2grid only: shear_eroded_volume (the detached particles whole and the top
            layer's eroded depth, net of deposits)
  outline   mpm2grid only: the soil no longer within the dam's seeded outline (grown by half a
            particle spacing), eroded_soil_volume: what the flow carried or pushed off the dam by
            any means (erosion, the drag on the surface soil, sliding)
"""
import argparse
import bisect
import csv
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def wall_time(run):
    with open(os.path.join(run, "run.json")) as f:
        return float(json.load(f)["wall_time_s"])


def mpm_run(run):
    s = rows(os.path.join(run, "series.csv"))
    with open(os.path.join(run, "effective_config.yaml")) as f:
        config = f.read().splitlines()
    h = next(line.split("spacing:")[1].split(",")[0].strip() for line in config if "spacing:" in line)
    drag = next(line.split(":")[1].strip() for line in config if line.startswith("drag:"))
    return {
        "solver": "mpm2grid",
        "resolution": f"h {float(h.split()[0]):g} m, {drag} drag",
        "wall_s": wall_time(run),
        "t": [float(r["time [s]"]) for r in s],
        "outflow": [float(r["outflow_water_discharge [m^2/s]"]) for r in s],
        "crest": [float(r["crest_height [m]"]) for r in s],
        "eroded": [float(r.get("law_eroded_volume [m^2]", r["shear_eroded_volume [m^2]"])) for r in s],
        "net": [float(r["shear_eroded_volume [m^2]"]) for r in s],
        "outline": [float(r["eroded_soil_volume [m^2]"]) for r in s],
        "shear": [float(r["bed_shear_max [Pa]"]) for r in s],
    }


def foam_runs(run):
    with open(os.path.join(run, "summary.json")) as f:
        summary = json.load(f)
    cells = int(summary["cells"])
    d = rows(os.path.join(run, "discharge.csv"))
    e = rows(os.path.join(run, "erosion.csv"))
    crest = {}
    for r in rows(os.path.join(run, "profiles.csv")):
        t = float(r["time_s"])
        crest[t] = max(crest.get(t, float("-inf")), float(r["y_m"]))
    with open(os.path.join(run, "scene_keys.txt")) as f:
        cell = next(line.split("=", 1)[1].strip() for line in f if line.startswith("mesh.cell_size"))
    foam = {
        "solver": "foam-erosion",
        "resolution": f"cell {float(cell.split()[0]):g} m ({cells} cells)",
        "wall_s": wall_time(run),
        "t": [float(r["time_s"]) for r in d],
        "outflow": [float(r["outlet_Q_m3_s"]) for r in d],
        "crest_t": sorted(crest),
        "crest": [crest[t] for t in sorted(crest)],
        "eroded_t": [0.0] + [float(r["time_s"]) for r in e],
        "eroded": [0.0] + [float(r["total_eroded_area_m2_per_m"]) for r in e],
        "shear": [float(r["max_shear_Pa"]) for r in e],
        "inflow": float(summary["peak_inlet_discharge"]),  # constant inflow, 1 m of crest: m^2/s
    }
    b = rows(os.path.join(run, "breach_model", "hydrograph.csv"))
    with open(os.path.join(run, "breach_model", "summary.json")) as f:
        stage = json.load(f)["final_stage"]
    breach = {
        "solver": "breach",
        "resolution": f"beside foam-erosion {foam['resolution'].split(' (')[0]}",
        "wall_s": float("nan"),
        "t": [float(r["time [s]"]) for r in b],
        "outflow": [float(r["outflow [m^3/s]"]) for r in b],
        "crest": [float(r["invert [m]"]) for r in b],
        "eroded": [float(r["eroded_volume [m^3]"]) for r in b],
        "shear": [float(r["stress [Pa]"]) for r in b],
        "stage": stage,
    }
    return foam, breach


def integral(t, q):
    return sum(0.5 * (q[i] + q[i - 1]) * (t[i] - t[i - 1]) for i in range(1, len(t)))


def peak_mean(t, q, window=1.0):
    """The largest mean of q over `window` seconds (the outlet's surges average out)."""
    volume = [0.0]
    for i in range(1, len(t)):
        volume.append(volume[-1] + 0.5 * (q[i] + q[i - 1]) * (t[i] - t[i - 1]))
    best = 0.0
    for i in range(len(t)):
        start = t[i] - window
        if start < t[0]:
            continue
        j = max(bisect.bisect_right(t, start) - 1, 0)  # t[j] <= start < t[j + 1]
        a = (start - t[j]) / (t[j + 1] - t[j]) if t[j + 1] > t[j] else 0.0
        best = max(best, (volume[i] - (volume[j] + a * (volume[j + 1] - volume[j]))) / window)
    return best


def first_time(t, q, level):
    return next((ti for ti, qi in zip(t, q) if qi > level), float("nan"))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--title", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--csv", required=True)
    ap.add_argument("--foam", action="append", default=[])
    ap.add_argument("--mpm", action="append", default=[])
    a = ap.parse_args()
    runs, breaches = [], []
    for run in a.foam:
        foam, breach = foam_runs(run)
        runs.append(foam)
        breaches.append(breach)
    runs += [mpm_run(r) for r in a.mpm]
    # The breach model gets the same inputs beside every foam-erosion run: one curve is enough
    # unless they differ.
    runs = breaches[:1] + runs

    fig, axes = plt.subplots(2, 2, figsize=(13, 8.5))
    ax = axes.ravel()
    styles = {"breach": ("k", ["-"]), "foam-erosion": ("tab:blue", ["--", "-"]), "mpm2grid": ("tab:red", [":", "--", "-", "-."])}
    count = {}
    for r in runs:
        colour, lines = styles[r["solver"]]
        k = count.get(r["solver"], 0)
        count[r["solver"]] = k + 1
        ls = lines[min(k, len(lines) - 1)]
        label = f"{r['solver']}, {r['resolution']}"
        ax[0].plot(r["t"], r["outflow"], color=colour, ls=ls, lw=1.2, label=label)
        ax[1].plot(r.get("crest_t", r["t"]), r["crest"], color=colour, ls=ls, lw=1.2, label=label)
        ax[2].plot(r.get("eroded_t", r["t"]), r["eroded"], color=colour, ls=ls, lw=1.2, label=label)
        if "outline" in r:
            ax[3].plot(r["t"], r["outline"], color=colour, ls=ls, lw=1.2, label=label + ": out of the outline")
            ax[3].plot(r["t"], r["eroded"], color="tab:orange", ls=ls, lw=1.0, label=label + ": by the bed shear")
    inflow = next((r["inflow"] for r in runs if "inflow" in r), float("nan"))
    if inflow == inflow:
        ax[0].axhline(inflow, color="0.6", lw=0.8, label=f"inflow {inflow:g} m$^2$/s")
    ax[0].set(xlabel="time (s)", ylabel="outflow (m$^2$/s per m of crest)", title="outflow hydrograph")
    ax[1].set(xlabel="time (s)", ylabel="crest / breach invert (m)", title="crest height (breach invert)")
    ax[2].set(xlabel="time (s)", ylabel="eroded volume (m$^3$ per m of crest)",
              title="eroded by the bed shear, kd (tau - tau_c)")
    ax[3].set(xlabel="time (s)", ylabel="soil volume (m$^3$ per m of crest)",
              title="mpm2grid: soil out of the dam's outline, and eroded")
    ax[3].legend(fontsize=7)
    for x in ax:
        x.grid(alpha=0.3)
    ax[0].legend(fontsize=7)
    fig.suptitle(f"{a.title}, one soil (kd, tau_c) through breach, mpm2grid and foam-erosion")
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)

    header = ["solver", "resolution", "wall_time_s", "eroded_m2", "eroded_at_10s_m2", "net_of_deposits_m2",
              "out_of_outline_m2", "final_crest_m", "peak_outflow_1s_mean_m2_s", "outflow_volume_m2", "outflow_starts_s",
              "largest_shear_Pa"]
    table = []
    for r in runs:
        te, er = r.get("eroded_t", r["t"]), r["eroded"]
        at10 = next((e for t, e in zip(te, er) if t >= 10 - 1e-9), float("nan"))
        table.append([r["solver"] + (f" ({r['stage']})" if "stage" in r else ""), r["resolution"], r["wall_s"],
                      er[-1], at10, r["net"][-1] if "net" in r else float("nan"),
                      r["outline"][-1] if "outline" in r else float("nan"), r["crest"][-1],
                      peak_mean(r["t"], r["outflow"]), integral(r["t"], r["outflow"]),
                      first_time(r["t"], r["outflow"], 0.01 * inflow), max(r["shear"])])
    with open(a.csv, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(table)
    print("| solver | resolution | wall time (s) | eroded by the shear (m^2/m) | at 10 s | net of deposits | "
          "out of the outline | final crest (m) | peak outflow, 1 s mean (m^2/s) | outflow volume (m^2/m) | "
          "outflow > 1% of inflow from (s) | largest bed shear (Pa) |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for row in table:
        print("| " + " | ".join([row[0], row[1], "-" if row[2] != row[2] else f"{row[2]:.0f}"] +
                                ["-" if v != v else f"{v:.3g}" for v in row[3:]]) + " |")


if __name__ == "__main__":
    main()
