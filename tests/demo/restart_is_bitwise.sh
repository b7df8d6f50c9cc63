#!/usr/bin/env bash
# A run stopped midway (time.max_steps) and continued with --restart latest produces exactly
# the same outputs as an uninterrupted run: summary.json, discharge.csv, the XDMF series and
# the last field file, compared byte for byte (h5diff for the HDF5 data).
#   restart_is_bitwise.sh WORK_DIR LAUNCHER... -- EXE
set -euo pipefail
work=$1; shift
launcher=()
while [ "$1" != "--" ]; do launcher+=("$1"); shift; done
shift
exe=$1
rm -rf "$work" && mkdir -p "$work"
"${launcher[@]}" "$exe" --out "$work/straight" --log-level warn
# The folder first holds a finished run of another scene: its checkpoints (steps 100, 150) are
# stale for the runs below and must neither be pruned in favour of nor restarted from.
"${launcher[@]}" "$exe" --out "$work/pieces" --log-level warn cells=1000
"${launcher[@]}" "$exe" --out "$work/pieces" --log-level warn time.max_steps=37
grep -q '"status": "stopped: time.max_steps = 37"' "$work/pieces/run.json"
"${launcher[@]}" "$exe" --out "$work/pieces" --log-level warn --restart latest time.max_steps=50
"${launcher[@]}" "$exe" --out "$work/pieces" --log-level warn --restart latest
grep -q '"status": "completed"' "$work/pieces/run.json"
"$(dirname "$0")/same_outputs.sh" "$work/straight" "$work/pieces"
echo "restarted twice (steps 37, 87): outputs identical to the uninterrupted run"
