#!/usr/bin/env bash
# Table 3.4 example 2 (solvers/mpm2grid/scenes/table_3_4_example2.yaml) at the dissertation's
# particle count (grid.spacing = 0.025 m: 432,960 particles at the start against the published
# 475,429) for STEPS steps: seconds per step and per particle-step on 1 and on 2 ranks (strong
# scaling, the two run in turn in every repeat), the particles the inlet adds (series.csv), the
# halo and migration traffic per step (run.json decomposition), the peak resident set size of
# every rank (/usr/bin/time), and the projection to more ranks (table_3_4_scaling.py).
# The run's end time is STEPS steps of the dt a probe run measures (5 steps, time.max_steps), so
# that every run completes: a run stopped by time.max_steps writes no decomposition block and no
# summary.json.
#   benchmarks/mpm2grid/run_table_3_4_scaling.sh [MPM2GRID]    (about 5 min on 2 idle cores)
#   env: REPEATS (3), STEPS (200), H (0.025 m), RANKS ("1 2"), and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
repeats=${REPEATS:-3} steps=${STEPS:-200} h=${H:-0.025 m} ranks_list=${RANKS:-1 2}
scene=$scenes/table_3_4_example2.yaml
work_dir table_3_4_scaling
# The probe: the time after 5 steps, from the stop line.
rc=$(run_one "$work/probe" 1 "$scene" "grid.spacing=$h" time.max_steps=5 "time.output=1000 s" "time.series=1000 s")
t5=$(sed -n 's/.*stopped at step 5 (t = \([0-9.e+-]*\) s).*/\1/p' "$work/probe.err")
[ -n "$t5" ] || { echo "probe failed ($rc): $(tail -2 "$work/probe.err")" >&2; exit 1; }
end=$(awk -v t="$t5" -v n="$steps" 'BEGIN { printf "%.6g", t / 5 * n }')
series=$(awk -v e="$end" 'BEGIN { printf "%.6g", e / 4 }')  # 4 samples: a sample cuts at most one step short
echo "dt ~ $(awk -v t="$t5" 'BEGIN { printf "%.4g", t / 5 }') s at h = $h: time.end = $end s for about $steps steps"
csv=$out/table_3_4_scaling.csv
echo "spacing,end_time_s,repeat,$("${metrics[@]}" --header)" > "$csv"
for ((r = 1; r <= repeats; r++)); do
  for ranks in $ranks_list; do
    run=$work/ranks$ranks-$r
    rc=$(run_one "$run" "$ranks" "$scene" "grid.spacing=$h" "time.end=$end s" "time.series=$series s" "time.output=1000 s")
    [ "$rc" = 0 ] || { echo "run $run failed ($rc): $(tail -2 "$run.err")" >&2; exit 1; }
    echo "$h,$end,$r,$("${metrics[@]}" "$run" "$run.rss")" >> "$csv"
    echo "$ranks rank(s), repeat $r: $(tail -1 "$csv" | cut -d, -f13) s per step"
  done
done
{
  echo "## Table 3.4 example 2 at the published particle count, 1 and 2 ranks (run_table_3_4_scaling.sh)"
  echo
  provenance "$run/run.json"
  echo
  $plot "$here/table_3_4_scaling.py" "$csv" "$out/table_3_4_scaling.png"
} | tee "$out/table_3_4_scaling.md"
