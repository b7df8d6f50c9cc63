#!/usr/bin/env bash
# Measures a study's cost per evaluation for the in-process and local-process models into
# benchmarks/results/studies/.   benchmarks/studies/run_study_overhead.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
mkdir -p "$root/benchmarks/results/studies"
"$build/bin/study_overhead" --out "$root/benchmarks/results/studies/study_overhead.csv" --repeats 5
