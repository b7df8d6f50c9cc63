#!/usr/bin/env bash
# Rebalancing by diffusion against a fresh METIS partition (decomposition.repartition: diffuse /
# fresh; solvers/mpm2grid/decomposition/diffuse_partition.hpp), on Table 3.4 example 2 at h = H
# from rest to END, on each rank count of RANKS (more ranks than cores: oversubscribed, so the
# counts mean what they would on a cluster): rebalances, the particles they moved, rank 0's
# time finding the new owners, the halo traffic per step (the parts' shapes) and the particles
# per rank at the end. Then, diffusing at SWEEP_RANKS ranks, each
# decomposition.imbalance of IMBALANCES: how far the most loaded rank's particle-steps of each
# species stay above the mean over the run against what the rebalances cost. rebalance.py
# tabulates.
#   benchmarks/mpm2grid/run_rebalance.sh [MPM2GRID]     (about 15 min on 2 cores at the defaults)
#   env: H (0.025 m), END (0.1 s), RANKS ("8 16 32"; at 2 and 4 ranks no rebalance is due by 0.1 s),
#        SWEEP_RANKS (16), IMBALANCES ("1.1 1.05 1.03"), and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
h=${H:-0.025 m} end=${END:-0.1} ranks_list=${RANKS:-8 16 32} sweep_ranks=${SWEEP_RANKS:-16} imbalances=${IMBALANCES:-1.1 1.05 1.03}
scene=$scenes/table_3_4_example2.yaml
work_dir rebalance
for ranks in $ranks_list; do
  for mode in diffuse fresh; do
    run=$work/$mode-r$ranks
    rc=$(run_one "$run" "$ranks" "$scene" "grid.spacing=$h" "time.end=$end s" "time.output=1000 s" \
      "time.series=1000 s" "decomposition.repartition=$mode")
    [ "$rc" = 0 ] || { echo "run $run failed ($rc): $(tail -2 "$run.err")" >&2; exit 1; }
    echo "$ranks ranks, $mode: done"
  done
done
for imbalance in $imbalances; do
  run=$work/imbalance$imbalance-r$sweep_ranks
  rc=$(run_one "$run" "$sweep_ranks" "$scene" "grid.spacing=$h" "time.end=$end s" "time.output=1000 s" \
    "time.series=1000 s" decomposition.repartition=diffuse "decomposition.imbalance=$imbalance")
  [ "$rc" = 0 ] || { echo "run $run failed ($rc): $(tail -2 "$run.err")" >&2; exit 1; }
  echo "$sweep_ranks ranks, imbalance $imbalance: done"
done
{
  echo "## Rebalancing by diffusion against fresh METIS partitions: example 2 at h = $h, 0 to $end s (run_rebalance.sh)"
  echo
  provenance "$run/run.json"
  echo
  $plot "$here/rebalance.py" "$work" "$sweep_ranks" "$imbalances" $ranks_list
} | tee "$out/rebalance.md"
