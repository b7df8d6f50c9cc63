#!/usr/bin/env bash
# The vertical cut of solvers/mpm2grid/scenes/cohesive_cut.yaml (H = 0.2 m, face at x = 0.3 m,
# friction 30 deg in the plane): dry it stands, saturated (soil.regions.0.saturated=true) it
# collapses; check_cohesive_cut.py checks either. Extra arguments are scene overrides.
#   run_cohesive_cut.sh MPM2GRID SCENE WORKDIR PYTHON dry|saturated [key=value ...]
set -euo pipefail
bin=$1 scene=$2 work=$3 python=$4 case=$5
shift 5
rm -rf "$work"
extra=()
[[ $case == saturated ]] && extra=(soil.regions.0.saturated=true)
"$bin" "$scene" --out "$work" --log-level warn "${extra[@]}" "$@"
"$python" "$(dirname "$0")/check_cohesive_cut.py" "$work" "$case" 0.2 0.3 30
