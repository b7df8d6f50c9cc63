#include "solvers/foam_erosion_fem/erosion/fem_erosion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <utility>

namespace suite::foam_erosion {

namespace {

// Largest factor 1/|m_i| of NodeMotion::area_consistent (|m_i| = cos(theta/2) = 0.25 at a corner
// turning by about 151 degrees); sharper corners move less than the offset would.
constexpr double kMaxCornerFactor = 4.0;
// The repose limiter stops once no element exceeds tan(angle) by more than this, relative.
constexpr double kReposeTolerance = 1e-9;

std::size_t at(int i) {
  return static_cast<std::size_t>(i);
}

// Why a curve, or a move from one curve to another, is not acceptable.
struct Failure {
  int element = -1;
  std::string reason;
};

std::string describe(const Failure& f) {
  return "element " + std::to_string(f.element) + " (nodes " + std::to_string(f.element) + "-" +
         std::to_string(f.element + 1) + ") " + f.reason;
}

std::string number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Element lengths above min_length (and above 0), no self-intersection.
std::optional<Failure> check_curve(const SurfaceCurve& curve, double min_length) {
  for (int e = 0; e < curve.element_count(); ++e) {
    const double length = curve.element_length(e);
    if (length <= 0 || length < min_length) {
      return Failure{
          e, "is " + number(length) + " m long, shorter than min_element_length = " + number(min_length) + " m"};
    }
  }
  if (const auto crossing = curve.find_self_intersection()) {
    return Failure{crossing->first, "touches or crosses element " + std::to_string(crossing->second)};
  }
  return std::nullopt;
}

// check_curve of `after`, and no element turned by 90 degrees or more from `before`.
std::optional<Failure> check_move(const SurfaceCurve& before, const SurfaceCurve& after, double min_length) {
  for (int e = 0; e < after.element_count(); ++e) {
    if (before.element_vector(e).dot(after.element_vector(e)) <= 0) {
      return Failure{e, "turns back on itself (dot of old and new tangent <= 0)"};
    }
  }
  return check_curve(after, min_length);
}

// Per node, the move per metre of depth d_i (see NodeMotion).
std::vector<Eigen::Vector2d> move_directions(const SurfaceCurve& curve, NodeMotion motion) {
  std::vector<Eigen::Vector2d> sums(at(curve.node_count()), Eigen::Vector2d::Zero());
  std::vector<double> weights(at(curve.node_count()), 0.0);
  for (int e = 0; e < curve.element_count(); ++e) {
    const Eigen::Vector2d v = curve.element_vector(e);
    const Eigen::Vector2d weighted_normal(-v.y(), v.x());  // L_e n_e
    const double length = v.norm();
    sums[at(e)] += weighted_normal;
    sums[at(e + 1)] += weighted_normal;
    weights[at(e)] += length;
    weights[at(e + 1)] += length;
  }
  std::vector<Eigen::Vector2d> directions(sums.size(), Eigen::Vector2d::Zero());
  for (std::size_t i = 0; i < sums.size(); ++i) {
    const double norm = weights[i] > 0 ? sums[i].norm() / weights[i] : 0.0;  // |m_i|
    if (norm < 1e-12) continue;                                              // folded: no direction
    const Eigen::Vector2d unit = sums[i].normalized();
    const double factor = motion == NodeMotion::area_consistent ? std::min(1.0 / norm, kMaxCornerFactor) : 1.0;
    directions[i] = -factor * unit;
  }
  return directions;
}

struct MoveOutcome {
  SurfaceCurve curve;
  std::vector<char> clamped;  // per node: the foundation truncated its motion
  std::optional<Failure> failure;
};

// Moves the interior nodes of `start` by `depth` in `substeps` equal parts, recomputing the
// directions from the current curve before each part; stops at the first invalid part.
MoveOutcome move_nodes(const SurfaceCurve& start, const std::vector<double>& depth, int substeps,
                       const ErosionSettings& s) {
  MoveOutcome out{start, std::vector<char>(at(start.node_count()), 0), std::nullopt};
  const double floor = s.foundation_level;
  for (int k = 0; k < substeps; ++k) {
    const SurfaceCurve before = out.curve;
    const auto directions = move_directions(before, s.motion);
    for (int i = 1; i + 1 < before.node_count(); ++i) {
      const Eigen::Vector2d q = before.node(i);
      Eigen::Vector2d p = q + (depth[at(i)] / substeps) * directions[at(i)];
      if (p.y() < floor && p.y() < q.y()) {  // truncate the path where it meets the foundation
        out.clamped[at(i)] = 1;
        if (q.y() <= floor) {
          p = q;
        } else {
          p = q + ((q.y() - floor) / (q.y() - p.y())) * (p - q);
          p.y() = floor;
        }
      }
      out.curve.set_node(i, p);
    }
    out.failure = check_move(before, out.curve, s.min_element_length);
    if (out.failure) return out;
  }
  return out;
}

void check_arguments(const SurfaceCurve& curve, const std::vector<double>& element_shear, double dt,
                     const ErosionSettings& s) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("erode: " + what); };
  if (element_shear.size() != at(curve.element_count())) {
    fail("element_shear has " + std::to_string(element_shear.size()) + " values for " +
         std::to_string(curve.element_count()) + " elements");
  }
  for (std::size_t e = 0; e < element_shear.size(); ++e) {
    if (!std::isfinite(element_shear[e])) fail("element_shear[" + std::to_string(e) + "] is not finite");
  }
  if (!(std::isfinite(dt) && dt >= 0)) fail("dt = " + number(dt) + " s, must be finite and >= 0");
  if (!(std::isfinite(s.law.kd) && s.law.kd >= 0)) fail("kd = " + number(s.law.kd) + " m^3/(N s), must be >= 0");
  if (!std::isfinite(s.law.tau_c)) fail("tau_c is not finite");
  if (!(std::isfinite(s.morphological_factor) && s.morphological_factor > 0)) {
    fail("morphological_factor = " + number(s.morphological_factor) + ", must be > 0");
  }
  if (!(std::isfinite(s.min_element_length) && s.min_element_length >= 0)) {
    fail("min_element_length = " + number(s.min_element_length) + " m, must be >= 0");
  }
  if (std::isnan(s.foundation_level) || s.foundation_level == std::numeric_limits<double>::infinity()) {
    fail("foundation_level must be a number or -infinity");
  }
  if (s.repose_angle_deg && !(*s.repose_angle_deg > 0 && *s.repose_angle_deg < 90)) {
    fail("repose_angle_deg = " + number(*s.repose_angle_deg) + " degrees, must be in (0, 90)");
  }
  if (s.max_substeps < 1) fail("max_substeps = " + std::to_string(s.max_substeps) + ", must be >= 1");
}

}  // namespace

