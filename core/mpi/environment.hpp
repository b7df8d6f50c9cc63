#pragma once
// MPI_Init/MPI_Finalize as an object owned by main. Nothing below main names the world
// communicator: main wraps it in a Comm and passes that down explicitly (see demo/main.cpp).

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

 private:
  ThreadLevel provided_ = ThreadLevel::single;
  bool owns_ = false;
};

}  // namespace suite::mpi
