#!/usr/bin/python3
"""`riceasv measure` against `riceasv render`'s truth: each truth grain matched to the measured grain
whose centroid is nearest (within 2 mm; a grain touching its neighbour or cut by the frame must be
flagged so, and is not compared); prints per grade the mean relative kernel-area error, the
worst one, the mean gel/kernel ratio and completeness error; fails when a grain not cut by the frame
is unmatched or not ok, when a cut grain is not flagged, when a kernel area of grades 2-5 is off by
more than KERNEL_TOLERANCE, or when the mean gel/kernel ratio does not rise from grade 2 to 6.
    check_against_truth.py RENDER_DIR MEASURE_DIR KERNEL_TOLERANCE
"""
import math
import sys
from collections import defaultdict
from pathlib import Path

from rice_tables import table


render, measure, tolerance = Path(sys.argv[1]), Path(sys.argv[2]), float(sys.argv[3])
pixel = float(Path(render / "truth.csv").read_text().split("pixel size ")[1].split(" mm")[0])
truth = table(render / "truth.csv")
measured = defaultdict(list)
for row in table(measure / "results.csv"):
    measured[Path(row["image"]).name].append(row)

failures, by_grade = [], defaultdict(lambda: defaultdict(list))
for t in truth:
    candidates = [m for m in measured[t["image"]] if m["status"] != "failed"]
    if not candidates:
        failures.append(f"{t['image']} grain {t['grain']}: no measured grain")
        continue
    m = min(candidates, key=lambda m: math.hypot(float(m["x_px"]) - float(t["x_px"]), float(m["y_px"]) - float(t["y_px"])))
    distance_mm = pixel * math.hypot(float(m["x_px"]) - float(t["x_px"]), float(m["y_px"]) - float(t["y_px"]))
    label = f"{t['image']} grain {t['grain']} (grade {t['grade']})"
    if t["cut_by_frame"] == "1":
        if "cut_by_frame" not in m["quality"] or m["status"] == "ok":
            failures.append(f"{label}: cut by the frame but measured {m['status']} '{m['quality']}'")
        continue
    if t["touching"] == "1":
        if "touching" not in m["quality"] or m["status"] == "ok":
            failures.append(f"{label}: touching a neighbour but measured {m['status']} '{m['quality']}'")
        continue
    if distance_mm > 2:
        failures.append(f"{label}: nearest measured grain {distance_mm:.2f} mm away")
        continue
    if m["status"] != "ok":
        failures.append(f"{label}: {m['status']} {m['quality']}")
    g = by_grade[int(t["grade"])]
    true_kernel = float(t["kernel_area_mm2"])
    if true_kernel > 0:
        error = float(m["kernel_area_mm2"]) / true_kernel - 1
        g["kernel"].append(error)
        if int(t["grade"]) <= 5 and abs(error) > tolerance:
            failures.append(f"{label}: kernel area {m['kernel_area_mm2']} mm^2, truth {true_kernel:.4f} ({error:+.2%})")
    if m["gel_kernel_ratio"]:
        g["ratio"].append(float(m["gel_kernel_ratio"]))
    g["completeness"].append(float(m["collar_completeness"]) - float(t["collar_completeness"]))
    g["gel"].append(float(m["gel_area_mm2"]) - float(t["gel_area_mm2"]))
    g["pieces"].append(int(m["kernel_pieces"]) == int(t["kernel_pieces"]))

mean = lambda v: sum(v) / len(v) if v else float("nan")
print("grade  grains  kernel area error mean/worst   gel error mean mm^2   ratio mean   completeness error mean/worst   pieces right")
for grade in sorted(by_grade):
    g = by_grade[grade]
    worst = max(g["kernel"], key=abs) if g["kernel"] else float("nan")
    worst_c = max(g["completeness"], key=abs)
    print(f"{grade:5d}  {len(g['completeness']):6d}  {mean(g['kernel']):+8.3%} / {worst:+8.3%}   {mean(g['gel']):+10.3f}   "
          f"{mean(g['ratio']):10.3f}   {mean(g['completeness']):+8.4f} / {worst_c:+8.4f}   {sum(g['pieces'])}/{len(g['pieces'])}")
ratios = [mean(by_grade[g]["ratio"]) for g in range(2, 7) if g in by_grade]
if any(b <= a for a, b in zip(ratios, ratios[1:])):
    failures.append(f"mean gel/kernel ratio does not rise from grade 2 to 6: {ratios}")
for f in failures:
    print("FAIL", f)
sys.exit(1 if failures else 0)
