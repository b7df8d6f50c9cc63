#!/usr/bin/env bash
# The sand pile (scenes/sand_pile.yaml, friction 30 deg) with flanks at 27 and 33 deg, checked by
# check_sand_pile.py.
#   run_sand_pile.sh EXE SCENE WORK_DIR PYTHON
set -euo pipefail
exe=$1 scene=$2 work=$3 python=$4
rm -rf "$work" && mkdir -p "$work"
for angle in 27 33; do
  slope=$("$python" -c "import math; print(math.tan(math.radians($angle)))")
  "$exe" "$scene" "soil.regions.0.trapezoid.upstream_slope=$slope" "soil.regions.0.trapezoid.downstream_slope=$slope" \
    --out "$work/flank_$angle" --log-level warn
done
"$python" "$(dirname "$0")/check_sand_pile.py" 30 "$work/flank_27" "$work/flank_33"
