// Distributions, random and quasi-random designs and Sobol' indices (docs/methods/studies.md: `sampling`,
// `sobol_indices`, validation references), against closed forms and OpenTURNS itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <openturns/SobolSequence.hxx>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/errors.hpp"
#include "studies/design/distributions.hpp"
#include "studies/design/sampling.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using namespace suite::studies;
using suite::config::Config;
constexpr double kPi = std::numbers::pi;

Distribution dist(const std::string& type, std::map<std::string, double> parameters) {
  return {type, std::move(parameters), std::nullopt};
}

Distribution parse(const std::string& yaml) {
  auto cfg = Config::from_string("distribution: " + yaml + "\n", "study.yaml");
  auto d = read_distribution(cfg.root().section("distribution"));
  cfg.finish();
  return d;
}

using suite::testing::input_error_of;

std::vector<double> column(const std::vector<Point>& points, std::size_t j) {
  std::vector<double> c;
  for (const auto& p : points) c.push_back(p[j]);
  return c;
}

double mean_of(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / v.size();
}

double variance_of(const std::vector<double>& v) {
  const double m = mean_of(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return s / (v.size() - 1);
}

std::vector<double> ranks(const std::vector<double>& v) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (std::size_t k = 0; k < order.size(); ++k) r[order[k]] = static_cast<double>(k);
  return r;
}

double spearman(const std::vector<double>& x, const std::vector<double>& y) {
  const auto rx = ranks(x), ry = ranks(y);
  const double mx = mean_of(rx), my = mean_of(ry);
  double sxy = 0, sxx = 0, syy = 0;
  for (std::size_t i = 0; i < rx.size(); ++i) {
    sxy += (rx[i] - mx) * (ry[i] - my);
    sxx += (rx[i] - mx) * (rx[i] - mx);
    syy += (ry[i] - my) * (ry[i] - my);
  }
  return sxy / std::sqrt(sxx * syy);
}

const std::vector<Distribution> kThree = {dist("normal", {{"mean", 2}, {"std", 0.5}}),
                                          dist("lognormal", {{"mean", 3}, {"std", 1.2}, {"location", 0}}),
                                          dist("triangular", {{"lower", 0}, {"mode", 1}, {"upper", 4}})};

