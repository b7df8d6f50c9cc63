#include "studies/design/variables.hpp"

#include <fmt/format.h>

#include <cctype>
#include <set>

#include "core/errors.hpp"

namespace suite::studies {

std::vector<Variable> read_variables(const config::Section& root) {
  std::vector<Variable> out;
  std::set<std::string> seen;
  for (const auto& s : root.sections("variables")) {
    Variable v;
    v.name = s.get<std::string>("name");
    const bool identifier =
        !v.name.empty() && (std::isalpha(static_cast<unsigned char>(v.name[0])) || v.name[0] == '_');
    for (char c : v.name)
      if (!identifier || !(std::isalnum(static_cast<unsigned char>(c)) || c == '_'))
        s.reject("name",
                 "must be an identifier (letters, digits, _; not starting with a digit) so templates can use it");
    if (!seen.insert(v.name).second) s.reject("name", "is used by another variable");
    if (auto d = s.optional_section("distribution")) {
      v.distribution = read_distribution(*d);
      // Without bounds the design's box is the 1e-6 and 1 - 1e-6 quantiles. They are not read as
      // defaults: the effective study.yaml (which a resume and the MPI ranks read) would then
      // hold them as explicit bounds, and explicit bounds truncate the distribution.
      const bool bounded = s.has("lower") || s.has("upper");
      v.lower = quantile(v.distribution, 1e-6);
      v.upper = quantile(v.distribution, 1.0 - 1e-6);
      if (bounded) {  // explicit bounds truncate the distribution (as Dakota does)
        v.lower = s.number("lower", v.lower, config::Range::any());
        v.upper = s.number("upper", v.upper, config::Range::any());
        v.distribution.truncation = std::make_pair(v.lower, v.upper);
        try {
          validate(v.distribution), quantile(v.distribution, 0.5);
        } catch (const InputError& e) {
          s.reject("lower", e.what());
        }
      }
    } else {
      v.lower = s.number("lower", config::Range::any());
      v.upper = s.number("upper", config::Range::any());
      v.distribution = {"uniform", {{"lower", v.lower}, {"upper", v.upper}}, std::nullopt};
    }
    if (v.upper < v.lower) s.reject("upper", fmt::format("is below lower ({})", v.lower));
    v.initial = s.number("initial", 0.5 * (v.lower + v.upper), config::Range::between(v.lower, v.upper));
    out.push_back(v);
  }
  if (out.empty()) root.reject("variables", "the study needs at least one variable");
  return out;
}

std::vector<std::string> names(const std::vector<Variable>& variables) {
  std::vector<std::string> n;
  for (const auto& v : variables) n.push_back(v.name);
  return n;
}

}  // namespace suite::studies
