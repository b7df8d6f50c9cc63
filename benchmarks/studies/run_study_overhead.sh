#!/usr/bin/env bash
# Measures a study's cost per evaluation for the in-process and local-process models, and the
# wall time of the dissertation's 216-run study on 2 threads, into benchmarks/results/studies/.
# The Slurm array backend has its own script (run_study_slurm_overhead.sh; needs root).
#   benchmarks/studies/run_study_overhead.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
mkdir -p "$root/benchmarks/results/studies"
"$build/bin/study_overhead" --out "$root/benchmarks/results/studies/study_overhead.csv" --repeats 5 \
  --dissertation "$root/studies/examples/dissertation_multidim_clay_CL.yaml" \
  --wall-out "$root/benchmarks/results/studies/study_216_wall.csv"
# The same through the `study` executable, its start included (about 0.45 s here, 0.35 s of it
# Open MPI's singleton MPI_Init).
wall=$root/benchmarks/results/studies/study_216_wall.csv
work=$(mktemp -d /tmp/suite-study-wall.XXXXXX)
trap 'rm -rf "$work"' EXIT
for material in clay_CL silty_sand_SM; do
  for plot in false true; do
    t=()
    for _ in 1 2 3 4 5; do
      rm -rf "$work/out"
      t0=$(date +%s.%N)
      "$build/bin/study" run "$root/studies/examples/dissertation_multidim_$material.yaml" --out "$work/out" \
        --log-level warn execution.concurrency=2 output.plot=$plot
      t+=("$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.6f", b - a }')")
    done
    m=$(printf '%s\n' "${t[@]}" | sort -g | sed -n 3p)
    name="study executable $material $([ $plot = true ] && echo with || echo without) charts"
    printf '%-52s %10.3f s\n' "$name" "$m"
    echo "$name,$m" >> "$wall"
  done
done
