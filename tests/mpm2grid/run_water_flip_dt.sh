#!/usr/bin/env bash
# The water's FLIP share (water.flip, docs/mpm2grid.md "Water: FLIP share") takes the step count
# out of a coarse flow: the embedded water column at 4 cells across its width, run at time.cfl 0.4
# and 0.1, with APIC alone (flip 0) and with flip 0.99, and the same column at 16 cells (APIC,
# converged in dt there) as the reference (check_water_flip_dt.py).
#   run_water_flip_dt.sh MPM2GRID WORKDIR PYTHON
set -euo pipefail
bin=$1 work=$2 python=$3
rm -rf "$work" && mkdir -p "$work"
coarse="grid.spacing=14.2875 mm"  # a / 4
for flip in 0 0.99; do
  for cfl in 0.4 0.1; do
    "$bin" --out "$work/flip${flip}_cfl$cfl" "$coarse" water.flip=$flip time.cfl=$cfl --log-level warn
  done
done
"$bin" --out "$work/reference" --log-level warn  # a / 16
"$python" "$(dirname "$0")/check_water_flip_dt.py" "$work"
