// Deterministic designs against Dakota's documented semantics (ParamStudy.cpp: counts, order,
// arithmetic) and the variables' validation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/config/config.hpp"
#include "studies/design/parameter_studies.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using namespace suite::studies;
using suite::config::Config;
using suite::testing::input_error_of;

Design design(const std::string& text, const std::vector<std::string>& overrides = {}) {
  auto cfg = Config::from_string(text, "study.yaml", overrides);
  const auto vars = read_variables(cfg.root());
  return read_design(cfg.root().section("method"), vars);
}

const std::string kTwo =
    "variables:\n  - {name: x, lower: 0, upper: 1}\n  - {name: y, lower: -2, upper: 2, initial: 1}\n";

TEST(Designs, MultidimIsTheDissertationGrid) {
  // partitions 5 over three variables: 6 x 6 x 6 = 216 points, the first variable fastest.
  const auto d = design(
      "variables:\n  - {name: Kd, lower: 300, upper: 1700}\n  - {name: Us, lower: 0.3, upper: 70}\n"
      "  - {name: Scale, lower: 0, upper: 5}\nmethod: {type: multidim, partitions: 5}\n");
  ASSERT_EQ(d.points.size(), 216u);
  EXPECT_EQ(d.points[0], (Point{300, 0.3, 0}));
  EXPECT_EQ(d.points[1], (Point{300 + 280, 0.3, 0}));
  EXPECT_EQ(d.points[5], (Point{1700, 0.3, 0}));
  EXPECT_EQ(d.points[6][1], 0.3 + (70 - 0.3) / 5);
  EXPECT_EQ(d.points[36][2], 1.0);
  EXPECT_EQ(d.points[215], (Point{1700, 0.3 + 5 * ((70 - 0.3) / 5), 5}));
}

TEST(Designs, MultidimPartitionsPerVariableAndZero) {
  // partitions [2, 0]: x over 3 levels, y held at its initial value.
  const auto d = design(kTwo + "method: {type: multidim, partitions: [2, 0]}\n");
  ASSERT_EQ(d.points.size(), 3u);
  EXPECT_EQ(d.points[1], (Point{0.5, 1.0}));
}

TEST(Designs, VectorFromFinalPointOrStepVector) {
  const auto a = design(kTwo + "method: {type: vector, final_point: [1, -1], num_steps: 4}\n");
  ASSERT_EQ(a.points.size(), 5u);  // num_steps + 1, from the initial point (0.5, 1)
  EXPECT_EQ(a.points[0], (Point{0.5, 1.0}));
  EXPECT_EQ(a.points[4], (Point{0.5 + 4 * 0.125, 1.0 + 4 * -0.5}));
  const auto b = design(kTwo + "method: {type: vector, step_vector: [0.1, 0.2], num_steps: 2}\n");
  EXPECT_EQ(b.points[2], (Point{0.5 + 2 * 0.1, 1.0 + 2 * 0.2}));
}

TEST(Designs, CenteredOneVariableAtATimeMinusThenPlus) {
  // 1 + 2 (2 + 1) = 7 points: centre, x - 2s, x - s, x + s, x + 2s, then y - s, y + s.
  const auto d = design(kTwo + "method: {type: centered, step_vector: [0.1, 0.5], steps_per_variable: [2, 1]}\n");
  ASSERT_EQ(d.points.size(), 7u);
  EXPECT_EQ(d.points[0], (Point{0.5, 1.0}));
  EXPECT_EQ(d.points[1], (Point{0.5 - 2 * 0.1, 1.0}));
  EXPECT_EQ(d.points[2], (Point{0.5 - 0.1, 1.0}));
  EXPECT_EQ(d.points[3], (Point{0.5 + 0.1, 1.0}));
  EXPECT_EQ(d.points[4], (Point{0.5 + 2 * 0.1, 1.0}));
  EXPECT_EQ(d.points[5], (Point{0.5, 0.5}));
  EXPECT_EQ(d.points[6], (Point{0.5, 1.5}));
}

