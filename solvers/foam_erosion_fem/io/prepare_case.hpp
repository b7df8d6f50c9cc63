#pragma once
// Builds a runnable case: writes the dictionaries, then runs blockMesh, checkMesh, topoSet (the
// crest and toe discharge sections), setFields (the reservoir) and, for ranks > 1, decomposePar.
// A mesh that checkMesh rejects stops here with checkMesh's own words.
#include <filesystem>
#include <vector>

#include "solvers/foam_erosion_fem/case/section_layout.hpp"
#include "solvers/foam_erosion_fem/runner/foam_runner.hpp"
#include "solvers/foam_erosion_fem/scenes/foam_scene.hpp"

namespace suite::foam_erosion {

struct PreparedCase {
  SectionLayout layout;
  std::vector<ProgramRun> runs;  // blockMesh, checkMesh, topoSet, setFields[, decomposePar]
};

PreparedCase prepare_case(const FoamScene& scene, FoamRunner& runner, double first_end_time);

}  // namespace suite::foam_erosion
