#include "core/run/phase_timers.hpp"

#include <nlohmann/json.hpp>
#include <set>

namespace suite {

void PhaseTimers::add(const std::string& phase, double seconds) { add(phase, seconds, 1); }

void PhaseTimers::add(const std::string& phase, double seconds, long long calls) {
  auto& t = totals_[phase];
  t.seconds += seconds;
  t.calls += calls;
}

double PhaseTimers::seconds(const std::string& phase) const {
  auto it = totals_.find(phase);
  return it == totals_.end() ? 0.0 : it->second.seconds;
}

nlohmann::json PhaseTimers::reduce_to_json(const mpi::Comm& comm) const {
  // Ranks may have seen different phases: agree on the union of the names (one gather), then
  // reduce all phases at once (four reductions, whatever the number of phases).
  std::string mine;
  for (const auto& [name, t] : totals_) mine += name + '\n';
  std::set<std::string> names;
  for (const auto& list : comm.all_gather(mine)) {
    for (std::size_t start = 0, nl; (nl = list.find('\n', start)) != std::string::npos; start = nl + 1)
      names.insert(list.substr(start, nl - start));
  }
  std::vector<double> sum, min, max, calls;
  for (const auto& name : names) {
    auto it = totals_.find(name);
    const double s = it == totals_.end() ? 0.0 : it->second.seconds;
    sum.push_back(s);
    calls.push_back(it == totals_.end() ? 0.0 : double(it->second.calls));
  }
  min = max = sum;
  comm.all_reduce(sum, mpi::Comm::Reduction::sum);
  comm.all_reduce(min, mpi::Comm::Reduction::min);
  comm.all_reduce(max, mpi::Comm::Reduction::max);
  comm.all_reduce(calls, mpi::Comm::Reduction::max);
  nlohmann::json out = nlohmann::json::object();
  std::size_t i = 0;
  for (const auto& name : names) {
    out[name] = {{"calls", static_cast<long long>(calls[i])},
                 {"min_s", min[i]},
                 {"mean_s", sum[i] / comm.size()},
                 {"max_s", max[i]}};
    ++i;
  }
  return out;
}

}  // namespace suite
