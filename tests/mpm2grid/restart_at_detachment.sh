#!/usr/bin/env bash
# restart_is_bitwise.sh with its two stops just before steps in which the excess-stress erosion
# detaches soil particles from the bed (the run's debug log names those steps). A detached
# particle's F_E becomes I at the start of the step; the run that goes on must then take the
# Kirchhoff stress of that F_E, as the restarted run, which knows no stress of before, does.
#   restart_at_detachment.sh WORK_DIR EXE SCENE_FILE OVERRIDES...
set -euo pipefail
work=$1 exe=$2
shift 2
rm -rf "$work" && mkdir -p "$work"
"$exe" --out "$work/probe" "$@" --log-level debug 2> "$work/probe.log"
mapfile -t steps < <(sed -n 's/.*\[debug\] step \([0-9]*\) (t = .*the erosion detached.*/\1/p' "$work/probe.log" | head -2)
if [ "${#steps[@]}" -lt 2 ]; then
  echo "the scene detached soil particles in ${#steps[@]} steps, 2 needed: make it erode more" >&2
  exit 1
fi
# Stopped after step k - 1, the run restarts into step k, which detaches.
first=$((steps[0] - 1)) second=$((steps[1] - steps[0]))
echo "stops before steps ${steps[0]} and ${steps[1]}, in which particles detach"
STOPS="$first $second" "$(dirname "$0")/restart_is_bitwise.sh" "$work/restart" "$exe" none "$@"
