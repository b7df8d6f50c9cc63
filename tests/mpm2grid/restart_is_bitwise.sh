#!/usr/bin/env bash
# An mpm2grid run stopped twice (time.max_steps) and continued with --restart latest produces
# exactly the same outputs as an uninterrupted run: summary.json, series.csv, profiles.csv, the
# XDMF series and the data of every particle file (h5diff). A SIGTERM mid-run checkpoints and
# stops, and its restart matches too. The scene is the embedded water column, shortened, or the
# scene file and overrides given (e.g. a dam scene with an active inlet); SIGNAL_END is the end
# time of the SIGTERM run ("none": skip it). The signal goes as soon as the run has written its
# second particle file (time.output), early in a run that takes about 1.4 s on one core: a run
# that completed before the signal fails the test.
#   restart_is_bitwise.sh WORK_DIR EXE [SIGNAL_END [SCENE_FILE OVERRIDES...]]
# LAUNCH (environment), if set, prefixes every run, e.g. "mpiexec -n 2": the same on 2 ranks.
set -euo pipefail
work=$1 exe=$2 signal_end=${3:-0.5s}
if [ $# -gt 3 ]; then
  scene=("${@:4}" checkpoint.every_steps=100000)
else
  scene=(time.end=0.05s time.output=0.01s checkpoint.every_steps=100000)
fi
rm -rf "$work" && mkdir -p "$work"
same() { "$(dirname "$0")/same_outputs.sh" "$1" "$2"; }
${LAUNCH:-} "$exe" --out "$work/straight" "${scene[@]}" --log-level warn
${LAUNCH:-} "$exe" --out "$work/pieces" "${scene[@]}" --log-level warn time.max_steps=137
grep -q '"status": "stopped: time.max_steps = 137"' "$work/pieces/run.json"
${LAUNCH:-} "$exe" --out "$work/pieces" "${scene[@]}" --log-level warn --restart latest time.max_steps=300
${LAUNCH:-} "$exe" --out "$work/pieces" "${scene[@]}" --log-level warn --restart latest
grep -q '"status": "completed"' "$work/pieces/run.json"
same "$work/straight" "$work/pieces"
echo "restarted twice (steps 137, 437): outputs identical to the uninterrupted run"

[ "$signal_end" = none ] && exit 0
# SIGTERM (a Slurm time limit) mid-run: checkpoint and stop, then restart.
${LAUNCH:-} "$exe" --out "$work/signal" "${scene[@]}" time.end=$signal_end >"$work/signal.log" 2>&1 &
pid=$!
for _ in $(seq 6000); do [ "$(ls "$work/signal/particles" 2>/dev/null | wc -l)" -ge 2 ] && break; sleep 0.01; done
kill -TERM $pid
wait $pid || true
grep -q '"status": "stopped: checkpoint and stop (SIGTERM/SIGINT)"' "$work/signal/run.json"
${LAUNCH:-} "$exe" --out "$work/signal" "${scene[@]}" time.end=$signal_end --restart latest --log-level warn
${LAUNCH:-} "$exe" --out "$work/signal_straight" "${scene[@]}" time.end=$signal_end --log-level warn
same "$work/signal_straight" "$work/signal"
echo "SIGTERM checkpointed and stopped; the restart matched the uninterrupted run"
