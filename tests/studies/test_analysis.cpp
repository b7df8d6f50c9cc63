// Tests of studies/analysis: response statistics, Dakota's correlation matrices, standardized
// regression, Morris elementary effects (docs/methods/studies.md, "Analysis and output" and
// "Validation references"). Closed forms on linear models, with OpenTURNS and Eigen as oracles.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <openturns/Point.hxx>
#include <openturns/Sample.hxx>
#include <random>
#include <set>
#include <vector>

#include "core/errors.hpp"
#include "studies/analysis/correlations.hpp"
#include "studies/analysis/morris.hpp"
#include "studies/analysis/statistics.hpp"

namespace suite::studies {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using Rows = std::vector<std::vector<double>>;

// ---------------------------------------------------------------- statistics

TEST(Statistics, HandValuesAndNaNSkipping) {
  // Valid values sorted: 1 1 2 3 4 5 6 9 (n = 8), one failed evaluation.
  const ResponseStatistics s = statistics({3, 1, kNaN, 4, 1, 5, 9, 2, 6});
  EXPECT_EQ(s.count, 8u);
  EXPECT_EQ(s.failed, 1u);
  EXPECT_DOUBLE_EQ(s.mean, 31.0 / 8.0);
  // sum of squares 173, minus n mean^2 = 120.125, over n - 1 = 7.
  EXPECT_NEAR(s.std, std::sqrt(52.875 / 7.0), 1e-14);
  EXPECT_EQ(s.min, 1.0);
  EXPECT_EQ(s.max, 9.0);
  // Type 7, h = 7 p: numpy.quantile([1,1,2,3,4,5,6,9], [.05,.25,.5,.75,.95]) = 1, 1.75, 3.5, 5.25, 7.95.
  const std::vector<std::pair<double, double>> expected{
      {0.05, 1.0}, {0.25, 1.75}, {0.5, 3.5}, {0.75, 5.25}, {0.95, 7.95}};
  ASSERT_EQ(s.quantiles.size(), expected.size());
  for (std::size_t q = 0; q < expected.size(); ++q) {
    EXPECT_EQ(s.quantiles[q].first, expected[q].first);
    EXPECT_NEAR(s.quantiles[q].second, expected[q].second, 1e-14) << "p = " << expected[q].first;
  }
}

TEST(Statistics, DegenerateSamples) {
  const ResponseStatistics none = statistics({kNaN, kNaN});
  EXPECT_EQ(none.count, 0u);
  EXPECT_EQ(none.failed, 2u);
  EXPECT_TRUE(std::isnan(none.mean));
  EXPECT_TRUE(std::isnan(none.quantiles[2].second));
  const ResponseStatistics one = statistics({42.0});
  EXPECT_EQ(one.count, 1u);
  EXPECT_EQ(one.mean, 42.0);
  EXPECT_TRUE(std::isnan(one.std));
  for (const auto& q : one.quantiles) EXPECT_EQ(q.second, 42.0);
  EXPECT_EQ(statistics({}).count, 0u);
}

TEST(Statistics, MomentsAgreeWithOpenTURNS) {
  std::mt19937_64 rng(7);
  std::lognormal_distribution<double> dist(1.0, 0.7);
  std::vector<double> v(1001);
  for (double& x : v) x = 1e6 + dist(rng);  // large offset: checks the two-pass variance
  const ResponseStatistics s = statistics(v);
  OT::Sample sample(v.size(), 1);
  for (std::size_t k = 0; k < v.size(); ++k) sample(k, 0) = v[k];
  EXPECT_NEAR(s.mean, sample.computeMean()[0], 1e-13 * std::abs(s.mean));  // summation order differs
  EXPECT_NEAR(s.std, sample.computeStandardDeviation()[0], 1e-9);
  EXPECT_EQ(s.min, sample.getMin()[0]);
  EXPECT_EQ(s.max, sample.getMax()[0]);
  // OpenTURNS 1.20 interpolates quantiles at h = n p - 1/2 (type 5), we at h = (n - 1) p (type 7):
  // with n = 1001 the median coincides (h = 500 both) and the others differ by < one order statistic.
  std::vector<double> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_DOUBLE_EQ(s.quantiles[2].second, sorted[500]);
  EXPECT_NEAR(s.quantiles[2].second, sample.computeQuantilePerComponent(0.5)[0], 1e-9);
  for (const auto& [p, q] : s.quantiles) {
    const auto k = static_cast<std::size_t>(p * 1000.0);
    EXPECT_GE(q, sorted[k - 1]);
    EXPECT_LE(q, sorted[k + 1]);
    EXPECT_NEAR(q, sample.computeQuantilePerComponent(p)[0], sorted[k + 1] - sorted[k - 1]);
  }
}

// ---------------------------------------------------------------- correlation oracles (Eigen)

Eigen::MatrixXd to_matrix(const Rows& rows) {
  Eigen::MatrixXd m(rows.size(), rows.front().size());
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (std::size_t c = 0; c < rows[k].size(); ++c) m(k, c) = rows[k][c];
  return m;
}

double pearson(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::VectorXd ca = a.array() - a.mean(), cb = b.array() - b.mean();
  return ca.dot(cb) / (ca.norm() * cb.norm());
}

// Average ranks (ties share the mean of their positions).
Eigen::VectorXd ranks(const Eigen::VectorXd& v) {
  std::vector<Eigen::Index> idx(v.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](Eigen::Index a, Eigen::Index b) { return v(a) < v(b); });
  Eigen::VectorXd r(v.size());
  for (Eigen::Index i = 0; i < v.size();) {
    Eigen::Index j = i;
    while (j + 1 < v.size() && v(idx[j + 1]) == v(idx[i])) ++j;
    for (Eigen::Index k = i; k <= j; ++k) r(idx[k]) = 0.5 * static_cast<double>(i + j);
    i = j + 1;
  }
  return r;
}

