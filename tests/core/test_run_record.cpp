#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/io/output_dir.hpp"
#include "core/run/build_info.hpp"
#include "core/run/run_record.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

TEST(RunRecord, RunJsonHasBuildRanksAndPhaseTimes) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(comm);
  suite::RunRecord rec(comm, "suite-test", {"suite-test", "scene.yaml"});
  rec.extra()["scene"] = "scene.yaml";
  suite::PhaseTimers t;
  t.add("p2g", 0.5);
  rec.write(dir / "run.json", t, "completed");
  comm.barrier();
  const auto j = read_json(dir / "run.json");
  EXPECT_EQ(j["program"], "suite-test");
  EXPECT_EQ(j["version"], suite::build_info().version);
  EXPECT_FALSE(j["git_hash"].get<std::string>().empty());
  EXPECT_FALSE(j["compiler"].get<std::string>().empty());
  EXPECT_NE(j["mpi_library"].get<std::string>().find("Open MPI"), std::string::npos);
  EXPECT_EQ(j["ranks"], comm.size());
  EXPECT_EQ(j["status"], "completed");
  EXPECT_EQ(j["scene"], "scene.yaml");
  EXPECT_DOUBLE_EQ(j["phases"]["p2g"]["max_s"].get<double>(), 0.5);
  EXPECT_GE(j["wall_time_s"].get<double>(), 0.0);
}

TEST(Summary, ScalarsWithUnitsAndNonFiniteAsNull) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(comm);
  suite::Summary s;
  s.set("peak_outflow", 812.5, "m^3/s");
  s.set("failed", true);
  s.set("time_to_peak", std::nan(""), "s");
  EXPECT_THROW(s.set("units", 1.0), suite::LibraryError);
  if (comm.is_root()) s.write(dir / "summary.json");
  comm.barrier();
  const auto j = read_json(dir / "summary.json");
  EXPECT_DOUBLE_EQ(j["peak_outflow"].get<double>(), 812.5);
  EXPECT_EQ(j["units"]["peak_outflow"], "m^3/s");
  EXPECT_TRUE(j["time_to_peak"].is_null());
  EXPECT_TRUE(j["failed"].get<bool>());
  // No temporary file is left beside it (write_file_atomic's summary.json.tmp.XXXXXX).
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find("summary.json.tmp"), std::string::npos) << entry.path();
}

TEST(OutputDir, CreatedOnceAndBadPathsAreOneErrorOnEveryRank) {
  suite::mpi::Comm comm(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(comm);
  const auto made = suite::io::prepare_output_dir(comm, dir / "a" / "b");
  EXPECT_TRUE(std::filesystem::is_directory(made));
  if (comm.is_root()) std::ofstream(dir / "file") << "x";
  comm.barrier();
  const std::string msg =
      suite::testing::input_error_of([&] { suite::io::prepare_output_dir(comm, dir / "file" / "sub"); });
  EXPECT_NE(msg.find("cannot use output folder"), std::string::npos) << msg;
  EXPECT_NE(msg.find("choose another with --out"), std::string::npos) << msg;
}

}  // namespace
