#!/usr/bin/python3
"""Charts of one mpm2grid output folder (docs/mpm2grid.md):

    plot_mpm2grid.py OUT_DIR

writes
  - OUT_DIR/snapshots/frame_NNNN.png, one per particles/step_*.h5 in step order: the particles
    (x, y; a side view in 3D) as squares of the particle spacing, water in one blue, soil coloured
    by its saturation (0 dry to 1 saturated), equal aspect over the scene's domain, the time in
    the title;
  - OUT_DIR/hydrograph.png from series.csv: the inflow and outflow discharges of water and the
    outflow of soil over time, the eroded soil volume on a second axis;
  - OUT_DIR/profiles.png from profiles.csv, if it holds rows: the crest profile (the soil
    surface per grid column) at every output time.
Run it with Debian's /usr/bin/python3 (numpy, h5py, matplotlib)."""
import csv
import re
import sys
from pathlib import Path

import h5py
import matplotlib
import numpy as np
import yaml

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import ListedColormap, Normalize  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from mpl_toolkits.axes_grid1 import make_axes_locatable  # noqa: E402

WATER_COLOUR = "#1f6fd1"
# YlOrBr from its sand yellow on (its first quarter is near white): dry sand to dark brown (saturated)
SOIL_COLOURS = ListedColormap(plt.get_cmap("YlOrBr")(np.linspace(0.25, 1.0, 256)), name="soil_saturation")
DPI = 100
# Factors to SI of the unit symbols an mpm2grid scene uses for lengths and densities.
UNIT_FACTORS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "km": 1e3, "ft": 0.3048, "in": 0.0254,
                "yd": 0.9144, "kg": 1.0, "g": 1e-3, "t": 1e3, "lb": 0.45359237}


class PlotError(Exception):
    pass


def si_value(text, where):
    """A scene value such as 0.5, "3.571875 mm" or "1000 kg/m^3" in SI units."""
    if isinstance(text, (int, float)):
        return float(text)
    m = re.fullmatch(r"\s*([-+]?[0-9.]+(?:[eE][-+]?[0-9]+)?)\s*(.*?)\s*", str(text))
    if not m:
        raise PlotError(f"effective_config.yaml: {where} = '{text}' is not a number with a unit")
    value, unit = float(m.group(1)), m.group(2)
    for sign, symbol, power in re.findall(r"([*/]?)\s*([A-Za-z]+)(?:\^(-?\d+))?", unit):
        if symbol not in UNIT_FACTORS:
            raise PlotError(f"effective_config.yaml: {where} = '{text}': unit '{symbol}' is not one of "
                            f"{', '.join(UNIT_FACTORS)}")
        value *= UNIT_FACTORS[symbol] ** (int(power or 1) * (-1 if sign == "/" else 1))
    return value


def read_scene(out):
    """From effective_config.yaml: the grid spacing h and the particle spacing (m), the domain's x
    and y ranges (m) and the water's density (kg/m^3)."""
    path = out / "effective_config.yaml"
    if not path.is_file():
        raise PlotError(f"{path} is missing: is {out} an mpm2grid output folder?")
    cfg = yaml.safe_load(path.read_text())
    try:
        grid, domain = cfg["grid"], cfg["domain"]
        h = si_value(grid["spacing"], "grid.spacing")
        spacing = h / float(grid.get("particles_per_cell", 1))
        lo = [si_value(v, "domain.lo") for v in domain["lo"]]
        hi = [si_value(v, "domain.hi") for v in domain["hi"]]
        density = si_value(cfg["water"]["density"], "water.density")
    except (KeyError, TypeError) as e:
        raise PlotError(f"{path} lacks the key {e}: is it an mpm2grid scene?") from e
    return h, spacing, (lo[0], hi[0]), (lo[1], hi[1]), density


