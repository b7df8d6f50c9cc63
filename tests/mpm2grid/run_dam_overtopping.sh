#!/usr/bin/env bash
# Table 3.4 example 2 (solvers/mpm2grid/scenes/table_3_4_example2.yaml) at 7.5 cells per dam
# height (grid.spacing 0.5 m) for 10 s: the inlet fills the reservoir, the water overtops the dam
# and leaves through the outlet. check_dam_run.py checks mass balance, the inflow, the outflow
# record, erosion and the crest profile. The inlet's q = 2 m/s * 7.25 m = 14.5 m^2/s; one layer
# of inflow is rho s H = 1000 kg/m^3 * 0.25 m * 7.25 m = 1812.5 kg per metre.
#   run_dam_overtopping.sh MPM2GRID SCENE WORKDIR PYTHON
set -euo pipefail
bin=$1 scene=$2 work=$3 python=$4
rm -rf "$work"
"$bin" "$scene" --out "$work" "grid.spacing=0.5 m" time.end=10s time.output=2s --log-level warn
"$python" "$(dirname "$0")/check_dam_run.py" "$work" 14.5 1812.5
