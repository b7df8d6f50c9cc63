// Cubic B-spline weights, the sparse block grid and APIC transfers (docs/methods/mpm2grid.md,
// "Validation references"): partition of unity, linear reproduction, gradient consistency, and
// conservation of mass, linear and angular momentum by P2G and by a G2P -> P2G round trip.
// Tolerances: these identities hold exactly in real arithmetic; sums of O(100) terms of O(1)
// lose about 1e-14 relative, so 1e-12 leaves a margin of a hundred.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "solvers/mpm2grid/boundary/walls.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/transfer/apic.hpp"

namespace suite::mpm2grid {
namespace {

constexpr double kRoundOff = 1e-12;

template <class T>
class Transfer : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(Transfer, Dims);

template <int Dim>
Vec<Dim> random_point(std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  Vec<Dim> x;
  for (int d = 0; d < Dim; ++d) x[d] = u(rng);
  return x;
}

TYPED_TEST(Transfer, WeightsArePartitionOfUnityReproduceLinearFunctionsAndHaveConsistentGradients) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(7);
  const double h = 0.013;
  for (int trial = 0; trial < 50; ++trial) {
    const Vec<Dim> xp = random_point<Dim>(rng, -0.3, 0.4);  // negative coordinates too
    const Stencil<Dim> s(xp, h);
    double sum = 0;
    Vec<Dim> first = Vec<Dim>::Zero(), grad_sum = Vec<Dim>::Zero();
    Mat<Dim> x_grad = Mat<Dim>::Zero(), second = Mat<Dim>::Zero();
    s.for_each([&](const Index<Dim>& k, const Index<Dim>& node) {
      Vec<Dim> xi;
      for (int d = 0; d < Dim; ++d) xi[d] = node[d] * h;
      const double w = s.weight(k);
      EXPECT_GE(w, 0.0);
      sum += w;
      first += w * xi;
      second += w * (xi - xp) * (xi - xp).transpose();
      grad_sum += s.gradient(k);
      x_grad += xi * s.gradient(k).transpose();
    });
    EXPECT_NEAR(sum, 1.0, kRoundOff);
    EXPECT_LT((first - xp).norm(), kRoundOff * h);
    EXPECT_LT(grad_sum.norm(), kRoundOff / h);
    EXPECT_LT((x_grad - Mat<Dim>::Identity()).norm(), kRoundOff);
    // APIC's D_p = sum_i w_ip (x_i - x_p)(x_i - x_p)^T = h^2 / 3 I for cubic B-splines.
    EXPECT_LT((second - h * h / 3 * Mat<Dim>::Identity()).norm(), kRoundOff * h * h);
  }
}

// The branch-free weights per axis (cubic_bspline_axis) against the piecewise N(r) of docs/methods/mpm2grid.md and
// dN/dr at the four distances, over the cell and at its ends (a few operations on O(1) values:
// 1e-15).
TEST(BsplineAxis, ClosedFormEqualsThePiecewiseKernel) {
  for (double xi : {-3.0, -2.75, -0.5, -1e-12, 0.0, 1e-12, 0.25, 0.5, 0.999999, 1.0, 7.3, 1e3 + 0.1}) {
    double w[4], dw[4];
    const int base = cubic_bspline_axis(xi, w, dw);
    EXPECT_EQ(base, static_cast<int>(std::floor(xi)) - 1);
    for (int k = 0; k < 4; ++k) {
      const double r = xi - (base + k);
      EXPECT_NEAR(w[k], cubic_bspline(r), 1e-15) << "xi = " << xi << ", k = " << k;
      EXPECT_NEAR(dw[k], cubic_bspline_derivative(r), 1e-15) << "xi = " << xi << ", k = " << k;
    }
  }
}

TYPED_TEST(Transfer, StencilSlotsAgreeWithNodeLookup) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(3);
  const double h = 0.1;
  BlockGrid<Dim> grid(h);
  std::vector<Vec<Dim>> points;
  for (int i = 0; i < 200; ++i) points.push_back(random_point<Dim>(rng, -2.0, 2.0));
  for (const auto& x : points) grid.touch(Stencil<Dim>(x, h));
  std::array<long, BlockGrid<Dim>::kNodes> slots;
  std::vector<int> seen(grid.nodes(), 0);
  for (const auto& x : points) {
    const Stencil<Dim> s(x, h);
    grid.stencil_slots(s, slots);
    int n = 0;
    s.for_each([&](const Index<Dim>&, const Index<Dim>& node) {
      const long slot = slots[n++];
      ASSERT_EQ(slot, grid.slot_of(node));
      ASSERT_GE(slot, 0);
      EXPECT_EQ(grid.node_of(slot), node);
    });
  }
  // Each active block holds 4^Dim distinct nodes: slots map back to distinct nodes.
  for (std::size_t b = 0; b < grid.blocks(); ++b)
    for (int l = 0; l < BlockGrid<Dim>::kNodes; ++l)
      EXPECT_EQ(grid.slot_of(grid.node_of(static_cast<long>(b * BlockGrid<Dim>::kNodes + l))),
                static_cast<long>(b * BlockGrid<Dim>::kNodes + l));
}

