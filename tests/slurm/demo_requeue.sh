#!/usr/bin/env bash
# slurm/suite-demo.sbatch on the private Slurm: the time-limit warning (USR1 to the batch
# script, as --signal=B:USR1@120 sends it) makes the run checkpoint and stop, the job requeues
# itself, the second start restarts from the newest checkpoint, and the final outputs equal
# those of an uninterrupted run byte for byte.
#   demo_requeue.sh SOURCE_DIR BIN_DIR WORK_DIR LAUNCHER...
set -euo pipefail
source "$(dirname "$0")/requeue_helpers.sh"
src=$1 bin=$2 work=$3; shift 3
launcher=("$@")
[ "$(id -u)" = 0 ] || { echo "needs root for the local Slurm; skipping"; exit 77; }
scene=(cells=200000 time.sample=0.0002s time.output=0.3s checkpoint.every_steps=1000000)
rm -rf "$work" && mkdir -p "$work" && cd "$work"

job=$(SUITE_BIN=$bin SUITE_OUT=$work/pieces sbatch --parsable --output="$work/job-%j.out" \
      "$src/slurm/suite-demo.sbatch" "${scene[@]}")
job=${job%%;*}
log=$work/job-$job.out
state() { job_state "$job"; }
for _ in $(seq 600); do grep -q "Ritter dam break" "$log" 2>/dev/null && break; sleep 0.1; done
grep -q "Ritter dam break" "$log" || { echo "the job did not start"; cat "$log"; scontrol show job "$job"; exit 1; }
scancel --signal=USR1 --batch "$job"
release_requeued_job "$job"
wait_for_job_end "$job" 900
cat "$log" | grep -v " step " || true
scontrol show job "$job" | grep -E "JobState|Restarts|ExitCode"
[ "$(state)" = COMPLETED ] || { echo "job ended $(state)"; exit 1; }
grep -q "start 2:" "$log" || { echo "the job was not requeued"; exit 1; }
grep -q "restarting from checkpoint_" "$log" || { echo "the second start did not restart from a checkpoint"; exit 1; }

"${launcher[@]}" "$bin/suite-demo" --out "$work/straight" "${scene[@]}" --log-level warn
"$src/tests/demo/same_outputs.sh" "$work/straight" "$work/pieces"
echo "job $job: checkpointed on the time-limit warning, requeued, restarted, and matched the uninterrupted run"
