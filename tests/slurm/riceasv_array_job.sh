#!/usr/bin/env bash
# slurm test: a rice classification batch split over a 2-task job array (slurm/riceasv_array.sbatch,
# parts of two photographs, a missing photograph among them) and merged by its --merge step gives
# the tables of the batch run in one process.
#   riceasv_array_job.sh STATE_DIR SOURCE_DIR BIN_DIR WORK_DIR
set -euo pipefail
STATE=$1 SRC=$2 BIN=$3 WORK=$4
[ "$(id -u)" = 0 ] || { echo "needs root for the local Slurm; skipping"; exit 77; }
export SLURM_CONF=$STATE/slurm.conf
rm -rf "$WORK" && mkdir -p "$WORK" && cd "$WORK"
"$BIN/riceasv" render --grades 2,4,6 --per-grade 4 --per-image 2 --seed 7 --pixel-size 0.03 --out "$WORK/labelled" \
  --log-level warn
"$BIN/riceasv" train "$WORK/labelled/truth.csv" --pixel-size 0.03 --folds 0 --validation-share 0 --test-share 0 \
  --out "$WORK/model" --log-level warn
photos=("$WORK/labelled" "$WORK/nowhere.png")
"$BIN/riceasv" classify "${photos[@]}" --model "$WORK/model" --pixel-size 0.03 --out "$WORK/whole" \
  --log-level warn || true  # exit 2: the missing photograph
job=$(SUITE_BIN=$BIN RICEASV_ARGS="--part-size 2" sbatch --parsable --array=0-1 --output="$WORK/task-%A_%a.out" \
  "$SRC/slurm/riceasv_array.sbatch" "$WORK/array" 0.03 "$WORK/model" "${photos[@]}")
SUITE_BIN=$BIN sbatch --wait --dependency=afterany:$job --output="$WORK/merge.out" \
  "$SRC/slurm/riceasv_array.sbatch" --merge "$WORK/array" || true  # exit 2: the missing photograph
cat "$WORK"/*.out
ls "$WORK/array/parts/0000" "$WORK/array/parts/0003" > /dev/null
cmp "$WORK/whole/classes.csv" "$WORK/array/classes.csv"
cmp "$WORK/whole/results.csv" "$WORK/array/results.csv"
grep -q "nowhere.png,0,,,failed," "$WORK/array/classes.csv"
echo "riceasv array: 2 tasks, 4 parts merged to the one-process tables"
