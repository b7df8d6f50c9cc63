#!/usr/bin/env bash
# slurm test: slurm/study.sbatch runs a study over 2 tasks (rank 0 hands out, rank 1 runs) and,
# submitted again into the same folder after losing part of the ledger, resumes to the same table.
#   study_job.sh STATE_DIR SOURCE_DIR BIN_DIR WORK_DIR
set -euo pipefail
STATE=$1 SRC=$2 BIN=$3 WORK=$4
[ "$(id -u)" = 0 ] || { echo "needs root for the local Slurm; skipping"; exit 77; }
export SLURM_CONF=$STATE/slurm.conf
rm -rf "$WORK" && mkdir -p "$WORK" && cd "$WORK"
spec=$SRC/studies/examples/dissertation_multidim_clay_CL.yaml
submit() {
  SUITE_BIN=$BIN SUITE_OUT=$WORK/study sbatch --parsable --wait --ntasks 2 --output="$WORK/job-%j.out" \
    "$SRC/slurm/study.sbatch" "$spec" output.plot=false || { cat "$WORK"/job-*.out; exit 1; }
}
submit
cat "$WORK"/job-*.out
[ "$(wc -l < "$WORK/study/tabular.dat")" = 217 ] || { echo "expected 216 rows"; exit 1; }
cp "$WORK/study/tabular.dat" "$WORK/first.dat"
head -n 120 "$WORK/study/ledger.jsonl" > "$WORK/l" && mv "$WORK/l" "$WORK/study/ledger.jsonl"
submit
grep -q "resuming the study" "$WORK"/job-*.out
cmp "$WORK/first.dat" "$WORK/study/tabular.dat"
echo "study job: 216 evaluations over 2 tasks; a resubmission resumed to the same table"
