#!/usr/bin/env bash
# An mpm2grid run stopped twice (time.max_steps) and continued with --restart latest produces
# exactly the same outputs as an uninterrupted run: summary.json, series.csv, profiles.csv, the
# XDMF series and the data of every particle file (h5diff). A stop request mid-run (the stop
# file) checkpoints and stops, and its restart matches too; STOP_FILE "none" skips that part.
# The scene is the embedded water column, shortened, or the scene file and overrides given (e.g.
# a dam scene with an active inlet). Every stop comes at a step count, not a time, so the test
# means the same on a fast machine as on a slow one.
#   restart_is_bitwise.sh WORK_DIR EXE [STOP_FILE [SCENE_FILE OVERRIDES...]]
# LAUNCH (environment), if set, prefixes every run, e.g. "mpiexec -n 2": the same on 2 ranks.
# STOPS (environment), if set, gives the two stops' step counts (default "137 300").
set -euo pipefail
work=$1 exe=$2 stop_file=${3:-stop}
read -r first second <<< "${STOPS:-137 300}"
if [ $# -gt 3 ]; then
  scene=("${@:4}" checkpoint.every_steps=100000)
else
  scene=(time.end=0.05s time.output=0.01s checkpoint.every_steps=100000)
fi
rm -rf "$work" && mkdir -p "$work"
same() { "$(dirname "$0")/same_outputs.sh" "$1" "$2"; }
${LAUNCH:-} "$exe" --out "$work/straight" "${scene[@]}" --log-level warn
${LAUNCH:-} "$exe" --out "$work/pieces" "${scene[@]}" --log-level warn time.max_steps=$first
grep -q "\"status\": \"stopped: time.max_steps = $first\"" "$work/pieces/run.json"
${LAUNCH:-} "$exe" --out "$work/pieces" "${scene[@]}" --log-level warn --restart latest time.max_steps=$second
${LAUNCH:-} "$exe" --out "$work/pieces" "${scene[@]}" --log-level warn --restart latest
grep -q '"status": "completed"' "$work/pieces/run.json"
same "$work/straight" "$work/pieces"
echo "restarted twice (steps $first, $((first + second))): outputs identical to the uninterrupted run"

[ "$stop_file" = none ] && exit 0
# A stop request mid-run: the `stop` file in the output folder (a user's or a script's request;
# the same checkpoint-and-stop as SIGTERM, whose handler tests/core/test_signals.cpp checks).
# It is put there while the run is stopped at step 137, so the run stops at step 138 on any
# machine, however fast; then it restarts and must match the uninterrupted run.
${LAUNCH:-} "$exe" --out "$work/stopped" "${scene[@]}" --log-level warn time.max_steps=137
touch "$work/stopped/stop"
${LAUNCH:-} "$exe" --out "$work/stopped" "${scene[@]}" --log-level warn --restart latest
grep -q '"status": "stopped: checkpoint and stop (SIGTERM, SIGINT or a stop file)"' "$work/stopped/run.json"
[ ! -e "$work/stopped/stop" ] || { echo "the stop file was not removed when acted on"; exit 1; }
ls "$work/stopped/checkpoints" | grep -q 'checkpoint_000000138.h5' ||
  { echo "no checkpoint at step 138:"; ls "$work/stopped/checkpoints"; exit 1; }
${LAUNCH:-} "$exe" --out "$work/stopped" "${scene[@]}" --restart latest --log-level warn
same "$work/straight" "$work/stopped"
echo "the stop file checkpointed and stopped the run at step 138; the restart matched the uninterrupted run"
