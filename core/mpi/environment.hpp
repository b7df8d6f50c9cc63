#pragma once
// MPI_Init/MPI_Finalize as an object owned by main. Nothing below main calls MPI_COMM_WORLD:
// main takes `env.world()` and passes the Comm down explicitly.
#include "core/mpi/comm.hpp"

namespace suite::mpi {

enum class ThreadLevel { single, funneled, serialized, multiple };

class Environment {
 public:
  // Initialises MPI with at least `required` thread support; throws LibraryError if the MPI
  // library provides less. If MPI is already initialised (e.g. by a test harness), it is left
  // to its owner and not finalised here.
  Environment(int& argc, char**& argv, ThreadLevel required = ThreadLevel::funneled);
  ~Environment();
  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;

  ThreadLevel provided() const { return provided_; }
  // A non-owning Comm for MPI_COMM_WORLD; main duplicates or splits it as it needs.
  Comm world() const;

 private:
  ThreadLevel provided_ = ThreadLevel::single;
  bool owns_ = false;
};

}  // namespace suite::mpi