// Residual of v after least squares on [1, X without column skip].
Eigen::VectorXd residual(const Eigen::MatrixXd& x, Eigen::Index skip, const Eigen::VectorXd& v) {
  Eigen::MatrixXd a(x.rows(), x.cols());
  a.col(0).setOnes();
  for (Eigen::Index c = 0, d = 1; c < x.cols(); ++c)
    if (c != skip) a.col(d++) = x.col(c);
  return v - a * a.colPivHouseholderQr().solve(v);
}

double partial(const Eigen::MatrixXd& x, Eigen::Index i, const Eigen::VectorXd& y) {
  return pearson(residual(x, i, x.col(i)), residual(x, i, y));
}

Eigen::MatrixXd rank_columns(const Eigen::MatrixXd& m) {
  Eigen::MatrixXd r(m.rows(), m.cols());
  for (Eigen::Index c = 0; c < m.cols(); ++c) r.col(c) = ranks(m.col(c));
  return r;
}

// ---------------------------------------------------------------- correlations

// y = 2 x1 - 3 x2 + e, x1 ~ U(0, 1), x2 ~ U(0, 2), e ~ N(0, 0.5^2), independent; plus the exact
// z = 2 x1 - 3 x2 as a second response.
struct LinearSample {
  Rows inputs, responses;
};

LinearSample linear_sample(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.5);
  LinearSample s;
  for (std::size_t k = 0; k < n; ++k) {
    const double x1 = u(rng), x2 = 2.0 * u(rng);
    s.inputs.push_back({x1, x2});
    s.responses.push_back({2.0 * x1 - 3.0 * x2 + noise(rng), 2.0 * x1 - 3.0 * x2});
  }
  return s;
}

