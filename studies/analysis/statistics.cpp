#include "studies/analysis/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace suite::studies {

const std::vector<double>& statistics_quantile_levels() {
  static const std::vector<double> levels{0.05, 0.25, 0.5, 0.75, 0.95};
  return levels;
}

double quantile_type7(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) throw std::invalid_argument("quantile_type7: empty sample");
  if (!(p >= 0.0 && p <= 1.0)) throw std::invalid_argument("quantile_type7: probability outside [0, 1]");
  const double h = static_cast<double>(sorted.size() - 1) * p;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  if (lo + 1 >= sorted.size()) return sorted.back();
  const double frac = h - static_cast<double>(lo);
  return sorted[lo] + frac * (sorted[lo + 1] - sorted[lo]);
}

ResponseStatistics statistics(const std::vector<double>& values) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  ResponseStatistics s;
  std::vector<double> valid;
  valid.reserve(values.size());
  for (double v : values) {
    if (std::isnan(v)) {
      ++s.failed;
    } else {
      valid.push_back(v);
    }
  }
  s.count = valid.size();
  if (valid.empty()) {
    s.mean = s.std = s.min = s.max = nan;
    for (double p : statistics_quantile_levels()) s.quantiles.emplace_back(p, nan);
    return s;
  }
  std::sort(valid.begin(), valid.end());
  const auto n = static_cast<double>(valid.size());
  // Two-pass mean and variance (no cancellation for responses with a large offset).
  double sum = 0.0;
  for (double v : valid) sum += v;
  s.mean = sum / n;
  if (valid.size() > 1) {
    double ss = 0.0;
    for (double v : valid) ss += (v - s.mean) * (v - s.mean);
    s.std = std::sqrt(ss / (n - 1.0));
  } else {
    s.std = nan;
  }
  s.min = valid.front();
  s.max = valid.back();
  for (double p : statistics_quantile_levels()) s.quantiles.emplace_back(p, quantile_type7(valid, p));
  return s;
}

}  // namespace suite::studies
