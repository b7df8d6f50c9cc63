#pragma once
// The 2D cross-section the CFD mesh is built on, and the dam surface the FEM erosion moves.
//
// The flow mesh is a Cartesian ("staircase") mesh: a background of axis-aligned rectangles,
// one cell thick in z, from which the cells whose centre lies inside the dam are removed
// (case/dam_cells.hpp); the faces they expose become the `dam` patch. Its cells are never
// tilted, because Debian's OpenFOAM v1912 reconstructs cell velocities wrongly on cells whose
// faces are not axis-aligned (docs/foam_erosion_fem.md), and interFoam then blows up.
//
//   x:  inlet |-- upstream: graded --|-- toe..crest edge --|-- crest edge..toe --|-- downstream: graded --| outlet
//   y:  floor .. top, vertical_cells cells (graded by vertical_grading)
//
// The two middle x blocks have uniform cells of mesh.cell_size (rounded so the downstream crest
// edge and the downstream toe are mesh lines, where the discharge sections are); the outer ones
// grow geometrically to far_cell_size at the inlet and outlet.
//
// The dam surface is the FEM curve `dam_nodes` (elements no longer than the cell size), kept
// apart from the mesh: the wall shear of the staircase faces is mapped onto its elements
// (coupling/wall_shear.hpp) and, after erosion, the background is cut again along the new curve.
#include <Eigen/Core>
#include <vector>

#include "solvers/foam_erosion_fem/scenes/foam_scene.hpp"

namespace suite::foam_erosion {

struct GradedSegment {
  double x0 = 0.0, x1 = 0.0;
  int cells = 1;
  double expansion = 1.0;  // last cell / first cell, in +x (blockMesh's simpleGrading)
};

struct SectionLayout {
  std::vector<Eigen::Vector2d> dam_nodes;  // upstream toe .. downstream toe, x increasing at first
  double x_inlet = 0.0, x_outlet = 0.0;
  double floor = 0.0, top = 0.0;  // levels, m
  double thickness = 0.0;         // z extent of the one-cell slab, m
  // The x blocks of the background mesh, inlet to outlet.
  std::vector<GradedSegment> x_blocks;
  int vertical_cells = 1;
  double vertical_grading = 1.0;  // top cell / bottom cell
  // Where discharge is measured (x, m): the downstream edge of the crest and the downstream toe.
  double x_crest_section = 0.0, x_toe_section = 0.0;

  // The initial dam of a scene: the trapezoid of dam.{height, crest_width, slopes} with its faces
  // cut into elements no longer than mesh.cell_size.
  static SectionLayout initial(const FoamScene& scene);
  // The same domain around another dam surface (after erosion, for re-meshing).
  SectionLayout with_dam_nodes(std::vector<Eigen::Vector2d> nodes) const;

  long long background_cells() const;
  // Area of the dam cross-section under dam_nodes, above the floor (m^2 per unit width).
  double dam_area() const;
};

}  // namespace suite::foam_erosion
