#include "studies/model/breach_model.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "core/errors.hpp"
#include "solvers/breach/run/run_breach.hpp"
#include "solvers/breach/model/simulate.hpp"

namespace suite::studies {

BreachModel::BreachModel(std::filesystem::path scene, std::vector<std::pair<std::string, Template>> set,
                         std::vector<std::string> responses, bool read_once)
    : scene_(std::move(scene)), set_(std::move(set)), responses_(std::move(responses)) {
  if (!read_once) return;
  try {
    variants_ = std::make_shared<const breach::SceneVariants>(config::Config::from_file(scene_));
  } catch (const InputError&) {
    // The scene needs the study's values to read (a key only `set` gives, or one it corrects):
    // each evaluation reads it with them, and reports the error if it still does not read.
  }
}

std::unique_ptr<Model> BreachModel::read(const config::Section& s, const std::vector<std::string>& variables) {
  const auto scene = s.file("scene");
  std::vector<std::pair<std::string, Template>> set;
  if (s.has("set")) {
    const YAML::Node node = s.raw("set");
    if (!node.IsMap()) s.reject("set", "must map scene keys to templates, e.g. soil.erodibility: \"{Kd} cm^3/(N s)\"");
    for (const auto& kv : node) {
      const auto key = kv.first.as<std::string>();
      Template t = Template::parse(kv.second.as<std::string>(), fmt::format("model.set.{}", key));
      for (const auto& name : t.names())
        if (std::find(variables.begin(), variables.end(), name) == variables.end())
          s.reject("set",
                   fmt::format("the template for '{}' uses '{}', which is not a variable of the study", key, name));
      set.emplace_back(key, std::move(t));
    }
  }
  auto responses = s.get<std::vector<std::string>>("responses");
  if (responses.empty()) s.reject("responses", "name at least one key of the breach summary, e.g. peak_outflow");
  // The summary's keys, from a run of the scene as it is: a misspelt response fails here, once.
  const auto probe = breach::make_summary(breach::Result{}).json();
  for (const auto& r : responses)
    if (!probe.contains(r) || r == "units" || probe.at(r).is_string())
      s.reject("responses", fmt::format("'{}' is not in the breach summary; valid: peak_outflow, time_to_peak, "
                                        "peak_breach_outflow, breach_initiation_time, final_bottom_width, "
                                        "final_depth, eroded_volume, ... (docs/breach.md)",
                                        r));
  const bool once = s.choice("read_scene", {"once", "every_evaluation"}, "once") == "once";
  return std::make_unique<BreachModel>(scene, std::move(set), std::move(responses), once);
}

breach::Scene BreachModel::scene_with(const std::map<std::string, double>& values) const {
  std::vector<std::pair<std::string, std::string>> settings;
  for (const auto& [key, t] : set_) settings.emplace_back(key, t.render(values));
  if (auto scene = variants_ ? variants_->with(settings) : std::nullopt) return *scene;
  std::vector<std::string> overrides;
  for (const auto& [key, value] : settings) overrides.push_back(key + "=" + value);
  return breach::Scene::read_complete(config::Config::from_file(scene_, overrides, "model.set"));
}

Outcome BreachModel::evaluate(long, const std::map<std::string, double>& values) const {
  Outcome out;
  try {
    const auto summary = breach::make_summary(breach::simulate(scene_with(values))).json();
    for (const auto& r : responses_) {
      const auto& v = summary.at(r);
      if (v.is_boolean()) {
        out.responses.push_back(v.get<bool>() ? 1.0 : 0.0);
      } else if (v.is_number()) {
        out.responses.push_back(v.get<double>());
      } else {
        out.responses.push_back(std::nan(""));
        if (out.reason.empty()) out.reason = fmt::format("response '{}' has no value in this run", r);
      }
    }
    out.ok = out.reason.empty();
  } catch (const std::exception& e) {
    out.ok = false;
    out.reason = e.what();
    out.responses.assign(responses_.size(), std::nan(""));
  }
  return out;
}

}  // namespace suite::studies