TEST(Distributions, EveryTypeMatchesItsClosedForm) {
  // The parameterisations documented in distributions.hpp, checked through the cdf.
  const double x = 1.7;
  EXPECT_NEAR(cdf(parse("{type: uniform, lower: 1, upper: 3}"), x), 0.35, 1e-14);
  EXPECT_NEAR(cdf(parse("{type: normal, mean: 2, std: 0.5}"), x), 0.5 * std::erfc(0.3 / 0.5 / std::sqrt(2.0)), 1e-12);
  {  // mean and std of the variable itself, not of its log
    const double mean = 3, sd = 1.2, s2 = std::log(1 + sd * sd / (mean * mean)), mu = std::log(mean) - s2 / 2;
    EXPECT_NEAR(cdf(parse("{type: lognormal, mean: 3, std: 1.2}"), x),
                0.5 * std::erfc(-(std::log(x) - mu) / std::sqrt(2 * s2)), 1e-12);
    EXPECT_NEAR(cdf(parse("{type: lognormal, mean: 4, std: 1.2, location: 1}"), x + 1),
                0.5 * std::erfc(-(std::log(x) - mu) / std::sqrt(2 * s2)), 1e-12);
  }
  EXPECT_NEAR(cdf(parse("{type: loguniform, lower: 1, upper: 10}"), x), std::log(x) / std::log(10.0), 1e-14);
  EXPECT_NEAR(cdf(parse("{type: triangular, lower: 0, mode: 1, upper: 4}"), x), 1 - (4 - x) * (4 - x) / 12, 1e-14);
  EXPECT_NEAR(cdf(parse("{type: exponential, rate: 2}"), x), 1 - std::exp(-2 * x), 1e-14);
  EXPECT_NEAR(cdf(parse("{type: exponential, rate: 2, location: 0.5}"), x), 1 - std::exp(-2 * (x - 0.5)), 1e-14);
  EXPECT_NEAR(cdf(parse("{type: beta, alpha: 2, beta: 1, lower: 1, upper: 3}"), x), 0.35 * 0.35, 1e-12);
  EXPECT_NEAR(cdf(parse("{type: gamma, shape: 1, rate: 2, location: 0.5}"), x), 1 - std::exp(-2 * (x - 0.5)), 1e-12);
  EXPECT_NEAR(cdf(parse("{type: gamma, shape: 2, rate: 3}"), x), 1 - std::exp(-3 * x) * (1 + 3 * x), 1e-12);
  EXPECT_NEAR(cdf(parse("{type: gumbel, scale: 0.5, location: 1}"), x), std::exp(-std::exp(-(x - 1) / 0.5)), 1e-14);
  EXPECT_NEAR(cdf(parse("{type: weibull, scale: 2, shape: 1.5, location: 0.2}"), x),
              1 - std::exp(-std::pow((x - 0.2) / 2, 1.5)), 1e-14);
  EXPECT_NEAR(quantile(parse("{type: uniform, lower: 1, upper: 3}"), 0.25), 1.5, 1e-14);
  // Defaults are recorded, so the effective configuration is complete.
  EXPECT_EQ(parse("{type: weibull, scale: 2, shape: 1.5}").parameters.at("location"), 0.0);
  EXPECT_EQ(distribution_types().size(), 10u);
  EXPECT_EQ(describe(parse("{type: normal, mean: 2, std: 0.5}")), "normal(mean=2, std=0.5)");
}

