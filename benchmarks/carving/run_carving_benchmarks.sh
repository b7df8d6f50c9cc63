#!/usr/bin/env bash
# Runs the carving benchmarks of issue 4 and charts them into benchmarks/results/carving/:
#   carving_speed           per-seed carve times, plain loop baseline, measure_hull, two-view slicing
#   carving_speed_accuracy  volume error against carve time over resolution and views, crease table
#   run_carving_batch.sh    seedcarve batch throughput by image format on 1, 2 and 3 MPI ranks
#   run_two_view_slices.sh  two-view volume error against the slice count (and neighbour averaging)
#
#   benchmarks/carving/run_carving_benchmarks.sh [BUILD_DIR]   (default build/release)
#
# Needs the targets carving_speed, carving_speed_accuracy and seedcarve built in BUILD_DIR, e.g.
#   cmake --build build/release --target carving_speed carving_speed_accuracy two_view_slices seedcarve
# The single-core benchmarks are pinned to one core with taskset when it is available. About
# 12-15 minutes on a 2-core machine.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
here=$root/benchmarks/carving
out=$root/benchmarks/results/carving
mkdir -p "$out"
pin=()
if command -v taskset > /dev/null; then pin=(taskset -c 0); fi

"${pin[@]}" "$build/bin/carving_speed" --out "$out/carving_speed.csv" --repeats 7
"${pin[@]}" "$build/bin/carving_speed_accuracy" --out "$out/carving_speed_accuracy.csv" \
  --crease-out "$out/carving_crease.csv" --repeats 5
"$here/run_carving_batch.sh" "$build" "$out/carving_batch.csv" 5 40
"$here/run_two_view_slices.sh" "$build"

/usr/bin/python3 "$here/plot_carving_speed.py" "$out/carving_speed.csv" "$out/carving_batch.csv" \
  "$out/carving_speed.png"
/usr/bin/python3 "$here/plot_carving_speed_accuracy.py" "$out/carving_speed_accuracy.csv" "$out/carving_crease.csv" \
  "$out/carving_speed_accuracy.png"
