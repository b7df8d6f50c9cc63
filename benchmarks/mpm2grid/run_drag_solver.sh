#!/usr/bin/env bash
# The consistent drag's Krylov solve (solvers/mpm2grid/coupling/consistent_drag.hpp): CG with each
# preconditioner of PCS on Table 3.4 example 2 with `drag: consistent`. drag_solver.py tabulates.
# 1. Iterations, the most a velocity component took in a step (deterministic), over the first
#    STEPS steps at h = H, on each rank count of RANKS (more ranks than cores: oversubscribed, the
#    counts hold), with the solve's rows on the coupled nodes' owners and in equal shares
#    (decomposition.drag_rows). A CG iteration costs two reductions and one halo exchange over
#    all the ranks, whatever the preconditioner.
# 2. Time on one rank, medians of REPEATS interleaved runs: the grid solve phase (the matrix's
#    assembly and the solve) and the step, over the STEPS steps at h = H and from rest to LONG_END
#    at h = LONG_H (the coupled region grown over the run).
#   benchmarks/mpm2grid/run_drag_solver.sh [MPM2GRID]     (about 8 min on 2 cores at the defaults)
#   env: PCS ("jacobi sor pbjacobi"), H (0.025 m), STEPS (60), RANKS ("1 2 16"), REPEATS (3),
#        LONG_H (0.1 m), LONG_END (1.5 s), and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
pcs=${PCS:-jacobi sor pbjacobi} h=${H:-0.025 m} steps=${STEPS:-60} ranks_list=${RANKS:-1 2 16}
repeats=${REPEATS:-3} long_h=${LONG_H:-0.1 m} long_end=${LONG_END:-1.5}
scene=$scenes/table_3_4_example2.yaml
common=(drag=consistent "time.output=1000 s" "time.series=1000 s")
work_dir drag_solver
for ranks in $ranks_list; do
  for rows in owners balanced; do
    [ "$ranks" = 1 ] && [ "$rows" = balanced ] && continue
    for pc in $pcs; do
      run=$work/iterations-$pc-$rows-r$ranks
      check_run "$(run_one "$run" "$ranks" "$scene" "grid.spacing=$h" "time.max_steps=$steps" "${common[@]}" \
        "decomposition.drag_rows=$rows" "petsc_options=-drag_pc_type $pc")" "$run"
    done
  done
  echo "$ranks ranks: iterations done"
done
for ((r = 1; r <= repeats; r++)); do
  for pc in $pcs; do
    run=$work/short-$pc-$r
    check_run "$(run_one "$run" 1 "$scene" "grid.spacing=$h" "time.max_steps=$steps" "${common[@]}" \
      "petsc_options=-drag_pc_type $pc")" "$run"
    run=$work/long-$pc-$r
    check_run "$(run_one "$run" 1 "$scene" "grid.spacing=$long_h" "time.end=$long_end s" "${common[@]}" \
      "petsc_options=-drag_pc_type $pc")" "$run"
  done
  echo "repeat $r done"
done
{
  echo "## The consistent drag's Krylov solve: CG's preconditioners on example 2 (run_drag_solver.sh)"
  echo
  provenance "$run/run.json"
  echo
  $plot "$here/drag_solver.py" "$work" "$h" "$steps" "$long_h" "$long_end" "$pcs" $ranks_list
} > "$out/drag_solver.md"
echo "wrote $out/drag_solver.md"
