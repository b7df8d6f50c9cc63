#include "studies/model/model.hpp"

#include "studies/model/breach_model.hpp"

namespace suite::studies {

std::unique_ptr<Model> read_model(const config::Section& s, const std::vector<std::string>& variables) {
  const std::string type = s.choice("type", {"breach"});
  (void)type;  // the built-in breach model; external commands and suite executables follow (issue 6)
  return BreachModel::read(s, variables);
}

}  // namespace suite::studies
