#include "studies/run/mpi_workers.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/mpi/task_farm.hpp"

namespace suite::studies {

namespace {

std::string encode(const RemoteOutcome& r) {
  auto responses = nlohmann::json::array();
  for (double x : r.outcome.responses) responses.push_back(std::isfinite(x) ? nlohmann::json(x) : nlohmann::json());
  return nlohmann::json{{"id", r.eval_id},        {"ok", r.outcome.ok}, {"reason", r.outcome.reason},
                        {"responses", responses}, {"wall_s", r.wall_s}, {"host", r.host}}
      .dump();
}

RemoteOutcome decode(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  RemoteOutcome r;
  r.eval_id = j.at("id").get<long>();
  r.outcome.ok = j.at("ok").get<bool>();
  r.outcome.reason = j.at("reason").get<std::string>();
  for (const auto& x : j.at("responses")) r.outcome.responses.push_back(x.is_null() ? std::nan("") : x.get<double>());
  r.wall_s = j.at("wall_s").get<double>();
  r.host = j.at("host").get<std::string>();
  return r;
}

}  // namespace

void run_mpi_workers(const mpi::Comm& comm, const std::vector<long>& pending,
                     const std::function<RemoteOutcome(long)>& evaluate,
                     const std::function<void(const RemoteOutcome&)>& record) {
  mpi::run_task_farm(
      comm, pending, [&](long id) { return encode(evaluate(id)); },
      [&](const std::string& text) { record(decode(text)); });
}

}  // namespace suite::studies
