#!/usr/bin/env bash
# Speed against accuracy on the dam-overtopping scene (Table 3.4 example 2,
# solvers/mpm2grid/scenes/table_3_4_example2.yaml) over the resolution (grid.spacing 0.5, 0.25,
# 0.125 m) and the drag (lumped against the consistent PETSc drag), for a fixed simulated time
# (END, 10 s: the overtopping flow reaches the outlet at about 7 s): the water volume through the
# outlet and the eroded soil volume (summary.json) against the wall time (run.json). The chart
# (plot_dam_convergence.py) takes the finest lumped run as the reference. Every configuration of
# a repeat runs in turn (the lumped and consistent runs of a resolution back to back);
# the finest resolution, 16x the coarsest's cost per simulated second, runs FINE_REPEATS times.
# SCENE_ARGS adds key=value overrides to every run (separated by ';'), NAME names the outputs:
# the bed-shear closure's erosion (docs/mpm2grid.md, "Bed shear and excess-stress erosion") is
#   NAME=dam_convergence_bed_shear SCENE_ARGS="soil.erosion=excess_stress;soil.erodibility=100 cm^3/(N s);
#   soil.critical_shear_stress=1 Pa;soil.settling_velocity=0.02 m/s;bed_shear.manning_n=0.02"
#   benchmarks/mpm2grid/run_dam_convergence.sh [MPM2GRID]   (about 10-12 min on 2 idle cores, most of it at 0.125 m)
#   env: REPEATS (3), FINE_REPEATS (1), SPACINGS ("0.5 0.25 0.125"), DRAGS ("lumped consistent"), END (10),
#        RANKS (1), SCENE_ARGS (none), NAME (dam_convergence), and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
repeats=${REPEATS:-3} fine_repeats=${FINE_REPEATS:-1} spacings=${SPACINGS:-0.5 0.25 0.125}
drags=${DRAGS:-lumped consistent} end=${END:-10} ranks=${RANKS:-1}
finest=$(printf '%s\n' $spacings | sort -g | head -1)
name=${NAME:-dam_convergence}
IFS=';' read -ra scene_args <<<"${SCENE_ARGS:-}"
work_dir "$name"
csv=$out/$name.csv
echo "spacing_m,drag,repeat,$("${metrics[@]}" --header)" > "$csv"
for ((r = 1; r <= repeats; r++)); do
  for h in $spacings; do
    [ "$h" = "$finest" ] && ((r > fine_repeats)) && continue
    for drag in $drags; do
      run=$work/$h-$drag-$r
      rc=$(run_one "$run" "$ranks" "$scenes/table_3_4_example2.yaml" "grid.spacing=$h m" "drag=$drag" "time.end=$end s" \
        "time.output=1000 s" ${scene_args[@]+"${scene_args[@]}"})
      [ "$rc" = 0 ] || { echo "run $run failed ($rc): $(tail -2 "$run.err")" >&2; exit 1; }
      echo "$h,$drag,$r,$("${metrics[@]}" "$run" "$run.rss")" >> "$csv"
      echo "h=$h $drag repeat $r: $(tail -1 "$csv" | cut -d, -f9) s wall, outflow $(tail -1 "$csv" | cut -d, -f21) m^2, eroded $(tail -1 "$csv" | cut -d, -f22) m^2"
    done
  done
done
{
  echo "## Dam overtopping (Table 3.4 example 2): outflow and eroded volume against wall time (run_dam_convergence.sh${NAME:+, $name})"
  echo
  [ -z "${SCENE_ARGS:-}" ] || { echo "Scene overrides: \`${SCENE_ARGS}\`."; echo; }
  provenance "$run/run.json"
  echo
  $plot "$here/plot_dam_convergence.py" "$csv" "$out/$name.png"
} | tee "$out/$name.md"
