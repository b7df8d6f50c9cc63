#include <gtest/gtest.h>

#include "core/mpi/comm.hpp"

namespace {

TEST(Comm, ReductionsPrefixSumsAndGathers) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const int n = comm.size(), r = comm.rank();
  EXPECT_EQ(comm.sum(static_cast<long long>(r + 1)), static_cast<long long>(n) * (n + 1) / 2);
  EXPECT_DOUBLE_EQ(comm.max(double(r)), n - 1.0);
  EXPECT_DOUBLE_EQ(comm.min(double(r)), 0.0);
  EXPECT_EQ(comm.exclusive_prefix_sum(static_cast<long long>(r + 1)), static_cast<long long>(r) * (r + 1) / 2);
  EXPECT_TRUE(comm.any(r == n - 1));
  EXPECT_FALSE(comm.all(r == 0 && n > 1));
  const auto all = comm.all_gather(static_cast<long long>(10 * r));
  for (int i = 0; i < n; ++i) EXPECT_EQ(all[static_cast<std::size_t>(i)], 10 * i);
  std::string s = r == 0 ? "from root" : "";
  comm.broadcast(s);
  EXPECT_EQ(s, "from root");
}

TEST(Comm, DupAndSplitOwnTheirCommunicators) {
  suite::mpi::Comm world(MPI_COMM_WORLD);
  auto dup = world.dup();
  EXPECT_NE(dup.raw(), world.raw());
  EXPECT_EQ(dup.size(), world.size());
  auto halves = world.split(world.rank() % 2, world.rank());
  EXPECT_EQ(halves.size(), (world.size() + 1 - world.rank() % 2) / 2);
  EXPECT_EQ(halves.sum(1LL), halves.size());
}

}  // namespace

#include "core/mpi/collective_try.hpp"

namespace {

TEST(CollectiveTry, AnInputErrorOnOneRankReachesEveryRank) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const int last = comm.size() - 1;
  std::string seen;
  try {
    suite::mpi::collective_try(comm, [&] {
      if (comm.rank() == last) throw suite::InputError("cannot resume 'q.csv': its header differs");
    });
  } catch (const suite::InputError& e) {
    seen = e.what();
  }
  EXPECT_NE(seen.find("cannot resume 'q.csv': its header differs"), std::string::npos) << seen;
  if (last != 0) {
    EXPECT_NE(seen.find("(seen on rank 1)"), std::string::npos) << seen;
  }
  EXPECT_NO_THROW(suite::mpi::collective_try(comm, [] {}));
}

}  // namespace
