#!/usr/bin/env bash
# Brings up a private single-node Slurm (munge, slurmctld, slurmd on localhost; no systemd,
# no cgroups) for the slurm-labelled tests, from Debian's slurm-wlm and munge packages.
#
#   slurm_up.sh STATE_DIR      writes STATE_DIR/slurm.conf, starts the daemons, waits for the
#                              node to be idle. Clients then need SLURM_CONF=STATE_DIR/slurm.conf.
#
# Everything (config, spool, logs, pid files) lives in STATE_DIR, on private ports, so a
# machine's own Slurm is never touched. Needs root (slurmd starts jobs as their user).
# Exit 0 when up; 77 (CTest's skip code) when not root; 1 with the reason otherwise.
set -euo pipefail
STATE=${1:?usage: slurm_up.sh STATE_DIR}
mkdir -p "$STATE"
STATE=$(cd "$STATE" && pwd)
export SLURM_CONF=$STATE/slurm.conf
T0=$(date +%s.%N)

if [ "$(id -u)" != 0 ]; then
  echo "slurm_up: the local Slurm needs root (slurmd launches jobs as their owner); skipping"
  exit 77
fi
for prog in slurmctld slurmd munged sbatch; do
  command -v $prog >/dev/null || { echo "slurm_up: $prog not found; install slurm-wlm and munge (./suite setup)"; exit 1; }
done

# --- munge: the machine's daemon if it runs, else one started here (never as root) -------
if ! munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1; then
  [ -s /etc/munge/munge.key ] || mungekey --create --keyfile=/etc/munge/munge.key
  chown munge:munge /etc/munge/munge.key
  chmod 0400 /etc/munge/munge.key
  install -d -o munge -g munge -m 0755 /run/munge
  install -d -o munge -g munge -m 0700 /var/lib/munge /var/log/munge
  runuser -u munge -- /usr/sbin/munged
  for _ in $(seq 50); do munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1 && break; sleep 0.1; done
  touch "$STATE/munged.started-here"
fi
# Capture first, then test: `grep -q` stopping early would SIGPIPE the writer under pipefail.
check=$(munge -n </dev/null | unmunge 2>&1 || true)
grep -q 'STATUS: *Success' <<<"$check" || { echo "slurm_up: munge does not work: $check"; exit 1; }

# --- already up? -----------------------------------------------------------------------
if [ -f "$STATE/slurm.conf" ] && scontrol ping 2>/dev/null | grep -q 'is UP'; then
  echo "slurm_up: already running ($SLURM_CONF)"; sinfo; exit 0
fi

# --- slurm.conf: this machine's topology; 90% of its memory (more makes the node INVAL) ---
NODE=localhost
HW=$(slurmd -C)
HW=$(sed -n -e '1{s/^NodeName=[^ ]* //' -e 's/RealMemory=[0-9]*//' -e 's/UpTime=.*//' -e 'p}' <<<"$HW")
MEM=$(( $(awk '/MemTotal/{print int($2/1024)}' /proc/meminfo) * 9 / 10 ))
mkdir -p "$STATE/spool/ctld" "$STATE/spool/d" "$STATE/log"
rm -rf "$STATE"/spool/ctld/* "$STATE"/spool/d/*   # fresh state: no stale DRAIN or jobs
cat > "$SLURM_CONF" <<CONF
# Written by tests/support/slurm/slurm_up.sh: a private single-node test cluster.
ClusterName=suitetest
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
MpiDefault=pmix
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MailProg=/bin/true
StateSaveLocation=$STATE/spool/ctld
SlurmdSpoolDir=$STATE/spool/d
SlurmctldPidFile=$STATE/slurmctld.pid
SlurmdPidFile=$STATE/slurmd.pid
SlurmctldLogFile=$STATE/log/slurmctld.log
SlurmdLogFile=$STATE/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
SlurmctldPort=${SUITE_SLURMCTLD_PORT:-16817}
SlurmdPort=${SUITE_SLURMD_PORT:-16818}
MinJobAge=300
KillWait=10
NodeName=$NODE NodeAddr=127.0.0.1 $HW RealMemory=$MEM State=UNKNOWN
PartitionName=debug Nodes=$NODE Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
CONF

failed_start() {
  echo "slurm_up: $1 did not start; its log ends with:"
  tail -n 15 "$STATE/log/$1.log" 2>/dev/null
  exit 1
}
slurmctld -f "$SLURM_CONF" || failed_start slurmctld
slurmd -f "$SLURM_CONF" -N $NODE || failed_start slurmd
st=""
for _ in $(seq 150); do
  st=$(sinfo -h -N -o '%T' 2>/dev/null | head -1 || true)
  case "$st" in idle) break ;; drain*|down*|inval*) sinfo -R; break ;; esac
  sleep 0.2
done
sinfo
echo "slurm_up: up in $(awk -v a="$T0" -v b="$(date +%s.%N)" 'BEGIN{printf "%.2f", b-a}') s, node $NODE is ${st:-unknown}; SLURM_CONF=$SLURM_CONF"
if [ "$st" != idle ]; then
  echo "slurm_up: node did not become idle; last log lines:"; tail -n 20 "$STATE/log/slurmctld.log" "$STATE/log/slurmd.log"
  exit 1
fi
