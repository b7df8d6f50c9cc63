#pragma once
// Cutting the dam out of the background mesh: the cells whose centre lies outside the dam
// cross-section are the flow domain, written as a cellSet for subsetMesh (which puts the faces
// it exposes on the `dam` patch). A cell belongs to the dam when its centre is inside the
// polygon of the dam nodes closed along the floor (even-odd rule, so an eroded surface that
// overhangs is still cut correctly).
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "solvers/foam_erosion_fem/case/section_layout.hpp"
#include "solvers/foam_erosion_fem/io/foam_reader.hpp"

namespace suite::foam_erosion {

inline constexpr const char* kFluidCellSet = "fluid";

bool inside_dam(const SectionLayout& layout, const Eigen::Vector2d& p);

// Indices of the background mesh's cells (given by their centres) that lie in the flow, increasing.
std::vector<int> fluid_cells(const std::vector<Eigen::Vector3d>& background_centres, const SectionLayout& layout);

// constant/polyMesh/sets/<name> of the case.
void write_cell_set(const std::filesystem::path& case_dir, const std::string& name, const std::vector<int>& cells);

}  // namespace suite::foam_erosion
