#!/usr/bin/env bash
# Threads inside a rank on a small machine (docs/methods/mpm2grid.md, "Threads inside a rank"):
# Table 3.4 example 2 at spacing H for STEPS steps, as RANKSxTHREADS configurations, REPEATS times
# interleaved (a load change hits all alike); with BASELINE, another build of mpm2grid (e.g. an
# earlier commit's) runs beside in the same interleaving, so that the two builds' ratios come from
# one run. The time is run.json's step phase on the slowest rank (no seeding or output); threads.py
# writes the medians per configuration and phase to threads.md. The many-core node's runs are
# run_node_scaling.sh's (HYBRID).
#   benchmarks/mpm2grid/run_threads.sh [MPM2GRID]      (about 6 min on 2 idle cores)
#   env: H (0.05 m), STEPS (300), REPEATS (5), CONFIGS ("1x1 1x2 2x1"), BASELINE (none), NAME
#        (threads), MPM_ARGS (more key=value overrides, e.g. free_water_field=true), and
#        common.sh's MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
h=${H:-0.05 m} steps=${STEPS:-300} repeats=${REPEATS:-5} configs=${CONFIGS:-1x1 1x2 2x1} name=${NAME:-threads}
baseline=${BASELINE:-}
read -r -a extra <<< "${MPM_ARGS:-}"
[ -z "$baseline" ] || [ -x "$baseline" ] || { echo "BASELINE=$baseline is not an executable" >&2; exit 2; }
for c in $configs; do
  [[ $c =~ ^[1-9][0-9]*x[1-9][0-9]*$ ]] || { echo "CONFIGS: '$c' is not RANKSxTHREADS, e.g. 1x2" >&2; exit 2; }
done
work_dir "$name"
csv=$out/$name.csv
echo "build,config,ranks,threads,repeat,$("${metrics[@]}" --header)" > "$csv"
builds=(current)
[ -n "$baseline" ] && builds+=(baseline)
current=$bin
for ((r = 1; r <= repeats; r++)); do
  for build in "${builds[@]}"; do
    bin=$current
    [ "$build" = baseline ] && bin=$baseline
    for c in $configs; do
      ranks=${c%x*} threads=${c#*x}
      run=$work/$build-$c-$r
      rc=$(OMP_NUM_THREADS=$threads run_one "$run" "$ranks" "$scenes/table_3_4_example2.yaml" "grid.spacing=$h" \
        "time.max_steps=$steps" "time.output=1000 s" ${extra[@]+"${extra[@]}"})
      [ "$rc" = 0 ] || { echo "run $run failed ($rc): $(tail -1 "$run.err")" >&2; exit 1; }
      echo "$build,$c,$ranks,$threads,$r,$("${metrics[@]}" "$run" "$run.rss")" >> "$csv"
      echo "$build $c repeat $r: step $(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["phases"]["step"]["max_s"])' "$run/run.json") s"
    done
  done
done
bin=$current
first=${configs%% *}
{
  echo "## Threads inside a rank: example 2 at h = $h, $steps steps${MPM_ARGS:+, $MPM_ARGS} (run_threads.sh)"
  echo
  provenance "$work/current-$first-1/run.json"
  [ -n "$baseline" ] && echo "Baseline: $baseline (git $(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1])).get("git_hash"))' "$work/baseline-$first-1/run.json"))."
  echo
  $plot "$here/threads.py" "$csv"
} | tee "$out/$name.md"
