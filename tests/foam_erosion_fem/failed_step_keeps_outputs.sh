#!/usr/bin/env bash
# A failure in the second of two coupling steps (interFoam replaced by a stand-in,
# failing_solver/interFoam, whose second call crashes (MODE crash) or leaves a result the
# coupling cannot read (MODE unreadable: the issue's missing wallShearStress, which ended the run
# with "internal error", exit 1)) must end the run with exit 3, keep the first step's outputs
# (erosion.csv row, profiles.csv, state.json, a summary.json with status failed and the eroded
# area of that step) and say which step failed and why.
#   failed_step_keeps_outputs.sh FOAM_EROSION WORK_DIR PYTHON MODE
set -euo pipefail
exe=$1 work=$2 python=$3 mode=$4
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work"
rc=0
CALL_COUNT=$work/calls FAIL_AT=2 FAIL_MODE=$mode PATH="$here/failing_solver:$PATH" "$exe" "time.end=1 s" reservoir.initial_level=0.368 \
  coupling.morphological_factor=1000 "mesh.cell_size=0.02 m" "mesh.far_cell_size=0.06 m" \
  --out "$work/out" --log-level warn 2> "$work/stderr" || rc=$?
cat "$work/stderr"
[ "$rc" = 3 ] || { echo "exit status $rc, expected 3 (a failed OpenFOAM step)"; exit 1; }
grep -q "coupling step 2 of 2" "$work/stderr" || { echo "the error does not name coupling step 2 of 2"; exit 1; }
if [ "$mode" = crash ]; then
  grep -q "FOAM FATAL ERROR" "$work/stderr" || { echo "the error does not quote the solver's log"; exit 1; }
  why="interFoam failed"
else
  grep -q "cannot read its result.*wallShearStress" "$work/stderr" || { echo "the error does not name the missing file"; exit 1; }
  why="cannot read its result"
fi
"$python" - "$work/out" "$why" <<'PY'
import csv, json, sys
out, why = sys.argv[1], sys.argv[2]
s = json.load(open(f"{out}/summary.json"))
assert s["status"] == "failed", s["status"]
assert s["failure"].startswith("coupling step 2 of 2") and why in s["failure"], s["failure"]
assert s["erosion_steps"] == 1, s["erosion_steps"]
rows = list(csv.DictReader(open(f"{out}/erosion.csv")))
assert len(rows) == 1, f"erosion.csv: {len(rows)} rows, expected the first step's"
total = float(rows[0]["total_eroded_area_m2_per_m"])
assert total > 0 and abs(total - s["eroded_area"]) <= 1e-9 * total, (total, s["eroded_area"])
state = json.load(open(f"{out}/state.json"))
assert state["step"] == 1, state["step"]
run = json.load(open(f"{out}/run.json"))
assert run["status"] == "failed", run["status"]
print(f"exit 3 after step 1 of 2: eroded {total:.4g} m^2/m kept in erosion.csv and summary.json")
PY
