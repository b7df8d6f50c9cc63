#include "studies/design/sampling.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <openturns/ComposedDistribution.hxx>
#include <openturns/CorrelationMatrix.hxx>
#include <openturns/Interval.hxx>
#include <openturns/LHSExperiment.hxx>
#include <openturns/LowDiscrepancyExperiment.hxx>
#include <openturns/MonteCarloExperiment.hxx>
#include <openturns/NormalCopula.hxx>
#include <openturns/RandomGenerator.hxx>
#include <openturns/ResourceMap.hxx>
#include <openturns/SaltelliSensitivityAlgorithm.hxx>
#include <openturns/Sample.hxx>
#include <openturns/SobolIndicesExperiment.hxx>
#include <openturns/SobolSequence.hxx>

#include "core/errors.hpp"
#include "studies/design/openturns_bridge.hpp"

namespace suite::studies {

std::mutex& openturns_random_mutex() {
  static std::mutex m;
  return m;
}

namespace {

// OpenTURNS 1.20 keeps 32 bits of the seed (see sampling.hpp).
void seed_openturns(std::uint64_t seed) {
  const std::uint64_t folded = (seed ^ (seed >> 32)) & 0xffffffffULL;
  OT::RandomGenerator::SetSeed(static_cast<OT::UnsignedInteger>(folded));
}

// Runs `f`, turning an OpenTURNS exception into a LibraryError (the checks above the calls should
// have caught anything the user can fix).
template <class F>
auto guarded(const char* what, F&& f) {
  try {
    return f();
  } catch (const OT::Exception& e) {
    throw LibraryError(fmt::format("OpenTURNS, {}: {}", what, e.what()));
  }
}

OT::Collection<OT::Distribution> openturns_marginals(const std::vector<Distribution>& marginals) {
  if (marginals.empty()) throw InputError("sampling needs at least one variable");
  OT::Collection<OT::Distribution> c;
  for (std::size_t i = 0; i < marginals.size(); ++i) {
    try {
      c.add(to_openturns(marginals[i]));
    } catch (const InputError& e) {
      throw InputError(fmt::format("variable {}: {}", i + 1, e.what()));
    }
  }
  return c;
}

std::vector<Point> to_points(const OT::Sample& s) {
  const std::size_t n = s.getSize(), m = s.getDimension();
  std::vector<Point> out(n, Point(m));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < m; ++j) out[i][j] = s(i, j);
  return out;
}

// The Pearson correlation of the Gaussian copula whose Spearman correlation is `spearman`.
OT::CorrelationMatrix copula_correlation(const std::vector<std::vector<double>>& spearman, std::size_t m) {
  if (spearman.size() != m)
    throw InputError(
        fmt::format("rank correlation matrix has {} rows; expected one per variable ({})", spearman.size(), m));
  OT::CorrelationMatrix s(m);
  for (std::size_t i = 0; i < m; ++i) {
    if (spearman[i].size() != m)
      throw InputError(
          fmt::format("rank correlation matrix row {} has {} entries; expected {}", i + 1, spearman[i].size(), m));
    for (std::size_t j = 0; j < m; ++j) {
      const double v = spearman[i][j];
      if (i == j) {
        if (std::abs(v - 1.0) > 1e-12)
          throw InputError(fmt::format("rank correlation matrix: diagonal entry {} is {}; it must be 1", i + 1, v));
      } else {
        if (!(v > -1.0 && v < 1.0))
          throw InputError(
              fmt::format("rank correlation matrix: entry ({}, {}) = {} must be in (-1, 1)", i + 1, j + 1, v));
        if (std::abs(v - spearman[j][i]) > 1e-12)
          throw InputError(
              fmt::format("rank correlation matrix is not symmetric: entry ({}, {}) = {} but ({}, {}) = {}", i + 1,
                          j + 1, v, j + 1, i + 1, spearman[j][i]));
        if (j < i) s(i, j) = v;
      }
    }
  }
  // OpenTURNS throws if the Gaussian-copula correlation is not positive definite.
  bool valid = false;
  OT::CorrelationMatrix r(m);
  try {
    r = OT::NormalCopula::GetCorrelationFromSpearmanCorrelation(s);
    valid = r.isPositiveDefinite();
  } catch (const OT::Exception&) {
    valid = false;
  }
  if (!valid)
    throw InputError(
        "rank correlation matrix is not a valid correlation matrix: its Gaussian-copula counterpart is not "
        "positive definite (the correlations contradict one another)");
  return r;
}

// Re-pairs the columns of `lhs` so that their ranks follow those of `copula_sample` (restricted
// pairing): each column keeps its values, hence its stratification.
void pair_by_rank(OT::Sample& lhs, const OT::Sample& copula_sample) {
  const std::size_t n = lhs.getSize(), m = lhs.getDimension();
  const OT::Sample ranks = copula_sample.rank();
  std::vector<double> column(n);
  for (std::size_t j = 0; j < m; ++j) {
    for (std::size_t i = 0; i < n; ++i) column[i] = lhs(i, j);
    std::sort(column.begin(), column.end());
    for (std::size_t i = 0; i < n; ++i) {
      // Continuous copula: no ties, ranks are exactly 0..n-1.
      const auto r = static_cast<std::size_t>(std::lround(ranks(i, j)));
      lhs(i, j) = column[std::min(r, n - 1)];
    }
  }
}

// Restores a ResourceMap string key on scope exit.
class PinnedResource {
 public:
  PinnedResource(const std::string& key, const std::string& value) : key_(key) {
    had_ = OT::ResourceMap::HasKey(key);
    if (had_) old_ = OT::ResourceMap::GetAsString(key);
    OT::ResourceMap::SetAsString(key, value);
  }
  ~PinnedResource() {
    if (had_) OT::ResourceMap::SetAsString(key_, old_);
  }
  PinnedResource(const PinnedResource&) = delete;
  PinnedResource& operator=(const PinnedResource&) = delete;

