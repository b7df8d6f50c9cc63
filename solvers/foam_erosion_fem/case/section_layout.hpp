#pragma once
// The 2D cross-section the CFD mesh is built on: a row of vertical columns from the bottom (floor
// or dam surface) to the flat top of the domain, one cell thick in z.
//
//   inlet |-- upstream floor --|-- dam: one column per surface element --|-- downstream floor --| outlet
//
// The dam surface nodes are the FEM erosion nodes and the mesh points of the `dam` patch, so the
// shear on a dam face is the shear on one FEM element and a node displacement is a mesh point
// displacement, with no interpolation between the two. The floor columns grow geometrically from
// the cell size at the dam to the far cell size at the inlet and outlet.
#include <Eigen/Core>
#include <vector>

#include "solvers/foam_erosion_fem/scenes/foam_scene.hpp"

namespace suite::foam_erosion {

struct FloorSegment {
  int cells = 1;
  double expansion = 1.0;  // last cell / first cell, in +x (blockMesh's simpleGrading)
};

struct SectionLayout {
  std::vector<Eigen::Vector2d> dam_nodes;  // upstream toe .. downstream toe, x increasing
  double x_inlet = 0.0, x_outlet = 0.0;
  double floor = 0.0, top = 0.0;  // levels, m
  double thickness = 0.0;         // z extent of the one-cell slab, m
  FloorSegment upstream, downstream;
  int vertical_cells = 1;
  double vertical_grading = 1.0;  // top cell / bottom cell in every column
  // Where discharge is measured (x, m): the downstream edge of the crest and the downstream toe.
  double x_crest_section = 0.0, x_toe_section = 0.0;

  // The initial dam of a scene: the trapezoid of dam.{height, crest_width, slopes} with its faces
  // cut into elements no longer than mesh.cell_size.
  static SectionLayout initial(const FoamScene& scene);
  // The same domain around another dam surface (after erosion, for re-meshing).
  SectionLayout with_dam_nodes(std::vector<Eigen::Vector2d> nodes) const;

  int columns() const { return static_cast<int>(dam_nodes.size()) + 1; }  // 2 floor + n-1 dam
  long long cells() const;
};

}  // namespace suite::foam_erosion