std::vector<double> lumped_mass(const SurfaceCurve& curve) {
  std::vector<double> mass(at(curve.node_count()), 0.0);
  for (int e = 0; e < curve.element_count(); ++e) {
    const double half = 0.5 * curve.element_length(e);
    mass[at(e)] += half;
    mass[at(e + 1)] += half;
  }
  return mass;
}

double integrate_nodal(const SurfaceCurve& curve, const std::vector<double>& nodal_values) {
  if (nodal_values.size() != at(curve.node_count())) {
    throw std::invalid_argument("integrate_nodal: " + std::to_string(nodal_values.size()) + " values for " +
                                std::to_string(curve.node_count()) + " nodes");
  }
  double sum = 0;
  for (int e = 0; e < curve.element_count(); ++e) {
    sum += 0.5 * curve.element_length(e) * (nodal_values[at(e)] + nodal_values[at(e + 1)]);
  }
  return sum;
}

std::vector<double> project_to_nodes(const SurfaceCurve& curve, const std::vector<double>& element_values,
                                     Projection projection) {
  const int n_elements = curve.element_count();
  if (element_values.size() != at(n_elements)) {
    throw std::invalid_argument("project_to_nodes: " + std::to_string(element_values.size()) + " values for " +
                                std::to_string(n_elements) + " elements");
  }
  const auto lengths = curve.element_lengths();
  for (int e = 0; e < n_elements; ++e) {
    if (!(lengths[at(e)] > 0)) {
      throw std::invalid_argument("project_to_nodes: element " + std::to_string(e) + " has zero length");
    }
  }
  // Right-hand side b_i = integral of phi_i f = sum over the node's elements of L_e f_e / 2.
  const std::size_t n = at(curve.node_count());
  std::vector<double> rhs(n, 0.0);
  for (int e = 0; e < n_elements; ++e) {
    const double half = 0.5 * lengths[at(e)] * element_values[at(e)];
    rhs[at(e)] += half;
    rhs[at(e + 1)] += half;
  }
  if (projection == Projection::lumped) {
    const auto mass = lumped_mass(curve);
    for (std::size_t i = 0; i < n; ++i) rhs[i] /= mass[i];
    return rhs;
  }
  // Consistent mass matrix: diagonal (L_{i-1} + L_i) / 3, off-diagonal L_e / 6. Symmetric and
  // strictly diagonally dominant, so the Thomas algorithm needs no pivoting.
  std::vector<double> diag(n, 0.0);
  std::vector<double> upper(n, 0.0);  // upper[i] = M_i,i+1 = M_i+1,i
  for (int e = 0; e < n_elements; ++e) {
    diag[at(e)] += lengths[at(e)] / 3.0;
    diag[at(e + 1)] += lengths[at(e)] / 3.0;
    upper[at(e)] = lengths[at(e)] / 6.0;
  }
  for (std::size_t i = 1; i < n; ++i) {
    const double factor = upper[i - 1] / diag[i - 1];
    diag[i] -= factor * upper[i - 1];
    rhs[i] -= factor * rhs[i - 1];
  }
  rhs[n - 1] /= diag[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) rhs[i] = (rhs[i] - upper[i] * rhs[i + 1]) / diag[i];
  return rhs;
}

