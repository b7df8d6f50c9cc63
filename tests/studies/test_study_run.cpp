// A study end to end on the in-process breach model: the table, the ledger, a study killed
// midway and resumed (same table as an uninterrupted run), failed evaluations recorded and
// skipped, the same table at any concurrency.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/config/config.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"
#include "studies/ledger/ledger.hpp"
#include "studies/run/study.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using namespace suite::studies;
namespace fs = std::filesystem;

using suite::testing::read_file;

// The default breach scene with kd (cm^3/(N s)) and s_u (kPa) as the variables.
const std::string kModel =
    "model:\n"
    "  type: breach\n"
    "  scene: " SUITE_BREACH_DEFAULT_SCENE
    "\n"
    "  set: {soil.erodibility: \"{kd} cm^3/(N s)\", soil.undrained_shear_strength: \"{su} kPa\"}\n"
    "  responses: [peak_outflow, breach_initiation_time]\n";

// 3 x 3 over kd and s_u; kd's lower bound may be set negative to provoke failed evaluations.
std::string spec(double kd_lower = 10.0, int concurrency = 2) {
  return "variables:\n"
         "  - {name: kd, lower: " +
         std::to_string(kd_lower) +
         ", upper: 50}\n"
         "  - {name: su, lower: 5, upper: 30}\n"
         "method: {type: multidim, partitions: 2}\n" +
         kModel + "execution: {concurrency: " + std::to_string(concurrency) + "}\noutput: {plot: false}\n";
}

StudyCounts run(const fs::path& dir, const std::string& text, bool resume = false, bool retry = false) {
  const suite::mpi::Comm self(MPI_COMM_SELF);
  suite::Logger log(self, "study", {suite::LogLevel::warn, false, nullptr});
  auto cfg = resume ? suite::config::Config::from_file(dir / "study.yaml")
                    : suite::config::Config::from_string(text, "study.yaml");
  return run_study(cfg, {dir, resume, retry}, log);
}

TEST(StudyRun, TableAndLedger) {
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  const auto c = run(dir / "a", spec());
  EXPECT_EQ(c.points, 9u);
  EXPECT_EQ(c.run, 9u);
  EXPECT_EQ(c.failed, 0u);
  EXPECT_EQ(Ledger::read(dir / "a" / "ledger.jsonl").size(), 9u);
  const std::string csv = read_file(dir / "a" / "tabular.csv");
  EXPECT_EQ(csv.rfind("eval_id,status,kd,su,peak_outflow,breach_initiation_time,reason\n", 0), 0u) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 10);
  EXPECT_NE(read_file(dir / "a" / "tabular.dat").find("peak_outflow"), std::string::npos);
  // A second `run` into the same folder is refused; the ledger says what to do.
  EXPECT_NE(suite::testing::input_error_of([&] { run(dir / "a", spec()); }).find("study resume"), std::string::npos);
}

TEST(StudyRun, SameTableAtAnyConcurrency) {
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  run(dir / "one", spec(10.0, 1));
  run(dir / "two", spec(10.0, 2));
  EXPECT_EQ(read_file(dir / "one" / "tabular.dat"), read_file(dir / "two" / "tabular.dat"));
}

// A run of `text` whose ledger is cut after 4 lines and half of the 5th (the kill; the tables
// are gone), resumed from its study.yaml, against an uninterrupted run.
void kill_and_resume(const std::string& text, std::size_t points) {
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  run(dir / "whole", text);
  run(dir / "killed", text);
  const std::string ledger = read_file(dir / "killed" / "ledger.jsonl");
  std::size_t cut = 0;
  for (int i = 0; i < 4; ++i) cut = ledger.find('\n', cut) + 1;
  std::ofstream(dir / "killed" / "ledger.jsonl", std::ios::trunc) << ledger.substr(0, cut + 20);
  fs::remove(dir / "killed" / "tabular.dat");
  const auto c = run(dir / "killed", "", true);
  EXPECT_EQ(c.reused, 4u);
  EXPECT_EQ(c.run, points - 4);
  EXPECT_EQ(read_file(dir / "killed" / "tabular.dat"), read_file(dir / "whole" / "tabular.dat"));
}

TEST(StudyRun, KilledAndResumedGivesTheSameTable) {
  kill_and_resume(spec(), 9);
}

// The same for a Latin hypercube over unbounded distributions: the resume reads the effective
// study.yaml, which must give the very same points (the design's quantile box is not written
// back as bounds, which would truncate the distributions and move every point by ~1e-7).
TEST(StudyRun, KilledAndResumedLhsOverDistributionsGivesTheSameTable) {
  kill_and_resume(
      "variables:\n"
      "  - {name: kd, distribution: {type: lognormal, mean: 30, std: 10}}\n"
      "  - {name: su, distribution: {type: uniform, lower: 5, upper: 30}}\n"
      "method: {type: sampling, sample_type: lhs, samples: 12, seed: 7}\n" +
          kModel + "output: {plot: false}\n",
      12);
}

