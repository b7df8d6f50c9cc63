#include "core/mpi/environment.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <cstdlib>
#include <utility>
#include <vector>

#include "core/errors.hpp"

namespace suite::mpi {
namespace {
int to_mpi(ThreadLevel t) {
  switch (t) {
    case ThreadLevel::single:
      return MPI_THREAD_SINGLE;
    case ThreadLevel::funneled:
      return MPI_THREAD_FUNNELED;
    case ThreadLevel::serialized:
      return MPI_THREAD_SERIALIZED;
    case ThreadLevel::multiple:
      return MPI_THREAD_MULTIPLE;
  }
  return MPI_THREAD_SINGLE;
}
ThreadLevel from_mpi(int t) {
  if (t >= MPI_THREAD_MULTIPLE) return ThreadLevel::multiple;
  if (t >= MPI_THREAD_SERIALIZED) return ThreadLevel::serialized;
  if (t >= MPI_THREAD_FUNNELED) return ThreadLevel::funneled;
  return ThreadLevel::single;
}

// True when a launcher started this process (Open MPI's mpirun, or a PMI/PMIx launcher such as
// srun): its variables are in the environment.
bool launched() {
  for (const char* name : {"OMPI_UNIVERSE_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}
}  // namespace

Environment::Environment(int& argc, char**& argv, ThreadLevel required) {
  int initialised = 0;
  SUITE_MPI_CHECK(MPI_Initialized(&initialised));
  int provided = MPI_THREAD_SINGLE;
  if (initialised) {
    SUITE_MPI_CHECK(MPI_Query_thread(&provided));
  } else {
    // Set for this process's MPI_Init only, then taken out again, so that programs it starts
    // (a study's evaluations, foam-erosion's mpirun) see the environment it was given.
    std::vector<const char*> set;
    if (!launched())
      for (const auto& [name, value] : {std::pair{"OMPI_MCA_pml", "ob1"}})
        if (!std::getenv(name)) setenv(name, value, 1), set.push_back(name);
    SUITE_MPI_CHECK(MPI_Init_thread(&argc, &argv, to_mpi(required), &provided));
    for (const char* name : set) unsetenv(name);
    owns_ = true;
  }
  provided_ = from_mpi(provided);
  if (provided < to_mpi(required)) {
    throw LibraryError(fmt::format("MPI provides thread level {} but {} was required", provided, to_mpi(required)));
  }
}

Environment::~Environment() {
  if (!owns_) return;
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised) MPI_Finalize();
}

}  // namespace suite::mpi
