#!/usr/bin/env bash
# Explicit against implicit forces (issue 29; docs/mpm2grid.md, "Implicit forces"): wall time and
# accuracy over the time step, one rank.
#   water column  the embedded default scene (a / 16, 0.18 s): explicit at time.cfl 0.4 and 0.1
#                 (the water's wave speed limits dt), implicit at cfl 0.4, 0.2, 0.1 with dt_max
#                 1 ms (the particles' speed limits dt). Accuracy: the front against Martin & Moyce
#                 and against the explicit cfl 0.1 run (the time-step error alone).
#   example 2     table_3_4_example2.yaml at grid.spacing DAM_SPACING (0.5 m), DAM_END (10 s):
#                 explicit at cfl 0.4 and 0.1 (the soil's P-wave limits dt), implicit with dt_max
#                 10 ms (the scene's), 40 ms and 0.1 s at cfl 0.4, and with the soil elastic in the
#                 solve (implicit.plasticity after_solve) at 10 ms. Accuracy: eroded volume, peak
#                 outflow and water front against the explicit cfl 0.1 run.
# Runs in turn, REPEATS times; implicit_forces.py takes the medians and writes the table and chart.
#   benchmarks/mpm2grid/run_implicit_forces.sh [MPM2GRID]     (about 6 min on 2 idle cores)
#   env: REPEATS (3), DAM_SPACING (0.5), DAM_END (10), REFERENCE (data/martin_moyce_1952_surge_front.csv),
#        NAME (the results' file name, implicit_forces; e.g. implicit_forces_h0.25 with DAM_SPACING=0.25),
#        and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
repeats=${REPEATS:-3} dam_spacing=${DAM_SPACING:-0.5} dam_end=${DAM_END:-10}
reference=${REFERENCE:-$root/data/martin_moyce_1952_surge_front.csv}
[ -f "$reference" ] || { echo "no reference data at $reference (set REFERENCE)" >&2; exit 2; }
name=${NAME:-implicit_forces}
work_dir "$name"
csv=$out/$name.csv
row=(/usr/bin/python3 "$here/implicit_forces.py" row "$reference")
echo "case,forces,cfl,dt_max_s,repeat,$("${row[@]}" --header)" > "$csv"
# case forces cfl dt_max [plasticity]
cases=(
  "water_column explicit 0.4 1e-3"
  "water_column explicit 0.1 1e-3"
  "water_column implicit 0.4 1e-3"
  "water_column implicit 0.2 1e-3"
  "water_column implicit 0.1 1e-3"
  "example2 explicit 0.4 10e-3"
  "example2 explicit 0.1 10e-3"
  "example2 implicit 0.4 10e-3"
  "example2 implicit 0.4 40e-3"
  "example2 implicit 0.4 0.1"
  "example2 implicit 0.4 10e-3 after_solve"
)
for ((r = 1; r <= repeats; r++)); do
  for c in "${cases[@]}"; do
    read -r scene_name forces cfl dt_max plasticity <<< "$c"
    if [ "$scene_name" = water_column ]; then
      scene=("$scenes/water_column_collapse.yaml" "time.output=1 s")
    else
      scene=("$scenes/table_3_4_example2.yaml" "grid.spacing=$dam_spacing m" "time.end=$dam_end s" "time.output=100 s")
    fi
    [ -z "${plasticity:-}" ] || scene+=("implicit.plasticity=$plasticity")
    forces=$forces${plasticity:+-$plasticity}
    run=$work/$scene_name-$forces-$cfl-$dt_max-$r
    rc=$(run_one "$run" 1 "${scene[@]}" "forces=${forces%%-*}" "time.cfl=$cfl" "time.dt_max=$dt_max s")
    [ "$rc" = 0 ] || { echo "run $run failed ($rc): $(tail -2 "$run.err")" >&2; exit 1; }
    echo "$scene_name,$forces,$cfl,$dt_max,$r,$("${row[@]}" "$scene_name" "$run")" >> "$csv"
    echo "$scene_name $forces cfl $cfl dt_max $dt_max repeat $r: $(tail -1 "$csv" | cut -d, -f6-9)"
  done
done
{
  echo "## Explicit against implicit forces, example 2 at $dam_spacing m: accuracy against wall time (run_implicit_forces.sh)"
  echo
  provenance "$run/run.json"
  echo
  echo "Water column at a / 16 to 0.18 s; example 2 at grid.spacing $dam_spacing m to $dam_end s; one rank; $repeats repeat(s)."
  echo
  $plot "$here/implicit_forces.py" report "$csv" "$out/$name.png"
} | tee "$out/$name.md"
