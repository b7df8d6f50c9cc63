#!/usr/bin/env bash
# The dissertation's Table 3.2 runtime study (data/dissertation_table_3_2_openfoam_runtimes.csv)
# next to the same case with adaptive time steps: 4 s of overtopping flow over the Table 3.4 dam
# (table_3_2_dam.yaml: the flows, the dam and why), inlet laws f1 (sine) and f2 (constant), fixed
# deltaT from 1e-3 down to 1e-4 s, on 1..N ranks, written every 0.05 s as there. Per run: flow
# cells, steps, interFoam wall time, and the water volume over the crest and the toe in the 4 s
# (accuracy, against the 1-rank deltaT = 1e-4 run of the same flow). The CSV keeps every run;
# plot_table_3_2.py draws wall time against deltaT beside the dissertation's and prints the table.
#   benchmarks/foam_erosion_fem/run_table_3_2.sh [BUILD_DIR]
#   FLOWS="f1 f2" DTS="1e-3 5e-4 2e-4 1e-4" RANKS="1 2" REPEATS=1 CELL=0.25 COURANT="0.5 0.25"
#   (the defaults; COURANT: the maxCo (and maxAlphaCo) of the adaptive runs; OUT: results folder;
#   APPEND=1 adds the runs to an existing table_3_2.csv, to run the study in parts)
# About 45 min on 2 cores with the defaults (the deltaT = 1e-4 runs take 6 min each).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
here=$root/benchmarks/foam_erosion_fem
flows=${FLOWS:-f1 f2} dts=${DTS:-1e-3 5e-4 2e-4 1e-4} ranks_list=${RANKS:-1 2} repeats=${REPEATS:-1}
cell=${CELL:-0.25} courants=${COURANT:-0.5 0.25}
out=${OUT:-$root/benchmarks/results/foam_erosion_fem}
mkdir -p "$out"
csv=$out/table_3_2.csv
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
declare -A inflow=(
  [f1]="inflow={type: sine, peak: 4 m^3/s, period: 10 s}"      # q = 4 m x (0.5 + 0.5 sin(0.2 pi t)) m/s
  [f2]="inflow={type: constant, discharge: 16 m^3/s}"          # q = 4 m x 4 m/s
)
header="flow,dt_s,ranks,repeat,cell_size_m,$(/usr/bin/python3 "$here/run_metrics.py" --header)"
if [ -n "${APPEND:-}" ] && [ -f "$csv" ]; then
  [ "$(head -1 "$csv")" = "$header" ] || { echo "$csv has other columns; run without APPEND"; exit 1; }
else
  echo "$header" > "$csv"
fi
for ((r = 1; r <= repeats; r++)); do
  for flow in $flows; do
    for ranks in $ranks_list; do
      for dt in $(printf "adaptive-%s " $courants) $dts; do
        run=$work/$flow-$dt-$ranks
        rm -rf "$run"
        case $dt in
          adaptive-*) step=("time.max_courant=${dt#adaptive-}" "time.max_alpha_courant=${dt#adaptive-}") ;;
          *) step=("time.fixed_dt=$dt s") ;;
        esac
        "$build/bin/foam-erosion" "$here/table_3_2_dam.yaml" "${inflow[$flow]}" "run.ranks=$ranks" "${step[@]}" \
          "mesh.cell_size=$cell m" "mesh.far_cell_size=$(awk "BEGIN { print 3 * $cell }") m" --out "$run" --log-level warn
        echo "$flow,$dt,$ranks,$r,$cell,$(/usr/bin/python3 "$here/run_metrics.py" "$run")" >> "$csv"
        tail -1 "$csv"
      done
    done
  done
done
/usr/bin/python3 "$here/plot_table_3_2.py" "$csv" "$root/data/dissertation_table_3_2_openfoam_runtimes.csv" \
  "$out/table_3_2.png" | tee "$out/table_3_2.md"
