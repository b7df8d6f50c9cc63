#pragma once
// Random and quasi-random designs and Sobol' sensitivity indices (docs/methods/studies.md, methods
// `sampling` and `sobol_indices`), built on OpenTURNS 1.20 (the Debian package):
//
//   lhs             OT::LHSExperiment on the independent OT::ComposedDistribution of the
//                   marginals, not optimized, default options (no re-shuffle, random position
//                   inside each stratum): every one of the n equal-probability strata of every
//                   marginal holds exactly one point.
//   random          OT::MonteCarloExperiment on the composed distribution.
//   sobol_sequence  OT::LowDiscrepancyExperiment(OT::SobolSequence, ..., restart = true), each
//                   coordinate mapped through its marginal's quantile function. OpenTURNS'
//                   SobolSequence starts at index 1, i.e. it SKIPS the all-zero first point of
//                   the Sobol' sequence (which would map to -inf for unbounded marginals): the first
//                   points in 2-D are (0.5, 0.5), (0.75, 0.25), (0.25, 0.75), (0.375, 0.375), ...
//                   Not randomized: the points depend on n and the marginals only, never on the seed.
//
// Seeds. OT::RandomGenerator is a process-global generator: every function here seeds it and
// draws while holding one mutex (openturns_random_mutex() in openturns_bridge.hpp), so the same
// seed gives bitwise the same points whatever other threads do through these functions. OpenTURNS
// 1.20 seeds its generator with 32 bits only (a 64-bit seed is truncated), so a 64-bit seed is
// folded to 32 bits as (seed ^ (seed >> 32)) mod 2^32: seeds below 2^32 are passed unchanged
// (the same points as OpenTURNS' RandomGenerator.SetSeed(seed) in Python), and distinct 64-bit
// seeds can coincide. Reproducibility holds for a given OpenTURNS version.
//
// Rank correlation. An optional Spearman rank-correlation matrix (symmetric, unit diagonal,
// entries in (-1, 1)) is turned into the Pearson correlation of a Gaussian copula with
// OT::NormalCopula::GetCorrelationFromSpearmanCorrelation (2 sin(pi rho_S / 6)), whose Spearman
// correlation is exactly the one asked for. InputError if that matrix is not positive definite.
//   random: the composed distribution with that OT::NormalCopula, sampled directly.
//   lhs:    OpenTURNS 1.20's LHSExperiment refuses dependent copulas, so the stratified LHS
//           columns are re-paired by rank (Iman & Conover's restricted pairing, as Dakota's LHS
//           does): row i of column j receives the value of the LHS column whose rank equals the
//           rank of row i in a sample of n points of the OT::NormalCopula. Every marginal keeps
//           its exact stratification; the sample's rank correlation is that of a copula sample
//           (target +- about (1 - rho^2) / sqrt(n)).
//   sobol_sequence: rejected (InputError): a low-discrepancy set cannot carry a rank correlation
//           without losing the property it is chosen for.
//
// Sobol' indices: OT::SobolIndicesExperiment (Monte Carlo base samples, pinned regardless of the
// ResourceMap key SobolIndicesExperiment-SamplingMethod) gives N (M + 2) points in OpenTURNS'
// order: A (N rows), B (N rows), then for i = 1..M the N rows of A with column i taken from B.
// OT::SaltelliSensitivityAlgorithm estimates the first-order and total indices from those rows
// and their outputs; the intervals are OpenTURNS' bootstrap ones (`bootstrap` resamplings of the
// N row-blocks, a kernel-smoothed distribution of the replicates, its (1 -+ confidence) / 2
// quantiles per index), with the generator seeded by `bootstrap_seed` so they are reproducible.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "studies/design/distributions.hpp"

namespace suite::studies {

using Point = std::vector<double>;

enum class SamplingKind { lhs, random, sobol_sequence };

// n points (each one value per marginal, in the marginals' order). n = 0 gives no points.
// InputError for no marginals, an invalid marginal, or a bad rank-correlation matrix.
std::vector<Point> sample(const std::vector<Distribution>& marginals, SamplingKind kind, std::size_t n,
                          std::uint64_t seed, const std::vector<std::vector<double>>& rank_correlation = {});

struct SaltelliDesign {
  std::vector<Point> points;  // base_size * (dimension + 2) points: A, B, then the M pick-freeze blocks
  std::size_t base_size = 0;  // N
  std::size_t dimension = 0;  // M
};

// InputError for n < 2, no marginals or an invalid marginal.
SaltelliDesign saltelli_design(const std::vector<Distribution>& marginals, std::size_t n, std::uint64_t seed);

struct SobolIndices {
  std::vector<double> first, total;                                  // one per variable
  std::vector<double> first_low, first_high, total_low, total_high;  // bootstrap interval bounds
};

// `outputs[k]` is the response at design.points[k]. InputError if the sizes disagree, an output is
// not finite (the pick-freeze estimator needs every run: rerun failed ones first), the outputs are
// all equal (no variance to apportion), confidence is not in (0, 1). bootstrap = 0 computes no
// intervals (the bounds are NaN).
SobolIndices sobol_indices(const SaltelliDesign& design, const std::vector<double>& outputs, double confidence = 0.95,
                           std::size_t bootstrap = 1000, std::uint64_t bootstrap_seed = 0);

}  // namespace suite::studies
