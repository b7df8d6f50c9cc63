#pragma once
// When a long run writes a checkpoint: every N steps, every M minutes of wall time, and
// whenever a signal asks for one (see run/signals.hpp). The wall clock is read on rank 0 only
// and the decision is reduced over the ranks, so every rank agrees without synchronised clocks.
//
// Scene keys (section `checkpoint`, all optional):
//   every_steps: 500      # 0: off
//   every: 30 min         # wall time between checkpoints; 0: off
//   keep: 2               # newest checkpoints kept on disk
#include <functional>
#include <optional>
#include <string>

#include "core/config/config.hpp"
#include "core/mpi/comm.hpp"
#include "core/run/signals.hpp"

namespace suite::checkpoint {

struct ScheduleSettings {
  long long every_steps = 0;   // 0: off
  double every_seconds = 0.0;  // wall-clock seconds; 0: off
  int keep = 2;

  // Reads the keys above from `section` (defaults as given); InputError for bad values.
  static ScheduleSettings read(const config::Section& section, const ScheduleSettings& defaults);
};

class Schedule {
 public:
  using Clock = std::function<double()>;  // monotonic seconds; the default is steady_clock
  explicit Schedule(ScheduleSettings settings, Clock clock = {});

  // True if a checkpoint is due after `step`: by step count, by wall time since the last
  // checkpoint (rank 0's clock), or because `signal` (already agreed over ranks) asks for one.
  // COLLECTIVE.
  bool due(const mpi::Comm& comm, long long step, SignalRequest signal);
  // Restarts the wall-time interval; call after every checkpoint, whatever its cause.
  void written();
  const ScheduleSettings& settings() const { return settings_; }

 private:
  ScheduleSettings settings_;
  Clock clock_;
  double last_ = 0.0;
};

// The end of every step of a checkpointing run: writes a checkpoint through `write` (and restarts
// the schedule's interval) when the schedule or `signal` asks for one or the run's step budget is
// spent (`budget_spent` says which budget), then returns why the run must stop now, if it must:
// a signal to checkpoint and stop, or the spent budget. `signal` is the request already agreed
// over the ranks (SignalWatcher::poll). COLLECTIVE.
std::optional<std::string> checkpoint_or_stop(const mpi::Comm& comm, Schedule& schedule, long long step,
                                              SignalRequest signal, const std::optional<std::string>& budget_spent,
                                              const std::function<void()>& write);

}  // namespace suite::checkpoint
