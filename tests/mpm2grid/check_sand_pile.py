#!/usr/bin/python3
"""The sand pile of scenes/sand_pile.yaml at two flank angles around the friction angle phi
(docs/methods/mpm2grid.md: the angle of repose close to the friction angle).
  - A flank 3 deg below phi stands: the eroded volume (soil that left the pile's section grown by
    half a particle spacing, summary.json) is exactly 0.
  - A flank 3 deg above phi slides: more than 1% of the pile leaves its section, and the final
    flanks (least-squares lines through the crest profile, profiles.csv, where it lies between
    15% and 85% of the final height) lie between phi - 5 deg and phi + 1 deg. Below phi because
    a sliding mass overshoots the angle it could stand at (the 40-degree pile ends at 25 deg);
    1 deg above for the profile's quantisation (s/2 = 2.5 mm over a rise of about 0.1 m).
    check_sand_pile.py PHI_DEG STANDING_DIR SLIDING_DIR"""
import csv
import json
import math
import sys
from pathlib import Path

import numpy as np

phi = float(sys.argv[1])
standing, sliding = Path(sys.argv[2]), Path(sys.argv[3])
failed = False


def check(ok, text):
    global failed
    print(("ok    " if ok else "FAIL  ") + text)
    failed |= not ok


def value(d, key):
    v = json.loads((d / "summary.json").read_text())[key]
    return v["value"] if isinstance(v, dict) else v


e = value(standing, "eroded_soil_volume")
check(e == 0, f"the flank at phi - 3 deg stands: eroded volume {e} m^2 (final crest {value(standing, 'final_crest_height'):.4f} m)")
e, v0 = value(sliding, "eroded_soil_volume"), value(sliding, "initial_soil_volume")
check(e > 0.01 * v0, f"the flank at phi + 3 deg slides: eroded {e:.5f} of {v0:.5f} m^2")
rows = list(csv.reader((sliding / "profiles.csv").read_text().splitlines()))[1:]
profile = np.array([[float(x) for x in r] for r in rows])
profile = profile[profile[:, 0] == profile[:, 0].max()]
x, y = profile[:, 1], profile[:, 2]
top, crest = y.max(), x[np.argmax(y)]
on = (y > 0.15 * top) & (y < 0.85 * top)
for name, side in (("left", on & (x < crest)), ("right", on & (x > crest))):
    angle = math.degrees(math.atan(abs(np.polyfit(x[side], y[side], 1)[0])))
    check(phi - 5 <= angle <= phi + 1, f"the slid pile's {name} flank ends at {angle:.1f} deg, within [{phi - 5}, {phi + 1}]")
sys.exit(1 if failed else 0)
