#!/usr/bin/env bash
# foam-erosion killed in the middle of a coupled run (the whole process group: foam-erosion and
# its interFoam, as a node failure or Slurm's time limit would) and restarted with
# --restart latest from its output folder gives the same erosion.csv, profiles.csv and
# discharge.csv, byte for byte, as the uninterrupted run.
#   restart_after_kill.sh FOAM_EROSION WORK_DIR
set -euo pipefail
bin=$1 work=$2
scene=("reservoir.initial_level=0.368 m" "coupling.morphological_factor=300" "time.end=1.5 s")
rm -rf "$work" && mkdir -p "$work"
"$bin" "${scene[@]}" --out "$work/straight" --log-level warn

setsid "$bin" "${scene[@]}" --out "$work/killed" --log-level warn &
pid=$!
# Kill it once step 2 is saved, while interFoam runs step 3.
for _ in $(seq 1200); do
  grep -q '"step": 2' "$work/killed/state.json" 2>/dev/null && break
  sleep 0.1
done
grep -q '"step": 2' "$work/killed/state.json" || { echo "the run did not reach step 2"; exit 1; }
sleep 1
kill -KILL -- -"$pid"
wait "$pid" 2>/dev/null || true
[ ! -f "$work/killed/discharge.csv" ] || { echo "the run finished before it was killed"; exit 1; }
"$bin" "${scene[@]}" --out "$work/killed" --restart latest --log-level warn
for f in erosion.csv profiles.csv discharge.csv; do
  cmp "$work/straight/$f" "$work/killed/$f"
done
echo "killed after step 2 and restarted: erosion.csv, profiles.csv and discharge.csv match the uninterrupted run"
