#pragma once
// Wall-clock time per named phase ("p2g", "grid solve", "output"...). A PhaseTimers object is
// owned by the solver (no global registry); ScopedPhase adds the time of one scope to a phase.
// Phases may nest; each phase's total is its own inclusive time.
#include <chrono>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "core/mpi/comm.hpp"

namespace suite {

struct PhaseTotal {
  double seconds = 0.0;
  long long calls = 0;
};

class PhaseTimers {
 public:
  void add(const std::string& phase, double seconds);
  // Adds a total measured elsewhere (`calls` calls that took `seconds` together).
  void add(const std::string& phase, double seconds, long long calls);
  const std::map<std::string, PhaseTotal>& totals() const { return totals_; }
  double seconds(const std::string& phase) const;

  // {"phase": {"calls": n, "min_s": .., "mean_s": .., "max_s": ..}, ...} over the ranks of
  // `comm`; phases missing on a rank count as 0 s there. COLLECTIVE.
  nlohmann::json reduce_to_json(const mpi::Comm& comm) const;

 private:
  std::map<std::string, PhaseTotal> totals_;
};

class ScopedPhase {
 public:
  ScopedPhase(PhaseTimers& timers, std::string phase)
      : timers_(timers), phase_(std::move(phase)), start_(std::chrono::steady_clock::now()) {}
  ~ScopedPhase() {
    timers_.add(phase_, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
  }
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;

 private:
  PhaseTimers& timers_;
  std::string phase_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace suite
