// The study pipeline's analyses on analytic models (expression model): Sobol indices of the
// Ishigami function, correlations and regression of a linear model, Morris effects, and
// `study analyze` reproducing analysis.json from the ledger.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "core/config/config.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"
#include "studies/run/study.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using namespace suite::studies;
namespace fs = std::filesystem;

nlohmann::json run(const fs::path& dir, const std::string& spec, bool analyze_only = false) {
  const suite::mpi::Comm self(MPI_COMM_SELF);
  suite::Logger log(self, "study", {suite::LogLevel::error, false, nullptr});
  auto cfg = analyze_only ? suite::config::Config::from_file(dir / "study.yaml")
                          : suite::config::Config::from_string(spec + "output: {plot: false}\n", "study.yaml");
  run_study(cfg, {dir, analyze_only, false, analyze_only}, log);
  std::ifstream in(dir / "analysis.json");
  return nlohmann::json::parse(in);
}

TEST(StudyAnalysis, IshigamiSobolIndicesThroughTheWholePipeline) {
  // a = 7, b = 0.1, X_i uniform(-pi, pi): S = (0.3139, 0.4424, 0), ST = (0.5576, 0.4424, 0.2437)
  // (Ishigami & Homma 1990; docs/methods/studies.md). N = 4000 base points, 20000 evaluations; the 95%
  // bootstrap intervals of the estimates must hold the analytic values (seed fixed).
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  const auto a = run(dir, R"X(variables:
  - {name: x1, distribution: {type: uniform, lower: -3.141592653589793, upper: 3.141592653589793}}
  - {name: x2, distribution: {type: uniform, lower: -3.141592653589793, upper: 3.141592653589793}}
  - {name: x3, distribution: {type: uniform, lower: -3.141592653589793, upper: 3.141592653589793}}
method: {type: sobol_indices, samples: 4000, seed: 5}
model:
  type: expression
  responses: {y: "sin(x1) + 7*sin(x2)**2 + 0.1*x3**4*sin(x1)"}
)X");
  ASSERT_EQ(a["points"], 4000 * 5);
  const auto& s = a["sobol_indices"]["y"];
  ASSERT_TRUE(s.contains("first")) << s.dump();
  const double first[] = {0.3139, 0.4424, 0.0}, total[] = {0.5576, 0.4424, 0.2437};
  for (int i = 0; i < 3; ++i) {
    // The intervals are informative (full widths 0.05-0.14 at N = 4000, against indices of
    // 0.24-0.56) and the estimates close to the truth.
    EXPECT_LT(s["first_high"][i].get<double>() - s["first_low"][i].get<double>(), 0.2) << i;
    EXPECT_LT(s["total_high"][i].get<double>() - s["total_low"][i].get<double>(), 0.2) << i;
    EXPECT_NEAR(s["first"][i].get<double>(), first[i], 0.05) << i;
    EXPECT_NEAR(s["total"][i].get<double>(), total[i], 0.05) << i;
    EXPECT_LE(s["first_low"][i].get<double>(), first[i] + 5e-5) << i;
    EXPECT_GE(s["first_high"][i].get<double>(), first[i] - 5e-5) << i;
    EXPECT_LE(s["total_low"][i].get<double>(), total[i] + 5e-5) << i;
    EXPECT_GE(s["total_high"][i].get<double>(), total[i] - 5e-5) << i;
  }
}

TEST(StudyAnalysis, LinearModelCorrelationsAndRegression) {
  // y = 2 x1 - 3 x2, x_i uniform(0, 1) independent: corr(y, x1) = 2/sqrt(13), corr(y, x2) =
  // -3/sqrt(13), the same standardized regression coefficients, R^2 = 1, partial correlations
  // +-1; sampling error of a correlation ~ 1/sqrt(n): tolerance 4/sqrt(2000) = 0.09.
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  const auto a = run(dir, R"X(variables:
  - {name: x1, lower: 0, upper: 1}
  - {name: x2, lower: 0, upper: 1}
method: {type: sampling, sample_type: lhs, samples: 2000, seed: 11}
model: {type: expression, responses: {y: "2*x1 - 3*x2"}}
)X");
  const double tol = 4.0 / std::sqrt(2000.0), r1 = 2.0 / std::sqrt(13.0), r2 = -3.0 / std::sqrt(13.0);
  const auto& c = a["correlations"];
  EXPECT_NEAR(c["pearson"][2][0].get<double>(), r1, tol);  // names: x1, x2, y
  EXPECT_NEAR(c["pearson"][2][1].get<double>(), r2, tol);
  EXPECT_NEAR(c["partial"][0][0].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(c["partial"][1][0].get<double>(), -1.0, 1e-9);
  const auto& reg = a["regression"]["y"];
  EXPECT_NEAR(reg["src"][0].get<double>(), r1, tol);
  EXPECT_NEAR(reg["src"][1].get<double>(), r2, tol);
  EXPECT_NEAR(reg["r2"].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(a["statistics"]["y"]["mean"].get<double>(), -0.5, 4.0 * std::sqrt(13.0 / 12.0 / 2000.0));
  // `study analyze` rebuilds the same analysis from the ledger.
  EXPECT_EQ(run(dir, "", true), a);
}

TEST(StudyAnalysis, MorrisScreening) {
  // f = 3 x1 + x2^2 + 0 x3 on [0, 1]^3: x1's effects are all 3 (mu* = 3, sigma = 0), x3 has none.
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  const auto a = run(dir, R"X(variables:
  - {name: x1, lower: 0, upper: 1}
  - {name: x2, lower: 0, upper: 1}
  - {name: x3, lower: 0, upper: 1}
method: {type: morris, trajectories: 20, levels: 4, seed: 3}
model: {type: expression, responses: {f: "3*x1 + x2**2 + 0*x3"}}
)X");
  ASSERT_EQ(a["points"], 20 * 4);
  const auto& m = a["morris"]["f"];
  EXPECT_NEAR(m["mu_star"][0].get<double>(), 3.0, 1e-9);
  EXPECT_NEAR(m["sigma"][0].get<double>(), 0.0, 1e-9);
  // On a 4-level grid (Delta = 2/3) every effect of x2^2 is (x + Delta)^2 - x^2 over Delta with
  // x in {0, 1/3}: 2/3 or 4/3, so mu* lies between them and sigma > 0.
  EXPECT_GE(m["mu_star"][1].get<double>(), 2.0 / 3.0 - 1e-12);
  EXPECT_LE(m["mu_star"][1].get<double>(), 4.0 / 3.0 + 1e-12);
  EXPECT_GT(m["sigma"][1].get<double>(), 0.0);
  EXPECT_NEAR(m["mu_star"][2].get<double>(), 0.0, 1e-12);
}

}  // namespace
