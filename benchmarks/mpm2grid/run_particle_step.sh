#!/usr/bin/env bash
# ns per particle-step per core of the full two-species step (P2G of both species, the drag-coupled
# grid solve, walls, G2P with the soil's return mapping), 2D and 3D, lumped drag against the
# consistent PETSc drag (CG and its default preconditioner: SOR since 2026-11-28, Jacobi before),
# on one rank. Scenes: two_species_2d.yaml (160,000 particles at h = 2.5 mm) and
# two_species_3d.yaml (42,240 at h = 1 cm), a water column on a soil bed. Each run stops after
# STEPS steps (time.max_steps); the time is run.json's step phase (no seeding, output or
# checkpoint), over steps x particles. The four configurations are run in turn,
# REPEATS times (interleaved, so that a load change hits all alike); medians and the
# consistent/lumped ratio of each repeat's pair go to particle_step.md.
#   benchmarks/mpm2grid/run_particle_step.sh [MPM2GRID]      (about 3 min on 2 idle cores)
#   env: REPEATS (3), STEPS (60), H2D (2.5 mm), H3D (0.01 m), and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
repeats=${REPEATS:-3} steps=${STEPS:-60}
h2d=${H2D:-2.5 mm} h3d=${H3D:-0.01 m}
work_dir particle_step
csv=$out/particle_step.csv
echo "dimension,drag,spacing,repeat,$("${metrics[@]}" --header)" > "$csv"
for ((r = 1; r <= repeats; r++)); do
  for dim in 2d 3d; do
    h=$h2d && [ $dim = 3d ] && h=$h3d
    for drag in lumped consistent; do
      run=$work/$dim-$drag-$r
      rc=$(run_one "$run" 1 "$here/two_species_$dim.yaml" "drag=$drag" "grid.spacing=$h" "time.max_steps=$steps")
      [ "$rc" = 0 ] || { echo "run $run failed ($rc): $(tail -1 "$run.err")" >&2; exit 1; }
      echo "$dim,$drag,$h,$r,$("${metrics[@]}" "$run" "$run.rss")" >> "$csv"
      echo "$dim $drag h=$h repeat $r: $(tail -1 "$csv" | cut -d, -f15) ns per particle-step"
    done
  done
done
{
  echo "## ns per particle-step (run_particle_step.sh)"
  echo
  provenance "$run/run.json"
  echo
  $plot "$here/plot_particle_step.py" "$csv" "$out/particle_step.png"
} | tee "$out/particle_step.md"
