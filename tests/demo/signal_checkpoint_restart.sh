#!/usr/bin/env bash
# What Slurm does to a long job, end to end through mpiexec: SIGUSR1 (the --signal warning)
# makes the run checkpoint and go on; SIGTERM (time limit, preemption) makes it checkpoint and
# stop; a restart from the newest checkpoint then finishes with outputs identical, byte for
# byte, to a run that was never interrupted.
#   signal_checkpoint_restart.sh WORK_DIR LAUNCHER... -- EXE
set -euo pipefail
work=$1; shift
launcher=()
while [ "$1" != "--" ]; do launcher+=("$1"); shift; done
shift
exe=$1
# Enough work (a few seconds on 2 ranks, also on a fast machine: at 200,000 cells a 2-core Xeon VM
# finished the run before mpiexec had passed SIGTERM on) for the signals to land mid-run.
scene=(cells=800000 time.sample=0.0002s time.output=0.3s checkpoint.every_steps=1000000)
rm -rf "$work" && mkdir -p "$work"

"${launcher[@]}" "$exe" --out "$work/pieces" "${scene[@]}" >"$work/pieces.log" 2>&1 &
pid=$!
wait_for() {  # wait_for PATTERN: until the run's log shows it (or 60 s)
  for _ in $(seq 600); do grep -q "$1" "$work/pieces.log" && return 0; sleep 0.1; done
  echo "timed out waiting for '$1'"; cat "$work/pieces.log"; kill $pid; exit 1
}
wait_for "Ritter dam break"
kill -USR1 $pid
wait_for "checkpoint checkpoint_.*written"
kill -TERM $pid
wait $pid || true
cat "$work/pieces.log" | grep -v " step " || true
grep -q '"status": "stopped: checkpoint and stop (SIGTERM, SIGINT or a stop file)"' "$work/pieces/run.json"
n=$(ls "$work/pieces/checkpoints" | grep -c '\.h5$')
[ "$n" = 2 ] || { echo "expected 2 checkpoints (USR1, TERM), found $n"; exit 1; }

"${launcher[@]}" "$exe" --out "$work/pieces" "${scene[@]}" --restart latest --log-level warn
"${launcher[@]}" "$exe" --out "$work/straight" "${scene[@]}" --log-level warn
"$(dirname "$0")/same_outputs.sh" "$work/straight" "$work/pieces"
echo "SIGUSR1 checkpointed, SIGTERM checkpointed and stopped, restart matched the uninterrupted run"
