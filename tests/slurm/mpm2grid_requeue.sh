#!/usr/bin/env bash
# slurm/mpm2grid.sbatch on the private Slurm, on Table 3.4 example 2 at 0.5 m for 10 s (the dam
# overtopped, water and no soil leaving through the outlet; about 5 s of computing): once the run
# has written a regular checkpoint, the time-limit warning (USR1 to the batch script, as
# --signal=B:USR1@300 sends it) makes mpm2grid checkpoint and stop on SIGTERM; the job requeues
# itself, the second start goes on with --restart latest, and the outputs (summary.json,
# series.csv, profiles.csv, the particle files) equal those of an uninterrupted run byte for byte.
# The job has 2 tasks: the domain is decomposed over 2 ranks, and so is the uninterrupted run.
#   mpm2grid_requeue.sh SOURCE_DIR BIN_DIR WORK_DIR
set -euo pipefail
source "$(dirname "$0")/requeue_helpers.sh"
same_outputs=$(cd "$(dirname "$0")/../mpm2grid" && pwd)/same_outputs.sh
src=$1 bin=$2 work=$3
[ "$(id -u)" = 0 ] || { echo "needs root for the local Slurm; skipping"; exit 77; }
scene=("$src/solvers/mpm2grid/scenes/table_3_4_example2.yaml" "grid.spacing=0.5 m" time.end=10s time.output=2s
       checkpoint.every_steps=500)
rm -rf "$work" && mkdir -p "$work" && cd "$work"

job=$(SUITE_BIN=$bin SUITE_OUT=$work/pieces sbatch --parsable --ntasks 2 --output="$work/job-%j.out" \
      "$src/slurm/mpm2grid.sbatch" "${scene[@]}")
job=${job%%;*}
log=$work/job-$job.out
state() { job_state "$job"; }
# The first regular checkpoint (step 500 of about 5,100) comes a fraction of a second into the run.
first_checkpoint() { compgen -G "$work/pieces/checkpoints/checkpoint_*.h5" >/dev/null; }
for _ in $(seq 600); do first_checkpoint && break; sleep 0.1; done
first_checkpoint || { echo "the run wrote no checkpoint in 60 s"; cat "$log"; scontrol show job "$job"; exit 1; }
scancel --signal=USR1 --batch "$job"
release_requeued_job "$job"
wait_for_job_end "$job" 600
grep -v " step " "$log" || true
scontrol show job "$job" | grep -E "JobState|Restarts|ExitCode"
[ "$(state)" = COMPLETED ] || { echo "job ended $(state)"; exit 1; }
grep -q "stopped at step .* on checkpoint and stop (SIGTERM, SIGINT or a stop file)" "$log" ||
  { echo "mpm2grid did not stop on the warning's SIGTERM (did the run end before the warning?)"; exit 1; }
grep -q "start 2:.*--restart latest" "$log" || { echo "the second start did not restart"; exit 1; }
grep -q "restarting from checkpoint_" "$work/pieces/log.txt" || { echo "mpm2grid did not restart"; exit 1; }
grep -q '"status": "completed"' "$work/pieces/run.json" || { echo "the requeued run did not complete"; exit 1; }

mpiexec -n 2 --oversubscribe --allow-run-as-root "$bin/mpm2grid" "${scene[@]}" --out "$work/straight" --log-level warn
"$same_outputs" "$work/straight" "$work/pieces"
echo "job $job: stopped on the time-limit warning, requeued, restarted, and matched the uninterrupted run"
