#!/usr/bin/python3
"""The table of run_soil_stiffness.sh from its CSV: per scene and soil stiffness, medians over
the repeats of the wall time, the time steps per simulated second and what limited them, the
cost per particle-step, and the run's outflow, eroded volume and final crest (identical over
repeats: the runs are deterministic), and the ratios of the stiff soil's to the soft soil's.
    soil_stiffness.py CSV
"""
import csv
import statistics
import sys
from collections import defaultdict

rows = list(csv.DictReader(open(sys.argv[1])))
runs = defaultdict(list)
for r in rows:
    runs[(r["scene"], r["young"])].append(r)


def median(key, group):
    return statistics.median(float(r[key]) for r in group)


print("| scene | E | steps per simulated s | dt limited by (steps) | wall s (median, min-max) | ns per particle-step "
      "| outflow water m^2 | eroded m^2 | final crest m |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
ratios = []
for scene in dict.fromkeys(r["scene"] for r in rows):
    per_young = {}
    for young in dict.fromkeys(r["young"] for r in rows if r["scene"] == scene):
        g = runs[(scene, young)]
        walls = [float(r["wall_s"]) for r in g]
        steps_per_s = median("steps", g) / median("end_time", g)
        per_young[young] = (steps_per_s, statistics.median(walls))
        print(f"| {scene} | {young} | {steps_per_s:.0f} | {g[0]['dt_limiter']} | {statistics.median(walls):.1f} "
              f"({min(walls):.1f}-{max(walls):.1f}) | {median('ns_per_particle_step', g):.0f} "
              f"| {median('outflow_water_volume', g):.1f} | {median('eroded_soil_volume', g):.3f} "
              f"| {median('crest_final_m', g):.4g} |")
    if len(per_young) == 2:
        (soft, (s0, w0)), (stiff, (s1, w1)) = per_young.items()
        ratios.append(f"- {scene}: {stiff} against {soft}: {s1 / s0:.2f}x the steps per simulated second, "
                      f"{w1 / w0:.2f}x the wall time.")
print()
print("\n".join(ratios))
