#include "solvers/foam_erosion_fem/coupling/loop_state.hpp"

#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "core/run/run_record.hpp"

namespace suite::foam_erosion {

namespace {

nlohmann::json points(const std::vector<Eigen::Vector2d>& p) {
  auto a = nlohmann::json::array();
  for (const auto& q : p) a.push_back({q.x(), q.y()});
  return a;
}

std::vector<Eigen::Vector2d> points(const nlohmann::json& a) {
  std::vector<Eigen::Vector2d> p;
  for (const auto& q : a) p.emplace_back(q.at(0).get<double>(), q.at(1).get<double>());
  return p;
}

}  // namespace

void LoopState::write(const std::filesystem::path& file) const {
  // nlohmann::json prints doubles so that they read back to the same bits.
  write_json_atomic(file, {{"step", step},
                           {"time", time},
                           {"remeshes", remeshes},
                           {"eroded_area", eroded_area},
                           {"nodes", points(nodes)},
                           {"mesh_nodes", points(mesh_nodes)}});
}

LoopState LoopState::read(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in)
    throw InputError(fmt::format("{}: no coupled-loop state to restart from (a run writes it after its first "
                                 "coupling step); run without --restart to start from t = 0",
                                 file.string()));
  try {
    const auto j = nlohmann::json::parse(in);
    LoopState s;
    s.step = j.at("step").get<int>();
    s.time = j.at("time").get<double>();
    s.remeshes = j.at("remeshes").get<int>();
    s.eroded_area = j.at("eroded_area").get<double>();
    s.nodes = points(j.at("nodes"));
    s.mesh_nodes = points(j.at("mesh_nodes"));
    return s;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not a coupled-loop state ({}); start again without --restart", file.string(),
                                 e.what()));
  }
}

}  // namespace suite::foam_erosion
