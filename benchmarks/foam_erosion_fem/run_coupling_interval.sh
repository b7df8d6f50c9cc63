#!/usr/bin/env bash
# foam-erosion's speed against accuracy for the coupled run (issue 7's chart of outflow volume
# and eroded area against mesh resolution and coupling interval against wall time): the default
# lab embankment scene (4 s of flow, morphological factor 100), over the coupling interval at the
# finest mesh (h = 0.01 m: 1, 0.5, 0.25 and 0.125 s) and over the mesh at the default interval
# (0.5 s: h = 0.02, 0.014 m). Per run: the whole run's wall time (flow, erosion, re-meshing),
# erosion steps, re-meshes, eroded area and the water volume over the crest and toe; the chart
# (plot_coupling_interval.py) compares them with the finest run (h = 0.01 m, 0.125 s).
#   benchmarks/foam_erosion_fem/run_coupling_interval.sh [BUILD_DIR] [REPEATS]   (about 5 min a repeat)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
repeats=${2:-3}
here=$root/benchmarks/foam_erosion_fem
out=${OUT:-$root/benchmarks/results/foam_erosion_fem}
mkdir -p "$out"
csv=$out/coupling_interval.csv
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
configs=("0.01 1" "0.01 0.5" "0.01 0.25" "0.01 0.125" "0.02 0.5" "0.014 0.5")
echo "cell_size_m,interval_s,repeat,$(/usr/bin/python3 "$here/run_metrics.py" --coupled --header)" > "$csv"
for ((r = 1; r <= repeats; r++)); do
  for c in "${configs[@]}"; do
    read -r h interval <<< "$c"
    run=$work/$h-$interval
    rm -rf "$run"
    "$build/bin/foam-erosion" "coupling.interval=$interval s" "mesh.cell_size=$h m" \
      "mesh.far_cell_size=$(awk "BEGIN { print 3 * $h }") m" --out "$run" --log-level warn
    echo "$h,$interval,$r,$(/usr/bin/python3 "$here/run_metrics.py" --coupled "$run")" >> "$csv"
    tail -1 "$csv"
  done
done
/usr/bin/python3 "$here/plot_coupling_interval.py" "$csv" "$out/coupling_interval.png" | tee "$out/coupling_interval.md"
