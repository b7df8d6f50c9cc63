#pragma once
// Summary statistics of one response over the evaluations of a study (docs/methods/studies.md,
// "Analysis and output"). NaN entries are failed evaluations: they are skipped and counted.
//
//   mean, std   sample mean and sample standard deviation (denominator count - 1, as Dakota
//               reports it); std is NaN when fewer than 2 values are valid, every field but
//               count/failed is NaN when none is.
//   quantiles   (p, q_p) for p = 0.05, 0.25, 0.5, 0.75, 0.95, Hyndman & Fan (1996) type 7, the
//               default of numpy.quantile, pandas and R: with the valid values sorted
//               x_0 <= ... <= x_{n-1}, h = (n - 1) p, q_p = x_floor(h) + (h - floor(h))
//               (x_floor(h)+1 - x_floor(h)). (OpenTURNS 1.20's Sample::computeQuantilePerComponent
//               interpolates at h = n p - 1/2 instead, Hyndman & Fan type 5; we chose type 7 so
//               that users who cross-check with numpy/pandas get the same numbers.)
#include <cstddef>
#include <utility>
#include <vector>

namespace suite::studies {

struct ResponseStatistics {
  std::size_t count = 0;   // valid (non-NaN) values
  std::size_t failed = 0;  // NaN values skipped
  double mean = 0.0, std = 0.0, min = 0.0, max = 0.0;
  std::vector<std::pair<double, double>> quantiles;  // (probability, value)
};

// The probabilities of ResponseStatistics::quantiles, in order.
const std::vector<double>& statistics_quantile_levels();

// Hyndman-Fan type 7 quantile of an ascending, NaN-free, non-empty sample; p in [0, 1].
double quantile_type7(const std::vector<double>& sorted, double p);

ResponseStatistics statistics(const std::vector<double>& values);

}  // namespace suite::studies
