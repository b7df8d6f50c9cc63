#!/usr/bin/env bash
# Stops the private Slurm started by slurm_up.sh STATE_DIR (and munged if it started it).
set -uo pipefail
STATE=${1:?usage: slurm_down.sh STATE_DIR}
[ -d "$STATE" ] || exit 0
export SLURM_CONF=$STATE/slurm.conf
[ "$(id -u)" = 0 ] || exit 0
[ -f "$SLURM_CONF" ] && scontrol shutdown 2>/dev/null
for f in "$STATE/slurmctld.pid" "$STATE/slurmd.pid"; do
  for _ in $(seq 50); do [ -f "$f" ] && kill -0 "$(cat "$f")" 2>/dev/null || break; sleep 0.2; done
  if [ -f "$f" ] && kill -0 "$(cat "$f")" 2>/dev/null; then kill "$(cat "$f")"; fi
done
if [ -f "$STATE/munged.started-here" ] && [ -f /run/munge/munged.pid ]; then
  kill "$(cat /run/munge/munged.pid)" 2>/dev/null
  rm -f "$STATE/munged.started-here"
fi
echo "slurm_down: stopped"
exit 0