TEST(Correlations, LinearModelClosedForms) {
  const std::size_t n = 10000;
  const LinearSample s = linear_sample(n, 2024);
  const CorrelationMatrices c = correlations({"x1", "x2"}, s.inputs, {"y", "z"}, s.responses);
  const double b1 = 2.0, b2 = -3.0, s1 = 1.0 / std::sqrt(12.0), s2 = 2.0 / std::sqrt(12.0), var_e = 0.25;
  const double sy = std::sqrt(b1 * b1 * s1 * s1 + b2 * b2 * s2 * s2 + var_e);
  // The standard error of a sample correlation is (1 - rho^2) / sqrt(n) <= 1 / sqrt(n); 4 of them
  // make a false failure practically impossible (and the seed is fixed anyway).
  const double tol = 4.0 / std::sqrt(static_cast<double>(n));

  ASSERT_EQ(c.names, (std::vector<std::string>{"x1", "x2", "y", "z"}));
  EXPECT_EQ(c.rows_used, n);
  EXPECT_EQ(c.rows_dropped, 0u);
  ASSERT_EQ(c.pearson.size(), 4u);
  ASSERT_EQ(c.spearman.size(), 4u);
  for (std::size_t a = 0; a < 4; ++a) {
    ASSERT_EQ(c.pearson[a].size(), 4u);
    EXPECT_NEAR(c.pearson[a][a], 1.0, 1e-12);
    EXPECT_NEAR(c.spearman[a][a], 1.0, 1e-12);
    for (std::size_t b = 0; b < 4; ++b) {
      EXPECT_NEAR(c.pearson[a][b], c.pearson[b][a], 1e-14);
      EXPECT_NEAR(c.spearman[a][b], c.spearman[b][a], 1e-14);
    }
  }
  EXPECT_NEAR(c.pearson[0][1], 0.0, tol);           // independent inputs
  EXPECT_NEAR(c.pearson[2][0], b1 * s1 / sy, tol);  // corr(y, x1) = b1 s1 / sy
  EXPECT_NEAR(c.pearson[2][1], b2 * s2 / sy, tol);  // corr(y, x2) = b2 s2 / sy
  EXPECT_NEAR(c.pearson[2][3], std::sqrt(1 - var_e / (sy * sy)), tol);

  // Partial layout: inputs x responses. Given x2, y's remaining variance is b1^2 s1^2 + var_e.
  ASSERT_EQ(c.partial.size(), 2u);
  ASSERT_EQ(c.partial[0].size(), 2u);
  ASSERT_EQ(c.partial_rank.size(), 2u);
  ASSERT_EQ(c.partial_rank[0].size(), 2u);
  EXPECT_NEAR(c.partial[0][0], b1 * s1 / std::sqrt(b1 * b1 * s1 * s1 + var_e), tol);
  EXPECT_NEAR(c.partial[1][0], b2 * s2 / std::sqrt(b2 * b2 * s2 * s2 + var_e), tol);
  // Exact linear response: partial correlations are +-1 (sign of b_i).
  EXPECT_NEAR(c.partial[0][1], 1.0, 1e-9);
  EXPECT_NEAR(c.partial[1][1], -1.0, 1e-9);
  EXPECT_GT(c.partial_rank[0][1], 0.9);  // ranks of a sum are not linear in the ranks: only near +-1
  EXPECT_LT(c.partial_rank[1][1], -0.9);

  const std::vector<Regression> reg = standardized_regression(s.inputs, s.responses);
  ASSERT_EQ(reg.size(), 2u);
  ASSERT_EQ(reg[0].src.size(), 2u);
  EXPECT_NEAR(reg[0].src[0], b1 * s1 / sy, tol);
  EXPECT_NEAR(reg[0].src[1], b2 * s2 / sy, tol);
  EXPECT_NEAR(reg[0].r2, 1.0 - var_e / (sy * sy), tol);
  EXPECT_NEAR(reg[1].r2, 1.0, 1e-10);
  EXPECT_EQ(reg[0].rows_used, n);
}

