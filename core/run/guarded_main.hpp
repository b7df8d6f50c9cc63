#pragma once
// The error policy of every executable, in one place:
//   InputError   -> one line "error: <message>" on rank 0, exit status 2 (all ranks read the
//                   same input and reach the same verdict, so no rank is left waiting);
//   other errors -> "internal error" on the ranks that saw it, then MPI_Abort on the whole
//                   communicator (exit status 1), because other ranks may be blocked in a
//                   collective call.
// Called by main only.
#include <functional>

#include "core/mpi/comm.hpp"

namespace suite {

int guarded_main(const mpi::Comm& world, const std::function<int()>& body);

}  // namespace suite
