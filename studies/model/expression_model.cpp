#include "studies/model/expression_model.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

namespace suite::studies {

std::unique_ptr<Model> ExpressionModel::read(const config::Section& s, const std::vector<std::string>& variables) {
  const YAML::Node node = s.raw("responses");
  if (!node.IsMap() || node.size() == 0)
    s.reject("responses", "map each response to a formula of the variables, e.g. {y: \"2*x1 - 3*x2\"}");
  std::vector<std::string> names;
  std::vector<Expression> formulas;
  for (const auto& kv : node) {
    const auto name = kv.first.as<std::string>();
    try {
      formulas.push_back(Expression::compile(kv.second.as<std::string>()));
    } catch (const InputError& e) {
      s.reject("responses", fmt::format("response '{}': {}", name, e.what()));
    }
    for (const auto& v : formulas.back().names())
      if (std::find(variables.begin(), variables.end(), v) == variables.end())
        s.reject("responses", fmt::format("response '{}' uses '{}', which is not a variable of the study", name, v));
    names.push_back(name);
  }
  return std::make_unique<ExpressionModel>(std::move(names), std::move(formulas));
}

Outcome ExpressionModel::evaluate(long, const std::map<std::string, double>& values) const {
  Outcome out;
  out.ok = true;
  for (std::size_t i = 0; i < formulas_.size(); ++i) {
    out.responses.push_back(formulas_[i].evaluate(values));
    if (!std::isfinite(out.responses.back()) && out.ok) {
      out.ok = false;
      out.reason = fmt::format("response '{}' is not finite ({})", names_[i], out.responses.back());
    }
  }
  return out;
}

}  // namespace suite::studies