ReposeResult limit_repose(SurfaceCurve& curve, double repose_angle_deg, int max_sweeps) {
  if (!(repose_angle_deg > 0 && repose_angle_deg < 90)) {
    throw std::invalid_argument("limit_repose: repose angle = " + number(repose_angle_deg) +
                                " degrees, must be in (0, 90)");
  }
  const double slope = std::tan(repose_angle_deg * std::numbers::pi / 180.0);
  const int n_nodes = curve.node_count();
  const int n_elements = curve.element_count();
  std::vector<double> x(at(n_nodes));
  std::vector<double> y(at(n_nodes));
  for (int i = 0; i < n_nodes; ++i) {
    x[at(i)] = curve.node(i).x();
    y[at(i)] = curve.node(i).y();
  }
  const std::vector<double> y_start = y;
  // Horizontal tributary widths of the interior nodes (the ends never move).
  std::vector<double> width(at(n_nodes), 0.0);
  for (int i = 1; i + 1 < n_nodes; ++i) width[at(i)] = 0.5 * (x[at(i + 1)] - x[at(i - 1)]);
  auto dx = [&](int e) { return x[at(e + 1)] - x[at(e)]; };
  auto too_steep = [&](int e) { return std::abs(y[at(e + 1)] - y[at(e)]) > slope * dx(e) * (1 + kReposeTolerance); };
  std::vector<char> relaxable(at(n_elements), 0);
  for (int e = 1; e + 2 < n_nodes; ++e) {
    relaxable[at(e)] = dx(e) > 0 && width[at(e)] > 0 && width[at(e + 1)] > 0;
  }

  ReposeResult result;
  bool changed = true;
  while (changed && result.sweeps < max_sweeps) {
    changed = false;
    const bool forward = result.sweeps % 2 == 0;
    for (int k = 0; k < n_elements; ++k) {
      const int e = forward ? k : n_elements - 1 - k;
      if (!relaxable[at(e)] || !too_steep(e)) continue;
      const int upper = y[at(e)] > y[at(e + 1)] ? e : e + 1;
      const int lower = upper == e ? e + 1 : e;
      const double excess = std::abs(y[at(e + 1)] - y[at(e)]) - slope * dx(e);
      const double w_upper = width[at(upper)];
      const double w_lower = width[at(lower)];
      y[at(upper)] -= excess * w_lower / (w_upper + w_lower);
      y[at(lower)] += excess * w_upper / (w_upper + w_lower);
      changed = true;
    }
    ++result.sweeps;
  }
  for (int i = 0; i < n_nodes; ++i) {
    if (y[at(i)] != y_start[at(i)]) {
      curve.set_node(i, Eigen::Vector2d(x[at(i)], y[at(i)]));
      ++result.nodes_moved;
    }
  }
  for (int e = 0; e < n_elements; ++e) result.elements_left += too_steep(e) ? 1 : 0;
  return result;
}

