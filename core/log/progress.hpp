#pragma once
// One progress line for long runs: step, simulated time, dt, wall time and an ETA from the
// simulated-time rate so far. Printed through the Logger (rank 0), at most every `interval`
// seconds of wall time. Not collective.
#include <chrono>

#include "core/log/logger.hpp"

namespace suite {

class ProgressLine {
 public:
  ProgressLine(Logger& log, double t_start, double t_end, double interval_seconds = 10.0);
  // Prints if the interval has passed (or `force`). Times in seconds of simulated time.
  void report(long long step, double t, double dt, bool force = false);
  // Estimated wall seconds to reach t_end, from the rate since construction; < 0 if unknown.
  double eta_seconds(double t) const;

 private:
  using clock = std::chrono::steady_clock;
  Logger& log_;
  double t_start_, t_end_, interval_;
  clock::time_point wall_start_, last_print_;
};

}  // namespace suite
