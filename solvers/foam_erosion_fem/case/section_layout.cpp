#include "solvers/foam_erosion_fem/case/section_layout.hpp"

#include <algorithm>
#include <cmath>

namespace suite::foam_erosion {

namespace {

// Geometric cells over `length` from size `near` (at the dam) to about `far`: the count that
// keeps the mean size, and the expansion blockMesh needs (last / first cell).
FloorSegment graded(double length, double near, double far, bool grows_in_plus_x) {
  FloorSegment s;
  s.cells = std::max(1, static_cast<int>(std::ceil(length / (0.5 * (near + far)))));
  const double ratio = s.cells > 1 ? far / near : 1.0;
  s.expansion = grows_in_plus_x ? ratio : 1.0 / ratio;
  return s;
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

  L.upstream = graded(scene.domain.upstream_length, h, scene.mesh.far_cell_size, false);
  L.downstream = graded(scene.domain.downstream_length, h, scene.mesh.far_cell_size, true);
  L.vertical_cells = std::max(2, static_cast<int>(std::ceil((L.top - dam.crest()) / h - 1e-9)));
  L.vertical_grading = scene.mesh.vertical_grading;
  return L;
}

SectionLayout SectionLayout::with_dam_nodes(std::vector<Eigen::Vector2d> nodes) const {
  SectionLayout L = *this;
  L.dam_nodes = std::move(nodes);
  return L;
}

long long SectionLayout::cells() const {
  const long long columns_x = upstream.cells + downstream.cells + static_cast<long long>(dam_nodes.size()) - 1;
  return columns_x * vertical_cells;
}

}  // namespace suite::foam_erosion