TEST(Correlations, AgreeWithEigenOracle) {
  // Correlated inputs and a nonlinear response, so that simple, partial and rank versions differ.
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Rows inputs, responses;
  for (int k = 0; k < 300; ++k) {
    const double x1 = u(rng), x2 = 0.5 * x1 + u(rng), x3 = u(rng);
    inputs.push_back({x1, x2, x3});
    responses.push_back({std::exp(2 * x1) + x2 * x3 + 0.1 * u(rng), x1 - x3 * x3});
  }
  const CorrelationMatrices c = correlations({"a", "b", "c"}, inputs, {"f", "g"}, responses);
  const std::vector<Regression> reg = standardized_regression(inputs, responses);
  const Eigen::MatrixXd x = to_matrix(inputs), y = to_matrix(responses);
  Eigen::MatrixXd all(x.rows(), 5);
  all << x, y;
  const Eigen::MatrixXd rall = rank_columns(all), rx = rank_columns(x), ry = rank_columns(y);
  for (Eigen::Index a = 0; a < 5; ++a)
    for (Eigen::Index b = 0; b < 5; ++b) {
      EXPECT_NEAR(c.pearson[a][b], pearson(all.col(a), all.col(b)), 1e-10);
      EXPECT_NEAR(c.spearman[a][b], pearson(rall.col(a), rall.col(b)), 1e-10);
    }
  for (Eigen::Index j = 0; j < 2; ++j) {
    // OLS on standardized columns gives the SRC; R^2 from the raw fit's residuals.
    Eigen::MatrixXd a(x.rows(), 4);
    a.col(0).setOnes();
    a.rightCols(3) = x;
    const Eigen::VectorXd beta = a.colPivHouseholderQr().solve(y.col(j));
    const Eigen::VectorXd res = y.col(j) - a * beta;
    const Eigen::VectorXd yc = y.col(j).array() - y.col(j).mean();
    const double sdy = std::sqrt(yc.squaredNorm() / static_cast<double>(x.rows() - 1));
    EXPECT_NEAR(reg[j].r2, 1.0 - res.squaredNorm() / yc.squaredNorm(), 1e-10);
    for (Eigen::Index i = 0; i < 3; ++i) {
      EXPECT_NEAR(c.partial[i][j], partial(x, i, y.col(j)), 1e-10);
      EXPECT_NEAR(c.partial_rank[i][j], partial(rx, i, ry.col(j)), 1e-10);
      const Eigen::VectorXd xc = x.col(i).array() - x.col(i).mean();
      const double sdx = std::sqrt(xc.squaredNorm() / static_cast<double>(x.rows() - 1));
      EXPECT_NEAR(reg[j].src[i], beta(i + 1) * sdx / sdy, 1e-10);
    }
  }
}

TEST(Correlations, SpearmanOfMonotoneTransformIsOne) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Rows inputs, responses;
  for (int k = 0; k < 200; ++k) {
    const double x = u(rng);
    inputs.push_back({x});
    responses.push_back({std::exp(5 * x), -std::pow(x, 7)});
  }
  const CorrelationMatrices c = correlations({"x"}, inputs, {"up", "down"}, responses);
  EXPECT_NEAR(c.spearman[0][1], 1.0, 1e-12);
  EXPECT_NEAR(c.spearman[0][2], -1.0, 1e-12);
  EXPECT_NEAR(c.spearman[1][2], -1.0, 1e-12);
  EXPECT_LT(c.pearson[0][1], 0.95);               // but not linearly related
  EXPECT_NEAR(c.partial_rank[0][0], 1.0, 1e-12);  // one input: partial = simple
  EXPECT_NEAR(c.partial[0][0], c.pearson[0][1], 1e-12);
}

TEST(Correlations, FailedRowsAreDroppedAndCounted) {
  LinearSample s = linear_sample(100, 11);
  const CorrelationMatrices clean = correlations({"x1", "x2"}, s.inputs, {"y", "z"}, s.responses);
  LinearSample with_failures = s;
  with_failures.inputs.insert(with_failures.inputs.begin() + 3, {0.5, 0.5});
  with_failures.responses.insert(with_failures.responses.begin() + 3, {kNaN, 1.0});
  with_failures.inputs.push_back({0.1, 0.2});
  with_failures.responses.push_back({1.0, kNaN});
  const CorrelationMatrices c = correlations({"x1", "x2"}, with_failures.inputs, {"y", "z"}, with_failures.responses);
  EXPECT_EQ(c.rows_used, 100u);
  EXPECT_EQ(c.rows_dropped, 2u);
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = 0; b < 4; ++b) {
      EXPECT_DOUBLE_EQ(c.pearson[a][b], clean.pearson[a][b]);
      EXPECT_DOUBLE_EQ(c.spearman[a][b], clean.spearman[a][b]);
    }
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t j = 0; j < 2; ++j) EXPECT_DOUBLE_EQ(c.partial[i][j], clean.partial[i][j]);
  const std::vector<Regression> reg = standardized_regression(with_failures.inputs, with_failures.responses);
  EXPECT_EQ(reg[0].rows_dropped, 2u);
}

