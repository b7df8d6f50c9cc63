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
#   example2_closure
#                 example 2 with the erosion as a function of time (issue 27's closure: the bed shear,
#                 kd (tau - tau_c) erosion, FLIP 0.99 for both species; CLOSURE_ARGS) at DAM_SPACING
#                 to CLOSURE_END (20 s): explicit at cfl 0.4 and 0.1, implicit with dt_max 10 ms,
#                 40 ms and 0.1 s at cfl 0.4, and at 40 ms with every GMRES solve to 1e-8
#                 (implicit-exact_krylov: the Newton iterations a perfect preconditioner would leave).
#                 Accuracy: the law's eroded volume and the peak outflow against explicit cfl 0.1.
# Runs in turn, REPEATS times; implicit_forces.py takes the medians and writes the table and chart.
#   benchmarks/mpm2grid/run_implicit_forces.sh [MPM2GRID]     (about 6 min on 2 idle cores)
#   env: REPEATS (3), DAM_SPACING (0.5), DAM_END (10), CLOSURE_END (20), REFERENCE
#        (data/martin_moyce_1952_surge_front.csv), SCENES (the scenes above to run, default
#        "water_column example2"; add example2_closure), NAME (the results' file name,
#        implicit_forces; e.g. implicit_forces_h0.25 with DAM_SPACING=0.25), and common.sh's MPM2GRID
#        MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
repeats=${REPEATS:-3} dam_spacing=${DAM_SPACING:-0.5} dam_end=${DAM_END:-10} closure_end=${CLOSURE_END:-20}
run_scenes=" ${SCENES:-water_column example2} "
# Issue 27's closure (benchmarks/results/dam_three_solvers/example2_free_water.md, without the free
# water's own field, which the implicit forces do not include).
closure=("soil.erosion=excess_stress" "soil.erodibility=100 cm^3/(N s)" "soil.critical_shear_stress=1 Pa"
  "soil.settling_velocity=0.02 m/s" "bed_shear.manning_n=0.016" "water.flip=0.99" "soil.flip=0.99")
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
  "example2_closure explicit 0.4 10e-3"
  "example2_closure explicit 0.1 10e-3"
  "example2_closure implicit 0.4 10e-3"
  "example2_closure implicit 0.4 40e-3"
  "example2_closure implicit 0.4 0.1"
  "example2_closure implicit 0.4 40e-3 exact_krylov"
)
failed=()
for ((r = 1; r <= repeats; r++)); do
  for c in "${cases[@]}"; do
    read -r scene_name forces cfl dt_max variant <<< "$c"
    [[ $run_scenes = *" $scene_name "* ]] || continue
    case $scene_name in
      water_column) scene=("$scenes/water_column_collapse.yaml" "time.output=1 s") ;;
      example2) scene=("$scenes/table_3_4_example2.yaml" "grid.spacing=$dam_spacing m" "time.end=$dam_end s"
        "time.output=100 s") ;;
      example2_closure) scene=("$scenes/table_3_4_example2.yaml" "grid.spacing=$dam_spacing m" "time.end=$closure_end s"
        "time.output=100 s" "drag=lumped" "${closure[@]}") ;;
    esac
    case ${variant:-} in
      after_solve) scene+=("implicit.plasticity=after_solve") ;;
      exact_krylov) scene+=("petsc_options=-implicit_ksp_rtol 1e-8") ;;
    esac
    forces=$forces${variant:+-$variant}
    run=$work/$scene_name-$forces-$cfl-$dt_max-$r
    rc=$(run_one "$run" 1 "${scene[@]}" "forces=${forces%%-*}" "time.cfl=$cfl" "time.dt_max=$dt_max s")
    if [ "$rc" != 0 ]; then  # a blow-up or a failed solve is a result: the setting's stability limit
      failed+=("$scene_name $forces cfl $cfl dt_max $dt_max s, repeat $r: $(grep -m1 '^error' "$run.err" | cut -c1-400)")
      echo "run $run failed ($rc): $(tail -2 "$run.err")" >&2
      continue
    fi
    good=$run
    echo "$scene_name,$forces,$cfl,$dt_max,$r,$("${row[@]}" "$scene_name" "$run")" >> "$csv"
    echo "$scene_name $forces cfl $cfl dt_max $dt_max repeat $r: $(tail -1 "$csv" | cut -d, -f6-9)"
  done
done
{
  echo "## Explicit against implicit forces, $(echo $run_scenes) at $dam_spacing m: accuracy against wall time (run_implicit_forces.sh)"
  echo
  provenance "${good:-$run}/run.json"  # the last run that finished (any run where none did)
  echo
  declare -A described=([water_column]="the water column at a / 16 to 0.18 s"
    [example2]="example 2 at grid.spacing $dam_spacing m to $dam_end s"
    [example2_closure]="example 2 with the erosion closure at grid.spacing $dam_spacing m to $closure_end s")
  for s in $run_scenes; do echo "- ${described[$s]}"; done
  echo
  echo "One rank; $repeats repeat(s)."

  echo
  $plot "$here/implicit_forces.py" report "$csv" "$out/$name.png"
  if [ ${#failed[@]} -gt 0 ]; then
    echo
    echo "Runs that did not finish (not in the table):"
    for f in "${failed[@]}"; do echo "- $f"; done
  fi
} | tee "$out/$name.md"
