#pragma once
// Study evaluations spread over MPI ranks (docs/methods/studies.md, "Execution"): rank 0 hands out
// evaluation ids one at a time as ranks 1..N-1 ask for work (so long and short evaluations
// balance themselves) and is the only rank that writes the ledger; each worker evaluates and
// sends back its outcome. COLLECTIVE over `comm` (size >= 2).
#include <functional>
#include <string>
#include <vector>

#include "core/mpi/comm.hpp"
#include "studies/model/model.hpp"

namespace suite::studies {

struct RemoteOutcome {
  long eval_id = 0;
  Outcome outcome;
  double wall_s = 0.0;
  std::string host;
};

// pending: the ids to run (rank 0; ignored elsewhere). evaluate: runs one id (workers).
// record: called on rank 0 for every outcome, in arrival order.
void run_mpi_workers(const mpi::Comm& comm, const std::vector<long>& pending,
                     const std::function<RemoteOutcome(long)>& evaluate,
                     const std::function<void(const RemoteOutcome&)>& record);

}  // namespace suite::studies
