#pragma once
// What a study evaluates: a model takes one point (the variables' values by name) and returns
// its responses, or says why it failed. Thread-safe: a study calls evaluate() from several
// threads at once.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/config/config.hpp"

namespace suite::studies {

struct Outcome {
  bool ok = false;
  std::string reason;             // why it failed: the error, the missing or non-finite response
  std::vector<double> responses;  // in the order of responses()
};

class Model {
 public:
  virtual ~Model() = default;
  // eval_id: the evaluation's number in the study (work directories and Dakota files carry it).
  virtual Outcome evaluate(long eval_id, const std::map<std::string, double>& values) const = 0;
  // Renders every template with `values` and checks the result against the model as far as it
  // can without evaluating (the breach model: the scene takes every key, unit and value); an
  // InputError names the template or key. A study calls it once before its first evaluation,
  // so a mistake that would fail every evaluation stops it at once. Nothing to check by default.
  virtual void check(const std::map<std::string, double>& /*values*/) const {}
  virtual const std::vector<std::string>& responses() const = 0;
};

// Reads the `model` section (type: breach | command); InputError names the key. Work
// directories of command models go under `work_root` (the study's output folder).
std::unique_ptr<Model> read_model(const config::Section& model, const std::vector<std::string>& variables,
                                  const std::filesystem::path& work_root);

}  // namespace suite::studies
