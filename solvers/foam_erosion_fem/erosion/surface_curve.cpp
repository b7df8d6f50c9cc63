#include "solvers/foam_erosion_fem/erosion/surface_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace suite::foam_erosion {

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Sign of the turn a -> b -> c: > 0 counter-clockwise, < 0 clockwise, 0 collinear.
double orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return cross(b - a, c - a);
}

// c lies in the bounding box of segment ab (used once c is known to be collinear with ab).
bool in_box(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= c.y() &&
         c.y() <= std::max(a.y(), b.y());
}

// Closed segments p1p2 and q1q2 share at least one point.
bool segments_meet(const Eigen::Vector2d& p1, const Eigen::Vector2d& p2, const Eigen::Vector2d& q1,
                   const Eigen::Vector2d& q2) {
  const double d1 = orientation(q1, q2, p1);
  const double d2 = orientation(q1, q2, p2);
  const double d3 = orientation(p1, p2, q1);
  const double d4 = orientation(p1, p2, q2);
  const bool p_straddles = (d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0);
  const bool q_straddles = (d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0);
  if (p_straddles && q_straddles) return true;
  return (d1 == 0 && in_box(q1, q2, p1)) || (d2 == 0 && in_box(q1, q2, p2)) || (d3 == 0 && in_box(p1, p2, q1)) ||
         (d4 == 0 && in_box(p1, p2, q2));
}

// Neighbouring elements a (node i-1 to i) and b (node i to i+1) overlap beyond their shared node
// only when they are collinear and point in opposite directions. "Collinear" allows the round-off
// of the cross product of two vectors of these lengths.
bool neighbours_fold(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double scale = a.norm() * b.norm();
  return a.dot(b) < 0 && std::abs(cross(a, b)) <= 1e-12 * scale;
}

}  // namespace

SurfaceCurve::SurfaceCurve(std::vector<Eigen::Vector2d> nodes) : nodes_(std::move(nodes)) {
  if (nodes_.size() < 2) {
    throw std::invalid_argument("SurfaceCurve: needs at least 2 nodes, got " + std::to_string(nodes_.size()));
  }
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (!nodes_[i].allFinite()) {
      throw std::invalid_argument("SurfaceCurve: node " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
}

std::vector<double> SurfaceCurve::element_lengths() const {
  std::vector<double> lengths(static_cast<std::size_t>(element_count()));
  for (int e = 0; e < element_count(); ++e) lengths[static_cast<std::size_t>(e)] = element_length(e);
  return lengths;
}

double SurfaceCurve::length() const {
  const auto lengths = element_lengths();
  return std::accumulate(lengths.begin(), lengths.end(), 0.0);
}

double SurfaceCurve::min_element_length() const {
  double shortest = std::numeric_limits<double>::infinity();
  for (int e = 0; e < element_count(); ++e) shortest = std::min(shortest, element_length(e));
  return shortest;
}

Eigen::Vector2d SurfaceCurve::element_tangent(int e) const {
  const Eigen::Vector2d v = element_vector(e);
  const double length = v.norm();
  return length > 0 ? Eigen::Vector2d(v / length) : Eigen::Vector2d::Zero();
}

Eigen::Vector2d SurfaceCurve::element_normal(int e) const {
  const Eigen::Vector2d t = element_tangent(e);
  return {-t.y(), t.x()};
}

std::vector<Eigen::Vector2d> SurfaceCurve::element_normals() const {
  std::vector<Eigen::Vector2d> normals(static_cast<std::size_t>(element_count()));
  for (int e = 0; e < element_count(); ++e) normals[static_cast<std::size_t>(e)] = element_normal(e);
  return normals;
}

std::vector<Eigen::Vector2d> SurfaceCurve::nodal_normals() const {
  // L_e n_e is the element vector turned +90 degrees, so the weighted sum needs no square roots.
  std::vector<Eigen::Vector2d> sums(nodes_.size(), Eigen::Vector2d::Zero());
  for (int e = 0; e < element_count(); ++e) {
    const Eigen::Vector2d v = element_vector(e);
    const Eigen::Vector2d weighted_normal(-v.y(), v.x());
    sums[static_cast<std::size_t>(e)] += weighted_normal;
    sums[static_cast<std::size_t>(e) + 1] += weighted_normal;
  }
  for (auto& s : sums) {
    const double norm = s.norm();
    s = norm > 0 ? Eigen::Vector2d(s / norm) : Eigen::Vector2d::Zero();
  }
  return sums;
}

double SurfaceCurve::area_below(const SurfaceCurve& other) const {
  // Polygon: this curve forward, then `other` backward. Walked that way the region between the
  // curves is on the right when `other` lies below, so the shoelace sum is negative there.
  if (other.nodes_.size() == nodes_.size()) {
    // Same node count: the polygon is the union of the quadrilaterals a_k a_k+1 b_k+1 b_k (their
    // shared edges a_k b_k cancel), and twice a quadrilateral's signed area is the cross product
    // of its diagonals. The diagonals are element-sized, so the round-off does not grow with the
    // coordinates, and identical curves give exactly 0.
    double twice_area = 0;
    for (std::size_t k = 0; k + 1 < nodes_.size(); ++k) {
      twice_area += cross(other.nodes_[k + 1] - nodes_[k], other.nodes_[k] - nodes_[k + 1]);
    }
    return -0.5 * twice_area;
  }
  const Eigen::Vector2d origin = nodes_.front();
  std::vector<Eigen::Vector2d> polygon;
  polygon.reserve(nodes_.size() + other.nodes_.size());
  for (const auto& p : nodes_) polygon.emplace_back(p - origin);
  for (auto it = other.nodes_.rbegin(); it != other.nodes_.rend(); ++it) polygon.emplace_back(*it - origin);
  double twice_area = 0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    twice_area += cross(polygon[k], polygon[(k + 1) % polygon.size()]);
  }
  return -0.5 * twice_area;
}

std::optional<ElementCrossing> SurfaceCurve::find_self_intersection() const {
  const int n = element_count();
  for (int e = 0; e + 1 < n; ++e) {
    if (neighbours_fold(element_vector(e), element_vector(e + 1))) return ElementCrossing{e, e + 1};
  }
  // Sweep in x: after sorting on the left end, element b can only meet element a while b's left
  // end is not right of a's right end.
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  auto x_min = [&](int e) { return std::min(node(e).x(), node(e + 1).x()); };
  auto x_max = [&](int e) { return std::max(node(e).x(), node(e + 1).x()); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return x_min(a) < x_min(b); });
  for (std::size_t i = 0; i < order.size(); ++i) {
    const int a = order[i];
    const double a_right = x_max(a);
    const double a_low = std::min(node(a).y(), node(a + 1).y());
    const double a_high = std::max(node(a).y(), node(a + 1).y());
    for (std::size_t j = i + 1; j < order.size() && x_min(order[j]) <= a_right; ++j) {
      const int b = order[j];
      if (std::abs(a - b) < 2) continue;  // neighbours share a node by construction
      if (std::max(node(b).y(), node(b + 1).y()) < a_low || std::min(node(b).y(), node(b + 1).y()) > a_high) continue;
      if (segments_meet(node(a), node(a + 1), node(b), node(b + 1)))
        return ElementCrossing{std::min(a, b), std::max(a, b)};
    }
  }
  return std::nullopt;
}

}  // namespace suite::foam_erosion
