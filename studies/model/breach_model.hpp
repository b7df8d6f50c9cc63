#pragma once
// The breach model in-process (solvers/breach): each evaluation renders the `set` templates into
// `key.path=value` overrides of a breach scene, runs suite::breach::simulate, and reads the
// responses from the run's summary (the keys of summary.json). About a millisecond an
// evaluation, no files, no processes.
//
//   model:
//     type: breach
//     scene: dam.yaml                      # relative to the study file
//     set:                                 # scene key -> template of the variables
//       soil.erodibility: "{Kd} (ft/h)/psf"
//       dam.height: "{4*(2**Scale)} ft"
//     responses: [peak_outflow, breach_initiation_time]
//
// A response that is null (e.g. no breach initiation) makes the evaluation failed, with the
// reason, as do scene errors the values provoke (a negative kd, a formation depth above the dam).
#include <filesystem>
#include <utility>

#include "studies/model/model.hpp"
#include "studies/template/template.hpp"

namespace suite::studies {

class BreachModel : public Model {
 public:
  BreachModel(std::filesystem::path scene, std::vector<std::pair<std::string, Template>> set,
              std::vector<std::string> responses);
  static std::unique_ptr<Model> read(const config::Section& model, const std::vector<std::string>& variables);

  Outcome evaluate(long eval_id, const std::map<std::string, double>& values) const override;
  const std::vector<std::string>& responses() const override { return responses_; }

 private:
  std::filesystem::path scene_;
  std::vector<std::pair<std::string, Template>> set_;
  std::vector<std::string> responses_;
};

}  // namespace suite::studies
