#pragma once
// A scene read once and varied many times. A parameter study runs one scene thousands of times
// with a few keys changed, and reading the YAML scene for each run cost a large share of what
// the run itself costs (both times: docs/studies.md, "Cost per evaluation"). SceneVariants
// reads the scene once and makes each variant by setting the changed keys on a copy, with
// Scene::read's units and ranges, the defaults that follow the dam (breach width, formation
// depth) and Scene::cross_section_problem's checks.
//
//   const breach::SceneVariants variants(config::Config::from_file("dam.yaml"));
//   if (auto scene = variants.with({{"soil.erodibility", "300 (ft/h)/psf"}, {"dam.height", "16 ft"}}))
//     simulate(*scene);
//   else  // the file read again with the settings as overrides: the scene, or the error naming the key
//     simulate(Scene::read_complete(config::Config::from_file("dam.yaml", {"soil.erodibility=300 (ft/h)/psf",
//                                                                          "dam.height=16 ft"})));
//
// with() gives, bit for bit, the scene that reading the file with the settings as overrides
// gives, or nothing (never a different scene). Nothing for a key outside keys(); for a key the
// scene's form lacks (an internal-erosion key without that section, a power-law key of a storage
// table, the peak of an inflow table); for a value that is not a plain "number [unit]" (YAML
// might read it otherwise); and for a value that breaks a range or a check, whose message is
// Scene::read's to give. Thread-safe: with() only reads the base scene.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/config/config.hpp"
#include "solvers/breach/model/scene.hpp"

namespace suite::breach {

class SceneVariants {
 public:
  // Reads the scene as Scene::read_complete does, with its InputErrors.
  explicit SceneVariants(const config::Config& cfg);

  const Scene& base() const { return base_; }
  // The base scene with each (key path, value) set, e.g. {"dam.height", "16 ft"}; see above.
  std::optional<Scene> with(const std::vector<std::pair<std::string, std::string>>& settings) const;

  // The keys with() sets: the dam's six, the soil's kd, tau_c, s_u and unit weight, the pool
  // level, the power-law storage's alpha, exponent and bottom, the inflow's peak (triangle or
  // sine) or discharge (constant), the breach's initial width and side slope, the headcut's
  // formation depth and coefficients, and the internal-erosion pipe's four keys.
  static std::vector<std::string> keys();

 private:
  Scene base_;
  // Whether the scene gives these, or leaves them to follow the dam.
  bool initial_width_given_ = false, formation_depth_given_ = false;
};

}  // namespace suite::breach
