#pragma once
// MPI_Init/MPI_Finalize as an object owned by main. Nothing below main names the world
// communicator: main wraps it in a Comm and passes that down explicitly (see demo/main.cpp).

#include <string>

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
  // given). Such a singleton also starts isolated (OMPI_MCA_ess_singleton_isolated: no Open MPI
  // daemon is forked, so no MPI_Comm_spawn) with its session files in a folder of its own under
  // the temporary folder (OMPI_MCA_orte_tmpdir_base, suite-mpi.PID.XXXXXX), removed after
  // MPI_Finalize, or by the next singleton once process PID is gone (a killed one); unless the
  // environment sets either variable.
  // Launched runs are left to the launcher and the site's settings. A bare MPI_Init: 0.23 s with
  // the daemon, 0.05 s isolated (2-core VM).
  Environment(int& argc, char**& argv, ThreadLevel required = ThreadLevel::funneled);
  ~Environment();
  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;

  ThreadLevel provided() const { return provided_; }

 private:
  ThreadLevel provided_ = ThreadLevel::single;
  bool owns_ = false;
  std::string session_dir_;  // this singleton's Open MPI session folder, removed at the end
};

}  // namespace suite::mpi
