#pragma once
// The variables of a study (spec/studies.md): a name, bounds, and an initial point (the centre
// of vector and centered studies; default the middle of the bounds).
//
//   variables:
//     - {name: Kd, lower: 300, upper: 1700}
//     - {name: Us, lower: 0.3, upper: 70, initial: 35}
//
// Values are plain numbers in whatever unit the model's template gives them.
#include <string>
#include <vector>

#include "core/config/config.hpp"

namespace suite::studies {

struct Variable {
  std::string name;
  double lower = 0.0, upper = 0.0, initial = 0.0;
};

// Reads the `variables` list; InputError for a missing or repeated name, lower > upper, or an
// initial point outside the bounds.
std::vector<Variable> read_variables(const config::Section& root);

std::vector<std::string> names(const std::vector<Variable>& variables);

}  // namespace suite::studies
