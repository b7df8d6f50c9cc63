#include "studies/run/mpi_workers.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"

namespace suite::studies {

namespace {

constexpr int kWorkTag = 11, kResultTag = 12;

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

void send_id(const mpi::Comm& comm, long long id, int to) {
  SUITE_MPI_CHECK(MPI_Send(&id, 1, MPI_LONG_LONG, to, kWorkTag, comm.raw()));
}

}  // namespace

void run_mpi_workers(const mpi::Comm& comm, const std::vector<long>& pending,
                     const std::function<RemoteOutcome(long)>& evaluate,
                     const std::function<void(const RemoteOutcome&)>& record) {
  if (comm.rank() == 0) {
    std::size_t next = 0;
    int busy = 0;
    for (int w = 1; w < comm.size(); ++w) {
      if (next < pending.size()) {
        send_id(comm, pending[next++], w);
        ++busy;
      } else {
        send_id(comm, -1, w);
      }
    }
    while (busy > 0) {
      MPI_Status status;
      SUITE_MPI_CHECK(MPI_Probe(MPI_ANY_SOURCE, kResultTag, comm.raw(), &status));
      int length = 0;
      SUITE_MPI_CHECK(MPI_Get_count(&status, MPI_CHAR, &length));
      std::string text(static_cast<std::size_t>(length), '\0');
      SUITE_MPI_CHECK(
          MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, kResultTag, comm.raw(), MPI_STATUS_IGNORE));
      if (next < pending.size()) {
        send_id(comm, pending[next++], status.MPI_SOURCE);
      } else {
        send_id(comm, -1, status.MPI_SOURCE);
        --busy;
      }
      record(decode(text));
    }
  } else {
    for (;;) {
      long long id = 0;
      SUITE_MPI_CHECK(MPI_Recv(&id, 1, MPI_LONG_LONG, 0, kWorkTag, comm.raw(), MPI_STATUS_IGNORE));
      if (id < 0) break;
      const std::string text = encode(evaluate(static_cast<long>(id)));
      SUITE_MPI_CHECK(MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, kResultTag, comm.raw()));
    }
  }
  comm.barrier();
}

}  // namespace suite::studies
