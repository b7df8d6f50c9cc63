#!/usr/bin/env bash
# The shipped mpm2grid study (studies/examples/mpm2grid_cohesion_reservoir.yaml): 3 x 3 runs of
# the mpm2grid executable on Table 3.4's example 2 dam through the command model, and what must
# hold of its table:
#   - every run succeeds and reports every response;
#   - a weaker soil erodes more: at each reservoir level the eroded soil volume at the lowest
#     cohesion (c0 = 1234 Pa, Table 3.4's c_C 0.002) is larger than at the highest (6169 Pa, c_C
#     0.010); the measured difference is 17-19 particles' areas, the quantum of the measure being one;
#   - a fuller reservoir releases more water: at each cohesion the outflow water volume from the
#     3.25 m level is larger than from the 2.25 m level (the extra metre over the upstream floor
#     is about 7 m^2 more water to start with; measured +4.4 to +5.9 m^2 in 15 s).
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
at = {(round(float(r["c0"])), float(r["level"])): r for r in rows}
for level in (2.25, 2.75, 3.25):
    weak, strong = float(at[(1234, level)]["eroded_soil_volume"]), float(at[(6169, level)]["eroded_soil_volume"])
    assert weak > strong, f"level {level}: eroded {weak} m^2 at c0 1234 Pa, not more than {strong} at 6169 Pa"
    print(f"level {level} m: eroded {weak:.4g} m^2 (c0 1234 Pa) > {strong:.4g} m^2 (c0 6169 Pa)")
for c0 in (1234, 3702, 6169):
    full, low = float(at[(c0, 3.25)]["outflow_water_volume"]), float(at[(c0, 2.25)]["outflow_water_volume"])
    assert full > low, f"c0 {c0} Pa: outflow {full} m^2 from the 3.25 m level, not more than {low} from 2.25 m"
    print(f"c0 {c0} Pa: outflow {full:.4g} m^2 (level 3.25 m) > {low:.4g} m^2 (level 2.25 m)")
PY
