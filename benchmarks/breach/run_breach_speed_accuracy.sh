#!/usr/bin/env bash
# Runs breach_speed_accuracy and charts it into benchmarks/results/breach/.
#   benchmarks/breach/run_breach_speed_accuracy.sh [BUILD_DIR]   (default build/release)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
out=$root/benchmarks/results/breach
mkdir -p "$out"
"$build/bin/breach_speed_accuracy" --out "$out/breach_speed_accuracy.csv" --repeats 7 --batch 2000
/usr/bin/python3 "$root/benchmarks/breach/plot_breach_speed_accuracy.py" "$out/breach_speed_accuracy.csv" \
  "$out/breach_speed_accuracy.png"
