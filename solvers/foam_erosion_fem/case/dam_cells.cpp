#include "solvers/foam_erosion_fem/case/dam_cells.hpp"

#include <fmt/format.h>

#include "solvers/foam_erosion_fem/case/foam_file.hpp"

namespace suite::foam_erosion {

bool inside_dam(const SectionLayout& L, const Eigen::Vector2d& p) {
  // Ray casting in +x over the closed polygon: dam nodes, then back along the floor.
  const auto& n = L.dam_nodes;
  bool inside = false;
  for (std::size_t i = 0, j = n.size() - 1; i < n.size(); j = i++) {
    const Eigen::Vector2d& a = n[i];
    const Eigen::Vector2d& b = n[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x_cross = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x_cross) inside = !inside;
    }
  }
  return inside;
}

std::vector<int> fluid_cells(const std::vector<Eigen::Vector3d>& centres, const SectionLayout& layout) {
  std::vector<int> fluid;
  for (std::size_t c = 0; c < centres.size(); ++c)
    if (!inside_dam(layout, {centres[c].x(), centres[c].y()})) fluid.push_back(static_cast<int>(c));
  return fluid;
}

void write_cell_set(const std::filesystem::path& case_dir, const std::string& name, const std::vector<int>& cells) {
  std::string out = foam_header("cellSet", name, "constant/polyMesh/sets");
  out += fmt::format("{}\n(\n", cells.size());
  for (int c : cells) out += fmt::format("{}\n", c);
  out += ")\n";
  write_case_file(case_dir, "constant/polyMesh/sets/" + name, out);
}

}  // namespace suite::foam_erosion
