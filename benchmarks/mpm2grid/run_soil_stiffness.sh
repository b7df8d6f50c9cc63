#!/usr/bin/env bash
# What the realistic embankment stiffness costs (issue 26): Table 3.4 example 2 and 05-HR-a at
# the demo resolution over the published 20 s, with the scenes' E = 24 MPa and with the
# dissertation's E = 353.7 kPa (the same cohesion in Pa, everything else as shipped): time steps
# per simulated second and what limits them, wall time, and the outflow, eroded volume and final
# crest. Each repeat runs every configuration in turn; the table has medians over repeats.
#   benchmarks/mpm2grid/run_soil_stiffness.sh [MPM2GRID]   (about 5 min on 2 idle cores, 2 runs at a time)
#   env: REPEATS (3), SCENES ("example2 05_hr_a"), YOUNGS ("353.7 kPa|24 MPa"), SPACING (the scene's),
#        and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
repeats=${REPEATS:-3} scene_names=${SCENES:-example2 05_hr_a}
IFS='|' read -r -a youngs <<< "${YOUNGS:-353.7 kPa|24 MPa}"
spacing=(${SPACING:+"grid.spacing=$SPACING m"})
work_dir soil_stiffness
csv=$out/soil_stiffness.csv
echo "scene,young,repeat,dt_limiter,crest_final_m,$("${metrics[@]}" --header)" > "$csv"
for ((r = 1; r <= repeats; r++)); do
  for s in $scene_names; do
    for e in "${youngs[@]}"; do
      run=$work/$s-${e// /}-$r
      rc=$(run_one "$run" 1 "$scenes/table_3_4_$s.yaml" "soil.young=$e" "${spacing[@]}" "time.output=1000 s")
      [ "$rc" = 0 ] || { echo "run $run failed ($rc): $(tail -2 "$run.err")" >&2; exit 1; }
      extra=$(/usr/bin/python3 -c 'import json, sys
r, s = json.load(open(sys.argv[1] + "/run.json")), json.load(open(sys.argv[1] + "/summary.json"))
limiters = sorted(r["dt_limiters"].items(), key=lambda kv: -kv[1])
print("; ".join(f"{k}: {v}" for k, v in limiters) + "," + str(s["final_crest_height"]))' "$run")
      echo "$s,$e,$r,$extra,$("${metrics[@]}" "$run" "$run.rss")" >> "$csv"
      echo "$s E=$e repeat $r: $(tail -1 "$csv" | cut -d, -f4,11)"
    done
  done
done
{
  echo "## What the realistic soil stiffness costs: Table 3.4 scenes at E = 24 MPa and 353.7 kPa (run_soil_stiffness.sh)"
  echo
  provenance "$run/run.json"
  echo
  $plot "$here/soil_stiffness.py" "$csv"
} | tee "$out/soil_stiffness.md"
