#include "core/checkpoint/schedule.hpp"

#include <chrono>
#include <limits>

namespace suite::checkpoint {

ScheduleSettings ScheduleSettings::read(const config::Section& section, const ScheduleSettings& defaults) {
  ScheduleSettings s;
  s.every_steps = section.integer("every_steps", defaults.every_steps, 0, std::numeric_limits<long long>::max());
  s.every_seconds = section.quantity("every", "s", defaults.every_seconds, config::Range::at_least(0));
  s.keep = static_cast<int>(section.integer("keep", defaults.keep, 1, 1000));
  return s;
}

Schedule::Schedule(ScheduleSettings settings, Clock clock) : settings_(settings), clock_(std::move(clock)) {
  if (!clock_) {
    clock_ = [] { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); };
  }
  last_ = clock_();
}

bool Schedule::due(const mpi::Comm& comm, long long step, SignalRequest signal) {
  const bool by_steps = settings_.every_steps > 0 && step % settings_.every_steps == 0;
  const bool by_time = comm.is_root() && settings_.every_seconds > 0.0 && clock_() - last_ >= settings_.every_seconds;
  return comm.any(by_steps || by_time || signal != SignalRequest::none);
}

void Schedule::written() {
  last_ = clock_();
}

std::optional<std::string> checkpoint_or_stop(const mpi::Comm& comm, Schedule& schedule, long long step,
                                              SignalRequest signal, const std::optional<std::string>& budget_spent,
                                              const std::function<void()>& write) {
  if (schedule.due(comm, step, signal) || budget_spent) {
    write();
    schedule.written();
  }
  if (budget_spent) return budget_spent;
  if (signal == SignalRequest::checkpoint_and_stop) return std::string(describe(signal));
  return std::nullopt;
}

}  // namespace suite::checkpoint
