#pragma once
// Writes a complete interFoam case (v1912) for a scene: mesh description, initial and boundary
// fields, physical properties, numerics, run control with the function objects the coupling
// reads (discharge through the inlet, crest, toe and outlet sections; wall shear on the dam)
// and parallel decomposition. The mesh itself is made by blockMesh and subsetMesh
// (run/prepare_case.hpp), so the initial fields are written after it: subsetMesh would otherwise
// have to cut them too.
//
// The inflow hydrograph goes in through variableHeightFlowRateInletVelocity +
// variableHeightFlowRate (spec step 3): interFoam then imposes the discharge on whatever depth
// is wet at the inlet. For the one-cell-thick slab the imposed flow is q(t) * thickness.
#include <filesystem>
#include <string>

#include "solvers/foam_erosion_fem/case/section_layout.hpp"
#include "solvers/foam_erosion_fem/scenes/foam_scene.hpp"

namespace suite::foam_erosion {

// The erodible patch (see block_mesh_dict.hpp).
inline constexpr const char* kDamPatch = "dam";

// Writes constant/ and system/ into `case_dir` (created). `end_time` is the first run's endTime
// (the coupled loop moves it on by one coupling interval per erosion step).
void write_case_setup(const FoamScene& scene, const SectionLayout& layout, const std::filesystem::path& case_dir,
                      double end_time);
// constant/: g, transportProperties (water and air), turbulenceProperties.
void write_constant(const FoamScene& scene, const std::filesystem::path& case_dir);
// system/fvSchemes and system/fvSolution of interFoam (VOF with MULES, PIMPLE, k-epsilon).
void write_numerics(const std::filesystem::path& case_dir);
// Writes the initial fields 0/ (uniform; setFields then fills the reservoir).
void write_initial_fields(const FoamScene& scene, const SectionLayout& layout, const std::filesystem::path& case_dir);

// The inflow hydrograph as an OpenFOAM Function1 of the slab's discharge (m^3/s through the
// one-cell-thick inlet): "constant v" or "table ((t0 q0) (t1 q1) ...)".
std::string inlet_flow_rate(const FoamScene& scene, const SectionLayout& layout);

// Rewrites only system/controlDict with a new endTime (the coupled loop's next interval).
void write_control_dict(const FoamScene& scene, const std::filesystem::path& case_dir, double end_time);

}  // namespace suite::foam_erosion
