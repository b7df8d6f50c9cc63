#!/usr/bin/env bash
# A study's cost per evaluation on the Slurm job-array backend (issue 6's benchmark), on the
# private single-node Slurm the slurm tests use (tests/support/slurm/slurm_up.sh; here with its
# own state folder and ports, so it never meets a test's Slurm). Needs root, like those tests.
#
#   benchmarks/studies/run_study_slurm_overhead.sh [BUILD_DIR] [REPEATS]
#
# Each case is the whole array workflow, timed from `study prepare` to the end of `study
# analyze` (which merges the ledger shards): `sbatch --array` of slurm/study_array.sbatch, then
# squeue polled every 0.05 s until the array has left the queue. The same study run by `study
# run` in one process on 2 threads is the reference; overhead per evaluation = (array wall -
# that wall) / evaluations. Medians of REPEATS (default 5). The merged table is checked against
# the one-process table. Writes benchmarks/results/studies/study_slurm_overhead.csv.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$root/build/release}" && pwd)
repeats=${2:-5}
bin=$build/bin
[ "$(id -u)" = 0 ] || { echo "the local Slurm needs root (slurmd starts jobs as their owner)"; exit 1; }

state=$build/slurm-bench
export SUITE_SLURMCTLD_PORT=${SUITE_SLURMCTLD_PORT:-16837} SUITE_SLURMD_PORT=${SUITE_SLURMD_PORT:-16838}
export SLURM_CONF=$state/slurm.conf
"$root/tests/support/slurm/slurm_up.sh" "$state" >/dev/null
trap '"$root/tests/support/slurm/slurm_down.sh" "$state" >/dev/null' EXIT

work=$(mktemp -d /tmp/suite-study-slurm-bench.XXXXXX)
trap '"$root/tests/support/slurm/slurm_down.sh" "$state" >/dev/null; rm -rf "$work"' EXIT

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.6f", b - a }'; }
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# A formula study of N evaluations (the engine's own cost; the model costs nothing).
formula_spec() {
  cat > "$work/formula_$1.yaml" <<EOF
variables:
  - {name: x, lower: 0, upper: 1}
method: {type: multidim, partitions: $(($1 - 1))}
model: {type: expression, responses: {y: "2*x"}}
output: {plot: false}
EOF
  echo "$work/formula_$1.yaml"
}

# Wall seconds of SPEC run by `study run` in one process (2 threads).
local_wall() {
  rm -rf "$work/local"
  local t0; t0=$(now)
  "$bin/study" run "$1" --out "$work/local" --log-level warn output.plot=false execution.concurrency=2
  elapsed "$t0" "$(now)"
}

# Seconds since midnight, from `date` or from a log line's [HH:MM:SS.mmm] (both local time).
clock() { date +%H:%M:%S.%N; }
seconds_of_day() { awk -F: '{ printf "%.6f\n", $1 * 3600 + $2 * 60 + $3 }'; }

# SPEC as an array of TASKS tasks: prepare, sbatch, wait, analyze. Prints the wall seconds, the
# seconds from sbatch to the first task's study starting (the tasks' first log line, after the
# executable's own start), and from the last task's last log line to the array leaving squeue.
array_wall() {
  local spec=$1 tasks=$2 dir=$work/array t0 job submitted gone first last
  rm -rf "$dir" "$work"/task-*.out
  t0=$(now)
  "$bin/study" prepare "$spec" --out "$dir" output.plot=false >/dev/null
  submitted=$(clock | seconds_of_day)
  job=$(SUITE_BIN=$bin sbatch --parsable --array=0-$((tasks - 1)) --output="$work/task-%A_%a.out" \
    "$root/slurm/study_array.sbatch" "$dir")
  while [ -n "$(squeue -h -j "$job" 2>/dev/null)" ]; do sleep 0.05; done
  gone=$(clock | seconds_of_day)
  "$bin/study" analyze "$dir" --log-level warn
  local wall; wall=$(elapsed "$t0" "$(now)")
  cmp -s "$dir/tabular.dat" "$work/local/tabular.dat" || { echo "array table differs from the local one" >&2; exit 1; }
  first=$(grep -h -o '^\[[0-9:.]*\]' "$work"/task-*.out | tr -d '[]' | seconds_of_day | sort -g | head -1)
  last=$(grep -h -o '^\[[0-9:.]*\]' "$work"/task-*.out | tr -d '[]' | seconds_of_day | sort -g | tail -1)
  echo "$wall $(elapsed "$submitted" "$first") $(elapsed "$last" "$gone")"
}

out=$root/benchmarks/results/studies/study_slurm_overhead.csv
mkdir -p "$(dirname "$out")"
{
  echo "# study_slurm_overhead: host $(hostname), $(nproc) cores, suite $(git -C "$root" describe --always --dirty 2>/dev/null), local single-node Slurm $(sinfo -V | cut -d' ' -f2)" \
    "(tests/support/slurm, sched/backfill, CR_Core), medians of $repeats repeats; wall from study prepare to the" \
    "end of study analyze; local = study run in one process on 2 threads"
  echo "case,array_tasks,evaluations,array_wall_seconds,local_wall_seconds,overhead_seconds_per_evaluation,sbatch_to_first_task_seconds,last_task_to_array_done_seconds"
} > "$out"

dissertation=$root/studies/examples/dissertation_multidim_clay_CL.yaml
for c in "1 formula 1" "8 formula 8" "2 formula 2000" "2 breach 216" "8 breach 216"; do
  read -r tasks model n <<<"$c"
  if [ "$model" = formula ]; then spec=$(formula_spec "$n"); name="formula ($((n / tasks)) per task)"
  else spec=$dissertation; name="dissertation breach study (216 runs)"; fi
  arr=() loc=() first=() last=()
  for _ in $(seq "$repeats"); do
    loc+=("$(local_wall "$spec")")
    read -r w f z <<<"$(array_wall "$spec" "$tasks")"
    arr+=("$w") first+=("$f") last+=("$z")
  done
  a=$(printf '%s\n' "${arr[@]}" | median) l=$(printf '%s\n' "${loc[@]}" | median)
  f=$(printf '%s\n' "${first[@]}" | median) z=$(printf '%s\n' "${last[@]}" | median)
  per=$(awk -v a="$a" -v l="$l" -v n="$n" 'BEGIN { printf "%.4g", (a - l) / n }')
  printf '%-38s %d tasks %4d evaluations: array %6.2f s, local %5.2f s, overhead %s s/evaluation;' \
    "$name" "$tasks" "$n" "$a" "$l" "$per"
  printf ' sbatch to first task %.2f s, last task to done %.2f s\n' "$f" "$z"
  echo "$name,$tasks,$n,$a,$l,$per,$f,$z" >> "$out"
done
echo "wrote $out"
