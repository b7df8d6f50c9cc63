#include <gtest/gtest.h>

#include "core/mpi/comm.hpp"
#include "core/mpi/environment.hpp"

namespace {

TEST(Environment, LeavesAnMpiItDidNotStartToItsOwner) {
  // The test main has initialised MPI already (with FUNNELED); this Environment must neither
  // re-initialise nor finalise it, and must report the thread level actually provided.
  int argc = 0;
  char** argv = nullptr;
  {
    suite::mpi::Environment env(argc, argv, suite::mpi::ThreadLevel::single);
    EXPECT_GE(static_cast<int>(env.provided()), static_cast<int>(suite::mpi::ThreadLevel::funneled));
  }
  int finalised = 1;
  MPI_Finalized(&finalised);
  EXPECT_EQ(finalised, 0);
  suite::mpi::Comm world(MPI_COMM_WORLD);
  EXPECT_EQ(world.sum(1LL), world.size()) << "MPI still usable";
}

}  // namespace
