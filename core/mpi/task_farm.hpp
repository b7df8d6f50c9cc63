#pragma once
// A task farm over MPI ranks: rank 0 hands out task ids one at a time as ranks 1..N-1 ask for
// work (long and short tasks balance themselves) and receives every result as text, in arrival
// order. Used by study evaluations and seed batches. COLLECTIVE over `comm` (size >= 2).
#include <functional>
#include <string>
#include <vector>

#include "core/mpi/comm.hpp"

namespace suite::mpi {

// pending: the ids to run (read on rank 0 only; ids must be >= 0). work: runs one id on a worker
// and returns its result as text. record: called on rank 0 with each result.
void run_task_farm(const Comm& comm, const std::vector<long>& pending, const std::function<std::string(long)>& work,
                   const std::function<void(const std::string&)>& record);

}  // namespace suite::mpi