TEST(Correlations, UndefinedEntriesAreNaN) {
  Rows inputs, responses;
  for (int k = 0; k < 20; ++k) {
    inputs.push_back({double(k), 3.0});  // second input held constant
    responses.push_back({2.0 * k + std::sin(k), 7.0});
  }
  const CorrelationMatrices c = correlations({"x", "fixed"}, inputs, {"y", "flat"}, responses);
  EXPECT_TRUE(std::isnan(c.pearson[0][1]));
  EXPECT_TRUE(std::isnan(c.spearman[1][2]));
  EXPECT_TRUE(std::isnan(c.pearson[3][0]));
  EXPECT_FALSE(std::isnan(c.pearson[0][2]));
  EXPECT_TRUE(std::isnan(c.partial[1][0]));
  EXPECT_TRUE(std::isnan(c.partial[0][1]));
  // The constant input leaves the conditioning set: x's partial correlation with y is the simple one.
  EXPECT_NEAR(c.partial[0][0], c.pearson[0][2], 1e-12);
  // Too few rows for partial correlations of 2 inputs.
  const CorrelationMatrices small = correlations({"a", "b"}, {{0, 1}, {1, 0}, {2, 5}}, {"y"}, {{1}, {2}, {4}});
  EXPECT_TRUE(std::isnan(small.partial[0][0]));
  EXPECT_FALSE(std::isnan(small.pearson[0][2]));
  EXPECT_THROW(correlations({"a"}, {{1.0}}, {"y"}, {{1.0}, {2.0}}), std::invalid_argument);
  EXPECT_THROW(correlations({"a", "b"}, {{1.0}}, {"y"}, {{1.0}}), std::invalid_argument);
}

// ---------------------------------------------------------------- Morris

TEST(Morris, DesignStructure) {
  const std::vector<double> lower{-1.0, 10.0, 0.0}, upper{1.0, 20.0, 5.0};
  const std::size_t r = 25, m = 3, p = 6;
  const MorrisDesign d = morris_design(lower, upper, r, p, 1234);
  ASSERT_EQ(d.points.size(), r * (m + 1));
  ASSERT_EQ(d.changed.size(), r * m);
  EXPECT_EQ(d.trajectories, r);
  EXPECT_EQ(d.dimension, m);
  const double delta = static_cast<double>(p) / (2.0 * (p - 1));
  std::vector<std::set<long>> levels_seen(m);
  for (std::size_t k = 0; k < d.points.size(); ++k)
    for (std::size_t i = 0; i < m; ++i) {
      ASSERT_EQ(d.points[k].size(), m);
      const double level = (d.points[k][i] - lower[i]) / (upper[i] - lower[i]) * (p - 1);
      EXPECT_NEAR(level, std::round(level), 1e-9) << "point " << k << " input " << i << " is off the grid";
      EXPECT_GE(d.points[k][i], lower[i]);
      EXPECT_LE(d.points[k][i], upper[i]);
      levels_seen[i].insert(std::lround(level));
    }
  for (std::size_t i = 0; i < m; ++i) EXPECT_EQ(levels_seen[i].size(), p);
  for (std::size_t t = 0; t < r; ++t) {
    std::set<std::size_t> moved;
    for (std::size_t j = 0; j < m; ++j) {
      const auto& a = d.points[t * (m + 1) + j];
      const auto& b = d.points[t * (m + 1) + j + 1];
      std::size_t differing = 0;
      for (std::size_t i = 0; i < m; ++i)
        if (a[i] != b[i]) {
          ++differing;
          EXPECT_EQ(i, d.changed[t * m + j]);
          EXPECT_NEAR(std::abs(b[i] - a[i]), delta * (upper[i] - lower[i]), 1e-12);
        }
      EXPECT_EQ(differing, 1u);
      moved.insert(d.changed[t * m + j]);
    }
    EXPECT_EQ(moved.size(), m);  // each input moves once per trajectory
  }
  // Seeded: the same seed reproduces the design, another seed does not.
  EXPECT_EQ(morris_design(lower, upper, r, p, 1234).points, d.points);
  EXPECT_NE(morris_design(lower, upper, r, p, 1235).points, d.points);
  EXPECT_THROW(morris_design(lower, upper, r, 5, 1), InputError);
  EXPECT_THROW(morris_design(lower, upper, 0, 4, 1), InputError);
  EXPECT_THROW(morris_design({1.0}, {0.0}, 2, 4, 1), InputError);
}