TEST(Designs, ListInline) {
  const auto d = design(kTwo + "method: {type: list, points: [0, 0, 1, 2, 0.5, -1]}\n");
  ASSERT_EQ(d.points.size(), 3u);
  EXPECT_EQ(d.points[2], (Point{0.5, -1}));
}

// Spearman correlation of two columns (no ties: continuous samples).
double spearman(const std::vector<Point>& pts, std::size_t a, std::size_t b) {
  auto ranks = [&](std::size_t c) {
    std::vector<std::size_t> idx(pts.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(), [&](auto i, auto j) { return pts[i][c] < pts[j][c]; });
    std::vector<double> r(pts.size());
    for (std::size_t k = 0; k < idx.size(); ++k) r[idx[k]] = static_cast<double>(k);
    return r;
  };
  const auto ra = ranks(a), rb = ranks(b);
  const double n = static_cast<double>(pts.size()), mean = (n - 1) / 2;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t k = 0; k < pts.size(); ++k)
    sab += (ra[k] - mean) * (rb[k] - mean), saa += (ra[k] - mean) * (ra[k] - mean),
        sbb += (rb[k] - mean) * (rb[k] - mean);
  return sab / std::sqrt(saa * sbb);
}

TEST(Designs, SamplingWithRankCorrelationAndTruncation) {
  // LHS of 4000 points with Spearman 0.7 requested: within 0.05 (sampling error ~1/sqrt(n));
  // a normal truncated by explicit bounds never leaves them; the same seed, the same points.
  const std::string spec =
      "variables:\n  - {name: a, lower: 0, upper: 1}\n"
      "  - {name: b, lower: -1, upper: 2, distribution: {type: normal, mean: 0, std: 3}}\n"
      "method: {type: sampling, samples: 4000, seed: 9, rank_correlation: [[1, 0.7], [0.7, 1]]}\n";
  const auto d = design(spec);
  ASSERT_EQ(d.points.size(), 4000u);
  EXPECT_NEAR(spearman(d.points, 0, 1), 0.7, 0.05);
  for (const auto& p : d.points) {
    EXPECT_GE(p[1], -1.0);
    EXPECT_LE(p[1], 2.0);
  }
  EXPECT_EQ(design(spec).points, d.points);
}

TEST(Designs, BadSpecificationsNameTheKey) {
  auto has = [](const std::string& msg, const std::string& part) {
    EXPECT_NE(msg.find(part), std::string::npos) << "'" << part << "' not in: " << msg;
  };
  has(input_error_of([&] { design(kTwo + "method: {type: multidim, partitions: [2, 3, 4]}\n"); }),
      "one per variable (2), not 3");
  has(input_error_of([&] { design(kTwo + "method: {type: list, points: [0, 0, 1]}\n"); }), "points of 2 values");
  has(input_error_of([&] { design(kTwo + "method: {type: list, points: [0, 0, 1.5, 0]}\n"); }),
      "point 2 has x = 1.5, outside its bounds [0, 1]");
  has(input_error_of([&] {
        design(kTwo + "method: {type: sampling, samples: 10, seed: 1, rank_correlation: [[1, 2], [2, 1]]}\n");
      }),
      "key 'method.rank_correlation'");
  has(input_error_of([&] { design(kTwo + "method: {type: multidm}\n"); }), "did you mean 'multidim'");
  has(input_error_of(
          [&] { design("variables:\n  - {name: x, lower: 1, upper: 0}\nmethod: {type: multidim, partitions: 1}\n"); }),
      "is below lower");
  has(input_error_of(
          [&] { design("variables:\n  - {name: 2x, lower: 0, upper: 1}\nmethod: {type: multidim, partitions: 1}\n"); }),
      "must be an identifier");
  has(input_error_of([&] { design(kTwo + "method: {type: vector, num_steps: 3}\n"); }),
      "either final_point or step_vector");
  // Morris's levels: the file and line, not only the method's name.
  has(input_error_of([&] { design(kTwo + "method: {type: morris, levels: 3}\n"); }),
      "key 'method.levels' = '3': must be even");
}

}  // namespace