// Angular momentum about the origin of the grid and of APIC particles (the affine part adds
// m_p (C_p D)^T's antisymmetric part, D = h^2/3 I): as an antisymmetric matrix sum m (x v^T - v x^T).
template <int Dim>
Mat<Dim> grid_angular_momentum(const BlockGrid<Dim>& grid, const NodeFields<Dim>& nodes) {
  Mat<Dim> L = Mat<Dim>::Zero();
  for (long i = 0; i < static_cast<long>(grid.nodes()); ++i) {
    const Vec<Dim> x = grid.position(i);
    L += x * nodes.momentum[i].transpose() - nodes.momentum[i] * x.transpose();
  }
  return L;
}

template <int Dim>
Mat<Dim> particle_angular_momentum(const Particles<Dim>& P, double h) {
  Mat<Dim> L = Mat<Dim>::Zero();
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Mat<Dim> affine = P.mass[p] * (P.C[p] * (h * h / 3)).transpose();
    L += P.mass[p] * (P.x[p] * P.v[p].transpose() - P.v[p] * P.x[p].transpose()) + affine - affine.transpose();
  }
  return L;
}

TYPED_TEST(Transfer, ApicConservesMassLinearAndAngularMomentum) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(11);
  const double h = 0.05;
  Particles<Dim> P;
  for (int i = 0; i < 300; ++i) {
    P.add(random_point<Dim>(rng, 0.0, 0.6), random_point<Dim>(rng, -1.0, 1.0), 0.5 + (i % 7) * 0.1, 1e-4);
    P.C.back() = Mat<Dim>::Random() * 3.0;
  }
  BlockGrid<Dim> grid(h);
  touch_blocks(P, grid);
  NodeFields<Dim> nodes;
  nodes.reset(grid.nodes());
  particles_to_grid(P, {}, grid, nodes);

  double mass = 0;
  Vec<Dim> momentum = Vec<Dim>::Zero();
  for (std::size_t i = 0; i < grid.nodes(); ++i) mass += nodes.mass[i], momentum += nodes.momentum[i];
  EXPECT_NEAR(mass, P.total_mass(), kRoundOff * P.total_mass());
  EXPECT_LT((momentum - P.momentum()).norm(), kRoundOff * P.total_mass());
  const Mat<Dim> L_particles = particle_angular_momentum(P, h), L_grid = grid_angular_momentum(grid, nodes);
  EXPECT_LT((L_grid - L_particles).norm(), kRoundOff * L_particles.norm());

  // G2P of the grid velocities and P2G again: the same grid momentum and angular momentum.
  for (std::size_t i = 0; i < grid.nodes(); ++i)
    nodes.velocity[i] = nodes.mass[i] > 0 ? Vec<Dim>(nodes.momentum[i] / nodes.mass[i]) : Vec<Dim>::Zero();
  std::vector<Mat<Dim>> grad_v;
  grid_to_particles(P, grid, nodes, grad_v);
  EXPECT_LT((P.momentum() - momentum).norm(), kRoundOff * P.total_mass());
  EXPECT_LT((particle_angular_momentum(P, h) - L_grid).norm(), kRoundOff * L_grid.norm());
  NodeFields<Dim> again;
  again.reset(grid.nodes());
  particles_to_grid(P, {}, grid, again);
  EXPECT_LT((grid_angular_momentum(grid, again) - L_grid).norm(), kRoundOff * L_grid.norm());
}

