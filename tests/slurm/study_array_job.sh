#!/usr/bin/env bash
# slurm test: a study split over a 2-task job array (slurm/study_array.sbatch), merged afterwards
# by `study analyze`, gives the same table as the study run in one process.
#   study_array_job.sh STATE_DIR SOURCE_DIR BIN_DIR WORK_DIR
set -euo pipefail
STATE=$1 SRC=$2 BIN=$3 WORK=$4
[ "$(id -u)" = 0 ] || { echo "needs root for the local Slurm; skipping"; exit 77; }
export SLURM_CONF=$STATE/slurm.conf
rm -rf "$WORK" && mkdir -p "$WORK" && cd "$WORK"
spec=$SRC/studies/examples/dissertation_multidim_clay_CL.yaml
"$BIN/study" run "$spec" --out "$WORK/whole" --log-level warn output.plot=false
"$BIN/study" prepare "$spec" --out "$WORK/array" output.plot=false
SUITE_BIN=$BIN sbatch --parsable --wait --array=0-1 --output="$WORK/task-%A_%a.out" \
  "$SRC/slurm/study_array.sbatch" "$WORK/array" || { cat "$WORK"/task-*.out; exit 1; }
cat "$WORK"/task-*.out
ls "$WORK/array/ledger.0.jsonl" "$WORK/array/ledger.1.jsonl"
"$BIN/study" analyze "$WORK/array" --log-level warn
cmp "$WORK/whole/tabular.dat" "$WORK/array/tabular.dat"
echo "study array: 2 tasks, shards merged to the one-process table"