 private:
  std::string key_, old_;
  bool had_ = false;
};

}  // namespace

std::vector<Point> sample(const std::vector<Distribution>& marginals, SamplingKind kind, std::size_t n,
                          std::uint64_t seed, const std::vector<std::vector<double>>& rank_correlation) {
  const auto coll = openturns_marginals(marginals);
  const std::size_t m = marginals.size();
  const bool correlated = !rank_correlation.empty();
  if (correlated && kind == SamplingKind::sobol_sequence)
    throw InputError(
        "a rank correlation cannot be imposed on a sobol_sequence design (re-pairing would destroy its low "
        "discrepancy); use lhs or random sampling");
  const OT::CorrelationMatrix r = correlated ? copula_correlation(rank_correlation, m) : OT::CorrelationMatrix(m);
  if (n == 0) return {};

  std::lock_guard lock(openturns_random_mutex());
  return guarded("sampling", [&] {
    seed_openturns(seed);
    switch (kind) {
      case SamplingKind::lhs: {
        OT::LHSExperiment experiment(OT::ComposedDistribution(coll), n);
        OT::Sample x = experiment.generate();
        if (correlated) pair_by_rank(x, OT::NormalCopula(r).getSample(n));
        return to_points(x);
      }
      case SamplingKind::random: {
        const OT::ComposedDistribution d =
            correlated ? OT::ComposedDistribution(coll, OT::NormalCopula(r)) : OT::ComposedDistribution(coll);
        return to_points(OT::MonteCarloExperiment(d, n).generate());
      }
      case SamplingKind::sobol_sequence: {
        OT::LowDiscrepancyExperiment experiment(OT::SobolSequence(m), OT::ComposedDistribution(coll), n, true);
        return to_points(experiment.generate());
      }
    }
    throw InputError("unknown sampling kind");
  });
}

