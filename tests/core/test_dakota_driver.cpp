// The analysis driver honours Dakota's active set vector (core/dakota/analysis_driver.hpp): the
// results file holds the values asked for and nothing else, since Dakota counts the values it
// expects from the ASV; derivative and metadata requests are refused with the fix named.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/dakota/analysis_driver.hpp"
#include "core/dakota/parameters_file.hpp"
#include "core/dakota/results_file.hpp"
#include "core/io/atomic_file.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using namespace suite::dakota;
using suite::testing::input_error_of;

struct Run {
  Results results;
  int evaluations = 0;
};

// Writes a parameters file with responses "a" and "b" and this ASV, runs the driver over a model
// whose summary is {a: 1.5, b: -2}, and reads back the results file expecting `expected` values.
Run drive(const std::filesystem::path& dir, const std::vector<int>& asv, std::size_t expected,
          std::vector<std::string> metadata = {}) {
  Parameters p;
  p.variables = {{"soil.erodibility", 1e-5}};
  p.responses = {"a", "b"};
  p.asv = asv;
  p.metadata = std::move(metadata);
  suite::io::write_file_atomic(dir / "params.in", write_parameters(p, ParametersFormat::standard));
  Run run;
  const suite::mpi::Comm self(MPI_COMM_SELF);
  run_analysis_driver(self, "model", {}, dir / "params.in", dir / "results.out", [&](const auto&) {
    ++run.evaluations;
    return nlohmann::json{{"a", 1.5}, {"b", -2.0}};
  });
  std::ifstream in(dir / "results.out");
  std::stringstream text;
  text << in.rdbuf();
  run.results = read_results(text.str(), "results.out", expected);
  return run;
}

TEST(DakotaDriver, ResultsHoldTheValuesTheActiveSetAsksFor) {
  const suite::mpi::Comm world(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(world);
  if (!world.is_root()) return;  // the driver of one evaluation runs on one rank here
  const auto both = drive(dir, {1, 1}, 2);
  EXPECT_EQ(both.results.values, (std::vector<double>{1.5, -2.0}));
  const auto second = drive(dir, {0, 1}, 1);
  EXPECT_EQ(second.results.values, (std::vector<double>{-2.0}));
  EXPECT_EQ(second.results.labels, (std::vector<std::string>{"b"}));
  const auto first = drive(dir, {1, 0}, 1);
  EXPECT_EQ(first.results.labels, (std::vector<std::string>{"a"}));
  EXPECT_TRUE(drive(dir, {0, 0}, 0).results.values.empty());
}

TEST(DakotaDriver, DerivativesAndMetadataAreRefusedBeforeAnyRun) {
  const suite::mpi::Comm world(MPI_COMM_WORLD);
  const auto dir = suite::testing::scratch_dir(world);
  if (!world.is_root()) return;  // the driver of one evaluation runs on one rank here
  for (const auto& asv : {std::vector<int>{1, 2}, std::vector<int>{3, 1}, std::vector<int>{1, 7}}) {
    int evaluations = -1;
    const auto what = input_error_of([&] { evaluations = drive(dir, asv, 0).evaluations; });
    EXPECT_NE(what.find("returns function values only: give Dakota's responses block numerical_gradients"),
              std::string::npos)
        << what;
    EXPECT_EQ(evaluations, -1) << "nothing ran";
  }
  EXPECT_NE(input_error_of([&] {
              drive(dir, {1, 2}, 0);
            }).find("response 'b' asks for its gradient (ASV 2)"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] {
              drive(dir, {1, 1}, 2, {"seconds"});
            }).find("asks for metadata (seconds)"),
            std::string::npos);
}

}  // namespace
