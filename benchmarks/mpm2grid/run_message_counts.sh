#!/usr/bin/env bash
# The decomposition's traffic of Table 3.4 example 2 (solvers/mpm2grid/scenes/table_3_4_example2.yaml)
# at 2 to 64 ranks (more ranks than cores: oversubscribed, so only the counts mean anything, not
# the times): halo and migration bytes and point-to-point messages per step (run.json's
# decomposition block, summed over the ranks), particles per rank. The counts follow from the
# partition and the particles' motion, not from timing, so they are what the same run sends on
# a cluster: the input of the communication model of issue 28. STEPS steps of the dt a probe run
# measures, after START simulated seconds (run first on the same ranks and continued from their
# checkpoint: the counts are of the STEPS steps only, and of the flow rather than of the scene at
# rest when START is some seconds); message_counts.py tabulates.
#   benchmarks/mpm2grid/run_message_counts.sh [MPM2GRID]     (about 4 min on 2 cores at the defaults)
#   env: STEPS (20), H (0.025 m), START (0 s), RANKS ("2 4 8 16 32 64"), and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
steps=${STEPS:-20} h=${H:-0.025 m} start=${START:-0} ranks_list=${RANKS:-2 4 8 16 32 64}
scene=$scenes/table_3_4_example2.yaml
work_dir message_counts
rc=$(run_one "$work/probe" 1 "$scene" "grid.spacing=$h" time.max_steps=5 "time.output=1000 s" "time.series=1000 s")
t5=$(sed -n 's/.*stopped at step 5 (t = \([0-9.e+-]*\) s).*/\1/p' "$work/probe.err")
[ -n "$t5" ] || { echo "probe failed ($rc): $(tail -2 "$work/probe.err")" >&2; exit 1; }
end=$(awk -v t="$t5" -v n="$steps" -v s="$start" 'BEGIN { printf "%.6g", s + t / 5 * n }')
csv=$out/message_counts.csv
echo "spacing,end_time_s,$("${metrics[@]}" --header)" > "$csv"
for ranks in $ranks_list; do
  run=$work/ranks$ranks
  args=("$scene" "grid.spacing=$h" "time.series=$end s" "time.output=1000 s")
  if awk -v s="$start" 'BEGIN { exit !(s > 0) }'; then
    rc=$(run_one "$run" "$ranks" "${args[@]}" "time.end=$start s")
    [ "$rc" = 0 ] || { echo "run $run to $start s failed ($rc): $(tail -2 "$run.err")" >&2; exit 1; }
    $nice_cmd $mpiexec_cmd -n "$ranks" "$bin" "${args[@]}" "time.end=$end s" --out "$run" --restart latest \
      --log-level warn 2> "$run.err" || { echo "run $run from $start s failed: $(tail -2 "$run.err")" >&2; exit 1; }
  else
    rc=$(run_one "$run" "$ranks" "${args[@]}" "time.end=$end s")
    [ "$rc" = 0 ] || { echo "run $run failed ($rc): $(tail -2 "$run.err")" >&2; exit 1; }
  fi
  echo "$h,$end,$("${metrics[@]}" "$run" "$run.rss")" >> "$csv"
  echo "$ranks ranks: done"
done
{
  echo "## Table 3.4 example 2: halo and migration traffic at ${ranks_list// /, } ranks (run_message_counts.sh)"
  echo
  provenance "$run/run.json"
  echo
  $plot "$here/message_counts.py" "$csv"
} | tee "$out/message_counts.md"
