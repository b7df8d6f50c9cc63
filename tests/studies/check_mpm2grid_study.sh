#!/usr/bin/env bash
# The shipped mpm2grid study (studies/examples/mpm2grid_cohesion_reservoir.yaml): 3 x 3 runs of
# the mpm2grid executable on Table 3.4's example 2 dam through the command model, and what must
# hold of its table:
#   - every run succeeds and reports every response;
#   - a weaker soil erodes more: at each reservoir level the eroded soil volume at the lowest
#     cohesion (c_C = 0.002) is larger than at the highest (0.010); the measured difference is
#     8-10 particles' areas, the quantum of the measure being one;
#   - a fuller reservoir releases more water: at each cohesion the outflow water volume from the
#     3.25 m level is larger than from the 2.25 m level (the extra metre over the upstream floor
#     is about 7 m^2 more water to start with; measured +4.5 m^2 in 15 s).
#   check_mpm2grid_study.sh STUDY STUDY_FILE WORKDIR PYTHON
set -euo pipefail
study=$1 spec=$2 work=$3 python=$4
rm -rf "$work"
"$study" run "$spec" --out "$work" --log-level warn output.plot=false
"$python" - "$work/tabular.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 9, f"{len(rows)} evaluations, not 9"
bad = [r for r in rows if r["status"] != "ok"]
assert not bad, f"failed evaluations: {bad}"
at = {(float(r["cC"]), float(r["level"])): r for r in rows}
for level in (2.25, 2.75, 3.25):
    weak, strong = float(at[(0.002, level)]["eroded_soil_volume"]), float(at[(0.010, level)]["eroded_soil_volume"])
    assert weak > strong, f"level {level}: eroded {weak} m^2 at c_C 0.002, not more than {strong} at 0.010"
    print(f"level {level} m: eroded {weak:.4g} m^2 (c_C 0.002) > {strong:.4g} m^2 (c_C 0.010)")
for cC in (0.002, 0.006, 0.010):
    full, low = float(at[(cC, 3.25)]["outflow_water_volume"]), float(at[(cC, 2.25)]["outflow_water_volume"])
    assert full > low, f"c_C {cC}: outflow {full} m^2 from the 3.25 m level, not more than {low} from 2.25 m"
    print(f"c_C {cC}: outflow {full:.4g} m^2 (level 3.25 m) > {low:.4g} m^2 (level 2.25 m)")
PY
