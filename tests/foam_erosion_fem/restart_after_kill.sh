#!/usr/bin/env bash
# foam-erosion killed in the middle of a coupled run (the whole process group: foam-erosion and
# its interFoam, as a node failure would) and restarted with --restart latest from its output
# folder gives the same erosion.csv, profiles.csv and discharge.csv, byte for byte, as the
# uninterrupted run. So does a run sent SIGTERM (foam-erosion alone, as scancel or the Slurm
# script's time-limit warning would): it stops its interFoam, leaves no process behind, writes
# summary.json with status "stopped" and exits 0 within seconds.
#   restart_after_kill.sh FOAM_EROSION WORK_DIR
set -euo pipefail
bin=$1 work=$2
scene=("reservoir.initial_level=0.368 m" "coupling.morphological_factor=300" "time.end=1.5 s")
rm -rf "$work" && mkdir -p "$work"
"$bin" "${scene[@]}" --out "$work/straight" --log-level warn

setsid "$bin" "${scene[@]}" --out "$work/killed" --log-level warn &
pid=$!
# Waits until the run in folder $1 has saved step $2, then one more second (interFoam runs the next step).
wait_for_step() {
  for _ in $(seq 1200); do
    grep -q "\"step\": $2" "$1/state.json" 2>/dev/null && break
    sleep 0.1
  done
  grep -q "\"step\": $2" "$1/state.json" || { echo "the run in $1 did not reach step $2"; exit 1; }
  sleep 1
}
wait_for_step "$work/killed" 2
kill -KILL -- -"$pid"
wait "$pid" 2>/dev/null || true
[ ! -f "$work/killed/discharge.csv" ] || { echo "the run finished before it was killed"; exit 1; }
"$bin" "${scene[@]}" --out "$work/killed" --restart latest --log-level warn
for f in erosion.csv profiles.csv discharge.csv; do
  cmp "$work/straight/$f" "$work/killed/$f"
done
echo "killed after step 2 and restarted: erosion.csv, profiles.csv and discharge.csv match the uninterrupted run"

setsid "$bin" "${scene[@]}" --out "$work/termed" --log-level warn &
pid=$!
wait_for_step "$work/termed" 1
start=$(date +%s)
kill -TERM "$pid"
rc=0
wait "$pid" || rc=$?
took=$(($(date +%s) - start))
[ "$rc" = 0 ] || { echo "SIGTERM: foam-erosion exited $rc, not 0"; exit 1; }
[ "$took" -le 20 ] || { echo "SIGTERM: foam-erosion took $took s to stop"; exit 1; }
if pgrep -g "$pid" > /dev/null; then echo "SIGTERM: processes of the run are still alive:"; pgrep -a -g "$pid"; exit 1; fi
grep -q '"status": "stopped"' "$work/termed/summary.json" || { echo "SIGTERM: summary.json does not say stopped"; exit 1; }
grep -q '"step": 1' "$work/termed/state.json" || { echo "SIGTERM: state.json moved past step 1"; exit 1; }
"$bin" "${scene[@]}" --out "$work/termed" --restart latest --log-level warn
for f in erosion.csv profiles.csv discharge.csv; do
  cmp "$work/straight/$f" "$work/termed/$f"
done
echo "SIGTERM during step 2: stopped in $took s with nothing left running; the restart matches the uninterrupted run"

# The finished run restarts only with its own scene: a changed soil or a finished end is refused
# (one line, exit 2, naming the key); a later time.end extends it, its first rows unchanged.
expect=$(dirname "$0")/../support/expect_input_error.sh
"$expect" "was written for another scene|soil.erodibility" \
  "$bin" "${scene[@]}" "soil.erodibility=30 cm^3/(N s)" --out "$work/termed" --restart latest
"$expect" "time.end|give a later time.end" "$bin" "${scene[@]}" --out "$work/termed" --restart latest
extended=("${scene[@]:0:2}" "time.end=2 s")
"$bin" "${extended[@]}" --out "$work/termed" --restart latest --log-level warn
grep -q '"status": "finished"' "$work/termed/summary.json" || { echo "the extended run did not finish"; exit 1; }
rows=$(wc -l < "$work/straight/erosion.csv")
head -n "$rows" "$work/termed/erosion.csv" | cmp - "$work/straight/erosion.csv" ||
  { echo "extending the run changed its first 1.5 s"; exit 1; }
[ "$(wc -l < "$work/termed/erosion.csv")" -gt "$rows" ] || { echo "the extension added no erosion step"; exit 1; }
echo "a changed soil and a finished end were refused; time.end 1.5 -> 2 s extended the run"
