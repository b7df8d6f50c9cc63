#!/usr/bin/python3
"""Checks a suite-demo output folder against Ritter's solution and the suite's output contract.

Usage: check_demo_outputs.py OUT_DIR RANKS

- The discharge at the dam equals (8/27) sqrt(g) h0^1.5 x width to round-off (closed form:
  1e-14 relative).
- The water balance (volume in the domain + time-integrated outflow = initial volume) holds
  within the sum of two error bounds, relative to the initial volume:
  (a) the midpoint rule on the sampled profile, largest at the first sample t1, where the
      rarefaction fan is narrowest (per unit width):
        c0 dx^2 / (36 g t1)               curvature h'' = 2 / (9 g t^2) over the fan (3 c0 t)
        + 2 (2 c0 / (3 g t1)) dx^2 / 8    the kinks at the fan's upstream edge and at the front
  (b) the trapezoidal rule for the outflow volume: (T - t_a) max|Q''| dt^2 / 12 over the time
      the front has been out (t_a = Ld / (2 c0)), with Q'' of Ritter's outflow at x = Ld taken
      numerically on a fine grid.
- Once the front passes the channel end, the outflow at time t equals width * h u of Ritter's
  solution there (1e-12 relative).
- run.json names the rank count and the phases; summary.json and the CSV header carry units;
  the effective configuration parses and holds the scene that ran; the XDMF series is valid.
"""
import csv
import json
import math
import sys
from pathlib import Path

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "core"))
import check_xdmf  # noqa: E402


def q(text) -> float:
    """'0.6 m' -> 0.6 (the demo scene states SI units)."""
    return float(str(text).split()[0])


def ritter(x, t, h0, g):
    c0 = math.sqrt(g * h0)
    xi = x / t
    if xi <= -c0:
        return h0, 0.0
    if xi >= 2 * c0:
        return 0.0, 0.0
    return (2 * c0 - xi) ** 2 / (9 * g), 2.0 / 3.0 * (c0 + xi)


def main(out: Path, ranks: int) -> int:
    summary = json.loads((out / "summary.json").read_text())
    run = json.loads((out / "run.json").read_text())
    scene = yaml.safe_load((out / "effective_config.yaml").read_text())
    h0, L = q(scene["reservoir"]["depth"]), q(scene["reservoir"]["length"])
    W, Ld = q(scene["reservoir"]["width"]), q(scene["channel"]["length"])
    g, cells = q(scene["gravity"]), int(scene["cells"])
    t1 = q(scene["time"]["sample"])
    c0 = math.sqrt(g * h0)
    dx = (L + Ld) / cells

    q_dam = 8.0 / 27.0 * math.sqrt(g) * h0**1.5 * W
    assert math.isclose(summary["discharge_at_dam"], q_dam, rel_tol=1e-14), (summary["discharge_at_dam"], q_dam)
    assert summary["units"]["discharge_at_dam"] == "m^3/s"

    midpoint = (c0 * dx**2 / (36 * g * t1) + 2 * (2 * c0 / (3 * g * t1)) * dx**2 / 8) / (h0 * L)
    t_end, t_a = q(scene["time"]["end"]), Ld / (2 * c0)
    trapezoid = 0.0
    if t_end > t_a:
        def outflow(t):
            h, u = ritter(Ld, t, h0, g)
            return W * h * u
        ts = [t_a + (t_end - t_a) * k / 4000 for k in range(4001)]
        e = (ts[1] - ts[0]) ** 2
        q2 = max(abs(outflow(ts[k - 1]) - 2 * outflow(ts[k]) + outflow(ts[k + 1])) / e for k in range(1, 4000))
        trapezoid = (t_end - t_a) * q2 * t1**2 / 12 / (h0 * L * W)
    bound = midpoint + trapezoid
    assert summary["max_balance_error"] <= bound, f"balance error {summary['max_balance_error']:.3e} > bound {bound:.3e}"

    with open(out / "discharge.csv") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    assert header[:3] == ["time [s]", "discharge_at_dam [m^3/s]", "outflow [m^3/s]"], header
    data = [[float(v) for v in r] for r in rows[1:]]
    times = [r[0] for r in data]
    assert times == sorted(times) and len(set(times)) == len(times), "CSV times must increase"
    for t, _, outflow, *rest in data:
        h, u = ritter(Ld, t, h0, g)
        assert math.isclose(outflow, W * h * u, rel_tol=1e-10, abs_tol=1e-15), (t, outflow, W * h * u)
    assert any(r[2] > 0 for r in data), "the default scene's front must reach the channel end"

    assert run["ranks"] == ranks, run["ranks"]
    assert run["status"] == "completed", run["status"]
    for phase in ("sample", "reduce", "output", "checkpoint"):
        assert phase in run["phases"], f"run.json lacks phase {phase}"
    assert run["version"] and run["git_hash"] and run["compiler"]

    n_outputs = len(list((out / "fields").glob("step_*.h5")))
    check_xdmf.main(out / "dam_break.xmf", n_outputs)
    print(f"{out}: Ritter discharge, water balance ({summary['max_balance_error']:.2e} <= {bound:.2e}), "
          f"outflow hydrograph, run.json, summary.json and {n_outputs} XDMF steps all check")
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), int(sys.argv[2])))
