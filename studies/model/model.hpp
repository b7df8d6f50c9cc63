#pragma once
// What a study evaluates: a model takes one point (the variables' values by name) and returns
// its responses, or says why it failed. Thread-safe: a study calls evaluate() from several
// threads at once.
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
  virtual Outcome evaluate(const std::map<std::string, double>& values) const = 0;
  virtual const std::vector<std::string>& responses() const = 0;
};

// Reads the `model` section (type: breach, ...); InputError names the key.
std::unique_ptr<Model> read_model(const config::Section& model, const std::vector<std::string>& variables);

}  // namespace suite::studies
