#pragma once
// analysis.json of a study (docs/methods/studies.md, "Analysis and output"): for every response its
// statistics; over the successful evaluations Dakota's four correlation matrices and the
// standardized regression coefficients with R^2; Sobol indices with bootstrap intervals for a
// sobol_indices design; Morris mu, mu* and sigma for a morris design. Failed evaluations are
// skipped and counted. Non-finite numbers are written as null.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "studies/design/parameter_studies.hpp"
#include "studies/ledger/ledger.hpp"

namespace suite::studies {

nlohmann::json analyze(const Design& design, const std::vector<std::string>& variables,
                       const std::vector<std::string>& responses, const std::map<long, LedgerEntry>& evaluations);

}  // namespace suite::studies
