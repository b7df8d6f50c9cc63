#pragma once
// The breach model in-process (solvers/breach): each evaluation renders the `set` templates into
// values of scene keys, runs suite::breach::simulate, and reads the responses from the run's
// summary (the keys of summary.json). About a millisecond an evaluation, no files, no processes.
//
//   model:
//     type: breach
//     scene: dam.yaml                      # relative to the study file
//     set:                                 # scene key -> template of the variables
//       soil.erodibility: "{Kd} (ft/h)/psf"
//       dam.height: "{4*(2**Scale)} ft"
//     responses: [peak_outflow, breach_initiation_time]
//     read_scene: once                     # or every_evaluation
//
// The scene is read once (breach::SceneVariants) and each evaluation sets its values on a copy.
// Values that copy cannot take as reading the scene would (a key it does not set, a value out
// of range) make that evaluation read the scene file again with them as `key.path=value`
// overrides, which gives the error naming the key; a scene that does not read without the
// study's values is read for every evaluation. `read_scene: every_evaluation` always reads it
// again (the path before; the table is the same bit for bit, only slower).
//
// A response that is null (e.g. no breach initiation) makes the evaluation failed, with the
// reason, as do scene errors the values provoke (a negative kd, a formation depth above the dam).
#include <filesystem>
#include <memory>
#include <utility>

#include "solvers/breach/model/scene_variants.hpp"
#include "studies/model/model.hpp"
#include "studies/template/template.hpp"

namespace suite::studies {

class BreachModel : public Model {
 public:
  // read_once: read the scene here and set each evaluation's values on a copy (see above).
  BreachModel(std::filesystem::path scene, std::vector<std::pair<std::string, Template>> set,
              std::vector<std::string> responses, bool read_once = true);
  static std::unique_ptr<Model> read(const config::Section& model, const std::vector<std::string>& variables);

  Outcome evaluate(long eval_id, const std::map<std::string, double>& values) const override;
  // The templates rendered and the scene read with them, without a run.
  void check(const std::map<std::string, double>& values) const override { scene_with(values); }
  const std::vector<std::string>& responses() const override { return responses_; }

 private:
  breach::Scene scene_with(const std::map<std::string, double>& values) const;

  std::filesystem::path scene_;
  std::vector<std::pair<std::string, Template>> set_;
  std::vector<std::string> responses_;
  std::shared_ptr<const breach::SceneVariants> variants_;  // null: read the scene every evaluation
};

}  // namespace suite::studies
