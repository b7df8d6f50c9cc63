#pragma once
// The dam surface of a 2D (one-cell-thick) case as an open polyline of linear finite elements
// (docs/methods/foam_erosion_fem.md step 6).
//
// Coordinates are in m: x streamwise (the flow goes +x), y up. Nodes run from upstream to
// downstream, element e joins node e to node e+1, and the soil lies to the right of the walking
// direction (below a bed walked in +x), the water to the left. The outward normal of an element
// is its unit tangent turned +90 degrees, n = (-t_y, t_x): it points into the water, (0, +1) for
// a flat bed walked in +x.
#include <Eigen/Core>
#include <optional>
#include <vector>

namespace suite::foam_erosion {

// Two elements of a curve that touch or cross (first < second).
struct ElementCrossing {
  int first = 0;
  int second = 0;
};

class SurfaceCurve {
 public:
  SurfaceCurve() = default;
  // At least 2 nodes with finite coordinates (m); throws std::invalid_argument otherwise.
  explicit SurfaceCurve(std::vector<Eigen::Vector2d> nodes);

  int node_count() const { return static_cast<int>(nodes_.size()); }
  int element_count() const { return node_count() - 1; }
  const std::vector<Eigen::Vector2d>& nodes() const { return nodes_; }
  const Eigen::Vector2d& node(int i) const { return nodes_[static_cast<std::size_t>(i)]; }
  void set_node(int i, const Eigen::Vector2d& p) { nodes_[static_cast<std::size_t>(i)] = p; }

  // Node e+1 minus node e (m).
  Eigen::Vector2d element_vector(int e) const { return node(e + 1) - node(e); }
  double element_length(int e) const { return element_vector(e).norm(); }
  // One length per element (m).
  std::vector<double> element_lengths() const;
  double length() const;
  double min_element_length() const;

  // Unit tangent (node e to node e+1) and outward unit normal of element e; both are zero for an
  // element of zero length.
  Eigen::Vector2d element_tangent(int e) const;
  Eigen::Vector2d element_normal(int e) const;
  std::vector<Eigen::Vector2d> element_normals() const;
  // Per node: the length-weighted average of the normals of the elements that share it,
  // normalised (sum of L_e n_e over those elements, divided by its norm). An end node takes the
  // normal of its one element. Zero where the weighted sum vanishes (a curve folded back on itself).
  std::vector<Eigen::Vector2d> nodal_normals() const;

  // Signed area (m^2 per unit width) between this curve and `other`, by the shoelace formula of
  // the closed polygon made of this curve's nodes followed by `other`'s nodes in reverse order.
  // Positive where `other` lies below this curve (soil removed: this = old, other = new surface).
  // Meant for two curves with the same end nodes (the polygon's closing edges then have zero
  // length); the count of nodes may differ. Exact up to round-off: with equal node counts it sums
  // the quadrilaterals between matching elements (round-off relative to element sizes, exactly 0
  // for identical curves), otherwise coordinates are taken relative to this curve's first node.
  double area_below(const SurfaceCurve& other) const;

  // The first pair of elements found that touch or cross, if any: two elements that are not
  // neighbours and share a point, or two neighbours that fold back onto each other (collinear and
  // pointing in opposite directions). Segments are pruned by sorting on their x extent, so the
  // cost is O(n log n) plus the pairs whose x extents overlap.
  std::optional<ElementCrossing> find_self_intersection() const;
  bool self_intersects() const { return find_self_intersection().has_value(); }

 private:
  std::vector<Eigen::Vector2d> nodes_;
};

}  // namespace suite::foam_erosion
