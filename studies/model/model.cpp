#include "studies/model/model.hpp"

#include "studies/model/breach_model.hpp"
#include "studies/model/command_model.hpp"
#include "studies/model/expression_model.hpp"

namespace suite::studies {

std::unique_ptr<Model> read_model(const config::Section& s, const std::vector<std::string>& variables,
                                  const std::filesystem::path& work_root) {
  const std::string type = s.choice("type", {"breach", "command", "expression"});
  if (type == "command") return CommandModel::read(s, variables, work_root);
  if (type == "expression") return ExpressionModel::read(s, variables);
  return BreachModel::read(s, variables);
}

}  // namespace suite::studies
