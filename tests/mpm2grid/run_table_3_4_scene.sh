#!/usr/bin/env bash
# One Table 3.4 scene (solvers/mpm2grid/scenes/table_3_4_*.yaml) as shipped: the demo resolution,
# the published 20 s. check_dam_run.py checks mass balance, the inflow, the outflow record, the
# erosion and the crest profile, and, given the scene, that the dam stands as built (crest within
# 1% of its height) until the water reaches the crest. The inlet's discharge and one inflow layer
# come from the scene: rows = the lattice rows whose centres lie below the inlet's height
# (boundary/inlet.hpp), q = velocity * rows * s, a layer = rho_w * s * rows * s, with s the
# particle spacing h / particles_per_cell.
#   run_table_3_4_scene.sh MPM2GRID SCENE WORKDIR PYTHON
set -euo pipefail
bin=$1 scene=$2 work=$3 python=$4
rm -rf "$work"
"$bin" "$scene" --out "$work" --log-level warn
read -r q layer < <("$python" - "$scene" <<'PY'
import math, re, sys, yaml
sc = yaml.safe_load(open(sys.argv[1]))
number = lambda v: float(re.match(r"\s*([-+0-9.eE]+)", str(v)).group(1))
s = number(sc["grid"]["spacing"]) / sc["grid"]["particles_per_cell"]
height, velocity = number(sc["inlet"]["height"]), number(sc["inlet"]["velocity"])
rows = math.ceil(height / s - 0.5 - 1e-9)
print(velocity * rows * s, 1000.0 * s * rows * s)
PY
)
"$python" "$(dirname "$0")/check_dam_run.py" "$work" "$q" "$layer" "$scene"
