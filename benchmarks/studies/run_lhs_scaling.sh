#!/usr/bin/env bash
# Scaling of a 10,000-run study with workers (issue 6's benchmark): the shipped LHS study of the
# breach model's soil (studies/examples/dissertation_lhs_soil.yaml) at 10,000 samples, without
# charts, through the `study` executable, on 1 and 2 threads of one process and over MPI ranks
# (rank 0 hands out evaluations, the others evaluate: 2 and 3 ranks, i.e. 1 and 2 workers).
# Wall time from start to the analysis written, median of REPEATS runs taken in turn; every run
# must give the same table. Writes benchmarks/results/studies/lhs_10000_scaling.csv.
#   benchmarks/studies/run_lhs_scaling.sh [BUILD_DIR] [REPEATS]    (about a minute on 2 cores)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
repeats=${2:-3}
spec=$root/studies/examples/dissertation_lhs_soil.yaml
out=$root/benchmarks/results/studies/lhs_10000_scaling.csv
work=$(mktemp -d /tmp/suite-lhs-scaling.XXXXXX)
trap 'rm -rf "$work"' EXIT
mpiexec=(mpiexec --oversubscribe)
[ "$(id -u)" = 0 ] && mpiexec+=(--allow-run-as-root)
configs=("threads 1" "threads 2" "ranks 2" "ranks 3")
declare -A times
for ((r = 1; r <= repeats; r++)); do
  for c in "${configs[@]}"; do
    read -r kind n <<< "$c"
    dir=$work/$kind-$n
    rm -rf "$dir"
    args=(run "$spec" --out "$dir" --log-level warn method.samples=10000 output.plot=false)
    t0=$(date +%s.%N)
    if [ "$kind" = threads ]; then
      "$build/bin/study" "${args[@]}" "execution.concurrency=$n"
    else
      "${mpiexec[@]}" -n "$n" "$build/bin/study" "${args[@]}"
    fi
    times[$c]+="$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }') "
    # The same table whatever the backend.
    cmp "$dir/tabular.csv" "$work/threads-1/tabular.csv"
  done
done
echo "backend,workers,median_wall_s,runs_s,speedup_vs_1_thread" > "$out"
base=$(printf '%s\n' ${times["threads 1"]} | sort -g | sed -n "$(((repeats + 1) / 2))p")
for c in "${configs[@]}"; do
  read -r kind n <<< "$c"
  m=$(printf '%s\n' ${times[$c]} | sort -g | sed -n "$(((repeats + 1) / 2))p")
  workers=$([ "$kind" = threads ] && echo "$n" || echo $((n - 1)))
  echo "$kind,$workers,$m,${times[$c]% },$(awk -v a="$base" -v b="$m" 'BEGIN { printf "%.2f", a / b }')" >> "$out"
done
cat "$out"