TEST(Distributions, BadInputNamesTheKey) {
  std::string e = input_error_of([] { parse("{type: normal, mean: 2, std: 0}"); });
  EXPECT_NE(e.find("study.yaml:1:"), std::string::npos) << e;
  EXPECT_NE(e.find("key 'distribution.std'"), std::string::npos) << e;
  EXPECT_NE(e.find("> 0"), std::string::npos) << e;

  e = input_error_of([] { parse("{type: normall, mean: 2, std: 1}"); });
  EXPECT_NE(e.find("key 'distribution.type'"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'normal'"), std::string::npos) << e;

  e = input_error_of([] { parse("{type: triangular, lower: 0, mode: 5, upper: 4}"); });
  EXPECT_NE(e.find("key 'distribution.mode'"), std::string::npos) << e;
  EXPECT_NE(e.find("[0, 4]"), std::string::npos) << e;

  e = input_error_of([] { parse("{type: uniform, lower: 3, upper: 3}"); });
  EXPECT_NE(e.find("key 'distribution.upper'"), std::string::npos) << e;

  e = input_error_of([] { parse("{type: lognormal, mean: -1, std: 1}"); });
  EXPECT_NE(e.find("key 'distribution.mean'"), std::string::npos) << e;

  e = input_error_of([] { parse("{type: loguniform, lower: 0, upper: 3}"); });
  EXPECT_NE(e.find("key 'distribution.lower'"), std::string::npos) << e;

  e = input_error_of([] { parse("{type: normal, mean: 2, sd: 1}"); });  // a typo of std
  EXPECT_NE(e.find("std"), std::string::npos) << e;

  // Distributions built in code are checked too.
  e = input_error_of([] { sample({dist("normal", {{"mean", 0}, {"std", -1}})}, SamplingKind::lhs, 4, 1); });
  EXPECT_NE(e.find("'std'"), std::string::npos) << e;
  e = input_error_of([] { validate(dist("gauss", {})); });
  EXPECT_NE(e.find("'gauss'"), std::string::npos) << e;
}

TEST(Sampling, CountsAndSeedReproducibility) {
  for (auto kind : {SamplingKind::lhs, SamplingKind::random, SamplingKind::sobol_sequence}) {
    const auto a = sample(kThree, kind, 37, 12345);
    ASSERT_EQ(a.size(), 37u);
    for (const auto& p : a) ASSERT_EQ(p.size(), 3u);
    const auto b = sample(kThree, kind, 37, 12345);
    for (std::size_t i = 0; i < a.size(); ++i)
      for (std::size_t j = 0; j < 3; ++j)
        ASSERT_EQ(std::bit_cast<std::uint64_t>(a[i][j]), std::bit_cast<std::uint64_t>(b[i][j]));
    const auto c = sample(kThree, kind, 37, 54321);
    if (kind == SamplingKind::sobol_sequence)
      EXPECT_EQ(a, c);  // deterministic, the seed plays no part
    else
      EXPECT_NE(a, c);
  }
  EXPECT_TRUE(sample(kThree, SamplingKind::lhs, 0, 1).empty());
  // OpenTURNS 1.20 keeps 32 bits of a seed; the high half is folded in, not dropped.
  EXPECT_NE(sample(kThree, SamplingKind::random, 5, 1), sample(kThree, SamplingKind::random, 5, 1 + (1ULL << 32)));

  const auto s1 = saltelli_design(kThree, 8, 7), s2 = saltelli_design(kThree, 8, 7);
  EXPECT_EQ(s1.points.size(), 8u * (3 + 2));
  EXPECT_EQ(s1.base_size, 8u);
  EXPECT_EQ(s1.dimension, 3u);
  EXPECT_EQ(s1.points, s2.points);
  EXPECT_NE(s1.points, saltelli_design(kThree, 8, 8).points);
}

TEST(Sampling, SaltelliBlocksAreAThenBThenPickFreeze) {
  const std::size_t n = 5, m = 3;
  const auto d = saltelli_design(kThree, n, 3);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t r = 0; r < n; ++r)
      for (std::size_t j = 0; j < m; ++j) {
        const double a = d.points[r][j], b = d.points[n + r][j], e = d.points[(2 + i) * n + r][j];
        EXPECT_EQ(e, j == i ? b : a) << "block " << i << " row " << r << " column " << j;
      }
}

TEST(Sampling, LhsStratifiesEveryMarginal) {
  // Each of the n equal-probability strata of every marginal holds exactly one point, with or
  // without a rank correlation (which re-pairs the columns but keeps their values).
  const std::vector<Distribution> marginals = {kThree[0],
                                               kThree[1],
                                               kThree[2],
                                               dist("gumbel", {{"scale", 0.5}, {"location", 1}}),
                                               dist("weibull", {{"scale", 2}, {"shape", 1.5}, {"location", 0}}),
                                               dist("beta", {{"alpha", 2}, {"beta", 5}, {"lower", -1}, {"upper", 1}})};
  const std::size_t n = 200, m = marginals.size();
  std::vector<std::vector<double>> rho(m, std::vector<double>(m, 0.0));
  for (std::size_t i = 0; i < m; ++i) rho[i][i] = 1;
  rho[0][1] = rho[1][0] = 0.6;
  rho[2][4] = rho[4][2] = -0.4;
  for (const auto& correlation : {std::vector<std::vector<double>>{}, rho}) {
    const auto x = sample(marginals, SamplingKind::lhs, n, 2024, correlation);
    for (std::size_t j = 0; j < m; ++j) {
      std::vector<int> count(n, 0);
      for (const auto& p : x) {
        const double u = cdf(marginals[j], p[j]) * n;
        ++count[std::min<std::size_t>(static_cast<std::size_t>(u), n - 1)];
      }
      EXPECT_TRUE(std::all_of(count.begin(), count.end(), [](int c) { return c == 1; }))
          << "variable " << j << (correlation.empty() ? "" : " (correlated)");
    }
  }
}

TEST(Sampling, MomentsWithinFourStandardErrors) {
  const std::size_t n = 20000;
  const double mu = 2, sigma = 0.5;  // normal
  const double lm = 3, ls = 1.2;     // lognormal, mean and std of the variable
  const double s2 = std::log(1 + ls * ls / (lm * lm));
  const double excess = std::exp(4 * s2) + 2 * std::exp(3 * s2) + 3 * std::exp(2 * s2) - 6;
  const std::vector<Distribution> marginals = {kThree[0], kThree[1]};
  for (auto kind : {SamplingKind::random, SamplingKind::lhs, SamplingKind::sobol_sequence}) {
    const auto x = sample(marginals, kind, n, 99);
    const auto a = column(x, 0), b = column(x, 1);
    // Standard errors of the iid estimators (LHS and Sobol' do better, never worse here).
    EXPECT_NEAR(mean_of(a), mu, 4 * sigma / std::sqrt(n));
    EXPECT_NEAR(variance_of(a), sigma * sigma, 4 * sigma * sigma * std::sqrt(2.0 / n));
    EXPECT_NEAR(mean_of(b), lm, 4 * ls / std::sqrt(n));
    EXPECT_NEAR(variance_of(b), ls * ls, 4 * ls * ls * std::sqrt((excess + 2) / n));
  }
}

TEST(Sampling, SobolSequenceIsOpenTurnsSobolSequenceThroughTheQuantiles) {
  const std::size_t n = 64;
  const auto unit =
      sample({dist("uniform", {{"lower", 0}, {"upper", 1}}), dist("uniform", {{"lower", 0}, {"upper", 1}}),
              dist("uniform", {{"lower", 0}, {"upper", 1}})},
             SamplingKind::sobol_sequence, n, 0);
  const auto scaled =
      sample({dist("uniform", {{"lower", -1}, {"upper", 3}}), dist("uniform", {{"lower", 10}, {"upper", 11}}),
              dist("uniform", {{"lower", 0}, {"upper", 8}})},
             SamplingKind::sobol_sequence, n, 0);
  const OT::Sample reference = OT::SobolSequence(3).generate(n);
  const double lo[] = {-1, 10, 0}, hi[] = {3, 11, 8};
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      EXPECT_EQ(unit[i][j], reference(i, j)) << i << "," << j;
      EXPECT_NEAR(scaled[i][j], lo[j] + (hi[j] - lo[j]) * reference(i, j), 1e-14) << i << "," << j;
    }
  // OpenTURNS skips the origin: the first point is the centre of the cube.
  EXPECT_EQ(unit[0], (Point{0.5, 0.5, 0.5}));
  EXPECT_EQ(unit[1], (Point{0.75, 0.25, 0.75}));
}

