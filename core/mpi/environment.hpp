#pragma once
// MPI_Init/MPI_Finalize as an object owned by main. Nothing below main names the world
// communicator: main wraps it in a Comm and passes that down explicitly (see demo/main.cpp).

namespace suite::mpi {

enum class ThreadLevel { single, funneled, serialized, multiple };

class Environment {
 public:
  // Initialises MPI with at least `required` thread support; throws LibraryError if the MPI
  // library provides less. If MPI is already initialised (e.g. by a test harness), it is left
  // to its owner and not finalised here. A process started without a launcher (no mpirun,
  // srun or PMIx variables) is an Open MPI singleton with no peers: it gets the ob1 messaging
  // layer, without probing the network stacks (UCX) a single process cannot use
  // (OMPI_MCA_pml=ob1 unless the environment sets it, for MPI_Init only: taken out of the
  // environment again after it, so that child processes get the environment this one was
  // given). Launched runs are left to the launcher and the site's settings. seedcarve --help:
  // 0.72 -> 0.51 s. (Starting it isolated too, ess_singleton_isolated, took it to 0.22 s, but
  // isolated singletons running at once share one session folder, and MPI-IO's shared file
  // pointers then failed to open HDF5 outputs.)
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
