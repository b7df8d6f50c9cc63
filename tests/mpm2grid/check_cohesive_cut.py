#!/usr/bin/python3
"""Checks the vertical cut of scenes/cohesive_cut.yaml, dry (stands) or saturated (collapses),
from its particle files and summary.json. The cut: height H, face at x = W, the top corner's
particle the one seeded nearest (W, H).
  dry:       the cut stands: no particle has left the cut's section grown by s/2 (eroded volume
             exactly 0, summary.json) and the top corner moved less than s/2 at every output
             time (s the particle spacing; the elastic settling is about 0.13 mm, see the scene);
  saturated: the soil particles' saturation is 1 inside the cut (the median soil particle's S,
             after the first output interval, is at least 0.99: only the particles within a
             stencil of the free surfaces see fewer water nodes), and the cut collapses: the top
             corner drops by more than H/2, and the slope of the deposit, a least-squares line
             through the crest profile (per column of width h, the soil's thickness read from
             its cells' fill, io/dam_measures.hpp) where it lies between 0.15 H and 0.85 H, is at most the friction angle
             phi + 5 deg (in 2D the soil's cone is Mohr-Coulomb in the plane with the scene's phi).
The 5 deg: the profile's points carry up to s/2 = 2.5 mm of quantisation over a fitted rise of
0.7 H = 0.14 m (about 1 deg), and a cohesionless slope in this MPM stands up to a few degrees
steeper than phi (a 46 deg slope of soil then at 43.9 deg in the plane stood for 1 s).
    check_cohesive_cut.py RUN_DIR dry|saturated H W PHI_DEG
"""
import glob
import json
import math
import sys
from pathlib import Path

import h5py
import numpy as np


def load(path):
    with h5py.File(path, "r") as f:
        return f["/soil/position"][:, :2], f["/soil/saturation"][:], len(f["/water/position"])


def main():
    run, case = Path(sys.argv[1]), sys.argv[2]
    H, W, phi = float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
    files = sorted(glob.glob(str(run / "particles" / "step_*.h5")))
    summary = json.loads((run / "summary.json").read_text())
    failures = []

    def check(ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if not ok:
            failures.append(what)

    x0, _, water0 = load(files[0])
    xs = np.unique(np.round(x0[:, 0], 12))
    s = float(np.min(np.diff(xs)))
    corner = int(np.argmin((x0[:, 0] - W) ** 2 + (x0[:, 1] - H) ** 2))
    frames = [load(f) for f in files[1:]]
    check(all(len(x) == len(x0) for x, _, _ in frames), f"{len(x0)} soil particles kept in every frame")
    moves = [float(np.linalg.norm(x[corner] - x0[corner])) for x, _, _ in frames]
    drop = float(x0[corner, 1] - frames[-1][0][corner, 1])
    eroded, initial = summary["eroded_soil_volume"], summary["initial_soil_volume"]

    if case == "dry":
        check(water0 == 0, f"dry: no water particles ({water0})")
        check(eroded == 0.0, f"dry cut stands: eroded volume {eroded:.3g} of {initial:.4g} m^2 is exactly 0")
        check(max(moves) < s / 2, f"dry cut stands: the top corner moved at most {max(moves) * 1e3:.3f} mm "
                                  f"(< s/2 = {s / 2 * 1e3:.2f} mm, H = {H} m)")
        return 1 if failures else 0

    check(water0 == len(x0), f"saturated: one pore-water particle per soil particle ({water0} and {len(x0)})")
    median = float(np.median(frames[0][1]))
    check(median >= 0.99, f"saturated: median soil saturation {median:.4f} >= 0.99 at the first output "
                          f"(mean {float(np.mean(frames[0][1])):.3f})")
    check(drop > 0.5 * H, f"saturated cut collapses: the top corner dropped {drop:.4f} m = {drop / H:.2f} H (> H/2); "
                          f"eroded volume {eroded:.4g} of {initial:.4g} m^2")
    x, _, _ = frames[-1]
    h = 2 * s if len(sys.argv) < 7 else float(sys.argv[6])  # 2 particles per cell per axis
    top = {}
    for c, y in zip(np.floor(x[:, 0] / h).astype(int), x[:, 1]):
        top[c] = max(top.get(c, -1.0), y + s / 2)
    cols = sorted(top)
    px = np.array([(c + 0.5) * h for c in cols])
    py = np.array([top[c] for c in cols])
    on = (py > 0.15 * H) & (py < 0.85 * H)
    if on.sum() < 3:
        check(False, f"saturated: the deposit has a slope between 0.15 H and 0.85 H ({on.sum()} columns)")
        return 1
    slope = -np.polyfit(px[on], py[on], 1)[0]
    angle = math.degrees(math.atan(slope))
    check(angle <= phi + 5.0, f"saturated deposit's slope {angle:.1f} deg (least squares over {on.sum()} columns) "
                              f"<= phi + 5 = {phi + 5:.1f} deg")
    print(f"runout: the farthest soil particle at x = {float(x[:, 0].max()) + s / 2:.4f} m (face at {W} m)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