TEST(Sampling, RankCorrelation) {
  const std::vector<Distribution> marginals = {kThree[0], kThree[1]};
  const std::vector<std::vector<double>> rho = {{1, 0.7}, {0.7, 1}};
  for (auto kind : {SamplingKind::lhs, SamplingKind::random}) {
    const auto x = sample(marginals, kind, 5000, 11, rho);
    EXPECT_NEAR(spearman(column(x, 0), column(x, 1)), 0.7, 0.05);
  }
  const auto independent = sample(marginals, SamplingKind::lhs, 5000, 11);
  EXPECT_NEAR(spearman(column(independent, 0), column(independent, 1)), 0.0, 0.05);

  std::string e = input_error_of([&] { sample(marginals, SamplingKind::sobol_sequence, 10, 1, rho); });
  EXPECT_NE(e.find("sobol_sequence"), std::string::npos) << e;
  e = input_error_of([&] { sample(marginals, SamplingKind::lhs, 10, 1, {{1, 0.7}, {0.6, 1}}); });
  EXPECT_NE(e.find("symmetric"), std::string::npos) << e;
  e = input_error_of([&] { sample(marginals, SamplingKind::lhs, 10, 1, {{1, 0.7}}); });
  EXPECT_NE(e.find("rows"), std::string::npos) << e;
  e = input_error_of([&] {
    sample({kThree[0], kThree[1], kThree[2]}, SamplingKind::random, 10, 1,
           {{1, 0.9, -0.9}, {0.9, 1, 0.9}, {-0.9, 0.9, 1}});
  });
  EXPECT_NE(e.find("positive definite"), std::string::npos) << e;
}

