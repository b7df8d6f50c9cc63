#include "studies/analysis/correlations.hpp"

#include <cmath>
#include <limits>
#include <openturns/CorrelationAnalysis.hxx>
#include <openturns/CorrelationMatrix.hxx>
#include <openturns/Indices.hxx>
#include <openturns/Sample.hxx>
#include <stdexcept>

namespace suite::studies {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using Matrix = std::vector<std::vector<double>>;

Matrix nan_matrix(std::size_t rows, std::size_t cols) {
  return Matrix(rows, std::vector<double>(cols, kNaN));
}

// The finite rows of [inputs | responses] in one OT::Sample (M + R columns).
struct Table {
  OT::Sample sample;
  std::size_t inputs = 0, responses = 0, dropped = 0;
};

Table make_table(const Matrix& inputs, const Matrix& responses, std::size_t m, std::size_t r) {
  if (inputs.size() != responses.size())
    throw std::invalid_argument("correlations: " + std::to_string(inputs.size()) + " input rows but " +
                                std::to_string(responses.size()) + " response rows");
  Table t;
  t.inputs = m;
  t.responses = r;
  std::size_t kept = 0;
  std::vector<bool> keep(inputs.size(), true);
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    if (inputs[k].size() != m || responses[k].size() != r)
      throw std::invalid_argument("correlations: row " + std::to_string(k) + " has " +
                                  std::to_string(inputs[k].size()) + " inputs and " +
                                  std::to_string(responses[k].size()) + " responses, expected " + std::to_string(m) +
                                  " and " + std::to_string(r));
    for (double v : inputs[k]) keep[k] = keep[k] && std::isfinite(v);
    for (double v : responses[k]) keep[k] = keep[k] && std::isfinite(v);
    if (keep[k]) ++kept;
  }
  t.dropped = inputs.size() - kept;
  t.sample = OT::Sample(kept, m + r);
  std::size_t row = 0;
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    if (!keep[k]) continue;
    for (std::size_t i = 0; i < m; ++i) t.sample(row, i) = inputs[k][i];
    for (std::size_t j = 0; j < r; ++j) t.sample(row, m + j) = responses[k][j];
    ++row;
  }
  return t;
}

// Column c of the sample holds one value only.
std::vector<bool> constant_columns(const OT::Sample& s) {
  const std::size_t n = s.getSize(), d = s.getDimension();
  std::vector<bool> constant(d, true);
  for (std::size_t c = 0; c < d; ++c)
    for (std::size_t k = 1; k < n && constant[c]; ++k) constant[c] = s(k, c) == s(0, c);
  return constant;
}

// Full simple-correlation matrix, NaN for rows/columns of constant columns.
Matrix simple(const OT::Sample& s, const std::vector<bool>& constant, bool rank) {
  const std::size_t d = s.getDimension();
  Matrix out = nan_matrix(d, d);
  if (s.getSize() < 2) return out;
  const OT::CorrelationMatrix c = rank ? s.computeSpearmanCorrelation() : s.computePearsonCorrelation();
  for (std::size_t a = 0; a < d; ++a)
    for (std::size_t b = 0; b < d; ++b)
      if (!constant[a] && !constant[b]) out[a][b] = c(a, b);
  return out;
}

// The non-constant inputs, as OT indices into the table's columns.
OT::Indices live_inputs(const Table& t, const std::vector<bool>& constant) {
  OT::Indices live;
  for (std::size_t i = 0; i < t.inputs; ++i)
    if (!constant[i]) live.add(i);
  return live;
}

enum class Coefficient { kPCC, kPRCC, kSRC };

// Coefficient of each input against response j (NaN for constant inputs), or all NaN when undefined.
std::vector<double> per_input(const Table& t, const std::vector<bool>& constant, const OT::Indices& live, std::size_t j,
                              Coefficient which) {
  std::vector<double> out(t.inputs, kNaN);
  const std::size_t col = t.inputs + j;
  if (live.getSize() == 0 || constant[col] || t.sample.getSize() < live.getSize() + 2) return out;
  const OT::CorrelationAnalysis analysis(t.sample.getMarginal(live), t.sample.getMarginal(col));
  OT::Point p;
  switch (which) {
    case Coefficient::kPCC:
      p = analysis.computePCC();
      break;
    case Coefficient::kPRCC:
      p = analysis.computePRCC();
      break;
    case Coefficient::kSRC:
      p = analysis.computeSRC();
      break;
  }
  for (std::size_t a = 0; a < live.getSize(); ++a) out[live[a]] = p[a];
  return out;
}

}  // namespace

CorrelationMatrices correlations(const std::vector<std::string>& input_names, const Matrix& inputs,
                                 const std::vector<std::string>& response_names, const Matrix& responses) {
  const std::size_t m = input_names.size(), r = response_names.size();
  const Table t = make_table(inputs, responses, m, r);
  CorrelationMatrices c;
  c.names = input_names;
  c.names.insert(c.names.end(), response_names.begin(), response_names.end());
  c.rows_used = t.sample.getSize();
  c.rows_dropped = t.dropped;
  const std::vector<bool> constant = constant_columns(t.sample);
  c.pearson = simple(t.sample, constant, false);
  c.spearman = simple(t.sample, constant, true);
  c.partial = nan_matrix(m, r);
  c.partial_rank = nan_matrix(m, r);
  const OT::Indices live = live_inputs(t, constant);
  for (std::size_t j = 0; j < r; ++j) {
    const std::vector<double> pcc = per_input(t, constant, live, j, Coefficient::kPCC);
    const std::vector<double> prcc = per_input(t, constant, live, j, Coefficient::kPRCC);
    for (std::size_t i = 0; i < m; ++i) {
      c.partial[i][j] = pcc[i];
      c.partial_rank[i][j] = prcc[i];
    }
  }
  return c;
}

std::vector<Regression> standardized_regression(const Matrix& inputs, const Matrix& responses) {
  const std::size_t m = inputs.empty() ? 0 : inputs.front().size();
  const std::size_t r = responses.empty() ? 0 : responses.front().size();
  const Table t = make_table(inputs, responses, m, r);
  const std::vector<bool> constant = constant_columns(t.sample);
  const OT::Indices live = live_inputs(t, constant);
  const Matrix pearson = simple(t.sample, constant, false);
  std::vector<Regression> out(r);
  for (std::size_t j = 0; j < r; ++j) {
    Regression& reg = out[j];
    reg.rows_used = t.sample.getSize();
    reg.rows_dropped = t.dropped;
    reg.src = per_input(t, constant, live, j, Coefficient::kSRC);
    // R^2 = r_xy' R_xx^-1 r_xy = sum_i src_i corr(x_i, y) for a least-squares fit with intercept.
    reg.r2 = live.getSize() == 0 ? kNaN : 0.0;
    for (std::size_t a = 0; a < live.getSize(); ++a) reg.r2 += reg.src[live[a]] * pearson[live[a]][m + j];
  }
  return out;
}

}  // namespace suite::studies
