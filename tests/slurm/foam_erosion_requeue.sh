#!/usr/bin/env bash
# slurm/foam_erosion.sbatch on the private Slurm: the time-limit warning (USR1 to the batch
# script, which sends SIGTERM to foam-erosion) stops the coupled run after its second saved step,
# foam-erosion stopping its interFoam itself; the job requeues itself, the second
# start goes on with --restart latest, and the records equal those of an uninterrupted run byte
# for byte.
#   foam_erosion_requeue.sh SOURCE_DIR BIN_DIR WORK_DIR
set -euo pipefail
source "$(dirname "$0")/requeue_helpers.sh"
src=$1 bin=$2 work=$3
[ "$(id -u)" = 0 ] || { echo "needs root for the local Slurm; skipping"; exit 77; }
scene=("reservoir.initial_level=0.368 m" "coupling.morphological_factor=300" "time.end=1.5 s")
rm -rf "$work" && mkdir -p "$work" && cd "$work"

job=$(SUITE_BIN=$bin SUITE_OUT=$work/pieces sbatch --parsable --ntasks 1 --output="$work/job-%j.out" \
      "$src/slurm/foam_erosion.sbatch" "${scene[@]}")
job=${job%%;*}
log=$work/job-$job.out
state() { job_state "$job"; }
for _ in $(seq 1800); do grep -q '"step": 2' "$work/pieces/state.json" 2>/dev/null && break; sleep 0.1; done
grep -q '"step": 2' "$work/pieces/state.json" || { echo "the run did not reach step 2"; cat "$log"; exit 1; }
scancel --signal=USR1 --batch "$job"
release_requeued_job "$job"
wait_for_job_end "$job" 1800
cat "$log"
[ "$(state)" = COMPLETED ] || { echo "job ended $(state)"; exit 1; }
grep -q "start 2:.*--restart latest" "$log" || { echo "the second start did not restart"; exit 1; }
grep -q "restarting from" "$work/pieces/log.txt" || { echo "foam-erosion did not restart"; exit 1; }
grep -q "stopped on signal 15" "$work/pieces/log.txt" || { echo "foam-erosion did not stop on the warning's SIGTERM"; exit 1; }

"$bin/foam-erosion" "${scene[@]}" --out "$work/straight" --log-level warn
for f in erosion.csv profiles.csv discharge.csv; do cmp "$work/straight/$f" "$work/pieces/$f"; done
echo "job $job: stopped on the time-limit warning, requeued, restarted, and matched the uninterrupted run"
