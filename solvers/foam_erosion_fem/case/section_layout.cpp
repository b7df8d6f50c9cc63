#include "solvers/foam_erosion_fem/case/section_layout.hpp"

#include <algorithm>
#include <cmath>

namespace suite::foam_erosion {

namespace {

// Geometric cells over [x0, x1] from size `near` (at the dam) to about `far`: the count that
// keeps the mean size, and the expansion blockMesh needs (last / first cell).
GradedSegment graded(double x0, double x1, double near, double far, bool grows_in_plus_x) {
  GradedSegment s{x0, x1};
  s.cells = std::max(1, static_cast<int>(std::ceil((x1 - x0) / (0.5 * (near + far)))));
  const double ratio = s.cells > 1 ? far / near : 1.0;
  s.expansion = grows_in_plus_x ? ratio : 1.0 / ratio;
  return s;
}

GradedSegment uniform(double x0, double x1, double h) {
  return {x0, x1, std::max(1, static_cast<int>(std::ceil((x1 - x0) / h - 1e-9))), 1.0};
}

// Appends the nodes of the straight face a -> b (a excluded) cut into elements <= h.
void append_face(std::vector<Eigen::Vector2d>& nodes, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double h) {
  const double length = (b - a).norm();
  if (length <= 0.0) return;
  const int n = std::max(1, static_cast<int>(std::ceil(length / h - 1e-9)));
  for (int i = 1; i <= n; ++i) nodes.push_back(a + (b - a) * (static_cast<double>(i) / n));
}

}  // namespace

SectionLayout SectionLayout::initial(const FoamScene& scene) {
  const auto& dam = scene.dam;
  const double h = scene.mesh.cell_size;
  SectionLayout L;
  L.floor = dam.foundation;
  L.top = scene.top();
  L.thickness = h;
  L.x_inlet = 0.0;
  const double x_toe_up = scene.domain.upstream_length;
  const double x_crest_up = x_toe_up + dam.upstream_slope * dam.height;
  const double x_crest_down = x_crest_up + dam.crest_width;
  const double x_toe_down = x_crest_down + dam.downstream_slope * dam.height;
  L.x_outlet = x_toe_down + scene.domain.downstream_length;
  L.x_crest_section = x_crest_down;
  L.x_toe_section = x_toe_down;

  const Eigen::Vector2d toe_up(x_toe_up, dam.foundation), crest_up(x_crest_up, dam.crest()),
      crest_down(x_crest_down, dam.crest()), toe_down(x_toe_down, dam.foundation);
  L.dam_nodes.push_back(toe_up);
  append_face(L.dam_nodes, toe_up, crest_up, h);
  append_face(L.dam_nodes, crest_up, crest_down, h);
  append_face(L.dam_nodes, crest_down, toe_down, h);

  const double far = scene.mesh.far_cell_size;
  if (x_toe_up > 0.0) L.x_blocks.push_back(graded(L.x_inlet, x_toe_up, h, far, false));
  L.x_blocks.push_back(uniform(x_toe_up, x_crest_down, h));
  L.x_blocks.push_back(uniform(x_crest_down, x_toe_down, h));
  if (L.x_outlet > x_toe_down) L.x_blocks.push_back(graded(x_toe_down, L.x_outlet, h, far, true));
  L.vertical_cells = std::max(2, static_cast<int>(std::ceil((L.top - L.floor) / h - 1e-9)));
  L.vertical_grading = scene.mesh.vertical_grading;
  return L;
}

SectionLayout SectionLayout::with_dam_nodes(std::vector<Eigen::Vector2d> nodes) const {
  SectionLayout L = *this;
  L.dam_nodes = std::move(nodes);
  return L;
}

long long SectionLayout::background_cells() const {
  long long nx = 0;
  for (const auto& b : x_blocks) nx += b.cells;
  return nx * vertical_cells;
}

double SectionLayout::dam_area() const {
  // Shoelace over the dam nodes closed along the floor.
  double twice = 0.0;
  const std::size_t n = dam_nodes.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = dam_nodes[i];
    const auto& b = dam_nodes[(i + 1) % n];
    twice += (a.x() - b.x()) * (a.y() + b.y() - 2.0 * floor);
  }
  return 0.5 * std::abs(twice);
}

}  // namespace suite::foam_erosion
