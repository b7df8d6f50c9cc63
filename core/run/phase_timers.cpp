#include "core/run/phase_timers.hpp"

#include <nlohmann/json.hpp>

namespace suite {

void PhaseTimers::add(const std::string& phase, double seconds) {
  auto& t = totals_[phase];
  t.seconds += seconds;
  t.calls += 1;
}

double PhaseTimers::seconds(const std::string& phase) const {
  auto it = totals_.find(phase);
  return it == totals_.end() ? 0.0 : it->second.seconds;
}

nlohmann::json PhaseTimers::reduce_to_json(const mpi::Comm& comm) const {
  // Ranks may have seen different phases: agree on the union of names first (rank 0's list,
  // extended by every other rank's, broadcast as one newline-separated string).
  std::string names;
  for (const auto& [name, t] : totals_) names += name + '\n';
  std::string all;
  for (int r = 0; r < comm.size(); ++r) {
    std::string mine = names;
    comm.broadcast(mine, r);
    all += mine;
  }
  std::map<std::string, int> union_names;
  std::size_t start = 0;
  for (std::size_t nl = all.find('\n'); nl != std::string::npos; nl = all.find('\n', start)) {
    union_names[all.substr(start, nl - start)] = 1;
    start = nl + 1;
  }
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, unused] : union_names) {
    auto it = totals_.find(name);
    const double s = it == totals_.end() ? 0.0 : it->second.seconds;
    const long long calls = it == totals_.end() ? 0 : it->second.calls;
    out[name] = {{"calls", comm.max(calls)},
                 {"min_s", comm.min(s)},
                 {"mean_s", comm.sum(s) / comm.size()},
                 {"max_s", comm.max(s)}};
  }
  return out;
}

}  // namespace suite
