#!/usr/bin/env bash
# What the slice count buys in the two-view elliptic-slice model, with and without the
# dissertation's neighbour averaging (issue 30, item 5): volume error against N on exact
# silhouettes of shapes of known volume and of the real grain's 36-view hull, at 20 and 40 px/mm,
# over 16 sub-pixel positions each. Writes into benchmarks/results/carving/:
#   two_view_slices.csv  one row per shape, px/mm, N and averaging (mean, spread, worst error; time)
#   two_view_slices.png  the chart
#   two_view_slices.md   the summary tables, with the machine, build and git hash of the run
#
#   benchmarks/carving/run_two_view_slices.sh [BUILD_DIR]   (default build/release)
#
# Needs the target two_view_slices built in BUILD_DIR:
#   cmake --build --preset release --target two_view_slices
# Runs on one core (taskset when available); about 15 s on a 2-core machine.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
here=$root/benchmarks/carving
out=$root/benchmarks/results/carving
mkdir -p "$out"
pin=()
if command -v taskset > /dev/null; then pin=(taskset -c 0); fi

"${pin[@]}" "$build/bin/two_view_slices" --out "$out/two_view_slices.csv" --positions 16 --repeats 5 > /dev/null
/usr/bin/python3 "$here/plot_two_view_slices.py" "$out/two_view_slices.csv" "$out/two_view_slices.png" \
  "$out/two_view_slices.md"
echo "wrote $out/two_view_slices.{csv,png,md}"