TEST(Morris, EffectsOfKnownFunction) {
  // f = 3 x1 + x2^2 + 0 x3 on [0, 1]^3: EE_1 = 3, EE_2 = x2 + x2' (varies), EE_3 = 0.
  const std::vector<double> lower(3, 0.0), upper(3, 1.0);
  const std::size_t r = 20;
  const MorrisDesign d = morris_design(lower, upper, r, 4, 42);
  std::vector<double> y;
  for (const auto& x : d.points) y.push_back(3 * x[0] + x[1] * x[1] + 0 * x[2]);
  const MorrisEffects e = morris_effects(d, y, lower, upper);
  ASSERT_EQ(e.mu_star.size(), 3u);
  EXPECT_NEAR(e.mu[0], 3.0, 1e-12);
  EXPECT_NEAR(e.mu_star[0], 3.0, 1e-12);
  EXPECT_NEAR(e.sigma[0], 0.0, 1e-12);
  EXPECT_EQ(e.mu_star[2], 0.0);
  EXPECT_EQ(e.sigma[2], 0.0);
  EXPECT_GT(e.mu_star[1], 0.0);
  EXPECT_GT(e.sigma[1], 0.0);
  // EE_2 takes the values 2/3 and 4/3 (p = 4, Delta = 2/3), so mu*_2 lies between them.
  EXPECT_GE(e.mu_star[1], 2.0 / 3.0 - 1e-12);
  EXPECT_LE(e.mu_star[1], 4.0 / 3.0 + 1e-12);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(e.count[i], r);
}

TEST(Morris, PhysicalUnitsAndFailedEvaluations) {
  // Effects are per physical unit: f = 3 x1 - 0.5 x2 over x1 in [2, 12], x2 in [-100, 100].
  const std::vector<double> lower{2.0, -100.0}, upper{12.0, 100.0};
  const MorrisDesign d = morris_design(lower, upper, 10, 4, 7);
  std::vector<double> y;
  for (const auto& x : d.points) y.push_back(3 * x[0] - 0.5 * x[1]);
  MorrisEffects e = morris_effects(d, y, lower, upper);
  EXPECT_NEAR(e.mu[0], 3.0, 1e-12);
  EXPECT_NEAR(e.mu[1], -0.5, 1e-12);
  EXPECT_NEAR(e.mu_star[1], 0.5, 1e-12);
  // A failed evaluation removes the (up to two) elementary effects it takes part in.
  y[d.dimension + 2] = kNaN;  // second trajectory, its middle point: two effects lost
  e = morris_effects(d, y, lower, upper);
  EXPECT_EQ(e.count[0] + e.count[1], 2u * 10u - 2u);
  EXPECT_NEAR(e.mu[0], 3.0, 1e-12);
  EXPECT_THROW(morris_effects(d, std::vector<double>(3, 0.0), lower, upper), std::invalid_argument);
}

}  // namespace
}  // namespace suite::studies