SaltelliDesign saltelli_design(const std::vector<Distribution>& marginals, std::size_t n, std::uint64_t seed) {
  const auto coll = openturns_marginals(marginals);
  if (n < 2) throw InputError(fmt::format("sobol_indices needs at least 2 base samples (got {})", n));
  SaltelliDesign d;
  d.base_size = n;
  d.dimension = marginals.size();
  std::lock_guard lock(openturns_random_mutex());
  d.points = guarded("Saltelli design", [&] {
    const PinnedResource pin("SobolIndicesExperiment-SamplingMethod", "MonteCarlo");
    seed_openturns(seed);
    OT::SobolIndicesExperiment experiment(OT::ComposedDistribution(coll), n, false);
    return to_points(experiment.generate());
  });
  if (d.points.size() != n * (d.dimension + 2))
    throw LibraryError(fmt::format("OpenTURNS SobolIndicesExperiment gave {} points; expected N (M + 2) = {}",
                                   d.points.size(), n * (d.dimension + 2)));
  return d;
}

SobolIndices sobol_indices(const SaltelliDesign& design, const std::vector<double>& outputs, double confidence,
                           std::size_t bootstrap, std::uint64_t bootstrap_seed) {
  const std::size_t n = design.base_size, m = design.dimension;
  if (n < 2 || m == 0 || design.points.size() != n * (m + 2))
    throw InputError(fmt::format("Saltelli design has {} points; expected N (M + 2) with N = {} >= 2, M = {} >= 1",
                                 design.points.size(), n, m));
  if (outputs.size() != design.points.size())
    throw InputError(
        fmt::format("sobol_indices: {} outputs for {} design points; every point needs its response (rerun failed "
                    "evaluations first)",
                    outputs.size(), design.points.size()));
  for (std::size_t k = 0; k < outputs.size(); ++k)
    if (!std::isfinite(outputs[k]))
      throw InputError(
          fmt::format("sobol_indices: the output of design point {} is {}; the pick-freeze estimator "
                      "needs every response (rerun failed evaluations first)",
                      k + 1, outputs[k]));
  if (std::all_of(outputs.begin(), outputs.end(), [&](double y) { return y == outputs.front(); }))
    throw InputError("sobol_indices: every output is the same; there is no variance to apportion");
  if (!(confidence > 0.0 && confidence < 1.0))
    throw InputError(fmt::format("sobol_indices: confidence level {} must be in (0, 1)", confidence));

  OT::Sample x(design.points.size(), m), y(outputs.size(), 1);
  for (std::size_t k = 0; k < design.points.size(); ++k) {
    if (design.points[k].size() != m)
      throw InputError(
          fmt::format("Saltelli design point {} has {} values; expected {}", k + 1, design.points[k].size(), m));
    for (std::size_t j = 0; j < m; ++j) x(k, j) = design.points[k][j];
    y(k, 0) = outputs[k];
  }

  SobolIndices out;
  std::lock_guard lock(openturns_random_mutex());
  guarded("Saltelli sensitivity", [&] {
    OT::SaltelliSensitivityAlgorithm algorithm(x, y, n);
    algorithm.setUseAsymptoticDistribution(false);
    algorithm.setConfidenceLevel(confidence);
    const OT::Point first = algorithm.getFirstOrderIndices();
    const OT::Point total = algorithm.getTotalOrderIndices();
    out.first.assign(first.begin(), first.end());
    out.total.assign(total.begin(), total.end());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (bootstrap == 0) {
      out.first_low = out.first_high = out.total_low = out.total_high = std::vector<double>(m, nan);
      return 0;
    }
    algorithm.setBootstrapSize(bootstrap);
    seed_openturns(bootstrap_seed);
    const OT::Interval fi = algorithm.getFirstOrderIndicesInterval();
    const OT::Interval ti = algorithm.getTotalOrderIndicesInterval();
    const OT::Point fl = fi.getLowerBound(), fh = fi.getUpperBound(), tl = ti.getLowerBound(), th = ti.getUpperBound();
    out.first_low.assign(fl.begin(), fl.end());
    out.first_high.assign(fh.begin(), fh.end());
    out.total_low.assign(tl.begin(), tl.end());
    out.total_high.assign(th.begin(), th.end());
    return 0;
  });
  return out;
}

}  // namespace suite::studies
