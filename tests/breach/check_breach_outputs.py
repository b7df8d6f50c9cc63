#!/usr/bin/python3
"""Checks a `breach` run on the default scene: check_breach_outputs.py OUT_DIR.

The CSV must carry units, follow the imposed storm exactly, and integrate (trapezoid rule on the
60 s rows) to the outflow volume in summary.json within 1e-3 (the rule's error for a hydrograph
that changes over ~1 h at 60 s spacing is ~(60 s / 1 h)^2 / 12 ~ 2e-5); the summary must close
the reservoir balance and name its units; the plot and run record must exist."""
import csv
import json
import sys
from pathlib import Path


def main(out):
    errors = []

    def check(cond, what):
        if not cond:
            errors.append(what)

    summary = json.loads((out / "summary.json").read_text())
    for key, unit in (("peak_outflow", "m^3/s"), ("time_to_peak", "s"), ("breach_initiation_time", "s"),
                      ("final_bottom_width", "m"), ("final_depth", "m"), ("eroded_volume", "m^3")):
        check(key in summary, f"summary.json lacks {key}")
        check(summary["units"].get(key) == unit, f"summary.json: unit of {key} is not {unit}")
    check(summary["failed"] is True, "the default scene should breach")
    check(abs(summary["mass_balance_error"]) < 1e-12 * summary["inflow_volume"], "mass balance does not close")

    with open(out / "hydrograph.csv", newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    for col in ("time [s]", "inflow [m^3/s]", "outflow [m^3/s]", "level [m]", "invert [m]", "bottom_width [m]"):
        check(col in header, f"hydrograph.csv lacks column '{col}'")
    data = [[float(v) for v in r] for r in rows[1:]]
    col = {h.split(" [")[0]: i for i, h in enumerate(header)}
    t = [r[col["time"]] for r in data]
    check(len(data) == 24 * 60 + 1, f"expected 1441 rows (24 h at 60 s), got {len(data)}")
    check(all(b > a for a, b in zip(t, t[1:])), "times do not increase")
    # The triangular storm: 800 m^3/s peak at 6 h, back to 0 at 20 h.
    for r in data[::97]:
        s, q = r[col["time"]], r[col["inflow"]]
        expected = 800 * s / 21600 if s <= 21600 else max(0.0, 800 * (72000 - s) / 50400)
        check(abs(q - expected) < 1e-9 * 800, f"inflow at {s} s is {q}, the storm gives {expected}")
    qo = [r[col["outflow"]] for r in data]
    volume = sum(0.5 * (qo[i] + qo[i + 1]) * (t[i + 1] - t[i]) for i in range(len(t) - 1))
    check(abs(volume / summary["outflow_volume"] - 1) < 1e-3,
          f"outflow integrates to {volume} m^3, summary says {summary['outflow_volume']} m^3")
    check(max(qo) <= summary["peak_outflow"] * (1 + 1e-9) and max(qo) > 0.99 * summary["peak_outflow"],
          f"sampled peak {max(qo)} vs summary peak {summary['peak_outflow']}")

    png = (out / "hydrographs.png").read_bytes()
    check(png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10000, "hydrographs.png missing or empty")
    run = json.loads((out / "run.json").read_text())
    check(run["program"] == "breach" and run["status"] == "completed", "run.json incomplete")
    effective = (out / "effective_config.yaml").read_text()
    check("side_slope" in effective and "tolerance" in effective, "effective_config.yaml lacks the defaults")

    for e in errors:
        print("FAIL:", e)
    print(f"{len(errors)} problems in {out}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1])))
