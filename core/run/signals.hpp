#pragma once
// Checkpoint-on-signal for long runs under Slurm.
//
//   SIGUSR1          -> checkpoint now and continue (Slurm's `--signal=USR1@300` warning, or
//                       `scancel --signal=USR1 <job>` for a snapshot on demand)
//   SIGTERM, SIGINT  -> checkpoint now and stop cleanly (Slurm sends SIGTERM at the time limit
//                       and on preemption/requeue, then waits KillWait seconds)
//
// The same requests as files in a folder the run names (its output folder), for a user on a
// login node or a script that cannot signal the job's processes:
//   <folder>/checkpoint_now -> checkpoint now and continue
//   <folder>/stop           -> checkpoint now and stop cleanly
// The run removes the file when it acts on it. Tests use them to stop a run at an exact step.
//
// The handler only sets a flag (async-signal-safe); the solver polls between steps, and the
// poll agrees across ranks, because mpirun/srun may deliver the signal to some ranks only.
// The flag is process-wide by nature (a signal handler has no other place to put it); one
// SignalWatcher at a time owns the handlers and restores the previous ones when destroyed.
#include <filesystem>

#include "core/mpi/comm.hpp"

namespace suite {

enum class SignalRequest { none = 0, checkpoint = 1, checkpoint_and_stop = 2 };

class SignalWatcher {
 public:
  // `request_dir`: the folder watched for the request files above (empty: none).
  explicit SignalWatcher(std::filesystem::path request_dir = {});
  ~SignalWatcher();
  SignalWatcher(const SignalWatcher&) = delete;
  SignalWatcher& operator=(const SignalWatcher&) = delete;

  // The strongest request seen on any rank since the last poll, by signal or by a request file
  // (looked for on rank 0, then removed); clears it. COLLECTIVE.
  SignalRequest poll(const mpi::Comm& comm);
  // The last signal number received (0 if none), for the log.
  int last_signal() const;

 private:
  std::filesystem::path request_dir_;
};

const char* describe(SignalRequest r);

}  // namespace suite
