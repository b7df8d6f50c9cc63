#include "studies/analysis/morris.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "core/errors.hpp"

namespace suite::studies {
namespace {

// Uniform integer in [0, n) by rejection (portable, unlike std::uniform_int_distribution).
std::size_t draw(std::mt19937_64& rng, std::size_t n) {
  const std::uint64_t range = n;
  const std::uint64_t limit =
      std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % range;
  std::uint64_t v = rng();
  while (v >= limit) v = rng();
  return static_cast<std::size_t>(v % range);
}

}  // namespace

MorrisDesign morris_design(const std::vector<double>& lower, const std::vector<double>& upper, std::size_t trajectories,
                           std::size_t levels, std::uint64_t seed) {
  const std::size_t m = lower.size();
  if (m == 0) throw InputError("morris: no variables");
  if (upper.size() != m) throw std::invalid_argument("morris_design: lower and upper differ in size");
  for (std::size_t i = 0; i < m; ++i)
    if (!(lower[i] <= upper[i]))
      throw InputError("morris: variable " + std::to_string(i + 1) + " has lower bound above its upper bound");
  if (trajectories == 0) throw InputError("morris: trajectories must be at least 1");
  if (levels < 2 || levels % 2 != 0)
    throw InputError("morris: levels must be an even number >= 2 (got " + std::to_string(levels) + ")");

  const std::size_t half = levels / 2;  // Delta = half grid intervals
  const double interval = 1.0 / static_cast<double>(levels - 1);
  auto to_physical = [&](std::size_t i, std::size_t level) {
    return level == levels - 1 ? upper[i] : lower[i] + static_cast<double>(level) * interval * (upper[i] - lower[i]);
  };

  MorrisDesign d;
  d.trajectories = trajectories;
  d.dimension = m;
  d.levels = levels;
  d.points.reserve(trajectories * (m + 1));
  d.changed.reserve(trajectories * m);
  std::mt19937_64 rng(seed);
  std::vector<std::size_t> level(m), order(m);
  std::vector<int> direction(m);
  for (std::size_t t = 0; t < trajectories; ++t) {
    for (std::size_t i = 0; i < m; ++i) {
      direction[i] = draw(rng, 2) == 0 ? 1 : -1;
      level[i] = draw(rng, half) + (direction[i] > 0 ? 0 : half);
    }
    for (std::size_t i = 0; i < m; ++i) order[i] = i;
    for (std::size_t i = m; i > 1; --i) std::swap(order[i - 1], order[draw(rng, i)]);  // Fisher-Yates
    std::vector<double> x(m);
    for (std::size_t i = 0; i < m; ++i) x[i] = to_physical(i, level[i]);
    d.points.push_back(x);
    for (std::size_t j = 0; j < m; ++j) {
      const std::size_t i = order[j];
      level[i] = direction[i] > 0 ? level[i] + half : level[i] - half;
      x[i] = to_physical(i, level[i]);
      d.points.push_back(x);
      d.changed.push_back(i);
    }
  }
  return d;
}

MorrisEffects morris_effects(const MorrisDesign& design, const std::vector<double>& outputs,
                             const std::vector<double>& lower, const std::vector<double>& upper) {
  const std::size_t m = design.dimension, r = design.trajectories;
  if (design.points.size() != r * (m + 1) || design.changed.size() != r * m)
    throw std::invalid_argument("morris_effects: inconsistent design");
  if (outputs.size() != design.points.size())
    throw std::invalid_argument("morris_effects: " + std::to_string(outputs.size()) + " outputs for " +
                                std::to_string(design.points.size()) + " design points");
  if (lower.size() != m || upper.size() != m) throw std::invalid_argument("morris_effects: bounds of wrong size");

  std::vector<std::vector<double>> effects(m);
  for (std::size_t t = 0; t < r; ++t) {
    for (std::size_t j = 0; j < m; ++j) {
      const std::size_t k = t * (m + 1) + j, i = design.changed[t * m + j];
      if (i >= m) throw std::invalid_argument("morris_effects: changed input out of range");
      const double dx = design.points[k + 1][i] - design.points[k][i];
      const double dy = outputs[k + 1] - outputs[k];
      if (std::isnan(dy) || dx == 0.0) continue;
      effects[i].push_back(dy / dx);
    }
  }

  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  MorrisEffects e;
  e.mu.assign(m, nan);
  e.mu_star.assign(m, nan);
  e.sigma.assign(m, nan);
  e.count.assign(m, 0);
  for (std::size_t i = 0; i < m; ++i) {
    const std::vector<double>& ee = effects[i];
    e.count[i] = ee.size();
    if (ee.empty()) continue;
    const auto n = static_cast<double>(ee.size());
    double sum = 0.0, sum_abs = 0.0;
    for (double v : ee) {
      sum += v;
      sum_abs += std::abs(v);
    }
    e.mu[i] = sum / n;
    e.mu_star[i] = sum_abs / n;
    if (ee.size() > 1) {
      double ss = 0.0;
      for (double v : ee) ss += (v - e.mu[i]) * (v - e.mu[i]);
      e.sigma[i] = std::sqrt(ss / (n - 1.0));
    }
  }
  return e;
}

}  // namespace suite::studies
