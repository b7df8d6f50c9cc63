#!/usr/bin/python3
"""Runs solvers/mpm2grid/plot/plot_mpm2grid.py on an mpm2grid dam run (Table 3.4 example 2 at
0.5 m for 10 s, the folder of the mpm2grid_dam_overtopping test) and checks its charts:
  - one snapshots/frame_NNNN.png per particles/step_*.h5, numbered from 0;
  - every frame shows the water (its blue) and the soil (the saturation colours) over large areas:
    at 0.5 m the reservoir and the dam each cover more than 10,000 pixels of a frame, so
    MIN_AREA_PIXELS cannot be met by the legend's or the colour bar's patches alone;
  - the water moves: the first and the last frame differ;
  - hydrograph.png holds the inflow line (its colour) and the eroded volume's line, and
    profiles.png the lines of the output times (their colours);
  - a folder that is not an mpm2grid output gives one "error:" line and a non-zero exit status.
    check_plots.py PLOT_SCRIPT RUN_DIR
"""
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib.image as mpimg
import numpy as np
from matplotlib import colormaps
from matplotlib.colors import to_rgb

MIN_AREA_PIXELS = 5000  # the dam and the water at 0.5 m each cover more than 10,000 pixels
MIN_LINE_PIXELS = 200  # a line across a chart's width at 100 dpi is 600 pixels or more
COLOUR_TOLERANCE = 0.06  # anti-aliasing blends edges; a line's core keeps its colour


def pixels_near(image, rgb, tol=COLOUR_TOLERANCE):
    return int(np.sum(np.all(np.abs(image[:, :, :3] - np.array(rgb)) < tol, axis=2)))


def main():
    script, run = sys.argv[1], Path(sys.argv[2])
    failures = []

    def check(ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if not ok:
            failures.append(what)

    done = subprocess.run([sys.executable, script, str(run)], capture_output=True, text=True)
    print(done.stdout + done.stderr, end="")
    check(done.returncode == 0, f"plot_mpm2grid.py exits 0 (got {done.returncode})")

    steps = sorted((run / "particles").glob("step_*.h5"))
    frames = sorted((run / "snapshots").glob("frame_*.png"))
    check(len(steps) > 1 and [f.name for f in frames] == [f"frame_{k:04d}.png" for k in range(len(steps))],
          f"{len(frames)} frames for {len(steps)} particle files, numbered from 0")
    # the water's colour and a soil pixel: red above blue by more than 0.25 (the saturation colours)
    water = to_rgb("#1f6fd1")
    images = [mpimg.imread(f) for f in frames]
    for f, image in zip(frames, images):
        rgb = image[:, : int(0.88 * image.shape[1]), :3]  # left of the colour bar
        n_water = pixels_near(rgb, water)
        n_soil = int(np.sum((rgb[:, :, 0] - rgb[:, :, 2] > 0.25) & (rgb[:, :, 0] > 0.35)))
        check(n_water > MIN_AREA_PIXELS and n_soil > MIN_AREA_PIXELS,
              f"{f.name}: {n_water} water and {n_soil} soil pixels (more than {MIN_AREA_PIXELS} each)")
    if len(images) > 1:
        check(images[0].shape == images[-1].shape and np.any(images[0] != images[-1]),
              "the first and the last frame have the same size and differ")

    hydrograph = mpimg.imread(run / "hydrograph.png")
    n_in, n_eroded = pixels_near(hydrograph, to_rgb("tab:blue")), pixels_near(hydrograph, to_rgb("tab:red"))
    check(n_in > MIN_LINE_PIXELS and n_eroded > MIN_LINE_PIXELS,
          f"hydrograph.png: {n_in} inflow-line and {n_eroded} eroded-volume pixels (more than {MIN_LINE_PIXELS})")
    profiles = mpimg.imread(run / "profiles.png")
    times = np.unique(np.loadtxt(run / "profiles.csv", delimiter=",", skiprows=1, usecols=0, ndmin=1))
    colours = [colormaps["viridis"](k / max(1, len(times) - 1))[:3] for k in range(len(times))]
    n_lines = sum(pixels_near(profiles, c) for c in colours)
    check(len(times) > 1 and n_lines > 2 * MIN_LINE_PIXELS,
          f"profiles.png: {n_lines} pixels in the colours of the {len(times)} output times' lines "
          f"(more than {2 * MIN_LINE_PIXELS}; later lines hide earlier ones where the crest did not move)")

    with tempfile.TemporaryDirectory() as empty:
        bad = subprocess.run([sys.executable, script, empty], capture_output=True, text=True)
        lines = bad.stderr.strip().splitlines()
        check(bad.returncode != 0 and len(lines) == 1 and lines[0].startswith("error: ") and "series.csv" in lines[0],
              f"an empty folder: exit {bad.returncode}, stderr {bad.stderr.strip()!r}")

    if failures:
        sys.exit(f"{len(failures)} check(s) failed")


if __name__ == "__main__":
    main()
