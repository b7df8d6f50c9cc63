#!/usr/bin/env bash
# A checkpoint restarts only the scene it was written for, and a later time.end extends a run.
# 1. Table 3.4 example 2 (coarse) runs to 1 s; it ends with a checkpoint of its final state.
# 2. Restarts that change the physics are refused with exit 2, one line naming the key and both
#    values: soil E, nu, friction angle, cohesion, the dam's geometry, a wall's kind, the wall
#    friction, the grid, and a different scene file (example 5, another cohesion).
# 3. A restart with the same time.end is refused (nothing left to run).
# 4. A restart may change time.output and time.series (frequent outputs before a failure): from
#    the 1 s checkpoint with 0.25 s and 0.1 s to 1.5 s, the outputs fall at 1.25 and 1.5 s and the
#    series rows at 1.1, 1.2, ... 1.5 s.
# 5. A restart with time.end = 2 s extends the run, and its outputs equal byte for byte those of
#    a run made to 2 s in one go (the 1 s end falls on an output time, so the steps are the same).
#   restart_scene_checks.sh WORK_DIR EXE SCENES_DIR
set -euo pipefail
work=$1 exe=$2 scenes=$3
here=$(cd "$(dirname "$0")" && pwd)
expect=$here/../support/expect_input_error.sh
rm -rf "$work" && mkdir -p "$work"
scene=("$scenes/table_3_4_example2.yaml" "grid.spacing=0.5 m" time.output=0.5s time.series=0.05s)
"$exe" "${scene[@]}" time.end=1s --out "$work/extended" --log-level warn
grep -q '"status": "completed"' "$work/extended/run.json"

refused() {  # refused KEY OVERRIDE...: a restart with the overrides names KEY and is refused
  local key=$1; shift
  "$expect" "was written for another scene|$key" "$exe" "${scene[@]}" time.end=1s "$@" \
    --out "$work/extended" --restart latest
  echo "refused as it should: $*"
}
refused soil.young "soil.young=20 MPa"
refused soil.poisson "soil.poisson=0.25"
refused soil.friction_angle "soil.friction_angle=30 deg"
refused soil.cohesion "soil.cohesion=2468 Pa"
refused "soil.regions[0].trapezoid.height" "soil.regions.0.trapezoid.height=3 m"
refused walls.y_low "walls.y_low=sticky"
refused wall_friction "wall_friction=0.5"
refused grid.spacing "grid.spacing=0.25 m"
"$expect" "was written for another scene|soil.cohesion|'4935 Pa' there, '1234 Pa' here" \
  "$exe" "$scenes/table_3_4_example5.yaml" "grid.spacing=0.5 m" time.output=0.5s time.series=0.05s time.end=1s \
  --out "$work/extended" --restart latest
"$expect" "time.end|give a later time.end" "$exe" "${scene[@]}" time.end=1s --out "$work/extended" --restart latest

cp -r "$work/extended" "$work/rescheduled"
"$exe" "${scene[@]}" time.end=1.5s time.output=0.25s time.series=0.1s --out "$work/rescheduled" --restart latest \
  --log-level warn
outputs=$(grep -o 'Time Value="[^"]*"' "$work/rescheduled/particles.xmf" | cut -d'"' -f2 | awk '$1 > 1.0001' | xargs)
rows=$(awk -F, 'NR > 1 && $1 > 1.0001 { print $1 }' "$work/rescheduled/series.csv" | xargs)
[ "$(printf '%.4f ' $outputs)" = "1.2500 1.5000 " ] || { echo "outputs after the restart at: $outputs" >&2; exit 1; }
[ "$(printf '%.4f ' $rows)" = "1.1000 1.2000 1.3000 1.4000 1.5000 " ] || { echo "series after the restart at: $rows" >&2; exit 1; }
echo "a restart with new output and series intervals keeps them: outputs at $outputs s"

"$exe" "${scene[@]}" time.end=2s --out "$work/extended" --restart latest --log-level warn
grep -q '"status": "completed"' "$work/extended/run.json"
"$exe" "${scene[@]}" time.end=2s --out "$work/straight" --log-level warn
"$here/same_outputs.sh" "$work/straight" "$work/extended"
echo "refused every change of the physics; extended from 1 s to 2 s identical to a run made in one go"