def read_csv(path):
    """Columns by name (the unit stripped) and the units by name."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise PlotError(f"{path} is empty")
    names = [h.split(" [")[0] for h in rows[0]]
    units = {n: (h.split(" [")[1].rstrip("]") if " [" in h else "") for n, h in zip(names, rows[0])}
    cols = {n: np.array([float(r[i]) for r in rows[1:]]) for i, n in enumerate(names)}
    return cols, units


def species(f, name, scalar):
    """(positions N x 2, scalar N) of one species in a particle file; empty if it has none."""
    if name not in f or f[name]["position"].shape[0] == 0:
        return np.empty((0, 2)), np.empty(0)
    return f[name]["position"][:, :2], f[name][scalar][:]


def draw_snapshots(out, spacing, xr, yr):
    files = sorted((out / "particles").glob("step_*.h5"))
    if not files:
        raise PlotError(f"{out}/particles holds no step_*.h5 files")
    frames = out / "snapshots"
    frames.mkdir(exist_ok=True)
    for old in frames.glob("frame_*.png"):
        old.unlink()
    width = 10.0
    fig, ax = plt.subplots(figsize=(width, width * (yr[1] - yr[0]) / (xr[1] - xr[0]) + 1.0))
    ax.set_xlim(*xr)
    ax.set_ylim(*yr)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    water = ax.scatter([], [], marker="s", color=WATER_COLOUR, linewidths=0)
    soil = ax.scatter([], [], c=[], marker="s", cmap=SOIL_COLOURS, norm=Normalize(0, 1), linewidths=0)
    bar = make_axes_locatable(ax).append_axes("right", size="2%", pad=0.1)
    fig.colorbar(soil, cax=bar, label="soil saturation")
    ax.legend(handles=[Patch(color=WATER_COLOUR, label="water"),
                       Patch(color=SOIL_COLOURS(0.5), label="soil (half saturated)")],
              loc="upper right")
    fig.tight_layout()
    fig.canvas.draw()
    # Each particle stands for a square of the particle spacing: its side in points.
    side = spacing * ax.get_window_extent().width / (xr[1] - xr[0]) * 72.0 / DPI
    for artist in (water, soil):
        artist.set_sizes([max(side, 0.7) ** 2])
    for k, path in enumerate(files):
        with h5py.File(path, "r") as f:
            xw, _ = species(f, "water", "pressure")
            xs, sat = species(f, "soil", "saturation")
            time = float(f.attrs["time"])
        water.set_offsets(xw)
        soil.set_offsets(xs)
        soil.set_array(sat)
        ax.set_title(f"t = {time:.3f} s   ({len(xw)} water, {len(xs)} soil particles)")
        fig.savefig(frames / f"frame_{k:04d}.png", dpi=DPI)
    plt.close(fig)
    return len(files)


def layered_rate(t, cumulative, layers=20):
    """The rate of a cumulative record that grows in whole layers (the inlet emits its water a
    layer of particles at a time), as the centred mean over enough series intervals to hold about
    `layers` layers at the mean rate, so that a layer more or less in one interval shows as a
    ripple of 1/layers, not as a spike. Returns (rate, window in s)."""
    steps = np.diff(cumulative)
    if len(t) < 2 or not np.any(steps > 0):
        return np.zeros_like(t), 0.0
    layer = steps[steps > 0].min()
    mean_rate = (cumulative[-1] - cumulative[0]) / (t[-1] - t[0])
    half = int(np.ceil(layers * layer / (mean_rate * np.median(np.diff(t))) / 2))
    i = np.arange(len(t))
    a, b = np.maximum(i - half, 0), np.minimum(i + half, len(t) - 1)
    return (cumulative[b] - cumulative[a]) / (t[b] - t[a]), min(2 * half * np.median(np.diff(t)), t[-1] - t[0])


def draw_hydrograph(out, water_density):
    s, units = read_csv(out / "series.csv")
    needed = ["time", "inflow_water_mass", "outflow_water_discharge", "outflow_soil_discharge", "eroded_soil_volume"]
    missing = [n for n in needed if n not in s]
    if missing:
        raise PlotError(f"{out}/series.csv lacks the columns {', '.join(missing)} (written by an older mpm2grid?)")
    t = s["time"]
    q_in, window = layered_rate(t, s["inflow_water_mass"])
    q_in = q_in / water_density
    unit_q, unit_v = units["outflow_water_discharge"], units["eroded_soil_volume"]
    fig, ax = plt.subplots(figsize=(9, 5))
    ax.plot(t, q_in, color="tab:blue", label=f"water inflow (mean over {window:.2g} s)")
    ax.plot(t, s["outflow_water_discharge"], color="tab:cyan", lw=1, label="water outflow")
    ax.plot(t, s["outflow_soil_discharge"], color="tab:brown", lw=1, label="soil outflow (as placed)")
    ax.set_xlabel("time (s)")
    ax.set_ylabel(f"discharge ({unit_q})")
    ax.grid(alpha=0.3)
    ax2 = ax.twinx()
    ax2.plot(t, s["eroded_soil_volume"], color="tab:red", ls="--", label="eroded soil volume")
    ax2.set_ylabel(f"eroded soil volume ({unit_v})")
    lines = ax.get_lines() + ax2.get_lines()
    ax.legend(lines, [ln.get_label() for ln in lines], loc="upper left")
    ax.set_title(f"{out.name}: discharges at the inlet and the outlet; eroded soil")
    fig.tight_layout()
    fig.savefig(out / "hydrograph.png", dpi=DPI)
    plt.close(fig)


def draw_profiles(out, column_width):
    """Returns False when profiles.csv holds no rows (a scene without soil)."""
    path = out / "profiles.csv"
    if not path.is_file():
        return False
    p, _ = read_csv(path)
    if len(p["time"]) == 0:
        return False
    times = np.unique(p["time"])
    colours = plt.get_cmap("viridis")
    fig, ax = plt.subplots(figsize=(9, 4.5))
    for k, time in enumerate(times):
        x, top = p["x"][p["time"] == time], p["top_y"][p["time"] == time]
        # each column's top as a flat segment of the column's width; a gap between columns breaks the line
        xs, ys = [], []
        for i, (xc, yc) in enumerate(zip(x, top)):
            if i > 0 and xc - x[i - 1] > 1.5 * column_width:
                xs.append(np.nan)
                ys.append(np.nan)
            xs += [xc - column_width / 2, xc + column_width / 2]
            ys += [yc, yc]
        ax.plot(xs, ys, color=colours(k / max(1, len(times) - 1)), lw=1.5, label=f"t = {time:.3g} s")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("soil surface y (m)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, ncol=2 if len(times) > 8 else 1, loc="upper right")
    ax.set_title(f"{out.name}: crest profile at each output time")
    fig.tight_layout()
    fig.savefig(out / "profiles.png", dpi=DPI)
    plt.close(fig)
    return True


def main(out):
    if not out.is_dir():
        raise PlotError(f"{out} is not a folder")
    if not (out / "series.csv").is_file():
        raise PlotError(f"{out}/series.csv is missing: is {out} an mpm2grid output folder?")
    h, spacing, xr, yr, water_density = read_scene(out)
    frames = draw_snapshots(out, spacing, xr, yr)
    draw_hydrograph(out, water_density)
    profiles = draw_profiles(out, h)
    print(f"{out}: {frames} snapshots in snapshots/, hydrograph.png" + (", profiles.png" if profiles else ""))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: plot_mpm2grid.py OUT_DIR")
    try:
        main(Path(sys.argv[1]))
    except (PlotError, OSError) as e:
        sys.exit(f"error: plot_mpm2grid.py: {e}")
