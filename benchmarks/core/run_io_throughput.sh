#!/usr/bin/env bash
# Runs io_throughput at 1 and 2 ranks and charts it into benchmarks/results/core/.
#   benchmarks/core/run_io_throughput.sh [BUILD_DIR]   (default build/release)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
out=$root/benchmarks/results/core
mkdir -p "$out"
flags=(--oversubscribe)
[ "$(id -u)" = 0 ] && flags+=(--allow-run-as-root)
for n in 1 2; do
  mpiexec -n $n "${flags[@]}" "$build/bin/io_throughput" --out "$out/io_throughput_np$n.csv" --repeats 5
done
/usr/bin/python3 "$root/benchmarks/core/plot_io_throughput.py" "$out/io_throughput.png" "$out"/io_throughput_np*.csv
