// The checkpoint schedule: by steps, by rank 0's wall clock (a fake clock here, so the test
// does not depend on timing), and on signals; every rank reaches the same decision.
#include <gtest/gtest.h>

#include "core/checkpoint/schedule.hpp"
#include "core/config/config.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using suite::SignalRequest;
using suite::checkpoint::Schedule;
using suite::checkpoint::ScheduleSettings;

TEST(CheckpointSchedule, StepsWallTimeAndSignalsAgreeOverRanks) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  double now = 100.0;
  // Only rank 0's clock counts: the other ranks' clocks run far ahead and must not trigger.
  Schedule s({10, 60.0, 2}, [&] { return comm.is_root() ? now : now + 1e6; });
  EXPECT_FALSE(s.due(comm, 1, SignalRequest::none));
  EXPECT_TRUE(s.due(comm, 10, SignalRequest::none));
  EXPECT_TRUE(s.due(comm, 3, SignalRequest::checkpoint));
  now += 59.0;
  EXPECT_FALSE(s.due(comm, 11, SignalRequest::none));
  now += 1.0;
  EXPECT_TRUE(s.due(comm, 12, SignalRequest::none)) << "60 s of rank 0's wall time since the start";
  s.written();
  EXPECT_FALSE(s.due(comm, 13, SignalRequest::none)) << "the interval restarts after a checkpoint";
}

TEST(CheckpointSchedule, SettingsFromTheSceneWithUnits) {
  auto cfg = suite::config::Config::from_string("checkpoint:\n  every: 30 min\n  keep: 3\n", "c.yaml");
  const auto s = ScheduleSettings::read(cfg.root().section("checkpoint"), {500, 0.0, 2});
  EXPECT_EQ(s.every_steps, 500);
  EXPECT_DOUBLE_EQ(s.every_seconds, 1800.0);
  EXPECT_EQ(s.keep, 3);
  auto bad = suite::config::Config::from_string("checkpoint:\n  keep: 0\n", "c.yaml");
  EXPECT_NE(suite::testing::input_error_of([&] {
              ScheduleSettings::read(bad.root().section("checkpoint"), {});
            }).find("c.yaml:2:9: key 'checkpoint.keep' = '0': must be a whole number in [1, 1000]"),
            std::string::npos);
}

}  // namespace
