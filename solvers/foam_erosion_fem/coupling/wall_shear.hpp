#pragma once
// Shear extraction (spec step 5): the bed shear stress on the dam, from interFoam's
// wallShearStress function object, mapped onto the FEM surface elements.
//
// interFoam's turbulence model is the incompressible one of the two-phase mixture, so the
// wallShearStress field is kinematic (m^2/s^2). At a dam face with water fraction alpha in its
// cell the stress in Pa is rho tau_kin with rho = alpha rho_water + (1 - alpha) rho_air: the
// water fraction weights it, and a dry face carries the (negligible) air shear. Only the
// component tangential to the face acts on the bed.
//
// The staircase faces are mapped onto the FEM elements: each face goes to the element nearest to
// its centre, and an element's stress is the length-weighted mean of its faces'. An element no
// face is nearest to (possible where the staircase is coarser than the curve) takes the mean of
// the nearest elements along the curve that have faces.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "solvers/foam_erosion_fem/scenes/foam_scene.hpp"

namespace suite::foam_erosion {

struct WallFaceShear {
  Eigen::Vector2d centre;
  double length = 0.0;  // m, in the section plane
  double alpha = 0.0;   // water fraction of the face's cell
  double shear = 0.0;   // tangential stress magnitude, Pa
};

// Reads <case_dir>/constant/polyMesh, <time_dir>/wallShearStress and <time_dir>/alpha.water.
// FoamReadError names the file if a field is missing or malformed.
std::vector<WallFaceShear> read_wall_shear(const std::filesystem::path& case_dir,
                                           const std::filesystem::path& time_dir, const std::string& patch,
                                           const Fluid& water, const Fluid& air);

// One stress per element of the curve through `nodes` (Pa). std::invalid_argument if there are
// no faces or fewer than two nodes.
std::vector<double> shear_on_elements(const std::vector<Eigen::Vector2d>& nodes,
                                      const std::vector<WallFaceShear>& faces);

}  // namespace suite::foam_erosion
