#pragma once
// Builds a runnable case: writes the dictionaries; meshes the section (blockMesh for the
// Cartesian background, the cellSet of the flow cells, subsetMesh to cut the dam out with its
// faces on the `dam` patch, checkMesh); writes the initial fields; runs topoSet (the crest and
// toe discharge sections), setFields (the reservoir) and, for ranks > 1, decomposePar.
// A mesh that checkMesh rejects stops here with checkMesh's own words.
#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include "solvers/foam_erosion_fem/case/section_layout.hpp"
#include "solvers/foam_erosion_fem/run/foam_runner.hpp"
#include "solvers/foam_erosion_fem/scenes/foam_scene.hpp"

namespace suite::foam_erosion {

struct MeshedSection {
  std::vector<Eigen::Vector3d> background_centres;  // cell centres of the background mesh
  std::vector<int> fluid;                           // its cells kept as the flow domain
  long long background_cells = 0;
  long long cells = 0;  // flow cells after the dam is cut out
  int dam_faces = 0;    // faces of the `dam` patch (the staircase surface)
};

struct PreparedCase {
  SectionLayout layout;
  MeshedSection mesh;
  std::vector<ProgramRun> runs;  // blockMesh, subsetMesh, checkMesh, topoSet, setFields[, decomposePar]
};

// Meshes the runner's case for `layout` (its system/blockMeshDict must be written): the steps
// above from blockMesh to checkMesh, appending each program run to `runs`. The background mesh
// is kept as constant/background.
MeshedSection mesh_section(const SectionLayout& layout, FoamRunner& runner, std::vector<ProgramRun>& runs);

PreparedCase prepare_case(const FoamScene& scene, FoamRunner& runner, double first_end_time);

}  // namespace suite::foam_erosion