TEST(SobolIndices, IshigamiWithinTheBootstrapIntervals) {
  // Ishigami f = sin x1 + a sin^2 x2 + b x3^4 sin x1, X_i ~ U(-pi, pi); exact indices from the
  // partial variances, compared with the 4-digit values of docs/methods/studies.md.
  const double a = 7, b = 0.1, p4 = std::pow(kPi, 4), p8 = p4 * p4;
  const double v1 = 0.5 * std::pow(1 + b * p4 / 5, 2), v2 = a * a / 8, v13 = 8 * b * b * p8 / 225;
  const double v = v1 + v2 + v13;
  const double s[3] = {v1 / v, v2 / v, 0.0}, st[3] = {(v1 + v13) / v, v2 / v, v13 / v};
  const double spec_s[3] = {0.3139, 0.4424, 0}, spec_st[3] = {0.5576, 0.4424, 0.2437};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(s[i], spec_s[i], 5e-5);
    EXPECT_NEAR(st[i], spec_st[i], 5e-5);
  }

  const std::size_t n = 10000;
  const Distribution u = dist("uniform", {{"lower", -kPi}, {"upper", kPi}});
  const auto design = saltelli_design({u, u, u}, n, 20240607);
  ASSERT_EQ(design.points.size(), n * 5);
  std::vector<double> y;
  for (const auto& x : design.points)
    y.push_back(std::sin(x[0]) + a * std::pow(std::sin(x[1]), 2) + b * std::pow(x[2], 4) * std::sin(x[0]));
  const auto r = sobol_indices(design, y, 0.95, 1000);
  ASSERT_EQ(r.first.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_LE(r.first_low[i], s[i]) << "S" << i + 1 << " = " << r.first[i];
    EXPECT_GE(r.first_high[i], s[i]) << "S" << i + 1 << " = " << r.first[i];
    EXPECT_LE(r.total_low[i], st[i]) << "ST" << i + 1 << " = " << r.total[i];
    EXPECT_GE(r.total_high[i], st[i]) << "ST" << i + 1 << " = " << r.total[i];
    EXPECT_LE(r.first_low[i], r.first[i]);
    EXPECT_GE(r.first_high[i], r.first[i]);
    EXPECT_LT(r.first_high[i] - r.first_low[i], 0.15);  // informative, not vacuous
    EXPECT_LT(r.total_high[i] - r.total_low[i], 0.15);
  }
  // Same design, outputs and bootstrap seed: the same intervals (fewer resamplings to save time).
  const auto once = sobol_indices(design, y, 0.9, 100, 5), twice = sobol_indices(design, y, 0.9, 100, 5);
  EXPECT_EQ(once.first, r.first);
  EXPECT_EQ(once.first_low, twice.first_low);
  EXPECT_EQ(once.total_high, twice.total_high);
  EXPECT_NE(once.first_low, r.first_low);
  const auto none = sobol_indices(design, y, 0.95, 0);
  EXPECT_EQ(none.total, r.total);
  EXPECT_TRUE(std::isnan(none.first_low[0]));

  std::string e = input_error_of([&] { sobol_indices(design, std::vector<double>(y.begin(), y.end() - 1)); });
  EXPECT_NE(e.find("outputs"), std::string::npos) << e;
  auto bad = y;
  bad[17] = std::nan("");
  e = input_error_of([&] { sobol_indices(design, bad); });
  EXPECT_NE(e.find("design point 18"), std::string::npos) << e;
}

}  // namespace
