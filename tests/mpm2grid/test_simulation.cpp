// Whole steps of the two-species model against closed forms (docs/methods/mpm2grid.md, "Validation
// references" and "Stability"): free fall, drag relaxation with both drag schemes and total
// momentum, and the explicit drag's divergence above dt = 2 tau_d while the implicit solve stays
// bounded at 100 times that step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "solvers/mpm2grid/model/simulation.hpp"

namespace suite::mpm2grid {
namespace {

template <class T>
class Steps : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(Steps, Dims);

// A cube of side `cells` h filled with 2^Dim particles per cell, in an open box far larger.
template <int Dim>
void fill_block(Particles<Dim>& P, double h, int cells, double density, const Vec<Dim>& v) {
  const int per_axis = 2 * cells;
  const double spacing = h / 2, volume = std::pow(spacing, Dim);
  int total = 1;
  for (int d = 0; d < Dim; ++d) total *= per_axis;
  for (int n = 0; n < total; ++n) {
    int r = n;
    Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) {
      x[d] = 1.0 + (r % per_axis + 0.5) * spacing;
      r /= per_axis;
    }
    P.add(x, v, density * volume, volume);
  }
}

template <int Dim>
SimulationSettings<Dim> open_settings(double h) {
  SimulationSettings<Dim> s;
  s.h = h;
  s.walls.lo = Vec<Dim>::Constant(-100), s.walls.hi = Vec<Dim>::Constant(100);
  for (auto& axis : s.walls.kind) axis = {WallKind::open, WallKind::open};
  s.water.density = 1000;
  s.water.eos.bulk_modulus = 1e5;
  s.soil.density = 2000;
  s.soil.porosity = 0.4;
  s.soil.conductivity = 1e-3;
  s.soil.material = HenckyDruckerPrager::from_young(1e6, 0.3, 0.5, 0.0, true);
  return s;
}

TYPED_TEST(Steps, FreeFallFollowsTheSymplecticEulerParabola) {
  // Uniform gravity gives every node the same velocity, so grad v = 0, J stays 1, no pressure:
  // v_n = v0 + n g dt exactly, x_n = x0 + n v0 dt + g dt^2 n (n + 1) / 2 (symplectic Euler), which
  // is the parabola x0 + v0 t + g t^2 / 2 plus g t dt / 2.
  constexpr int Dim = TypeParam::value;
  auto s = open_settings<Dim>(0.1);
  s.gravity[1] = -9.81;
  Simulation<Dim> sim(s);
  Vec<Dim> v0 = Vec<Dim>::Zero();
  v0[0] = 0.7;
  fill_block(sim.water(), s.h, 3, 1000, v0);
  const Vec<Dim> x0 = sim.water().x[5];
  const double dt = 1e-3;
  const int n = 200;
  for (int i = 0; i < n; ++i) sim.step(dt);
  const double t = n * dt;
  Vec<Dim> expected = x0 + v0 * t;
  expected[1] += -9.81 * dt * dt * n * (n + 1) / 2.0;
  // The particle seeded sixth, wherever the steps' reordering put it.
  const auto& w = sim.water();
  const auto p = static_cast<std::size_t>(std::find(w.id.begin(), w.id.end(), 5) - w.id.begin());
  ASSERT_LT(p, w.size());
  // Round-off over 200 steps of O(1) positions: 1e-12.
  EXPECT_LT((w.x[p] - expected).norm(), 1e-12);
  EXPECT_NEAR(w.v[p][1], -9.81 * t, 1e-12);
  EXPECT_NEAR(w.J[p], 1.0, 1e-12);
  // Against the continuous parabola: off by g t dt / 2 (first order in dt).
  EXPECT_NEAR(w.x[p][1], x0[1] - 9.81 * t * t / 2, 9.81 * t * dt / 2 * 1.0001);
}

// Soil and water particles at the same places, soil at rest, water moving: the relative velocity
// decays by a constant factor per step (spec: (1 + dt d (m_s + m_w)/(m_s m_w))^-1 for the lumped
// solve; with equal particle volumes d (m_s + m_w)/(m_s m_w) = c_E (1/rho_s + 1/rho_w) at every
// node), and total momentum is conserved. The closed form is for unbounded uniform species: once
// the species have moved apart, nodes near the edge of a finite block see other mass ratios, and
// that difference travels inwards at most 4 cells a step (a particle reads nodes within 2 h, a node
// particles within 2 h). So the block reaches 4 steps + 4 cells beyond its central particle, which
// then follows the closed form to round-off. The velocities are small (1 mm/s) so that no particle
// moves a noticeable part of a cell even where the explicit drag grows them a thousandfold, and the
// materials soft (wave speeds about 1 m/s) so that their waves stay stable at dt = 100 tau_d: the
// test is about the drag alone.
template <int Dim>
struct DragRun {
  double relative = 0, momentum_drift = 0, factor = 0;
};

template <int Dim>
DragRun<Dim> relax(DragScheme scheme, double dt_over_tau, int steps) {
  auto s = open_settings<Dim>(0.1);
  s.drag = scheme;
  s.water.eos.bulk_modulus = 100;
  s.soil.material = HenckyDruckerPrager::from_young(2e3, 0.3, 0.5, 0.0, true);
  Simulation<Dim> sim(s);
  constexpr double v0 = 1e-3;
  Vec<Dim> vw = Vec<Dim>::Zero();
  vw[0] = v0;
  // One step from co-located species is exact on every particle; more need the margin.
  const int cells = steps == 1 ? 2 : 2 * (4 * steps + 4);
  fill_block<Dim>(sim.soil(), s.h, cells, s.soil.density, Vec<Dim>::Zero());
  fill_block(sim.water(), s.h, cells, s.water.density, vw);
  // The particle just past the block's centre along every axis (2 particles per cell per axis).
  std::size_t centre = 0, stride = 1;
  for (int d = 0; d < Dim; ++d, stride *= 2 * cells) centre += cells * stride;
  const double rate = s.soil.drag_coefficient(s.water.density) * (1 / s.soil.density + 1 / s.water.density);
  const double tau = 1 / rate, dt = dt_over_tau * tau;
  const Vec<Dim> p0 = sim.soil().momentum() + sim.water().momentum();
  for (int i = 0; i < steps; ++i) sim.step(dt);
  DragRun<Dim> r;
  r.relative = (sim.water().v[centre][0] - sim.soil().v[centre][0]) / v0;
  r.momentum_drift = (sim.soil().momentum() + sim.water().momentum() - p0).norm() / p0.norm();
  r.factor = scheme == DragScheme::lumped ? std::pow(1 / (1 + dt * rate), steps) : std::pow(1 - dt * rate, steps);
  return r;
}

// The block grows with the steps (4 cells a step each way), so 3D runs fewer steps.
template <int Dim>
constexpr int kRelaxSteps = Dim == 2 ? 6 : 1;

TYPED_TEST(Steps, DragRelaxationMatchesTheClosedFormForBothSchemes) {
  constexpr int Dim = TypeParam::value;
  for (DragScheme scheme : {DragScheme::lumped, DragScheme::explicit_euler})
    for (double ratio : {0.1, 0.5, 1.5}) {
      const auto r = relax<Dim>(scheme, ratio, kRelaxSteps<Dim>);
      // The central particle's nodes see the unbounded mass ratio: the closed form to round-off.
      EXPECT_NEAR(r.relative, r.factor, 1e-12) << "dt/tau " << ratio;
      // Sums of about 10^4 momenta: a relative round-off of N eps = 1e-12 at worst.
      EXPECT_LT(r.momentum_drift, 1e-11);
    }
}

TYPED_TEST(Steps, ExplicitDragDivergesAboveTwoTauWhileTheImplicitSolveStaysBounded) {
  constexpr int Dim = TypeParam::value;
  // Explicit: the relative velocity is multiplied by 1 - dt/tau a step, |1 - dt/tau| > 1 for
  // dt > 2 tau. At 1.9 tau it shrinks (0.9 a step), at 4 tau it grows (3 a step).
  const int steps = kRelaxSteps<Dim>;
  const auto just_stable = relax<Dim>(DragScheme::explicit_euler, 1.9, steps);
  const auto unstable = relax<Dim>(DragScheme::explicit_euler, 4.0, steps);
  EXPECT_LT(std::abs(just_stable.relative), 1.0);
  EXPECT_GT(std::abs(unstable.relative), std::pow(2.9, steps));
  EXPECT_NEAR(unstable.relative, unstable.factor, 1e-12 * std::abs(unstable.factor));
  // The implicit solve at 100 tau: relative velocity 1/101 a step, momentum still conserved.
  const auto implicit = relax<Dim>(DragScheme::lumped, 100.0, steps);
  EXPECT_NEAR(implicit.relative, std::pow(1 / 101.0, steps), 1e-12);
  EXPECT_LT(implicit.momentum_drift, 1e-11);
}

}  // namespace
}  // namespace suite::mpm2grid
