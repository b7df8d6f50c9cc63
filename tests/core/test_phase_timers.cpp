#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <thread>

#include "core/run/phase_timers.hpp"

namespace {

TEST(PhaseTimers, ScopesAddUpPerPhase) {
  suite::PhaseTimers t;
  for (int i = 0; i < 3; ++i) {
    suite::ScopedPhase s(t, "p2g");
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  t.add("solve", 0.25);
  EXPECT_EQ(t.totals().at("p2g").calls, 3);
  EXPECT_GE(t.seconds("p2g"), 0.015);  // sleep_for waits at least the requested time
  EXPECT_DOUBLE_EQ(t.seconds("solve"), 0.25);
  EXPECT_DOUBLE_EQ(t.seconds("absent"), 0.0);
}

TEST(PhaseTimers, ReductionGivesMinMeanMaxOverRanks) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  suite::PhaseTimers t;
  t.add("io", 1.0 + comm.rank());
  if (comm.rank() == comm.size() - 1) t.add("only_last", 2.0);
  const auto j = t.reduce_to_json(comm);
  const int n = comm.size();
  EXPECT_DOUBLE_EQ(j["io"]["min_s"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["io"]["max_s"].get<double>(), double(n));
  EXPECT_DOUBLE_EQ(j["io"]["mean_s"].get<double>(), (n + 1) / 2.0);
  EXPECT_DOUBLE_EQ(j["only_last"]["max_s"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["only_last"]["min_s"].get<double>(), n == 1 ? 2.0 : 0.0);
}

}  // namespace
