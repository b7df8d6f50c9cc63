#pragma once
// Morris elementary effects for screening (docs/methods/studies.md, method `morris`).
//
// References: M. D. Morris, "Factorial sampling plans for preliminary computational
// experiments", Technometrics 33(2), 161-174, 1991 (trajectories, mu, sigma); F. Campolongo,
// J. Cariboni, A. Saltelli, "An effective screening design for sensitivity analysis of large
// models", Environ. Model. Softw. 22, 1509-1518, 2007 (mu*, the mean absolute effect).
// OpenTURNS 1.20 has no Morris class (that lives in the separate otmorris module), so the
// method is written here.
//
// Design: r trajectories of M + 1 points each on the p-level grid {0, 1/(p-1), ..., 1}^M of the
// unit cube, mapped linearly onto [lower, upper]. p must be even and >= 2; the step is
// Delta = p / (2 (p - 1)), i.e. p/2 grid intervals (Morris's recommendation, which makes every
// level equally likely). Each trajectory draws, per input, a direction s_i = +-1 and a base level
// from the p/2 levels from which a step s_i Delta stays inside [0, 1], and a random order of the
// inputs; point j + 1 is point j with input order[j] moved by s_i Delta. This is Morris's
// B* = (J x* + (Delta/2)((2B - J) D* + J)) P* with a uniform x*, D* and P*.
// Random numbers: std::mt19937_64 seeded with `seed`, with our own bounded-integer draws, so the
// same seed gives the same design with any standard library.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace suite::studies {

struct MorrisDesign {
  // trajectories * (dimension + 1) points in physical units; trajectory t is
  // points[t (dimension + 1)] .. points[t (dimension + 1) + dimension].
  std::vector<std::vector<double>> points;
  std::size_t trajectories = 0, dimension = 0, levels = 0;
  // trajectories * dimension entries: changed[t dimension + j] is the input that differs
  // between points t (dimension + 1) + j and t (dimension + 1) + j + 1.
  std::vector<std::size_t> changed;
};

// InputError for levels odd or < 2, no trajectories, no inputs, or lower > upper.
MorrisDesign morris_design(const std::vector<double>& lower, const std::vector<double>& upper, std::size_t trajectories,
                           std::size_t levels, std::uint64_t seed);

struct MorrisEffects {
  // Per input, over its elementary effects EE = (y(x + dx e_i) - y(x)) / dx, dx the step in
  // physical units (+- Delta (upper_i - lower_i)); effects involving a NaN output (a failed
  // evaluation) are skipped. mu = mean EE, mu_star = mean |EE|, sigma = sample standard deviation
  // of EE (denominator count - 1). NaN when count is 0 (sigma: when count < 2).
  std::vector<double> mu, mu_star, sigma;
  std::vector<std::size_t> count;  // elementary effects used per input (trajectories when none failed)
};

// outputs[k] is the response at design.points[k]; std::invalid_argument when sizes disagree.
// An input with lower == upper has zero step and gets NaN effects.
MorrisEffects morris_effects(const MorrisDesign& design, const std::vector<double>& outputs,
                             const std::vector<double>& lower, const std::vector<double>& upper);

}  // namespace suite::studies
