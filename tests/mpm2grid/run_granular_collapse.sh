#!/usr/bin/env bash
# Granular column collapse (solvers/mpm2grid/scenes/granular_column_collapse.yaml): the dry,
# cohesionless column runs to rest and check_granular_collapse.py compares its runout with the
# quasi-2D experiments (Lube et al. 2005). Extra arguments are scene overrides (e.g. the tall
# column: soil.regions.0.box.hi=[0.1, 0.3]).
#   run_granular_collapse.sh MPM2GRID SCENE WORKDIR PYTHON [key=value ...]
set -euo pipefail
bin=$1 scene=$2 work=$3 python=$4
shift 4
rm -rf "$work"
"$bin" "$scene" --out "$work" --log-level warn "$@"
"$python" "$(dirname "$0")/check_granular_collapse.py" "$work"
