#!/usr/bin/env bash
# foam-erosion flow speed and accuracy (issue 7's benchmarks): the lab embankment overtopped for
# 2 s of flow (reservoir at the weir level for q = 0.03 m^2/s, erosion off so every run computes
# the same flow), over mesh resolution with adaptive time steps (maxCo 0.5), and at the finest
# mesh with fixed time steps as in the dissertation's Table 3.2, and at the finest mesh on 2 ranks
# (strong scaling; decomposePar simple, mpirun). Per run: ranks, flow cells, time steps,
# interFoam wall time (run.json phase "flow"), wall seconds per simulated second, and the water
# volume over the crest in the 2 s (the accuracy measure, against the finest adaptive run).
# Each configuration runs REPEATS times, in turn, and the CSV keeps every run; the chart uses
# medians.
#   benchmarks/foam_erosion_fem/run_flow_speed.sh [BUILD_DIR] [REPEATS]   (about 10 min on 2 cores)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
here=$root/benchmarks/foam_erosion_fem
repeats=${2:-3}
out=$root/benchmarks/results/foam_erosion_fem
mkdir -p "$out"
csv=$out/flow_speed.csv
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
common=("soil.erodibility=0 cm^3/(N s)" "reservoir.initial_level=0.368 m" "time.end=2 s")
configs=(
  "adaptive 0.02 1" "adaptive 0.014 1" "adaptive 0.01 1"
  "fixed_1e-3 0.01 1" "fixed_5e-4 0.01 1" "adaptive 0.01 2"
)
echo "config,cell_size_m,ranks,repeat,$(/usr/bin/python3 "$here/run_metrics.py" --header)" > "$csv"
for ((r = 1; r <= repeats; r++)); do
  for c in "${configs[@]}"; do
    read -r name h ranks <<< "$c"
    extra=("run.ranks=$ranks")
    case $name in fixed_*) extra+=("time.fixed_dt=${name#fixed_} s") ;; esac
    run=$work/$name-$h-$ranks
    rm -rf "$run"
    "$build/bin/foam-erosion" "${common[@]}" "mesh.cell_size=$h m" "mesh.far_cell_size=$(awk "BEGIN { print 3 * $h }") m" \
      "${extra[@]}" --out "$run" --log-level warn
    echo "$name,$h,$ranks,$r,$(/usr/bin/python3 "$here/run_metrics.py" "$run")" >> "$csv"
    tail -1 "$csv"
  done
done
/usr/bin/python3 "$here/plot_flow_speed.py" "$csv" "$out/flow_speed.png"
