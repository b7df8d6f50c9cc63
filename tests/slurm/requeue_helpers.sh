# Shell functions for the tests that requeue a job on the private Slurm (demo_requeue.sh,
# foam_erosion_requeue.sh, mpm2grid_requeue.sh). Source this file; SLURM_CONF must be set.

# The job's state: PENDING, RUNNING, COMPLETED, FAILED...
job_state() { scontrol show job "$1" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p'; }

# After the time-limit warning: waits until Slurm has requeued JOB (Restarts=1, PENDING), then
# starts it at once (Slurm holds a requeued job back for a while with a BeginTime).
# The script's own message comes before `scontrol requeue` takes effect, so this waits for
# Slurm's count, not for the message. slurmd refuses a launch whose credential is not newer (in
# whole seconds) than the requeue's revocation ("Job credential revoked", and the job then
# FAILS): a second passes before the release.
release_requeued_job() {
  local job=$1
  for _ in $(seq 600); do
    scontrol show job "$job" | grep -q "Restarts=1" && [ "$(job_state "$job")" = PENDING ] && break
    sleep 0.1
  done
  sleep 2
  scontrol update JobId="$job" StartTime=now || true
}

# Waits until JOB has ended (COMPLETED, FAILED, CANCELLED or TIMEOUT), polling every 0.2 s for at
# most TRIES times; the caller then checks job_state.
wait_for_job_end() {
  local job=$1 tries=$2
  for _ in $(seq "$tries"); do
    case "$(job_state "$job")" in COMPLETED | FAILED | CANCELLED | TIMEOUT) return 0 ;; esac
    sleep 0.2
  done
}
