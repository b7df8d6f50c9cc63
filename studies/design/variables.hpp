#pragma once
// The variables of a study (docs/methods/studies.md): a name, bounds, an initial point (the centre
// of vector and centered studies; default the middle of the bounds) and, for sampling designs,
// a distribution (default uniform over the bounds; see distributions.hpp for the types).
//
//   variables:
//     - {name: Kd, lower: 300, upper: 1700}
//     - {name: Us, lower: 0.3, upper: 70, initial: 35}
//     - {name: tau_c, distribution: {type: lognormal, mean: 2, std: 0.5}}   # bounds optional:
//                                               # the 1e-6 and 1 - 1e-6 quantiles by default
//
// Values are plain numbers in whatever unit the model's template gives them.
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "studies/design/distributions.hpp"

namespace suite::studies {

struct Variable {
  std::string name;
  double lower = 0.0, upper = 0.0, initial = 0.0;
  Distribution distribution;  // uniform(lower, upper) unless given
};

// Reads the `variables` list; InputError for a missing or repeated name, lower > upper, or an
// initial point outside the bounds.
std::vector<Variable> read_variables(const config::Section& root);

std::vector<std::string> names(const std::vector<Variable>& variables);

}  // namespace suite::studies
