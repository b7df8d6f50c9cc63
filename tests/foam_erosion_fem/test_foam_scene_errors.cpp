// Bad foam-erosion scenes (issue 31: at least 25 cases): each is refused while the scene is read,
// before any OpenFOAM program runs, with one message naming the key and what it must be.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/config/config.hpp"
#include "solvers/foam_erosion_fem/scenes/foam_scene.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using namespace suite::foam_erosion;
const std::filesystem::path kScene =
    std::filesystem::path(SUITE_SOURCE_DIR) / "solvers/foam_erosion_fem/scenes/lab_embankment.yaml";

std::string error_of(const std::vector<std::string>& overrides) {
  return suite::testing::input_error_of([&] {
    auto cfg = suite::config::Config::from_file(kScene, overrides);
    (void)FoamScene::read(cfg.root());
    cfg.finish();
  });
}

TEST(FoamSceneErrors, EachBadInputNamesItsKeyAndTheFix) {
  // override -> parts of the message
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"soil.erodibility=-5 cm^3/(N s)", {"soil.erodibility", ">= 0"}},
      {"soil.erodibility=5 m", {"soil.erodibility", "cannot be converted"}},
      {"soil.critical_shear_stress=-1 Pa", {"soil.critical_shear_stress", ">= 0"}},
      {"soil.erodability=5 cm^3/(N s)", {"erodability", "did you mean 'erodibility'"}},
      {"soil.unit_weight=120 lb/ft^3", {"soil.unit_weight", "cannot be converted"}},
      {"dam.height=0 m", {"dam.height", "> 0"}},
      {"dam.upstream_slope=0", {"dam.upstream_slope", "> 0"}},
      {"dam.crest_width=-0.1 m", {"dam.crest_width"}},
      {"gravity=0 m/s^2", {"gravity", "> 0"}},
      {"reservoir.initial_level=0.6 m", {"reservoir.initial_level", "between the foundation"}},
      {"reservoir.initial_level=0 m", {"reservoir.initial_level", "wet the inlet"}},
      {"reservoir.tailwater_level=1 m", {"reservoir.tailwater_level", "between the foundation"}},
      {"domain.height=0.25 m", {"domain.height", "taller than the dam"}},
      {"domain.upstream_length=0 m", {"domain.upstream_length", "> 0"}},
      {"mesh.cell_size=0.2 m", {"mesh.cell_size", "fewer than"}},
      {"mesh.cell_size=0 m", {"mesh.cell_size", "> 0"}},
      {"mesh.far_cell_size=0.005 m", {"mesh.far_cell_size", ">= 0.01"}},
      {"mesh.vertical_grading=20", {"mesh.vertical_grading", "[0.1, 10]"}},
      {"flow.turbulence=kOmega", {"flow.turbulence", "kEpsilon"}},
      {"flow.water.density=0 kg/m^3", {"flow.water.density", "> 0"}},
      {"flow.air.viscosity=-1e-5 m^2/s", {"flow.air.viscosity", "> 0"}},
      {"flow.surface_tension=-0.07 N/m", {"flow.surface_tension", ">= 0"}},
      {"flow.wall_roughness=-1 mm", {"flow.wall_roughness", ">= 0"}},
      {"time.end=0 s", {"time.end", "> 0"}},
      {"time.write_interval=0.3 s", {"time.write_interval", "does not divide coupling.interval"}},
      {"time.fixed_dt=1 s", {"time.fixed_dt", "longer than coupling.interval"}},
      {"coupling.interval=5 s", {"coupling.interval", "longer than time.end"}},
      {"coupling.interval=0.3 s", {"coupling.interval", "does not divide time.end"}},
      {"coupling.morphological_factor=0", {"coupling.morphological_factor", "> 0"}},
      {"run.decomposition=scotch", {"run.decomposition", "hierarchical"}},
      {"inflow.type=weird", {"inflow.type", "constant"}},
  };
  EXPECT_GE(cases.size(), 25u);
  for (const auto& [override_, parts] : cases) {
    const std::string what = error_of({override_});
    for (const auto& part : parts) EXPECT_NE(what.find(part), std::string::npos) << override_ << ": " << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << override_ << ": one line: " << what;
  }
  // A rough wall is a wall function's: refused on laminar walls.
  const std::string laminar = error_of({"flow.turbulence=laminar", "flow.wall_roughness=1.5 mm"});
  EXPECT_NE(laminar.find("flow.wall_roughness"), std::string::npos) << laminar;
  EXPECT_NE(laminar.find("kEpsilon"), std::string::npos) << laminar;
}

}  // namespace
