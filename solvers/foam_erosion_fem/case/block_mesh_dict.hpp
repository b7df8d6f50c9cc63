#pragma once
// system/blockMeshDict of the background mesh of a SectionLayout: one hex block per x block
// (inlet to outlet), every block with the same vertical cells and grading so neighbouring blocks
// share their points exactly. All cells are axis-aligned rectangles. blockMesh numbers the cells
// of each block after those of the block upstream of it, row by row, so every face between two
// cells of a row has its normal in +x (the discharge sections rely on this; subsetMesh keeps the
// order).
//
// Patches: inlet, outlet, atmosphere (top), floor (non-erodible bottom), dam (empty here: it
// receives the faces subsetMesh exposes when it removes the dam's cells), frontAndBack (empty).
#include <string>

#include "solvers/foam_erosion_fem/case/section_layout.hpp"

namespace suite::foam_erosion {

std::string block_mesh_dict(const SectionLayout& layout);

}  // namespace suite::foam_erosion
