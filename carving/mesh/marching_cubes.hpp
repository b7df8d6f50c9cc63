#pragma once
// Marching cubes: the triangle mesh of an iso-surface of a scalar field sampled on a regular grid,
// used to turn a carved seed's occupancy grid into its surface (docs/methods/carving.md).
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "carving/mesh/surface_mesh.hpp"

namespace suite::carving {

// Samples of a scalar field on a regular grid. Sample (i, j, k) sits at origin + spacing * (i, j, k).
struct ScalarField {
  std::array<int, 3> n{};           // samples per axis
  Eigen::Vector3d origin{0, 0, 0};  // position of sample (0,0,0), mm
  double spacing = 1;               // mm between samples
  std::vector<float> values;        // index i + n[0] * (j + n[1] * k)
  // Sample (i, j, k); no bounds check.
  float at(int i, int j, int k) const {
    return values[static_cast<std::size_t>(i) +
                  static_cast<std::size_t>(n[0]) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(n[1]) * k)];
  }
};

// The iso-surface {value = iso} of `field`; "inside" is value > iso (a NaN sample is outside).
// Classic marching cubes with the full 256-case tables (marching_cubes_tables.hpp). Each crossed grid
// edge gets one vertex, placed by linear interpolation of the two samples and shared by the cubes
// around that edge, so a field that is <= iso on the whole border of the grid gives a closed mesh.
// Triangles are oriented outward (away from the inside). Memory besides the mesh: five index arrays of
// one grid slice. Throws std::invalid_argument if a count is negative, values.size() != n0*n1*n2, or
// spacing is not positive; std::length_error if the mesh would need more than INT_MAX vertices.
SurfaceMesh marching_cubes(const ScalarField& field, float iso);

}  // namespace suite::carving