TYPED_TEST(Transfer, AffineVelocityFieldIsTransferredExactly) {
  // APIC reproduces an affine field v(x) = v0 + A x: after P2G and G2P, v_p and C_p are exact.
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(5);
  const double h = 0.02;
  const Vec<Dim> v0 = Vec<Dim>::LinSpaced(0.3, 0.9);
  const Mat<Dim> A = Mat<Dim>::Random();
  Particles<Dim> P;
  for (int i = 0; i < 2000; ++i) {
    const Vec<Dim> x = random_point<Dim>(rng, 0.0, Dim == 2 ? 0.3 : 0.12);
    P.add(x, v0 + A * x, 1.0, 1.0);
    P.C.back() = A;
  }
  BlockGrid<Dim> grid(h);
  touch_blocks(P, grid);
  NodeFields<Dim> nodes;
  nodes.reset(grid.nodes());
  particles_to_grid(P, {}, grid, nodes);
  for (std::size_t i = 0; i < grid.nodes(); ++i)
    nodes.velocity[i] = nodes.mass[i] > 0 ? Vec<Dim>(nodes.momentum[i] / nodes.mass[i]) : Vec<Dim>::Zero();
  std::vector<Mat<Dim>> grad_v;
  const auto x = P.x;
  grid_to_particles(P, grid, nodes, grad_v);
  for (std::size_t p = 0; p < P.size(); ++p) {
    EXPECT_LT((P.v[p] - (v0 + A * x[p])).norm(), 1e-10);
    EXPECT_LT((P.C[p] - A).norm(), 1e-9);
    EXPECT_LT((grad_v[p] - A).norm(), 1e-9);
  }
  // The divergence alone (the water's J update) is the full gradient's trace, bit for bit, with
  // the same v_p and C_p.
  const auto v = P.v;
  const auto C = P.C;
  std::vector<double> divergence(P.size());
  grid_to_particles_each<VelocityGradient::divergence>(P, grid, nodes, nullptr, nullptr, nullptr,
                                                       [&](std::size_t p, double d) { divergence[p] = d; });
  for (std::size_t p = 0; p < P.size(); ++p) {
    ASSERT_EQ(divergence[p], grad_v[p].trace());
    ASSERT_EQ(P.v[p], v[p]);
    ASSERT_EQ(P.C[p], C[p]);
  }
}

