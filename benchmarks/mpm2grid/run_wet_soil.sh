#!/usr/bin/env bash
# Where the consistent drag's rows live over the ranks (docs/mpm2grid.md, "Over several ranks"):
# decomposition.balance_wet_soil (the wet soil as a third balance quantity) and
# decomposition.drag_rows (the owners' rows or equal shares), on Table 3.4 example 2 with
# `drag: consistent`, in each combination of CONFIGS. wet_soil.py tabulates.
# 1. Counts (deterministic) over the first STEPS steps at h = H on each rank count of RANKS (more
#    ranks than cores: oversubscribed, the counts hold): the coupled nodes the busiest rank owns
#    and solves against the mean, CG iterations, halo bytes and messages a step, the particles'
#    and the wet soil's imbalance.
# 2. Time on 2 ranks, REPEATS interleaved rounds of every configuration: the grid solve phase
#    (with the drag's rows, exchange and Krylov seconds of the busiest rank) and the step, over
#    the STEPS steps at h = H and from rest to LONG_END at h = LONG_H (the coupled region grown
#    over the run).
#   benchmarks/mpm2grid/run_wet_soil.sh [MPM2GRID]     (about 10 min on 2 cores at the defaults)
#   env: H (0.025 m), STEPS (60), RANKS ("2 16"), REPEATS (3), LONG_H (0.1 m), LONG_END (3 s),
#        CONFIGS (WET:ROWS pairs, "true:auto true:owners false:owners true:balanced false:balanced";
#        the first is the default) and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
h=${H:-0.025 m} steps=${STEPS:-60} ranks_list=${RANKS:-2 16} repeats=${REPEATS:-3} long_h=${LONG_H:-0.1 m}
long_end=${LONG_END:-3} configs=${CONFIGS:-true:auto true:owners false:owners true:balanced false:balanced}
scene=$scenes/table_3_4_example2.yaml
common=(drag=consistent "time.output=1000 s" "time.series=1000 s")
work_dir wet_soil
# The scene keys of configuration WET:ROWS.
keys() { echo "decomposition.balance_wet_soil=${1%:*} decomposition.drag_rows=${1#*:}"; }
for ranks in $ranks_list; do
  for c in $configs; do
    run=$work/counts-${c/:/-}-r$ranks
    # shellcheck disable=SC2046
    check_run "$(run_one "$run" "$ranks" "$scene" "grid.spacing=$h" "time.max_steps=$steps" "${common[@]}" \
      $(keys "$c"))" "$run"
  done
  echo "$ranks ranks: counts done"
done
for ((r = 1; r <= repeats; r++)); do
  for c in $configs; do
    run=$work/short-${c/:/-}-$r
    # shellcheck disable=SC2046
    check_run "$(run_one "$run" 2 "$scene" "grid.spacing=$h" "time.max_steps=$steps" "${common[@]}" $(keys "$c"))" \
      "$run"
    run=$work/long-${c/:/-}-$r
    # shellcheck disable=SC2046
    check_run "$(run_one "$run" 2 "$scene" "grid.spacing=$long_h" "time.end=$long_end s" "${common[@]}" \
      $(keys "$c"))" "$run"
  done
  echo "repeat $r done"
done
{
  echo "## The consistent drag's rows over the ranks: the wet soil balanced, the rows in equal shares (run_wet_soil.sh)"
  echo
  provenance "$run/run.json"
  echo
  $plot "$here/wet_soil.py" "$work" "$h" "$steps" "$long_h" "$long_end" "$ranks_list" $configs
} > "$out/wet_soil.md"
echo "wrote $out/wet_soil.md"
