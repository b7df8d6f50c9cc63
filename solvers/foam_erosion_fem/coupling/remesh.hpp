#pragma once
// Feedback of the eroded surface to the flow (spec step 7). The staircase mesh cannot follow a
// surface that moves by less than a cell, and mesh motion would tilt cells (which Debian's
// OpenFOAM v1912 cannot run, docs/foam_erosion_fem.md); so the section is cut again from the
// same background whenever the eroded curve changes the set of flow cells:
//   1. the case so far is kept as `archive_dir` (its time directories and logs stay readable);
//   2. a new case is written and meshed on the eroded dam (blockMesh, cut, subsetMesh,
//      checkMesh) with its discharge sections (topoSet);
//   3. the fields of the latest time are mapped onto it at the same time (mapFields, nearest
//      cell). mapFields leaves the cells the erosion opened (outside the old mesh) at their
//      initial values, dry and at rest; their water fraction is then set to that of the nearest
//      old cell, so no air pocket appears under the overflow (velocity stays 0: bed cells);
//   4. the discharge records so far are carried over, and for ranks > 1 the case is decomposed.
#include <filesystem>
#include <vector>

#include "solvers/foam_erosion_fem/run/prepare_case.hpp"

namespace suite::foam_erosion {

// `old_mesh` is the section the runner's case has now; returns the new one.
MeshedSection remesh_case(const FoamScene& scene, const SectionLayout& layout, const MeshedSection& old_mesh,
                          FoamRunner& runner, const std::filesystem::path& archive_dir, double end_time,
                          std::vector<ProgramRun>& runs);

}  // namespace suite::foam_erosion
