#!/usr/bin/python3
"""Checks a granular column collapse run of mpm2grid (scenes/granular_column_collapse.yaml) against
the runout of the quasi-2D (channel) experiments, from its particle files and series.csv:
  - the column came to rest: the kinetic energy at the end is below 1e-3 of its peak, and the front
    moved less than half a particle spacing over the last output interval;
  - the runout ratio (L_inf - L0)/L0 lies in the experiments' band around their fit for the run's
    aspect ratio a = H0/L0, for the deposit's front (below).
L0, H0: the initial column's length and height (its farthest particle's centre + s/2, s the
particle spacing). The runout measure, L_inf: the deposit's front leaving out its thinnest
tail, the position that 98% of the soil (particles of equal mass) lies behind (QUANTILE). Why a
share of the mass: the scene's deposit ends in a tail that thins to one or two particle layers
at every resolution and grows longer as h shrinks (a = 1, soil.flip 0.99, h = 10 / 5 / 2.5 mm:
farthest particle 1.49 / 1.87 / 2.04, the tail beyond the 98% point 2% of the mass); a front
at a thickness of a fraction of H0 falls inside that tail and does not converge either (3% of
H0: 1.49 / 1.87 / 1.61); the 98% point does (1.34 / 1.41 / 1.37; a = 6: 6.80 / 7.73 / 7.76),
benchmarks/results/mpm2grid/granular_collapse.md has all four aspect ratios. Printed and
reported beside it: the farthest particle + s/2, and the front where the deposit's thickness
(particle area per column of width H0/20) last reaches 3% of H0.

The fit. Lube, Huppert, Sparks & Freundt 2005 (Phys. Rev. E 72, 041301), columns collapsing in a
rectangular channel: (L_inf - L0)/L0 ~ 1.2 a for a < 2.3 and ~ 1.9 a^(2/3) for a > 2.3 (the same
two regimes, with these constants, are quoted for the quasi-2D collapses of Lajeunesse, Monnier &
Homsy 2005, Phys. Fluids 17, 103302, in K. Kumar's 2015 Cambridge thesis, ch. 2, "Granular column
collapse"). Balmforth & Kerswell 2005 (J. Fluid Mech. 538, 399-428, abstract) find in channels
(L_inf - L0)/L0 ~ a^(0.9 +- 0.1) (wide) and a^(0.65 +- 0.05) (narrow slots), with a "numerical
constant of proportionality [that] shows clear material dependence".
The band: the fit times [2/3, 4/3]. Its width stands for that material dependence and the
scatter between the experiment series (the axisymmetric prefactors of Lube 2005 and Lajeunesse
2004 for similar media, 1.24 and 1.35, already differ by 9%); it is a judgement from those
sources, not a published error bar.
Resolution: the regression tests run the scene at its 10 mm (20 cells per H0 at a = 1); the
`slow` tests run 5 and 2.5 mm and compare the two (check_collapse_convergence.py).
    check_granular_collapse.py RUN_DIR [--report JSON]
"""
import csv
import glob
import json
import math
import sys
from pathlib import Path

import h5py
import numpy as np

BAND = (2.0 / 3.0, 4.0 / 3.0)  # times the fit, see above
REST_ENERGY = 1e-3             # final over peak kinetic energy
QUANTILE = 0.98                # the runout: the point this share of the soil lies behind
THIN = 0.03                    # reported: the front where the thickness last reaches this share of H0


def fit(a):
    return 1.2 * a if a < 2.3 else 1.9 * a ** (2.0 / 3.0)


def soil(path):
    with h5py.File(path, "r") as f:
        return f["/soil/position"][:, :2]


def deposit_front(x, s, threshold, width):
    """The deposit's front (m): thickness per column of `width` (m) from x = 0 outwards (particle
    area s^2 per particle), the last crossing of `threshold` (m), linear between column centres."""
    counts = np.bincount(np.floor(x / width).astype(int).clip(min=0))
    thickness = counts * s * s / width
    above = np.flatnonzero(thickness >= threshold)
    if len(above) == 0:
        return 0.0
    k = int(above[-1])
    nxt = float(thickness[k + 1]) if k + 1 < len(thickness) else 0.0
    f = (float(thickness[k]) - threshold) / (float(thickness[k]) - nxt)
    return (k + 0.5 + f) * width


def main():
    run = Path(sys.argv[1])
    report = Path(sys.argv[sys.argv.index("--report") + 1]) if "--report" in sys.argv else None
    files = sorted(glob.glob(str(run / "particles" / "step_*.h5")))
    failures = []

    def check(ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if not ok:
            failures.append(what)

    if len(files) < 3:
        print(f"FAIL  {run}: fewer than 3 particle files")
        return 1
    x0, before, end = soil(files[0]), soil(files[-2]), soil(files[-1])
    # The seeding lattice's spacing: the smallest gap between distinct x in the first row.
    xs = np.unique(np.round(x0[:, 0], 12))
    s = float(np.min(np.diff(xs)))
    L0 = float(x0[:, 0].max()) + s / 2
    H0 = float(x0[:, 1].max()) + s / 2
    a = H0 / L0
    L_inf = float(end[:, 0].max()) + s / 2
    moved = float(end[:, 0].max() - before[:, 0].max())

    rows = list(csv.reader((run / "series.csv").read_text().splitlines()))
    k = [h.split(" [")[0] for h in rows[0]].index("kinetic_energy")
    energy = [float(r[k]) for r in rows[1:]]
    peak, last = max(energy), energy[-1]
    check(len(end) == len(x0), f"no soil lost: {len(end)} of {len(x0)} particles")
    check(peak > 0 and last < REST_ENERGY * peak,
          f"at rest: final kinetic energy {last:.3g} J/m < {REST_ENERGY} x peak {peak:.3g} J/m")
    check(abs(moved) < s / 2, f"the front moved {moved * 1e3:.2f} mm over the last output interval (< s/2 = "
                              f"{s / 2 * 1e3:.2f} mm)")

    front = float(np.quantile(end[:, 0], QUANTILE))
    thin = min(deposit_front(end[:, 0], s, THIN * H0, H0 / 20), L_inf)
    ratio, farthest, expected = (front - L0) / L0, (L_inf - L0) / L0, fit(a)
    lo, hi = BAND[0] * expected, BAND[1] * expected
    check(lo <= ratio <= hi,
          f"runout of the deposit ({QUANTILE:.0%} of the soil behind) (L_inf - L0)/L0 = ({front:.4f} - {L0:.4f})/{L0:.4f}"
          f" = {ratio:.3f} at a = H0/L0 = {a:.3f}: in the experiments' band [{lo:.3f}, {hi:.3f}] around the fit "
          f"{expected:.3f} (Lube et al. 2005)")
    height = float(end[:, 1].max()) + s / 2
    print(f"runout to the farthest particle {farthest:.3f}, to a thickness of {THIN:g} H0 {(thin - L0) / L0:.3f}; "
          f"final height {height:.4f} m (H_inf/H0 = {height / H0:.3f})")
    if report:
        report.write_text(json.dumps({"a": a, "L0": L0, "H0": H0, "s": s, "runout_deposit": ratio,
                                      "runout_farthest": farthest, "runout_thin": (thin - L0) / L0,
                                      "fit": expected, "band": [lo, hi],
                                      "H_inf_over_H0": height / H0, "at_rest": last < REST_ENERGY * peak,
                                      "front_moved_m": moved, "checks_failed": failures}, indent=1) + "\n")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
