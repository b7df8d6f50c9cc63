#pragma once
// system/blockMeshDict for a SectionLayout: one hex block per column, every column with the same
// vertical cell count and grading so neighbouring blocks share their points exactly. Blocks are
// listed from the inlet to the outlet, so blockMesh numbers the cells of each column after those
// of the column upstream of it and every face between two columns has its normal in +x (the
// discharge sections rely on this).
//
// Patches: inlet, outlet, atmosphere (top), floor (non-erodible bottom), dam (the erodible
// surface, one face per FEM element, in node order), frontAndBack (empty).
#include <string>

#include "solvers/foam_erosion_fem/case/section_layout.hpp"

namespace suite::foam_erosion {

std::string block_mesh_dict(const SectionLayout& layout);

}  // namespace suite::foam_erosion