TEST(StudyRun, FailedEvaluationsAreRecordedAndRetried) {
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  // kd from -30: the first column of the grid (kd = -30) is rejected by the breach scene.
  const auto c = run(dir / "f", spec(-30.0));
  EXPECT_EQ(c.failed, 3u);
  const std::string csv = read_file(dir / "f" / "tabular.csv");
  EXPECT_NE(csv.find("failed"), std::string::npos);
  EXPECT_NE(csv.find("soil.erodibility"), std::string::npos) << "the reason names the key";
  const std::string dat = read_file(dir / "f" / "tabular.dat");
  EXPECT_EQ(std::count(dat.begin(), dat.end(), '\n'), 1 + 6) << "failed evaluations stay out of the table";
  // Resuming reruns nothing; --retry-failed reruns exactly the failed three (which fail again).
  EXPECT_EQ(run(dir / "f", "", true).run, 0u);
  EXPECT_EQ(run(dir / "f", "", true, true).run, 3u);
}

// A mistake every evaluation would repeat (here a misspelt key in the model's `set`) stops the
// study before its first evaluation: the templates are rendered with every variable at its median
// and checked against the scene (issue 31; it ran all 9 and then failed). Nothing is written.
TEST(StudyRun, AMisspeltKeyStopsTheStudyBeforeAnyEvaluation) {
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  std::string text = spec();
  const auto at = text.find("soil.erodibility");
  text.replace(at, std::string("soil.erodibility").size(), "soil.erodability");
  const auto what = suite::testing::input_error_of([&] { run(dir / "misspelt", text); });
  EXPECT_NE(what.find("the model rejects the study's inputs before any evaluation (checked with every variable at "
                      "its median: kd = 30, su = 17.5)"),
            std::string::npos)
      << what;
  EXPECT_NE(what.find("model.set 'soil.erodability=30 cm^3/(N s)': unknown key"), std::string::npos) << what;
  EXPECT_FALSE(fs::exists(dir / "misspelt" / "ledger.jsonl"));
  // A template Python would reject, the same.
  std::string inf = spec();
  inf.replace(inf.find("{kd} cm^3/(N s)"), std::string("{kd} cm^3/(N s)").size(), "{kd/0} cm^3/(N s)");
  EXPECT_NE(suite::testing::input_error_of([&] { run(dir / "inf", inf); }).find("before any evaluation"),
            std::string::npos);
  // Values only some points take still fail just those points: kd from -10 is rejected by the
  // scene, but the median (20) is not.
  EXPECT_NO_THROW(run(dir / "partly", spec(-10.0))) << "some evaluations failing is a result";
}

// A study none of whose evaluations gives its responses stops with an error quoting the first
// failure (it exited 0 before) once the tables are written: here no breach, so no initiation time.
TEST(StudyRun, AStudyWhoseEvaluationsAllFailIsAnError) {
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  std::string text = spec();
  const std::string set = "set: {";
  text.insert(text.find(set) + set.size(), "inflow.peak: \"0 m^3/s\", reservoir.initial_level: \"5 m\", ");
  const auto what = suite::testing::input_error_of([&] { run(dir / "dry", text); });
  EXPECT_NE(what.find("every one of the 9 evaluations failed; the first (evaluation 1): "), std::string::npos) << what;
  EXPECT_NE(what.find("breach_initiation_time"), std::string::npos) << what;
  EXPECT_TRUE(fs::exists(dir / "dry" / "tabular.csv"));
}

TEST(StudyRun, RelativePathsSurviveAResumeFromElsewhere) {
  // A spec naming its scene relative to itself, run with a relative output folder, resumed from
  // another working directory: study.yaml holds absolute paths, work folders are absolute.
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  fs::create_directories(dir / "spec");
  fs::copy_file(SUITE_BREACH_DEFAULT_SCENE, dir / "spec" / "dam.yaml");
  std::string text = spec();
  text.replace(text.find(SUITE_BREACH_DEFAULT_SCENE), std::string(SUITE_BREACH_DEFAULT_SCENE).size(), "dam.yaml");
  std::ofstream(dir / "spec" / "study.yaml") << text;
  const auto cwd = fs::current_path();
  fs::current_path(dir);
  {
    const suite::mpi::Comm self(MPI_COMM_SELF);
    suite::Logger log(self, "study", {suite::LogLevel::warn, false, nullptr});
    run_study(suite::config::Config::from_file("spec/study.yaml"), {"rel", false, false}, log);
  }
  fs::current_path(cwd);
  EXPECT_TRUE(fs::exists(dir / "rel" / "tabular.dat"));
  fs::remove(dir / "rel" / "tabular.dat");
  const auto c = run(dir / "rel", "", true);  // from the test's own working directory
  EXPECT_EQ(c.reused, 9u);
  EXPECT_TRUE(fs::exists(dir / "rel" / "tabular.dat"));
}

}  // namespace
