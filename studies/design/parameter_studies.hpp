#pragma once
// Deterministic designs with Dakota's semantics (Dakota ParamStudy.cpp: multidim_loop,
// vector_loop, centered_loop; same counts, same order, same arithmetic):
//
//   multidim  (partitions p_i, one value or one per variable): prod(p_i + 1) points,
//             x_i = lower_i + k_i (upper_i - lower_i) / p_i, the first variable fastest;
//             p_i = 0 holds variable i at its initial value.
//   vector    (final_point or step_vector, num_steps): num_steps + 1 points
//             x = initial + k step, step = (final - initial) / num_steps.
//   centered  (step_vector s_i, steps_per_variable d_i): the initial point, then for each
//             variable in turn initial + k s_i e_i for k = -d_i..d_i, k != 0 (1 + 2 sum d_i points).
//   list      (points: [[...], ...] or file: a CSV/whitespace table with one column per variable,
//             in the variables' order, an optional header line).
// and the sampling designs (sampling.hpp, morris.hpp), drawn from the variables' distributions:
//   sampling       (sample_type: lhs | random | sobol_sequence, samples, seed, and optionally
//                  rank_correlation: the Spearman matrix [[1, 0.5], [0.5, 1]], Iman-Conover)
//   sobol_indices  (samples N, seed): Saltelli's pick-freeze design, N (M + 2) points
//   morris         (trajectories r, levels p (even), seed): r (M + 1) points on a p-level grid
//                  over the bounds
// A seed that is not given is drawn once and written into study.yaml, so every study can be
// repeated exactly.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "studies/analysis/morris.hpp"
#include "studies/design/sampling.hpp"
#include "studies/design/variables.hpp"

namespace suite::studies {

std::vector<Point> multidim_points(const std::vector<Variable>& variables, const std::vector<long long>& partitions);
std::vector<Point> vector_points(const Point& initial, const Point& step, long long num_steps);
std::vector<Point> centered_points(const Point& initial, const Point& step, const std::vector<long long>& steps);

struct Design {
  std::string method;
  std::vector<Point> points;
  std::uint64_t seed = 0;
  std::optional<SaltelliDesign> saltelli;  // sobol_indices: for the estimator
  std::optional<MorrisDesign> morris;      // morris: for the elementary effects
  std::vector<double> lower, upper;        // the variables' bounds
};

// Reads the `method` section for the designs above; InputError names the key.
Design read_design(const config::Section& method, const std::vector<Variable>& variables);

}  // namespace suite::studies
