#pragma once
// A model given by formulas of the variables (Python-style arithmetic, template/expression.hpp):
// analytic test functions (Ishigami, linear models) and quick closed-form models.
//
//   model:
//     type: expression
//     responses: {y: "sin(x1) + 7*sin(x2)**2 + 0.1*x3**4*sin(x1)"}
#include "studies/model/model.hpp"
#include "studies/template/expression.hpp"

namespace suite::studies {

class ExpressionModel : public Model {
 public:
  ExpressionModel(std::vector<std::string> names, std::vector<Expression> formulas)
      : names_(std::move(names)), formulas_(std::move(formulas)) {}
  static std::unique_ptr<Model> read(const config::Section& model, const std::vector<std::string>& variables);

  Outcome evaluate(long eval_id, const std::map<std::string, double>& values) const override;
  const std::vector<std::string>& responses() const override { return names_; }

 private:
  std::vector<std::string> names_;
  std::vector<Expression> formulas_;
};

}  // namespace suite::studies
