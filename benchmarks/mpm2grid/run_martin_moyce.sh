#!/usr/bin/env bash
# Speed against accuracy on the water-column collapse (solvers/mpm2grid/scenes/water_column_collapse.yaml,
# Martin & Moyce 1952): grid.spacing = a / CELLS (a = 0.05715 m, as tests/mpm2grid/run_martin_moyce.sh),
# 0.18 s simulated (T up to 3.3), one rank. Per run: the wall time (run.json's wall_time_s and the
# step phase), the particles, and the front's error against the experiment (the largest and the
# mean relative error over the published points with T <= 3.0) and, in the chart, against the
# finest run (the discretization error alone; the experiment's own offset, an inviscid front
# leading a hand-pulled gate's by 10-19%, does not shrink with h), and the largest error with the
# front started later by the best offset dT (the release time the experiment did not record). Resolutions run in turn,
# REPEATS times; the chart and table (plot_martin_moyce.py) take medians of the times.
#   benchmarks/mpm2grid/run_martin_moyce.sh [MPM2GRID]     (about 2 min on 2 idle cores; CELLS="8 16 32 64" about 12 min)
#   env: REPEATS (3), CELLS ("8 16 32"), REFERENCE (data/martin_moyce_1952_surge_front.csv),
#        and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
repeats=${REPEATS:-3} cells_list=${CELLS:-8 16 32}
reference=${REFERENCE:-$root/data/martin_moyce_1952_surge_front.csv}
[ -f "$reference" ] || { echo "no reference data at $reference (set REFERENCE)" >&2; exit 2; }
work_dir martin_moyce
csv=$out/martin_moyce.csv
echo "cells,spacing_mm,repeat,$("${metrics[@]}" --header),$(/usr/bin/python3 "$here/martin_moyce_front.py" --header)" > "$csv"
for ((r = 1; r <= repeats; r++)); do
  for cells in $cells_list; do
    h=$(awk -v n="$cells" 'BEGIN { printf "%.10g", 57.15 / n }')
    run=$work/a_over_$cells-$r
    rc=$(run_one "$run" 1 "$scenes/water_column_collapse.yaml" "grid.spacing=$h mm" "time.output=1 s")
    [ "$rc" = 0 ] || { echo "run $run failed ($rc): $(tail -2 "$run.err")" >&2; exit 1; }
    echo "$cells,$h,$r,$("${metrics[@]}" "$run" "$run.rss"),$(/usr/bin/python3 "$here/martin_moyce_front.py" "$reference" 3.0 "$run")" >> "$csv"
    echo "a/$cells repeat $r: $(tail -1 "$csv" | cut -d, -f9) s wall, front error $(tail -1 "$csv" | cut -d, -f31)"
  done
done
{
  echo "## Martin & Moyce water column: front error against wall time (run_martin_moyce.sh)"
  echo
  provenance "$run/run.json"
  echo
  $plot "$here/plot_martin_moyce.py" "$csv" "$out/martin_moyce.png"
} | tee "$out/martin_moyce.md"
