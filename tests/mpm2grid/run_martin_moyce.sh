#!/usr/bin/env bash
# The embedded water-column scene at 8, 16 (the scene's own) and 32 cells across the column,
# checked against Martin & Moyce (1952) and for convergence in h (check_martin_moyce.py).
#   run_martin_moyce.sh MPM2GRID REFERENCE_CSV WORKDIR PYTHON
set -euo pipefail
bin=$1 reference=$2 work=$3 python=$4
rm -rf "$work"
runs=()
for cells in 8 16 32; do
  h=$(awk -v n="$cells" 'BEGIN { printf "%.10g", 57.15 / n }')
  "$bin" --out "$work/a_over_$cells" "grid.spacing=$h mm" --log-level warn
  runs+=("$work/a_over_$cells")
done
"$python" "$(dirname "$0")/check_martin_moyce.py" "$reference" 0.22 0.10 0.6 3.0 "${runs[@]}"
