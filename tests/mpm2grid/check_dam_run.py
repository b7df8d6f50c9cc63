#!/usr/bin/python3
"""Checks an overtopping dam run of mpm2grid (a Table 3.4 scene) from its series.csv,
profiles.csv and summary.json:
  - mass balance: water in the domain + water out = initial water + inflow, soil in the domain +
    soil out = initial soil, at every row (the CSV holds 12 significant digits: 1e-11 relative);
  - the inflow is rho q t within one particle layer (never more: a layer is emitted once it has
    fully entered), q the inlet's discharge per metre;
  - the outflow discharge column integrates to the outflow mass (the discharge is the mass booked
    over each interval), and summary.json's peak and time to peak are its largest entry;
  - the dam was overtopped: water left through the outlet, and the eroded soil volume is positive;
  - the crest profile exists at every output time and its highest point is the crest height;
  - given the scene file (a trapezoid dam), the dam stands as built until the water reaches it:
    the seeded crest lies within half a particle spacing of the drawing's height (the lattice's
    rows), and the crest height stays within 1% of the dam's height of the seeded one at every
    row before the water front first comes within a cell of the crest's upstream edge (into the
    profile's column whose surface is the crest). The measure moves in steps of a quarter cell,
    one particle's share of a cell's fill, so 1% at the demo resolution means no change at all.
    check_dam_run.py RUN_DIR Q_PER_METRE LAYER_MASS [SCENE]
"""
import csv
import json
import sys
from collections import defaultdict
from pathlib import Path

ROUND = 1e-11  # 12 significant digits in the CSV, a few values summed
WATER_DENSITY = 1000.0


def table(path):
    rows = list(csv.reader(Path(path).read_text().splitlines()))
    names = [h.split(" [")[0] for h in rows[0]]
    return {n: [float(r[i]) for r in rows[1:]] for i, n in enumerate(names)}


def main():
    run, q, layer = Path(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3])
    s = table(run / "series.csv")
    summary = json.loads((run / "summary.json").read_text())
    failures = []

    def check(ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if not ok:
            failures.append(what)

    w0, s0 = s["water_mass"][0], s["soil_mass"][0]
    worst_w = worst_s = 0.0
    for i in range(len(s["time"])):
        total = w0 + s["inflow_water_mass"][i]
        worst_w = max(worst_w, abs(s["water_mass"][i] + s["outflow_water_mass"][i] - total) / max(total, 1.0))
        worst_s = max(worst_s, abs(s["soil_mass"][i] + s["outflow_soil_mass"][i] - s0) / s0)
    check(worst_w < ROUND, f"water mass balance closes: worst relative error {worst_w:.2e} < {ROUND}")
    check(worst_s < ROUND, f"soil mass balance closes: worst relative error {worst_s:.2e} < {ROUND}")

    short = [WATER_DENSITY * q * t - m for t, m in zip(s["time"], s["inflow_water_mass"])]
    # A layer due exactly at a sample time may be one rounding of the clock short of it (the
    # clock sums the steps; the CSV rounds it): allow the layer itself, to round-off.
    check(min(short) > -ROUND * max(1.0, max(s["inflow_water_mass"])) and max(short) <= layer * (1 + 1e-9),
          f"inflow = rho q t within one layer ({layer} kg): shortfall from {min(short):.4g} to {max(short):.4g} kg")

    integral = 0.0
    for i in range(1, len(s["time"])):
        integral += s["outflow_water_discharge"][i] * (s["time"][i] - s["time"][i - 1]) * WATER_DENSITY
    out = s["outflow_water_mass"][-1]
    check(abs(integral - out) <= 1e-9 * max(out, 1.0),
          f"outflow discharge integrates to the outflow mass: {integral:.6g} vs {out:.6g} kg")
    peak = max(s["outflow_water_discharge"])
    at = s["time"][s["outflow_water_discharge"].index(peak)]
    check(abs(summary["peak_water_outflow"] - peak) <= 1e-9 * peak and abs(summary["time_to_peak"] - at) < 1e-9,
          f"summary peak {summary['peak_water_outflow']:.6g} m^2/s at {summary['time_to_peak']:.4g} s is the "
          f"series' largest ({peak:.6g} at {at:.4g} s)")

    check(summary["outflow_water_volume"] > 0 and peak > 0, f"the dam was overtopped: "
          f"{summary['outflow_water_volume']:.4g} m^2 of water left, peak {peak:.4g} m^2/s")
    check(summary["eroded_soil_volume"] > 0,
          f"the overtopped dam eroded: {summary['eroded_soil_volume']:.4g} m^2 of "
          f"{summary['initial_soil_volume']:.4g} m^2")

    profiles = defaultdict(list)
    for t, top in zip(*(lambda p: (p["time"], p["top_y"]))(table(run / "profiles.csv"))):
        profiles[t].append(top)
    last = max(profiles)
    check(abs(max(profiles[last]) - summary["final_crest_height"]) < 1e-9,
          f"{len(profiles)} crest profiles; the last one's top {max(profiles[last]):.4g} m is the final crest height")

    if len(sys.argv) > 4:
        import yaml  # Debian's python3-yaml, only for this check
        scene = yaml.safe_load(Path(sys.argv[4]).read_text())
        h = float(str(scene["grid"]["spacing"]).split()[0])
        spacing = h / float(scene["grid"]["particles_per_cell"])
        dam = scene["soil"]["regions"][0]["trapezoid"]
        height, edge = float(dam["height"]), float(dam["toe"]) + float(dam["height"]) / float(dam["upstream_slope"])
        seeded = s["crest_height"][0]
        check(abs(seeded - height) <= spacing / 2, f"the seeded crest {seeded:.4g} m lies within half a particle "
              f"spacing ({spacing / 2:.4g} m) of the drawing's {height:.4g} m")
        reach = next((i for i, x in enumerate(s["water_front"]) if x > edge - h), len(s["time"]))
        before = [abs(c - seeded) for c in s["crest_height"][:reach]]
        when = f"{s['time'][reach]:.4g} s" if reach < len(s["time"]) else "never"
        check(reach > 1 and max(before) <= 0.01 * height,
              f"the dam stands until the water comes within a cell of its crest (x = {edge - h:.4g} m, at {when}): "
              f"crest within {max(before):.4g} m of the seeded {seeded:.4g} m over {reach} rows (1% of the height: "
              f"{0.01 * height:.4g} m)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