// The tiled transfers (grid/node_tile.hpp, transfer/stencil_rows.hpp) against the sums of the
// spec written node by node with Stencil's weights and gradients and BlockGrid's slots, for
// particles in no particular order (so that groups recur and tiles are flushed and gathered many
// times), in every form the step uses: the soil's full stresses with drag coefficients and the
// buoyancy from node pressures, the water's pressures (isotropic stress), each with the forces
// apart and folded into the momentum times dt. The two sum the same terms in another order: the
// relative difference is round-off (kRoundOff, see the top).
TYPED_TEST(Transfer, TiledTransfersEqualTheNodeByNodeSums) {
  constexpr int Dim = TypeParam::value;
  std::mt19937 rng(17);
  const double h = 0.05, dt = 1e-3;
  Particles<Dim> P;
  std::vector<Mat<Dim>> tau;
  std::vector<double> extra, solid;
  for (int i = 0; i < 400; ++i) {
    P.add(random_point<Dim>(rng, -0.4, 0.3), random_point<Dim>(rng, -1.0, 1.0), 0.5 + (i % 5) * 0.2, 1e-3);
    P.C.back() = Mat<Dim>::Random() * 3.0;
    P.J.back() = 0.9 + 0.05 * (i % 4);
    tau.push_back(Mat<Dim>::Random() * 1e4);
    extra.push_back(1e3 * (1 + i % 3));
    solid.push_back(6e-4 * (1 + i % 2));
  }
  BlockGrid<Dim> grid(h);
  touch_blocks(P, grid);
  std::vector<double> node_pressure(grid.nodes());
  std::uniform_real_distribution<double> pressure(0.0, 2e3);
  for (auto& p : node_pressure) p = pressure(rng);
  for (const bool water : {true, false})     // pressures (water) or stresses, drag and buoyancy (soil)
    for (const bool fold : {false, true}) {  // forces apart or in the momentum times dt
      SCOPED_TRACE(std::string(water ? "water" : "soil") + (fold ? ", folded" : ", apart"));
      P2GSources<Dim> in{.fold_dt = fold ? dt : 0.0};
      if (water)
        in.pressure = &extra;
      else
        in.tau = &tau, in.drag = &extra, in.solid_volume = &solid, in.node_pressure = &node_pressure;
      NodeFields<Dim> tiled, direct;
      tiled.reset(grid.nodes());
      direct.reset(grid.nodes());
      particles_to_grid(P, in, grid, tiled);
      std::array<long, BlockGrid<Dim>::kNodes> slots;
      for (std::size_t p = 0; p < P.size(); ++p) {
        const Stencil<Dim> st(P.x[p], h);
        grid.stencil_slots(st, slots);
        const Mat<Dim> stress = water ? Mat<Dim>(-P.J[p] * extra[p] * Mat<Dim>::Identity()) : tau[p];
        Vec<Dim> grad_p = Vec<Dim>::Zero();  // the buoyancy's sum_i p_i grad w_ip
        int n = 0;
        st.for_each([&](const Index<Dim>& k, const Index<Dim>&) {
          grad_p += node_pressure[static_cast<std::size_t>(slots[static_cast<std::size_t>(n++)])] * st.gradient(k);
        });
        const Vec<Dim> body = water ? Vec<Dim>::Zero() : Vec<Dim>(-solid[p] * grad_p);
        n = 0;
        st.for_each([&](const Index<Dim>& k, const Index<Dim>& node) {
          const auto i = static_cast<std::size_t>(slots[static_cast<std::size_t>(n++)]);
          Vec<Dim> xi;
          for (int d = 0; d < Dim; ++d) xi[d] = node[d] * h;
          const double w = st.weight(k);
          const Vec<Dim> f = -P.volume0[p] * stress * st.gradient(k) + w * body;
          direct.mass[i] += w * P.mass[p];
          direct.momentum[i] += w * P.mass[p] * (P.v[p] + P.C[p] * (xi - P.x[p])) + (fold ? dt : 0.0) * f;
          if (!fold) direct.force[i] += f;
          (water ? direct.pressure[i] : direct.drag[i]) += w * (water ? P.mass[p] : 1.0) * extra[p];
        });
      }
      double mass = 0, momentum = 0, force = 0, ext = 0;  // scales: the largest of each
      for (std::size_t i = 0; i < grid.nodes(); ++i) {
        mass = std::max(mass, direct.mass[i]);
        momentum = std::max(momentum, direct.momentum[i].norm());
        force = std::max(force, direct.force[i].norm());
        ext = std::max({ext, direct.pressure[i], direct.drag[i]});
      }
      ASSERT_GT(force + (fold ? 1.0 : 0.0), 0.0);
      for (std::size_t i = 0; i < grid.nodes(); ++i) {
        ASSERT_NEAR(tiled.mass[i], direct.mass[i], kRoundOff * mass);
        ASSERT_LT((tiled.momentum[i] - direct.momentum[i]).norm(), kRoundOff * momentum);
        ASSERT_LE((tiled.force[i] - direct.force[i]).norm(), kRoundOff * force);  // folded: both 0
        ASSERT_NEAR(tiled.pressure[i], direct.pressure[i], kRoundOff * ext);
        ASSERT_NEAR(tiled.drag[i], direct.drag[i], kRoundOff * ext);
      }
    }
  // G2P of an arbitrary velocity field against v = sum w v_i, B = sum w v_i (x_i - x_p)^T, G =
  // sum v_i grad w^T, and of a scalar field (the saturation's water masses) against sum w f_i.
  NodeFields<Dim> nodes;
  nodes.reset(grid.nodes());
  for (auto& v : nodes.velocity) v = random_point<Dim>(rng, -2.0, 2.0);
  std::vector<Mat<Dim>> grad_v;
  std::vector<double> sampled;
  const auto x = P.x;
  grid_to_particles(P, grid, nodes, grad_v, &node_pressure, &sampled);
  // The water's G2P samples only the divergence (one gradient component per velocity component):
  // the same velocities and C, and the full gradient's trace.
  Particles<Dim> W = P;
  W.x = x;
  std::vector<double> divergence(P.size());
  grid_to_particles_each<VelocityGradient::divergence>(W, grid, nodes, nullptr, nullptr, nullptr,
                                                       [&](std::size_t p, double div) { divergence[p] = div; });
  for (std::size_t p = 0; p < P.size(); ++p) {
    ASSERT_TRUE(W.v[p] == P.v[p]);
    ASSERT_TRUE(W.C[p] == P.C[p]);
    ASSERT_NEAR(divergence[p], grad_v[p].trace(), kRoundOff * 2 / h);
  }
  std::array<long, BlockGrid<Dim>::kNodes> slots;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Stencil<Dim> st(x[p], h);
    grid.stencil_slots(st, slots);
    Vec<Dim> v = Vec<Dim>::Zero();
    Mat<Dim> B = Mat<Dim>::Zero(), G = Mat<Dim>::Zero();
    double f = 0;
    int n = 0;
    st.for_each([&](const Index<Dim>& k, const Index<Dim>& node) {
      const auto i = static_cast<std::size_t>(slots[static_cast<std::size_t>(n++)]);
      const Vec<Dim>& vi = nodes.velocity[i];
      f += st.weight(k) * node_pressure[i];
      Vec<Dim> xi;
      for (int d = 0; d < Dim; ++d) xi[d] = node[d] * h;
      v += st.weight(k) * vi;
      B += st.weight(k) * vi * (xi - x[p]).transpose();
      G += vi * st.gradient(k).transpose();
    });
    // Velocities of O(2) m/s over O(100) terms; gradients O(2 / h).
    ASSERT_LT((P.v[p] - v).norm(), kRoundOff * 2);
    ASSERT_LT((P.C[p] - apic_inverse_d(h) * B).norm(), kRoundOff * 2 / h);
    ASSERT_LT((grad_v[p] - G).norm(), kRoundOff * 2 / h);
    ASSERT_NEAR(sampled[p], f, kRoundOff * 2e3);  // node values up to 2e3
  }
}

}  // namespace
}  // namespace suite::mpm2grid

