#pragma once
// Dakota's four correlation matrices and standardized regression coefficients over the
// evaluations of a study (docs/methods/studies.md, "Analysis and output"). Computed with OpenTURNS 1.20
// (OT::Sample::computePearsonCorrelation / computeSpearmanCorrelation, OT::CorrelationAnalysis::
// computePCC / computePRCC / computeSRC); OpenTURNS stays out of this header.
//
// Rows (evaluations) with a non-finite input or response -- NaN marks a failed evaluation -- are
// dropped and counted in rows_dropped; every matrix is computed over the same remaining rows.
//
// Layout, as Dakota prints it:
//   names             the inputs, then the responses
//   pearson, spearman (M + R) x (M + R) simple correlations over all columns, raw and on ranks
//                     (ties get their average rank)
//   partial,          M x R: partial[i][j] is the correlation of input i with response j given all
//   partial_rank      the other inputs (residuals of linear regressions on them), raw and on ranks
// Undefined entries are NaN: every entry involving a constant column (such an input is also left
// out of the conditioning set of the other partial correlations); every partial entry when fewer
// than (non-constant inputs + 2) rows remain; every entry when fewer than 2 rows remain.
#include <cstddef>
#include <string>
#include <vector>

namespace suite::studies {

struct CorrelationMatrices {
  std::vector<std::string> names;  // inputs then responses
  std::vector<std::vector<double>> pearson, spearman, partial, partial_rank;
  std::size_t rows_used = 0, rows_dropped = 0;
};

// inputs[k] (M values) and responses[k] (R values) belong to evaluation k; std::invalid_argument
// when the row counts or widths disagree with the names.
CorrelationMatrices correlations(const std::vector<std::string>& input_names,
                                 const std::vector<std::vector<double>>& inputs,
                                 const std::vector<std::string>& response_names,
                                 const std::vector<std::vector<double>>& responses);

// Least-squares fit y = b0 + sum_i b_i x_i of each response on the inputs (with intercept):
// src[i] = b_i sd(x_i) / sd(y) (signed), r2 the coefficient of determination of the fit
// (= sum_i src_i corr(x_i, y)). Same row dropping and NaN rules as correlations(); r2 is NaN
// when fewer than (non-constant inputs + 2) rows remain.
struct Regression {
  std::vector<double> src;
  double r2 = 0.0;
  std::size_t rows_used = 0, rows_dropped = 0;
};

std::vector<Regression> standardized_regression(const std::vector<std::vector<double>>& inputs,
                                                const std::vector<std::vector<double>>& responses);

}  // namespace suite::studies
