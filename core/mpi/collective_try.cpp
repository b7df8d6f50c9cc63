#include "core/mpi/collective_try.hpp"

#include <fmt/format.h>

namespace suite::mpi {

void agree_on_input_error(const Comm& comm, const std::string& local_problem) {
  const long long mine = local_problem.empty() ? comm.size() : comm.rank();
  const long long first = -comm.max(-mine);  // lowest failing rank, or size if none failed
  if (first == comm.size()) return;
  std::string message = local_problem;
  comm.broadcast(message, static_cast<int>(first));
  throw InputError(comm.size() > 1 && first != 0 ? fmt::format("{} (seen on rank {})", message, first) : message);
}

}  // namespace suite::mpi
