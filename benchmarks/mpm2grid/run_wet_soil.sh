#!/usr/bin/env bash
# The wet soil as a third balance quantity (decomposition.balance_wet_soil; docs/mpm2grid.md,
# "Over several ranks") on Table 3.4 example 2 with `drag: consistent`, on and off. wet_soil.py
# tabulates.
# 1. Counts (deterministic) over the first STEPS steps at h = H on each rank count of RANKS (more
#    ranks than cores: oversubscribed, the counts hold): the coupled nodes the busiest rank owns
#    against the mean, CG iterations, halo bytes and messages a step, the particles' and the wet
#    soil's imbalance.
# 2. Time on 2 ranks, REPEATS interleaved pairs: the grid solve phase (with the drag's rows,
#    exchange and Krylov seconds of the busiest rank) and the step, over the STEPS steps at h = H
#    and from rest to LONG_END at h = LONG_H (the coupled region grown over the run).
#   benchmarks/mpm2grid/run_wet_soil.sh [MPM2GRID]     (about 10 min on 2 cores at the defaults)
#   env: H (0.025 m), STEPS (60), RANKS ("2 16"), REPEATS (3), LONG_H (0.1 m), LONG_END (3 s),
#        and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
h=${H:-0.025 m} steps=${STEPS:-60} ranks_list=${RANKS:-2 16} repeats=${REPEATS:-3} long_h=${LONG_H:-0.1 m}
long_end=${LONG_END:-3}
scene=$scenes/table_3_4_example2.yaml
common=(drag=consistent "time.output=1000 s" "time.series=1000 s")
work_dir wet_soil
for ranks in $ranks_list; do
  for wet in true false; do
    run=$work/counts-$wet-r$ranks
    check_run "$(run_one "$run" "$ranks" "$scene" "grid.spacing=$h" "time.max_steps=$steps" "${common[@]}" \
      "decomposition.balance_wet_soil=$wet")" "$run"
  done
  echo "$ranks ranks: counts done"
done
for ((r = 1; r <= repeats; r++)); do
  for wet in true false; do
    run=$work/short-$wet-$r
    check_run "$(run_one "$run" 2 "$scene" "grid.spacing=$h" "time.max_steps=$steps" "${common[@]}" \
      "decomposition.balance_wet_soil=$wet")" "$run"
    run=$work/long-$wet-$r
    check_run "$(run_one "$run" 2 "$scene" "grid.spacing=$long_h" "time.end=$long_end s" "${common[@]}" \
      "decomposition.balance_wet_soil=$wet")" "$run"
  done
  echo "repeat $r done"
done
{
  echo "## The wet soil as a third balance quantity: example 2 with the consistent drag (run_wet_soil.sh)"
  echo
  provenance "$run/run.json"
  echo
  $plot "$here/wet_soil.py" "$work" "$h" "$steps" "$long_h" "$long_end" $ranks_list
} > "$out/wet_soil.md"
echo "wrote $out/wet_soil.md"
