#!/usr/bin/env bash
# slurm test: submits mpi_hello.sbatch to the private Slurm, waits, checks that both ranks ran.
#   submit_and_check.sh STATE_DIR MPI_HELLO_EXE WORK_DIR
set -euo pipefail
STATE=$1 EXE=$2 WORK=$3
[ "$(id -u)" = 0 ] || { echo "needs root for the local Slurm; skipping"; exit 77; }
export SLURM_CONF=$STATE/slurm.conf
mkdir -p "$WORK" && cd "$WORK" && rm -f hello-*.out
out=$(sbatch --parsable --wait --output="$WORK/hello-%j.out" "$(dirname "$0")/mpi_hello.sbatch" "$EXE") || {
  echo "sbatch failed (job ${out:-?})"; cat "$WORK"/hello-*.out 2>/dev/null; exit 1; }
job=${out%%;*}
file="$WORK/hello-$job.out"
cat "$file"
scontrol show job "$job" | grep -E "JobState|ExitCode" || true
grep -q "hello from rank 0 of 2" "$file"
grep -q "hello from rank 1 of 2" "$file"
grep -q "sum of ranks = 1 (expected 1)" "$file"
echo "slurm job $job: 2 ranks ran and reduced correctly"
