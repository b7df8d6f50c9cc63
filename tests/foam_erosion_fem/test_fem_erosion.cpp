// FEM erosion of the dam surface (docs/methods/foam_erosion_fem.md step 6): closed forms on a flat bed
// and at corners, the eroded area against the time integral of the rate, the L2 projections,
// the foundation clamp, the repose limiter's area balance, substepping and the area formula.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "solvers/foam_erosion_fem/erosion/fem_erosion.hpp"

namespace {

using namespace suite::foam_erosion;
using Eigen::Vector2d;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// Flat bed at height y from x = 0 to length, n elements of equal length.
SurfaceCurve flat_bed(double length, int n, double y) {
  std::vector<Vector2d> nodes;
  for (int i = 0; i <= n; ++i) nodes.emplace_back(length * i / n, y);
  return SurfaceCurve(nodes);
}

// Trapezoidal dam 3 m high: toe (0, 0), upstream slope 3H:1V to the crest (9, 3)-(13, 3),
// downstream slope 3H:1V to the toe (22, 0); elements of about h along each straight part.
SurfaceCurve trapezoid_dam(double h) {
  const std::vector<Vector2d> corners{{0, 0}, {9, 3}, {13, 3}, {22, 0}};
  std::vector<Vector2d> nodes{corners.front()};
  for (std::size_t k = 0; k + 1 < corners.size(); ++k) {
    const Vector2d a = corners[k];
    const Vector2d b = corners[k + 1];
    const int n = static_cast<int>(std::ceil((b - a).norm() / h));
    for (int j = 1; j <= n; ++j) nodes.emplace_back(a + (b - a) * (static_cast<double>(j) / n));
  }
  return SurfaceCurve(nodes);
}

// Bed stress on the dam: above tau_c = 2 Pa only for 5 m < x < 20 m (peak 22 Pa mid-crest), so
// the elements at the two fixed ends do not erode.
std::vector<double> dam_stress(const SurfaceCurve& curve) {
  std::vector<double> tau(static_cast<std::size_t>(curve.element_count()));
  for (int e = 0; e < curve.element_count(); ++e) {
    const double x = 0.5 * (curve.node(e).x() + curve.node(e + 1).x());
    const double s = std::sin(std::numbers::pi * (x - 5) / 15);
    tau[static_cast<std::size_t>(e)] = x > 5 && x < 20 ? 2 + 20 * s * s : 0.0;
  }
  return tau;
}

TEST(FemErosion, FlatBedUnderUniformStressDropsByTheClosedForm) {
  // L = 10 m, N = 50 elements (h = 0.2 m), bed at 2 m; tau = 7 Pa > tau_c = 2 Pa with
  // kd = 1e-4 m/(s Pa): e = 5e-4 m/s, dt = 10 s, d = e dt = 5 mm per step, 20 steps.
  const double length = 10;
  const int n = 50;
  const double h = length / n;
  const double y0 = 2;
  SurfaceCurve curve = flat_bed(length, n, y0);
  ErosionSettings s;
  s.law = {1e-4, 2};
  const std::vector<double> tau(n, 7.0);
  const double dt = 10;
  const int steps = 20;
  const double rate = 1e-4 * (7 - 2);
  const double d = rate * dt;

  // First step, from the flat bed: every interior node drops by d (normals exactly (0, 1)). The
  // end nodes are fixed, so the removed polygon is a trapezoid with top L, bottom L - 2h and
  // height d: area (L - h) d. The lumped projection of a uniform rate is uniform, so
  // rate_integral = e dt L; its part on the half elements at the two ends, pinned_end_integral =
  // e dt h, is the end-element correction: eroded_area = rate_integral - pinned_end_integral.
  // Tolerances: the rate terms are sums of 50 positive terms (1e-14 relative). The new heights
  // 2 m - 5 mm are stored to eps y0 = 4.4e-16 m, 1e-13 of d, which bounds the area (1e-12).
  const SurfaceCurve initial = curve;
  const ErosionStepReport first = erode(curve, tau, dt, s);
  EXPECT_NEAR(first.eroded_area, (length - h) * d, 1e-12 * (length - h) * d);
  EXPECT_NEAR(first.rate_integral, rate * dt * length, 1e-14 * rate * dt * length);
  EXPECT_NEAR(first.pinned_end_integral, rate * dt * h, 1e-14 * rate * dt * h);
  EXPECT_NEAR(first.eroded_area, first.rate_integral - first.pinned_end_integral, 1e-12 * first.rate_integral);
  EXPECT_NEAR(first.max_depth, d, 1e-12 * d);
  EXPECT_EQ(first.substeps, 1);
  for (int i = 1; i < n; ++i) EXPECT_NEAR(curve.node(i).y(), y0 - d, 1e-12 * y0) << "node " << i;

  // Later steps: the end elements now slope, so the nodes next to the fixed ends move obliquely.
  // A node's normal depends only on its two elements, so this reaches one node further inward
  // per step: after k steps the nodes k..N-k have only ever moved straight down, by exactly k d
  // (round-off of k subtractions, 1e-12 relative).
  for (int k = 1; k < steps; ++k) erode(curve, tau, dt, s);
  for (int i = steps; i <= n - steps; ++i) {
    EXPECT_NEAR(curve.node(i).y(), y0 - steps * d, 1e-12 * y0) << "node " << i;
    EXPECT_EQ(curve.node(i).x(), initial.node(i).x()) << "node " << i;
  }
  EXPECT_EQ(curve.node(0), Vector2d(0, y0));
  EXPECT_EQ(curve.node(n), Vector2d(length, y0));

  // The morphological factor only scales time: f = 4 with dt / 4 gives the same step (exactly,
  // the factors are powers of two).
  SurfaceCurve a = flat_bed(length, n, y0);
  SurfaceCurve b = flat_bed(length, n, y0);
  erode(a, tau, dt, s);
  s.morphological_factor = 4;
  erode(b, tau, dt / 4, s);
  for (int i = 0; i <= n; ++i) EXPECT_EQ(a.node(i), b.node(i));
}

TEST(FemErosion, CornersMoveLikeTheParallelOffsetOfTheirFaces) {
  // A crest (0, 1)-(1, 1), a vertical face down to (1, 0) and a floor to (2, 0), h = 0.1 m, all
  // under the same stress: every face moves in by d, so the convex corner (1, 1) goes to
  // (1 - d, 1 - d) and the concave corner (1, 0) to (1 - d, -d) (the offset curve), which the
  // default NodeMotion::area_consistent reproduces to round-off.
  std::vector<Vector2d> nodes;
  for (int i = 0; i <= 10; ++i) nodes.emplace_back(0.1 * i, 1.0);
  for (int i = 1; i <= 10; ++i) nodes.emplace_back(1.0, 1.0 - 0.1 * i);
  for (int i = 1; i <= 10; ++i) nodes.emplace_back(1.0 + 0.1 * i, 0.0);
  SurfaceCurve curve(nodes);
  ErosionSettings s;
  s.law = {1e-3, 0};
  const double d = 0.02;  // e dt = 1e-3 * 2 * 10
  erode(curve, std::vector<double>(static_cast<std::size_t>(curve.element_count()), 2.0), 10, s);
  EXPECT_NEAR(curve.node(10).x(), 1 - d, 1e-14);
  EXPECT_NEAR(curve.node(10).y(), 1 - d, 1e-14);
  EXPECT_NEAR(curve.node(20).x(), 1 - d, 1e-14);
  EXPECT_NEAR(curve.node(20).y(), -d, 1e-14);
  EXPECT_NEAR(curve.node(15).x(), 1 - d, 1e-14) << "the face moves straight in";
}

TEST(FemErosion, ErodedAreaConvergesToTheTimeIntegralOfTheRateAtFirstOrder) {
  // Trapezoidal dam (h = 0.25 m, two convex and two concave corners), nonuniform stress,
  // kd = 1e-5 m/(s Pa): 1500 s in n = 20, 40, 80, 160 steps (up to 1.5 cm per step, 2.3 m^2 in
  // all). Per step the polygon area differs from the trapezoid integral of the moves by terms
  // quadratic in the move (curvature, the product of neighbouring moves), so the relative
  // difference D(n) of the sums is O(dt): D(n) / D(2n) -> 2. The stress vanishes at the ends, so
  // the pinned end nodes take no part.
  auto relative_difference = [](int n, NodeMotion motion) {
    SurfaceCurve curve = trapezoid_dam(0.25);
    const auto tau = dam_stress(curve);
    ErosionSettings s;
    s.law = {1e-5, 2};
    s.motion = motion;
    double eroded = 0;
    double integral = 0;
    for (int k = 0; k < n; ++k) {
      const ErosionStepReport r = erode(curve, tau, 1500.0 / n, s);
      EXPECT_EQ(r.pinned_end_integral, 0.0);
      eroded += r.eroded_area;
      integral += r.rate_integral;
    }
    return (eroded - integral) / integral;
  };
  std::vector<double> diff;
  for (int n : {20, 40, 80, 160}) diff.push_back(relative_difference(n, NodeMotion::area_consistent));
  for (std::size_t k = 0; k + 1 < diff.size(); ++k) {
    // First order: halving dt halves the difference, within 10 %.
    EXPECT_NEAR(diff[k] / diff[k + 1], 2.0, 0.2) << "D = " << diff[k] << " then " << diff[k + 1];
  }
  EXPECT_LT(std::abs(diff.back()), 0.01);
  // Moving by d along the unit normal sweeps only |m_i| d at the corners, a relative error of
  // about 6e-4 here that no dt removes: the difference stops halving.
  const double coarse = relative_difference(40, NodeMotion::unit_normal);
  const double fine = relative_difference(160, NodeMotion::unit_normal);
  EXPECT_LT(coarse / fine, 1.5) << "unit_normal: D = " << coarse << " then " << fine;
}

TEST(FemErosion, ProjectionsKeepTheIntegralAndTheirOtherProperties) {
  // Curved, nonuniform mesh and a positive, rough element field.
  std::vector<Vector2d> nodes;
  for (int i = 0; i <= 40; ++i) {
    const double x = 0.25 * i + 0.05 * std::sin(1.7 * i);
    nodes.emplace_back(x, 0.5 * std::sin(0.3 * x) + 0.1 * x);
  }
  const SurfaceCurve curve(nodes);
  std::vector<double> f(40);
  for (std::size_t e = 0; e < f.size(); ++e) f[e] = 1e-6 * (1.5 + std::sin(2.3 * static_cast<double>(e)));
  const auto lengths = curve.element_lengths();
  double exact = 0;
  for (std::size_t e = 0; e < f.size(); ++e) exact += lengths[e] * f[e];
  const auto lumped = project_to_nodes(curve, f, Projection::lumped);
  const auto consistent = project_to_nodes(curve, f, Projection::consistent);
  // Both keep the integral (Galerkin orthogonality against the constant 1); round-off only.
  EXPECT_NEAR(integrate_nodal(curve, lumped), exact, 1e-14 * exact);
  EXPECT_NEAR(integrate_nodal(curve, consistent), exact, 1e-14 * exact);
  // Lumped: a length-weighted average of the neighbouring values, so inside their range.
  for (std::size_t i = 0; i < lumped.size(); ++i) {
    const double lo = i == 0 ? f[0] : (i == f.size() ? f.back() : std::min(f[i - 1], f[i]));
    const double hi = i == 0 ? f[0] : (i == f.size() ? f.back() : std::max(f[i - 1], f[i]));
    EXPECT_GE(lumped[i], lo * (1 - 1e-15));
    EXPECT_LE(lumped[i], hi * (1 + 1e-15));
    EXPECT_GT(lumped[i], 0);
  }
  // Consistent: orthogonal to every P1 function, so it also keeps the first moment in the arc
  // length s (integral of u s, exact for P1 u by Simpson's rule).
  double s0 = 0;
  double moment_data = 0;
  double moment_projection = 0;
  for (int e = 0; e < curve.element_count(); ++e) {
    const double len = lengths[static_cast<std::size_t>(e)];
    const double s1 = s0 + len;
    const double u0 = consistent[static_cast<std::size_t>(e)];
    const double u1 = consistent[static_cast<std::size_t>(e) + 1];
    moment_data += f[static_cast<std::size_t>(e)] * len * 0.5 * (s0 + s1);
    moment_projection += len / 6 * (u0 * s0 + (u0 + u1) * (s0 + s1) + u1 * s1);
    s0 = s1;
  }
  EXPECT_NEAR(moment_projection, moment_data, 1e-13 * moment_data);

  // Element averages of a linear function g(s) = 3 + 2 s on a uniform straight mesh (h = 0.5 m,
  // N = 40). Lumped: an interior node averages the two midpoint values, which is g there exactly;
  // an end node is off by g' h / 2. Consistent: the exact nodal values satisfy every interior
  // row of M u = b but not the two end rows (residual g' h^2 / 12), so the error is
  // w_i = w_0 rho^i from each end, rho = sqrt(3) - 2 (root of rho^2 + 4 rho + 1 = 0), and the
  // end row gives w_0 (2 + rho) = g' h / 2: w_0 = g' h / (2 sqrt 3). The other end adds rho^N.
  const double h = 0.5;
  const int n = 40;
  const SurfaceCurve line = flat_bed(h * n, n, 0);
  std::vector<double> averages(n);
  for (int e = 0; e < n; ++e) averages[static_cast<std::size_t>(e)] = 3 + 2 * h * (e + 0.5);
  const auto lump_line = project_to_nodes(line, averages, Projection::lumped);
  const auto cons_line = project_to_nodes(line, averages, Projection::consistent);
  auto g = [&](int i) { return 3 + 2 * h * i; };
  for (int i = 1; i < n; ++i) EXPECT_NEAR(lump_line[static_cast<std::size_t>(i)], g(i), 1e-13 * g(i));
  EXPECT_NEAR(lump_line[0] - g(0), 2 * h / 2, 1e-13);
  const double rho = std::sqrt(3.0) - 2;
  const double w0 = 2 * h / (2 * std::sqrt(3.0));
  EXPECT_NEAR(cons_line[0] - g(0), w0, 1e-13);
  EXPECT_NEAR(cons_line[static_cast<std::size_t>(n)] - g(n), -w0, 1e-13);
  for (int i = 1; i <= 6; ++i) {
    EXPECT_NEAR(cons_line[static_cast<std::size_t>(i)] - g(i), w0 * std::pow(rho, i), 1e-13) << "node " << i;
  }
  EXPECT_NEAR(cons_line[static_cast<std::size_t>(n / 2)], g(n / 2), 1e-12) << "|rho|^20 = 3.6e-12";
}

TEST(FemErosion, NothingMovesBelowTheCriticalStress) {
  SurfaceCurve curve = trapezoid_dam(0.25);
  const SurfaceCurve before = curve;
  std::vector<double> tau(static_cast<std::size_t>(curve.element_count()), 0.0);
  for (std::size_t e = 0; e < tau.size(); ++e) tau[e] = 2.0 * static_cast<double>(e % 3) / 2.0;  // 0, 1, 2 Pa
  for (Projection p : {Projection::lumped, Projection::consistent}) {
    ErosionSettings s;
    s.law = {1e-3, 2};  // tau <= tau_c everywhere
    s.projection = p;
    const ErosionStepReport r = erode(curve, tau, 1e6, s);
    EXPECT_EQ(r.eroded_area, 0.0);
    EXPECT_EQ(r.rate_integral, 0.0);
    EXPECT_EQ(r.max_depth, 0.0);
    for (int i = 0; i < curve.node_count(); ++i) EXPECT_EQ(curve.node(i), before.node(i));
  }
}

TEST(FemErosion, FoundationStopsTheErosion) {
  // Flat bed at 1 m over a foundation at 0.95 m, 2 cm per step: the nodes reach the foundation
  // in the third step (where 1 cm of the move is cut) and stay there.
  const int n = 20;
  SurfaceCurve curve = flat_bed(4, n, 1.0);
  ErosionSettings s;
  s.law = {1e-3, 0};
  s.foundation_level = 0.95;
  const std::vector<double> tau(n, 2.0);
  double eroded = 0;
  for (int k = 0; k < 5; ++k) {
    const ErosionStepReport r = erode(curve, tau, 10, s);
    EXPECT_EQ(r.nodes_clamped, k < 2 ? 0 : n - 1) << "step " << k;
    eroded += r.eroded_area;
  }
  for (int i = 1; i < n; ++i) EXPECT_EQ(curve.node(i).y(), 0.95) << "clamped exactly onto the foundation";
  // The removed polygon is then a trapezoid: top L = 4 m, bottom from node 1 to node N-1 (these
  // two drifted towards the fixed ends, see the flat-bed test), height 5 cm. The step areas add
  // up to it to round-off (5 sums of 20 element-sized terms).
  const double bottom = curve.node(n - 1).x() - curve.node(1).x();
  EXPECT_GT(bottom, 4 - 2 * 0.2);
  EXPECT_NEAR(eroded, 0.5 * (4 + bottom) * 0.05, 1e-14);

  // The dam on its foundation (y = 0, where its end nodes sit) under 12 Pa on the downstream
  // slope, 10 steps of 5 cm: the slope nodes move obliquely (down and upstream) and the ones
  // near the toe are cut where their path meets the foundation; none goes below it.
  SurfaceCurve dam = trapezoid_dam(0.25);
  s.law = {1e-5, 2};
  s.foundation_level = 0;
  std::vector<double> dam_tau(static_cast<std::size_t>(dam.element_count()), 0.0);
  for (int e = 0; e < dam.element_count(); ++e) {
    const double x = 0.5 * (dam.node(e).x() + dam.node(e + 1).x());
    dam_tau[static_cast<std::size_t>(e)] = x > 14 && x < 21.5 ? 12.0 : 0.0;
  }
  int clamped = 0;
  for (int k = 0; k < 10; ++k) clamped += erode(dam, dam_tau, 500, s).nodes_clamped;
  EXPECT_GT(clamped, 0);
  int on_foundation = 0;
  for (int i = 1; i + 1 < dam.node_count(); ++i) {
    EXPECT_GE(dam.node(i).y(), 0.0) << "node " << i;
    on_foundation += dam.node(i).y() == 0.0 ? 1 : 0;
  }
  EXPECT_GT(on_foundation, 0);
}

// A headcut: crest at 2 m to x = 4 m, a face dropping 2 m over 0.4 m (slope 5, 79 degrees),
// floor at 0 m to x = 10 m; h = 0.2 m in x. The end elements are flat.
SurfaceCurve headcut() {
  std::vector<Vector2d> nodes;
  for (int i = 0; i <= 50; ++i) {
    const double x = 0.2 * i;
    nodes.emplace_back(x, x < 4 ? 2.0 : (x < 4.4 ? 2.0 - 5.0 * (x - 4.0) : 0.0));
  }
  return SurfaceCurve(nodes);
}

double max_slope(const SurfaceCurve& curve) {
  double steepest = 0;
  for (int e = 0; e < curve.element_count(); ++e) {
    const Vector2d v = curve.element_vector(e);
    steepest = std::max(steepest, std::abs(v.y()) / v.x());
  }
  return steepest;
}

TEST(FemErosion, ReposeLimiterKeepsTheAreaAndTheAngle) {
  const double angle = 35;
  const double tan_angle = std::tan(angle * std::numbers::pi / 180);
  // Erosion of the face with and without the limiter: the same move, then sand slides. Each
  // slide changes the area by -a w_upper + b w_lower = 0 exactly; what is left is round-off of
  // a few hundred sweeps of y updates (|y| <= 2 m, eps |y| w = 1e-16 m^2 each), far below
  // 1e-12 of the 0.23 m^2 eroded.
  std::vector<double> tau(50, 0.0);
  for (std::size_t e = 18; e < 24; ++e) tau[e] = 10;
  ErosionSettings s;
  s.law = {1e-3, 2};
  SurfaceCurve free_curve = headcut();
  SurfaceCurve limited = headcut();
  const ErosionStepReport without = erode(free_curve, tau, 10, s);
  s.repose_angle_deg = angle;
  const ErosionStepReport with = erode(limited, tau, 10, s);
  EXPECT_GT(without.eroded_area, 0.1);
  EXPECT_NEAR(with.eroded_area, without.eroded_area, 1e-12 * without.eroded_area);
  EXPECT_EQ(with.rate_integral, without.rate_integral);
  EXPECT_GT(with.nodes_limited_by_repose, 0);
  EXPECT_EQ(with.repose_elements_left, 0);
  // Stops once no element is steeper than tan(angle) by more than 1e-9 relative.
  EXPECT_LE(max_slope(limited), tan_angle * (1 + 1e-9));
  EXPECT_GT(max_slope(free_curve), 5.0);

  // The limiter alone on the headcut: the area between before and after is zero to round-off,
  // measured against the area the sand moved (sum of |dy_i| w_i, 1.2 m^2).
  const SurfaceCurve before = headcut();
  SurfaceCurve after = before;
  const ReposeResult r = limit_repose(after, angle);
  double displaced = 0;
  for (int i = 0; i < after.node_count(); ++i) displaced += std::abs(after.node(i).y() - before.node(i).y()) * 0.2;
  EXPECT_GT(displaced, 1.0);
  EXPECT_NEAR(before.area_below(after), 0.0, 1e-12 * displaced);
  EXPECT_EQ(r.elements_left, 0);
  EXPECT_LE(max_slope(after), tan_angle * (1 + 1e-9));
  for (int i = 0; i < after.node_count(); ++i) EXPECT_EQ(after.node(i).x(), before.node(i).x()) << "vertical moves";

  // A steep element at a fixed end cannot shed sand without losing area: it is left and counted.
  SurfaceCurve end_cliff({{0, 0}, {0.2, 1}, {0.4, 1}, {0.6, 1}, {0.8, 1}});
  const ReposeResult cliff = limit_repose(end_cliff, angle);
  EXPECT_EQ(cliff.elements_left, 1);
  EXPECT_EQ(cliff.nodes_moved, 0);
}

TEST(FemErosion, InvalidMovesAreSubsteppedOrRejected) {
  // A wall (0, 0)-(0.1, 1) at the fixed upstream end, then a flat crest; only the wall and the
  // first crest element erode, 1.5 m in one step. In one move the corner node (0.1, 1) goes
  // straight along its initial bisector and swings the wall element by more than 90 degrees.
  // Substeps recompute the normals: the corner turns downwards as the wall flattens, each
  // substep turns the wall by less than 90 degrees, and the result is a valid curve.
  std::vector<Vector2d> nodes{{0, 0}, {0.1, 1}};
  for (int i = 1; i <= 10; ++i) nodes.emplace_back(0.1 + i, 1);
  const SurfaceCurve wall(nodes);
  std::vector<double> tau(static_cast<std::size_t>(wall.element_count()), 0.0);
  tau[0] = tau[1] = 1.0;
  ErosionSettings s;
  s.law = {1.5, 0};
  s.max_substeps = 1;
  SurfaceCurve one_move = wall;
  try {
    erode(one_move, tau, 1.0, s);
    ADD_FAILURE() << "a single move should invert the wall element";
  } catch (const CurveValidityError& e) {
    EXPECT_EQ(e.element(), 0);
    EXPECT_NE(std::string(e.what()).find("element 0 (nodes 0-1) turns back"), std::string::npos) << e.what();
  }
  EXPECT_EQ(one_move.nodes(), wall.nodes()) << "a rejected step leaves the curve as it was";
  s.max_substeps = 64;
  SurfaceCurve substepped = wall;
  const ErosionStepReport r = erode(substepped, tau, 1.0, s);
  EXPECT_GT(r.substeps, 1);
  EXPECT_FALSE(substepped.self_intersects());
  EXPECT_GT(substepped.min_element_length(), 0.5);

  // A 90-degree ridge eroded 0.3 m at uniform rate, with nodes 0.1 m apart in x: the offset of
  // its two faces swallows the elements next to the apex whatever the substeps (an edge
  // collapse, which a mesh with a fixed node count cannot follow), so erode throws.
  std::vector<Vector2d> ridge_nodes;
  for (int i = 0; i <= 20; ++i) ridge_nodes.emplace_back(0.1 * i, 1 - std::abs(0.1 * i - 1));
  SurfaceCurve ridge(ridge_nodes);
  s.law = {0.3, 0};
  try {
    erode(ridge, std::vector<double>(20, 1.0), 1.0, s);
    ADD_FAILURE() << "the ridge cannot be eroded this far in one coupling step";
  } catch (const CurveValidityError& e) {
    EXPECT_TRUE(e.element() == 9 || e.element() == 10) << e.what();
    EXPECT_NE(std::string(e.what()).find("even with 64 substeps"), std::string::npos) << e.what();
  }

  // Too short an element is named too, and an invalid incoming curve is refused.
  s.law = {1e-3, 0};
  s.min_element_length = 0.15;
  try {
    SurfaceCurve short_elements = flat_bed(1, 10, 0);
    erode(short_elements, std::vector<double>(10, 1.0), 1.0, s);
    ADD_FAILURE() << "elements of 0.1 m are below min_element_length";
  } catch (const CurveValidityError& e) {
    EXPECT_NE(std::string(e.what()).find("incoming curve is invalid: element 0"), std::string::npos) << e.what();
  }
}

TEST(SurfaceCurve, AreaNormalsAndSelfIntersection) {
  // Old: (0,0)-(1,0)-(2,0). New with the middle node at (1, -1): a triangle of base 2 m and
  // height 1 m below the old curve, area 1 m^2; the other way round -1; raised to (1, 0.5),
  // -0.5. Same with the coordinates shifted by 1e6 m (computed relative to the first node).
  for (double shift : {0.0, 1e6}) {
    const Vector2d o(shift, shift);
    const SurfaceCurve old_curve({o + Vector2d(0, 0), o + Vector2d(1, 0), o + Vector2d(2, 0)});
    const SurfaceCurve lower({o + Vector2d(0, 0), o + Vector2d(1, -1), o + Vector2d(2, 0)});
    const SurfaceCurve upper({o + Vector2d(0, 0), o + Vector2d(1, 0.5), o + Vector2d(2, 0)});
    EXPECT_DOUBLE_EQ(old_curve.area_below(lower), 1.0);
    EXPECT_DOUBLE_EQ(lower.area_below(old_curve), -1.0);
    EXPECT_DOUBLE_EQ(old_curve.area_below(upper), -0.5);
    // Different node counts: the square (0,0)-(2,0) over (0,-2)... as a 4-node lower curve.
    const SurfaceCurve box({o + Vector2d(0, 0), o + Vector2d(0, -2), o + Vector2d(2, -2), o + Vector2d(2, 0)});
    EXPECT_DOUBLE_EQ(old_curve.area_below(box), 4.0);
  }

  // Normals point into the water: up for a bed walked in +x, right for a wall walked down.
  const SurfaceCurve corner({{0, 1}, {1, 1}, {1, 0}});
  EXPECT_EQ(corner.element_normal(0), Vector2d(0, 1));
  EXPECT_EQ(corner.element_normal(1), Vector2d(1, 0));
  const auto nodal = corner.nodal_normals();
  EXPECT_NEAR((nodal[1] - Vector2d(1, 1) / std::sqrt(2.0)).norm(), 0, 1e-15);
  EXPECT_EQ(nodal[0], Vector2d(0, 1));
  // Length weighting: element lengths 1 and 3 give (3, 1) / sqrt(10) at the shared node.
  const SurfaceCurve uneven({{0, 3}, {1, 3}, {1, 0}});
  EXPECT_NEAR((uneven.nodal_normals()[1] - Vector2d(3, 1) / std::sqrt(10.0)).norm(), 0, 1e-15);
  EXPECT_DOUBLE_EQ(uneven.min_element_length(), 1.0);
  EXPECT_DOUBLE_EQ(uneven.length(), 4.0);

  // Self-intersection: a loop crosses, a fold back onto the previous element overlaps, touching
  // at a point counts, a zigzag that comes close does not.
  const SurfaceCurve loop({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, -1}, {3, -1}});
  ASSERT_TRUE(loop.find_self_intersection().has_value());
  EXPECT_EQ(loop.find_self_intersection()->first, 0);
  EXPECT_EQ(loop.find_self_intersection()->second, 3);
  const SurfaceCurve fold({{0, 0}, {2, 0}, {1, 0}, {1, -1}});
  ASSERT_TRUE(fold.self_intersects());
  EXPECT_EQ(fold.find_self_intersection()->second, 1);
  const SurfaceCurve touch({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 0}, {1, -1}});
  EXPECT_TRUE(touch.self_intersects());
  std::vector<Vector2d> zigzag;
  for (int i = 0; i < 400; ++i) zigzag.emplace_back(0.01 * i, i % 2 == 0 ? 0.0 : 1.0);
  EXPECT_FALSE(SurfaceCurve(zigzag).self_intersects());
  zigzag.emplace_back(0.5, 0.5);  // back across the whole zigzag
  const auto crossing = SurfaceCurve(zigzag).find_self_intersection();
  ASSERT_TRUE(crossing.has_value());
  EXPECT_EQ(crossing->second, 399);
}

}  // namespace
