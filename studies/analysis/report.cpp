#include "studies/analysis/report.hpp"

#include <fmt/format.h>

#include <cmath>

#include "studies/analysis/correlations.hpp"
#include "studies/analysis/morris.hpp"
#include "studies/analysis/statistics.hpp"

namespace suite::studies {

namespace {

nlohmann::json number(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}
nlohmann::json numbers(const std::vector<double>& v) {
  auto a = nlohmann::json::array();
  for (double x : v) a.push_back(number(x));
  return a;
}
nlohmann::json matrix(const std::vector<std::vector<double>>& m) {
  auto a = nlohmann::json::array();
  for (const auto& row : m) a.push_back(numbers(row));
  return a;
}

}  // namespace

nlohmann::json analyze(const Design& design, const std::vector<std::string>& variables,
                       const std::vector<std::string>& responses, const std::map<long, LedgerEntry>& evaluations) {
  nlohmann::json out;
  out["method"] = design.method;
  out["variables"] = variables;
  out["responses"] = responses;
  out["points"] = design.points.size();
  if (design.seed) out["seed"] = design.seed;
  std::size_t failed = 0;
  std::vector<std::vector<double>> x, y;
  // One output column per response over all design points (NaN where missing or failed).
  std::vector<std::vector<double>> column(responses.size(), std::vector<double>(design.points.size(), std::nan("")));
  for (const auto& [id, e] : evaluations) {
    if (!e.ok) {
      ++failed;
      continue;
    }
    x.push_back(e.inputs);
    y.push_back(e.responses);
    for (std::size_t r = 0; r < responses.size(); ++r)
      if (id >= 1 && static_cast<std::size_t>(id) <= design.points.size())
        column[r][static_cast<std::size_t>(id - 1)] = e.responses[r];
  }
  out["evaluations"] = evaluations.size();
  out["failed"] = failed;
  out["missing"] = design.points.size() > evaluations.size() ? design.points.size() - evaluations.size() : 0;

  auto& stats = out["statistics"];
  for (std::size_t r = 0; r < responses.size(); ++r) {
    const auto s = statistics(column[r]);
    nlohmann::json q = nlohmann::json::object();
    for (const auto& [p, v] : s.quantiles) q[fmt::format("{:g}", p)] = number(v);
    stats[responses[r]] = {{"count", s.count},     {"failed", s.failed},   {"mean", number(s.mean)},
                           {"std", number(s.std)}, {"min", number(s.min)}, {"max", number(s.max)},
                           {"quantiles", q}};
  }

  if (design.method == "vector" || design.method == "centered") {
    // One-at-a-time designs move the inputs together or one by one: correlations and
    // regression over them mean nothing (Dakota computes them for multidim and sampling only).
    out["correlations"] = {{"skipped", "not computed for " + design.method + " designs"}};
  } else if (x.size() >= variables.size() + 3) {
    const auto c = correlations(variables, x, responses, y);
    out["correlations"] = {{"names", c.names},
                           {"pearson", matrix(c.pearson)},
                           {"spearman", matrix(c.spearman)},
                           {"partial", matrix(c.partial)},
                           {"partial_rank", matrix(c.partial_rank)},
                           {"rows", c.rows_used}};
    auto& reg = out["regression"];
    const auto regs = standardized_regression(x, y);
    for (std::size_t r = 0; r < responses.size(); ++r)
      reg[responses[r]] = {{"src", numbers(regs[r].src)}, {"r2", number(regs[r].r2)}};
  } else {
    out["correlations"] = {{"skipped", "fewer successful evaluations than variables + 3"}};
  }

  if (design.saltelli) {
    auto& sob = out["sobol_indices"];
    for (std::size_t r = 0; r < responses.size(); ++r) {
      try {
        const auto si = sobol_indices(*design.saltelli, column[r]);
        sob[responses[r]] = {{"variables", variables},
                             {"first", numbers(si.first)},
                             {"first_low", numbers(si.first_low)},
                             {"first_high", numbers(si.first_high)},
                             {"total", numbers(si.total)},
                             {"total_low", numbers(si.total_low)},
                             {"total_high", numbers(si.total_high)},
                             {"confidence", 0.95}};
      } catch (const std::exception& e) {
        // Saltelli's estimator pairs every point with others: it needs them all.
        sob[responses[r]] = {{"error", e.what()}};
      }
    }
  }
  if (design.morris) {
    auto& mo = out["morris"];
    for (std::size_t r = 0; r < responses.size(); ++r) {
      const auto m = morris_effects(*design.morris, column[r], design.lower, design.upper);
      mo[responses[r]] = {{"variables", variables},
                          {"mu", numbers(m.mu)},
                          {"mu_star", numbers(m.mu_star)},
                          {"sigma", numbers(m.sigma)}};
    }
  }
  return out;
}

}  // namespace suite::studies