namespace suite::mpm2grid {
namespace {

// The closed-form integral of the cubic B-spline (the walls' inside fraction) against the
// midpoint rule at 20,000 points over [-2, 2] (its error is at most dr^2 / 24 times the change of
// N', which is below 1: 1.7e-9), with its values at -2, 0, 2 and one cell beyond a wall (1/24).
TEST(BsplineIntegral, MatchesTheQuadratureOfTheKernel) {
  EXPECT_EQ(cubic_bspline_integral(-2.5), 0.0);
  EXPECT_EQ(cubic_bspline_integral(-2.0), 0.0);
  EXPECT_EQ(cubic_bspline_integral(0.0), 0.5);
  EXPECT_EQ(cubic_bspline_integral(2.0), 1.0);
  EXPECT_NEAR(cubic_bspline_integral(-1.0), 1.0 / 24, 1e-15);
  const int n = 20000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double r = -2 + 4.0 * (i + 0.5) / n;
    sum += cubic_bspline(r) * 4.0 / n;
    if (i % 1000 == 999) {
      EXPECT_NEAR(cubic_bspline_integral(r + 2.0 / n), sum, 2e-9) << r;
    }
  }
}

// A box full of material up to its walls: for every node, the weights of particles on a fine
// lattice inside, times their volume, sum to the node's inside fraction times h^Dim (what
// the mixture's solid fraction divides by).
TEST(BsplineIntegral, InsideFractionIsTheWeightOfAFullBox) {
  Walls<2> walls;
  walls.lo = Vec<2>(0, 0), walls.hi = Vec<2>(1, 1);
  const double h = 0.125, s = h / 64;
  for (const Vec<2>& node : {Vec<2>(0, 0.5), Vec<2>(-h, 0.5), Vec<2>(h, h), Vec<2>(0.5, 0.5), Vec<2>(1 + h, 1)}) {
    double sum = 0;
    for (double x = s / 2; x < 1; x += s)
      for (double y = s / 2; y < 1; y += s)
        sum += cubic_bspline((x - node[0]) / h) * cubic_bspline((y - node[1]) / h) * s * s / (h * h);
    EXPECT_NEAR(sum, walls.inside_fraction(node, h), 1e-4) << node.transpose();
  }
}

}  // namespace
}  // namespace suite::mpm2grid
