#include <gtest/gtest.h>

#include <sstream>

#include "core/errors.hpp"
#include "core/log/logger.hpp"
#include "core/log/progress.hpp"

namespace {

TEST(Logger, InfoOnRankZeroOnlyErrorsOnEveryRank) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  std::ostringstream out;
  suite::Logger log(comm, "test", {suite::LogLevel::info, false, &out});
  log.info("value {}", 42);
  log.debug("hidden");
  log.error("bad {}", "thing");
  log.flush();
  const std::string s = out.str();
  EXPECT_EQ(s.find("value 42") != std::string::npos, comm.rank() == 0) << s;
  EXPECT_EQ(s.find("hidden"), std::string::npos);
  EXPECT_NE(s.find("bad thing"), std::string::npos);
  if (comm.size() > 1) {
    EXPECT_NE(s.find(fmt::format("[rank {}]", comm.rank())), std::string::npos) << s;
  }
}

TEST(Logger, AllRanksOptionAndLevels) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  std::ostringstream out;
  suite::Logger log(comm, "test", {suite::LogLevel::debug, true, &out});
  log.debug("from every rank");
  log.flush();
  EXPECT_NE(out.str().find("from every rank"), std::string::npos);
  EXPECT_EQ(suite::parse_log_level("warn"), suite::LogLevel::warn);
  EXPECT_THROW(suite::parse_log_level("verbose"), suite::InputError);
}

TEST(ProgressLine, ReportsStepTimeAndEta) {
  suite::mpi::Comm comm(MPI_COMM_SELF);
  std::ostringstream out;
  suite::Logger log(comm, "run", {suite::LogLevel::info, false, &out});
  suite::ProgressLine p(log, 0.0, 10.0, 1000.0);
  p.report(1, 0.1, 0.1);  // within the interval: nothing
  EXPECT_EQ(out.str(), "");
  p.report(7, 5.0, 0.01, true);
  log.flush();
  EXPECT_NE(out.str().find("step        7  t = 5 s of 10 s  dt = 1.000e-02 s"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("ETA"), std::string::npos);
}

}  // namespace
