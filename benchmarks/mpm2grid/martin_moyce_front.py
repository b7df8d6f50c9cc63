#!/usr/bin/python3
"""The surge front of one water-column run against Martin & Moyce (1952), as in
tests/mpm2grid/check_martin_moyce.py: Z = z / a interpolated in series.csv at every published
T = t sqrt(2 g / a) <= T_MAX. Prints one CSV fragment: the largest and the mean |Z / Z_ref - 1|,
the largest with the front started later by the offset dT in [0, T_first) that makes it smallest
(the test's second check: the experiment's release time was not recorded) and that dT in ms,
and the simulated Z at the published points, ';'-separated (for the error against the finest run).
    martin_moyce_front.py REFERENCE_CSV T_MAX RUN_DIR        or  --header"""
import csv
import math
import sys
from pathlib import Path

A, G = 0.05715, 9.81
if sys.argv[1] == "--header":
    print("front_error_max,front_error_mean,front_error_shifted,front_shift_ms,front_Z")
    sys.exit()
rows_of = lambda p: list(csv.reader(l for l in Path(p).read_text().splitlines() if not l.startswith("#")))
t_max = float(sys.argv[2])
points = [(float(T), float(Z)) for T, Z in rows_of(sys.argv[1])[1:] if float(T) <= t_max]
rows = rows_of(Path(sys.argv[3]) / "series.csv")
head = [h.split(" [")[0] for h in rows[0]]
times = [float(r[head.index("time")]) for r in rows[1:]]
fronts = [float(r[head.index("water_front")]) for r in rows[1:]]


def front_at(t):
    i = next(k for k in range(1, len(times)) if times[k] >= t)
    return fronts[i - 1] + (fronts[i] - fronts[i - 1]) * (t - times[i - 1]) / (times[i] - times[i - 1])


scale = math.sqrt(2 * G / A)
Z = [front_at(T / scale) / A for T, _ in points]
err = [abs(z / zr - 1) for z, (_, zr) in zip(Z, points)]
shifted, dT = min((max(abs(front_at((T - k * 0.005) / scale) / A / zr - 1) for T, zr in points), k * 0.005)
                  for k in range(int(points[0][0] / 0.005)))
print(f"{max(err):.6g},{sum(err) / len(err):.6g},{shifted:.6g},{1e3 * dT / scale:.4g},{';'.join(f'{z:.6g}' for z in Z)}")