ErosionStepReport erode(SurfaceCurve& curve, const std::vector<double>& element_shear, double dt,
                        const ErosionSettings& settings) {
  check_arguments(curve, element_shear, dt, settings);
  if (const auto failure = check_curve(curve, settings.min_element_length)) {
    throw CurveValidityError("erode: the incoming curve is invalid: " + describe(*failure), failure->element);
  }
  const int n_nodes = curve.node_count();
  std::vector<double> element_rate(element_shear.size());
  for (std::size_t e = 0; e < element_shear.size(); ++e) element_rate[e] = settings.law.rate(element_shear[e]);
  const auto nodal_rate = project_to_nodes(curve, element_rate, settings.projection);
  const auto mass = lumped_mass(curve);
  const double scale = dt * settings.morphological_factor;

  ErosionStepReport report;
  std::vector<double> depth(at(n_nodes), 0.0);
  for (int i = 0; i < n_nodes; ++i) {
    report.rate_integral += scale * mass[at(i)] * nodal_rate[at(i)];
    depth[at(i)] = scale * nodal_rate[at(i)];
  }
  report.pinned_end_integral = scale * (mass.front() * nodal_rate.front() + mass.back() * nodal_rate.back());
  depth.front() = 0;  // the end nodes join the fixed floor of the CFD mesh
  depth.back() = 0;

  SurfaceCurve moved = curve;
  if (std::any_of(depth.begin(), depth.end(), [](double d) { return d != 0; })) {
    for (int substeps = 1;; substeps *= 2) {
      MoveOutcome outcome = move_nodes(curve, depth, substeps, settings);
      if (!outcome.failure) {
        moved = std::move(outcome.curve);
        report.substeps = substeps;
        report.nodes_clamped = static_cast<int>(std::count(outcome.clamped.begin(), outcome.clamped.end(), 1));
        break;
      }
      if (substeps > settings.max_substeps / 2) {
        throw CurveValidityError("erode: " + describe(*outcome.failure) + " even with " + std::to_string(substeps) +
                                     " substeps of the step dt = " + number(dt) + " s",
                                 outcome.failure->element);
      }
    }
  }
  if (settings.repose_angle_deg) {
    const ReposeResult repose = limit_repose(moved, *settings.repose_angle_deg);
    report.nodes_limited_by_repose = repose.nodes_moved;
    report.repose_elements_left = repose.elements_left;
    if (const auto failure = check_curve(moved, settings.min_element_length)) {
      throw CurveValidityError("erode: after the repose limiter, " + describe(*failure), failure->element);
    }
  }
  report.eroded_area = curve.area_below(moved);
  for (int i = 0; i < n_nodes; ++i)
    report.max_depth = std::max(report.max_depth, (moved.node(i) - curve.node(i)).norm());
  curve = std::move(moved);
  return report;
}

}  // namespace suite::foam_erosion
