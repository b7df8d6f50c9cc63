#!/usr/bin/env bash
# slurm test: a seed batch split over a 2-task job array (slurm/seedcarve_array.sbatch) and
# merged by its --merge step gives the table of the batch run in one process, failed seed included.
#   seedcarve_array_job.sh STATE_DIR SOURCE_DIR BIN_DIR WORK_DIR
set -euo pipefail
STATE=$1 SRC=$2 BIN=$3 WORK=$4
[ "$(id -u)" = 0 ] || { echo "needs root for the local Slurm; skipping"; exit 77; }
export SLURM_CONF=$STATE/slurm.conf
rm -rf "$WORK" && mkdir -p "$WORK" && cd "$WORK"
scene=$SRC/tests/carving/data/small_sphere.yaml
"$BIN/seedcarve" render "$scene" --out "$WORK/ball1" --log-level warn
"$BIN/seedcarve" render "$scene" --out "$WORK/ball2" --log-level warn shape.radius=0.7
printf 'id,images,weight_mg\nball1,ball1,4.3\nmissing,nowhere,\nball2,ball2,1.5\n' > "$WORK/manifest.csv"
"$BIN/seedcarve" batch "$WORK/manifest.csv" --profile "$WORK/ball1/profile.yaml" --out "$WORK/whole" --log-level warn
job=$(SUITE_BIN=$BIN sbatch --parsable --array=0-1 --output="$WORK/task-%A_%a.out" \
  "$SRC/slurm/seedcarve_array.sbatch" "$WORK/manifest.csv" "$WORK/array" "$WORK/ball1/profile.yaml")
SUITE_BIN=$BIN sbatch --wait --dependency=afterany:$job --output="$WORK/merge.out" \
  "$SRC/slurm/seedcarve_array.sbatch" --merge "$WORK/array" || { cat "$WORK"/*.out; exit 1; }
cat "$WORK"/*.out
ls "$WORK/array/results.0.csv" "$WORK/array/results.1.csv"
# Same seeds, order, status and numbers; wall time and host may differ.
strip() { cut -d, -f1-10 "$1"; }
diff <(strip "$WORK/whole/results.csv") <(strip "$WORK/array/results.csv")
grep -q '^missing,carving,.*,failed,' "$WORK/array/results.csv"
echo "seedcarve array: 2 tasks merged to the one-process table"
