// The consistent (PETSc) drag solve of coupling/consistent_drag.hpp against mathematical truths,
// in 2D and 3D, on 1 and 2 ranks:
//   a. it solves the block system [[M_s + dt D, -dt D], [-dt D, M_w + dt D]] v = b, compared with
//      a dense Cholesky solve of the same system that the test assembles from the particles
//      itself (soil block first, then water: another layout than the class's interleaved rows),
//      also where most soil particles are far from the water (a2: their terms are skipped);
//   b. it conserves the total momentum sum_i (m_s v_s + m_w v_w) = sum_i (b_s + b_w), for dt far
//      below and far above the drag relaxation time;
//   c. with co-located species, a uniform relative velocity and m_s,i / d_i, m_w,i / d_i the same
//      on every node, it gives the lumped closed form's velocities (the row sums of D are d_i);
//   d. split over the ranks (half of the soil particles' drag terms and half of the coupled nodes
//      per rank, or three quarters of the nodes on rank 0; the grid replicated) it gives the
//      1-rank solution on each rank's nodes, with the Krylov rows in equal shares or the owners';
//   e. a Krylov solve that stops early is an error that names the options prefix and the reason;
//   f. a whole model step with the consistent drag relaxes as the closed form;
// and NodeNumbering::own_all gives each rank's coupled nodes a disjoint range, in rank order.
// Tolerances: the Krylov solve runs with -drag_ksp_rtol 1e-14; each test states its bound.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "solvers/mpm2grid/coupling/consistent_drag.hpp"
#include "solvers/mpm2grid/coupling/drag_solve.hpp"
#include "solvers/mpm2grid/model/simulation.hpp"
#include "solvers/mpm2grid/transfer/apic.hpp"
#include "tests/support/petsc_environment.hpp"

namespace suite::mpm2grid {
namespace {

// "stop_" gives a solver that may take one iteration only (test e).
testing::PetscEnvironment* const environment =
    testing::add_petsc_environment("-drag_ksp_rtol 1e-14 -stop_ksp_max_it 1");

template <class T>
class ConsistentDragTest : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(ConsistentDragTest, Dims);

// Two particle clouds, their grid and node fields, as the simulation's step builds them.
template <int Dim>
struct Scene {
  double h = 0.1;
  BlockGrid<Dim> grid{0.1};
  Particles<Dim> soil, water;
  std::vector<double> soil_drag;  // (c_E V)_p, kg/s
  NodeFields<Dim> soil_nodes, water_nodes;

  void build(const Vec<Dim>& gravity, const std::vector<Mat<Dim>>& soil_tau, const std::vector<Mat<Dim>>& water_tau) {
    grid.clear();
    touch_blocks(water, grid);
    touch_blocks(soil, grid);
    soil_nodes.reset(grid.nodes());
    water_nodes.reset(grid.nodes());
    const auto stress = [](const std::vector<Mat<Dim>>& tau) { return tau.empty() ? nullptr : &tau; };
    particles_to_grid(soil, {.tau = stress(soil_tau), .drag = &soil_drag}, grid, soil_nodes);
    particles_to_grid(water, {.tau = stress(water_tau)}, grid, water_nodes);
    for (std::size_t i = 0; i < grid.nodes(); ++i) {
      soil_nodes.force[i] += soil_nodes.mass[i] * gravity;
      water_nodes.force[i] += water_nodes.mass[i] * gravity;
    }
  }

  // The drag relaxation time on the coupled nodes: sum of m_s m_w / (m_s + m_w) over sum of d.
  double relaxation_time() const {
    double reduced = 0, drag = 0;
    for (std::size_t i = 0; i < grid.nodes(); ++i) {
      const double ms = soil_nodes.mass[i], mw = water_nodes.mass[i];
      if (!drag_coupled(ms, mw)) continue;
      reduced += ms * mw / (ms + mw);
      drag += soil_nodes.drag[i];
    }
    return reduced / drag;
  }
};

constexpr double kSoilDensity = 2000, kWaterDensity = 1000, kDragCoefficient = 1e6;  // kg/m^3, kg/(m^3 s)

template <int Dim>
Vec<Dim> uniform_vec(std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  Vec<Dim> v;
  for (int d = 0; d < Dim; ++d) v[d] = u(rng);
  return v;
}

template <int Dim>
Mat<Dim> uniform_mat(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Mat<Dim> m;
  for (int r = 0; r < Dim; ++r)
    for (int c = 0; c < Dim; ++c) m(r, c) = u(rng);
  return m;
}

// An irregular scene: the soil cloud and the water cloud overlap over about half their width,
// so there are coupled nodes, soil-only and water-only nodes. Masses, drag coefficients,
// velocities, APIC matrices and stresses (hence forces) vary from particle to particle.
template <int Dim>
Scene<Dim> irregular_scene(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> factor(0.5, 1.5);
  Scene<Dim> s;
  const int count = Dim == 2 ? 60 : 150;
  const double volume = std::pow(s.h / 2, Dim);
  Vec<Dim> lo = Vec<Dim>::Constant(0.3), hi = Vec<Dim>::Constant(0.6), shift = Vec<Dim>::Zero();
  shift[0] = 0.15;
  std::vector<Mat<Dim>> soil_tau, water_tau;
  for (int p = 0; p < count; ++p) {
    Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) x[d] = std::uniform_real_distribution<double>(lo[d], hi[d])(rng);
    const double v = volume * factor(rng);
    s.soil.add(x, uniform_vec<Dim>(rng, -1, 1), kSoilDensity * v * factor(rng), v);
    s.soil.C.back() = uniform_mat<Dim>(rng, 5.0);
    s.soil_drag.push_back(kDragCoefficient * v * factor(rng));
    soil_tau.push_back(uniform_mat<Dim>(rng, 1e3));
  }
  for (int p = 0; p < count; ++p) {
    Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) x[d] = std::uniform_real_distribution<double>(lo[d], hi[d])(rng) + shift[d];
    const double v = volume * factor(rng);
    s.water.add(x, uniform_vec<Dim>(rng, -1, 1), kWaterDensity * v * factor(rng), v);
    s.water.C.back() = uniform_mat<Dim>(rng, 5.0);
    water_tau.push_back(-1e3 * factor(rng) * Mat<Dim>::Identity());  // a pressure
  }
  Vec<Dim> gravity = Vec<Dim>::Zero();
  gravity[Dim - 1] = -9.81;
  s.build(gravity, soil_tau, water_tau);
  return s;
}

// The velocities of both species, one entry per node slot.
template <int Dim>
struct Velocities {
  std::vector<Vec<Dim>> soil, water;
};

// The reference: the block system assembled here from the particles, dense, with the soil
// block first and the water block after it, solved by Cholesky (it is SPD).
template <int Dim>
Velocities<Dim> dense_solve(const Scene<Dim>& s, double dt) {
  const std::size_t nodes = s.grid.nodes();
  std::vector<long> index(nodes, -1);
  long n = 0;
  for (std::size_t i = 0; i < nodes; ++i)
    if (s.soil_nodes.mass[i] > 0 && s.water_nodes.mass[i] > 0) index[i] = n++;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  for (std::size_t i = 0; i < nodes; ++i)
    if (index[i] >= 0) {
      A(index[i], index[i]) += s.soil_nodes.mass[i];
      A(n + index[i], n + index[i]) += s.water_nodes.mass[i];
    }
  std::array<long, BlockGrid<Dim>::kNodes> slots;
  for (std::size_t p = 0; p < s.soil.size(); ++p) {
    const Stencil<Dim> st(s.soil.x[p], s.h);
    s.grid.stencil_slots(st, slots);
    std::vector<std::pair<long, double>> coupled;  // (row, N_i(x_p))
    int k = 0;
    st.for_each([&](const Index<Dim>& corner, const Index<Dim>&) {
      const long row = index[static_cast<std::size_t>(slots[static_cast<std::size_t>(k++)])];
      if (row >= 0) coupled.emplace_back(row, st.weight(corner));
    });
    for (const auto& [i, wi] : coupled)
      for (const auto& [j, wj] : coupled) {
        const double c = dt * s.soil_drag[p] * wi * wj;
        A(i, j) += c;
        A(n + i, n + j) += c;
        A(i, n + j) -= c;
        A(n + i, j) -= c;
      }
  }
  const Eigen::LLT<Eigen::MatrixXd> cholesky(A);
  EXPECT_EQ(cholesky.info(), Eigen::Success) << "the block matrix is not SPD";
  Velocities<Dim> v{std::vector<Vec<Dim>>(nodes, Vec<Dim>::Zero()), std::vector<Vec<Dim>>(nodes, Vec<Dim>::Zero())};
  for (int d = 0; d < Dim; ++d) {
    Eigen::VectorXd b(2 * n);
    for (std::size_t i = 0; i < nodes; ++i)
      if (index[i] >= 0) {
        b[index[i]] = s.soil_nodes.momentum[i][d] + dt * s.soil_nodes.force[i][d];
        b[n + index[i]] = s.water_nodes.momentum[i][d] + dt * s.water_nodes.force[i][d];
      }
    const Eigen::VectorXd x = cholesky.solve(b);
    for (std::size_t i = 0; i < nodes; ++i)
      if (index[i] >= 0) {
        v.soil[i][d] = x[index[i]];
        v.water[i][d] = x[n + index[i]];
      }
  }
  for (std::size_t i = 0; i < nodes; ++i) {
    if (index[i] >= 0) continue;
    const double ms = s.soil_nodes.mass[i], mw = s.water_nodes.mass[i];
    if (ms > 0) v.soil[i] = (s.soil_nodes.momentum[i] + dt * s.soil_nodes.force[i]) / ms;
    if (mw > 0) v.water[i] = (s.water_nodes.momentum[i] + dt * s.water_nodes.force[i]) / mw;
  }
  return v;
}

// Largest |v| over the slots where `take` holds, of both species.
template <int Dim, class Take>
double largest(const Velocities<Dim>& v, Take&& take) {
  double m = 0;
  for (std::size_t i = 0; i < v.soil.size(); ++i)
    if (take(i)) m = std::max({m, v.soil[i].norm(), v.water[i].norm()});
  return m;
}

// Largest |a - b| over the slots where `take` holds.
template <int Dim, class Take>
double largest_difference(const Velocities<Dim>& a, const Velocities<Dim>& b, Take&& take) {
  double m = 0;
  for (std::size_t i = 0; i < a.soil.size(); ++i)
    if (take(i)) m = std::max({m, (a.soil[i] - b.soil[i]).norm(), (a.water[i] - b.water[i]).norm()});
  return m;
}

template <int Dim>
Velocities<Dim> velocities(const Scene<Dim>& s) {
  return {s.soil_nodes.velocity, s.water_nodes.velocity};
}

// a. Agreement with the dense solve at dt = the relaxation time, on every node (coupled or not).
// The Krylov solve stops at ||b - A v|| <= 1e-14 ||b||; the error is that residual amplified by
// the condition number of the Jacobi-scaled matrix, 40 to 500 for these scenes, so about 1e-11 at
// worst (measured: 1e-13). Bound: 1e-10 of the largest velocity.
TYPED_TEST(ConsistentDragTest, SolvesTheBlockSystemLikeADenseCholesky) {
  constexpr int Dim = TypeParam::value;
  const mpi::Comm self(MPI_COMM_SELF);
  ConsistentDrag<Dim> drag(self);  // reused: the scenes have different numbers of coupled nodes
  for (unsigned seed : {1u, 2u, 1u}) {
    Scene<Dim> s = irregular_scene<Dim>(seed);
    const double dt = s.relaxation_time();
    const Velocities<Dim> reference = dense_solve(s, dt);
    const auto numbering = NodeNumbering::own_all(self, s.soil_nodes, s.water_nodes);
    ASSERT_GT(numbering.owned, 10);
    ASSERT_LT(numbering.owned, static_cast<long>(s.grid.nodes()));
    const SolveStats stats = drag.solve(s.grid, s.soil, s.soil_drag, s.soil_nodes, s.water_nodes, dt, numbering);
    EXPECT_GT(stats.reason, 0);
    EXPECT_EQ(stats.reason_name.rfind("CONVERGED", 0), 0u) << stats.reason_name;
    EXPECT_EQ(stats.unknowns, 2 * numbering.owned);
    const auto all = [](std::size_t) { return true; };
    const double scale = largest(reference, all);
    EXPECT_LT(largest_difference(velocities(s), reference, all), 1e-10 * scale)
        << "seed " << seed << ", " << stats.iterations << " iterations";
  }
}

// b. Total momentum. In exact arithmetic sum(M v) = sum(b) (the drag columns sum to zero); the
// solve leaves the residual r = b - A v, and sum(A v) - sum(b) = -sum(r), |sum(r)| <= sqrt(rows)
// ||r||, ||r|| <= 1e-14 ||b|| <= 1e-14 sum |b| (unpreconditioned norm), sqrt(rows) <= 20 here.
// Bound: 1e-12 sum |b|, five times that (measured: below 1e-15, dt = 1e3 tau included).
TYPED_TEST(ConsistentDragTest, ConservesTotalMomentumForSmallAndLargeSteps) {
  constexpr int Dim = TypeParam::value;
  const mpi::Comm self(MPI_COMM_SELF);
  ConsistentDrag<Dim> drag(self);  // reused over the calls
  for (double ratio : {1e-3, 1e3}) {
    Scene<Dim> s = irregular_scene<Dim>(3);
    const double dt = ratio * s.relaxation_time();
    const auto numbering = NodeNumbering::own_all(self, s.soil_nodes, s.water_nodes);
    const SolveStats stats = drag.solve(s.grid, s.soil, s.soil_drag, s.soil_nodes, s.water_nodes, dt, numbering);
    Vec<Dim> momentum = Vec<Dim>::Zero(), b = Vec<Dim>::Zero(), b_abs = Vec<Dim>::Zero();
    for (std::size_t i = 0; i < s.grid.nodes(); ++i) {
      momentum += s.soil_nodes.mass[i] * s.soil_nodes.velocity[i] + s.water_nodes.mass[i] * s.water_nodes.velocity[i];
      const Vec<Dim> bi = s.soil_nodes.momentum[i] + dt * s.soil_nodes.force[i];
      const Vec<Dim> wi = s.water_nodes.momentum[i] + dt * s.water_nodes.force[i];
      b += bi + wi;
      b_abs += bi.cwiseAbs() + wi.cwiseAbs();
    }
    for (int d = 0; d < Dim; ++d)
      EXPECT_NEAR(momentum[d], b[d], 1e-12 * b_abs[d])
          << "dt = " << ratio << " tau, component " << d << ", " << stats.iterations << " iterations";
  }
}

// a2. Only the soil particles whose stencils reach a block with coupled nodes add drag terms
// (ConsistentDrag's assembly skips the others). A soil layer across five blocks along x (a block
// is 0.4 m) under water over 0.3 m of it: the particles near the water's edge, in blocks without
// coupled nodes whose stencils reach the next block, must still count. Against the dense solve
// over all particles, within a's bound; the particles' groups given (as the model's step gives
// them) or found by the solve give the same velocities bit for bit.
TYPED_TEST(ConsistentDragTest, SoilAwayFromTheWaterAddsNoTermsAndNoneIsMissed) {
  constexpr int Dim = TypeParam::value;
  const mpi::Comm self(MPI_COMM_SELF);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> factor(0.5, 1.5);
  Scene<Dim> s;
  const double volume = std::pow(s.h / 2, Dim);
  const auto layer = [&](double x_lo, double x_hi, int count, Particles<Dim>& P, double density) {
    for (int p = 0; p < count; ++p) {
      Vec<Dim> x = uniform_vec<Dim>(rng, 0.45, 0.7);
      x[0] = std::uniform_real_distribution<double>(x_lo, x_hi)(rng);
      const double v = volume * factor(rng);
      P.add(x, uniform_vec<Dim>(rng, -1, 1), density * v, v);
      if (&P == &s.soil) s.soil_drag.push_back(kDragCoefficient * v);
    }
  };
  layer(1.02, 1.32, Dim == 2 ? 40 : 120, s.water, kWaterDensity);
  layer(0.05, 1.95, Dim == 2 ? 200 : 600, s.soil, kSoilDensity);
  Vec<Dim> gravity = Vec<Dim>::Zero();
  gravity[Dim - 1] = -9.81;
  s.build(gravity, {}, {});
  std::vector<int> groups;
  BlockGrid<Dim> same_grid(s.h);  // the groups as the model's step finds them (the same blocks)
  touch_blocks(s.water, same_grid);
  touch_blocks(s.soil, same_grid, &groups);
  ASSERT_EQ(same_grid.blocks(), s.grid.blocks());
  const double dt = s.relaxation_time();
  const Velocities<Dim> reference = dense_solve(s, dt);
  const auto numbering = NodeNumbering::own_all(self, s.soil_nodes, s.water_nodes);
  ASSERT_GT(numbering.owned, 10);
  ConsistentDrag<Dim> drag(self);
  drag.solve(s.grid, s.soil, s.soil_drag, s.soil_nodes, s.water_nodes, dt, numbering);
  const Velocities<Dim> found = velocities(s);
  drag.solve(s.grid, s.soil, s.soil_drag, s.soil_nodes, s.water_nodes, dt, numbering, &groups);
  const Velocities<Dim> given = velocities(s);
  const auto all = [](std::size_t) { return true; };
  EXPECT_LT(largest_difference(found, reference, all), 1e-10 * largest(reference, all));
  EXPECT_EQ(largest_difference(found, given, all), 0.0);
}

// c. Co-located species (the same particles, soil and water masses and drag all proportional to
// a per-particle volume), uniform velocities and gravity: m_s,i, m_w,i and d_i are proportional
// to one nodal volume, so the lumped solution is uniform, and a uniform velocity solves the
// consistent system too because D's row sums are d_i. Bound: 1e-10 of the largest velocity, as in
// a; the scaled condition number grows with dt (measured errors: below 1e-12, at dt = 100 tau).
TYPED_TEST(ConsistentDragTest, UniformRelativeVelocityGivesTheLumpedSolution) {
  constexpr int Dim = TypeParam::value;
  const mpi::Comm self(MPI_COMM_SELF);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> factor(0.5, 1.5);
  Scene<Dim> s;
  const Vec<Dim> u_soil = uniform_vec<Dim>(rng, -1, 1), u_water = uniform_vec<Dim>(rng, -1, 1);
  for (int p = 0; p < (Dim == 2 ? 60 : 150); ++p) {
    const Vec<Dim> x = uniform_vec<Dim>(rng, 0.3, 0.6);
    const double v = std::pow(s.h / 2, Dim) * factor(rng);
    s.soil.add(x, u_soil, kSoilDensity * v, v);
    s.water.add(x, u_water, kWaterDensity * v, v);
    s.soil_drag.push_back(kDragCoefficient * v);
  }
  Vec<Dim> gravity = Vec<Dim>::Zero();
  gravity[Dim - 1] = -9.81;
  s.build(gravity, {}, {});
  ConsistentDrag<Dim> drag(self);
  for (double ratio : {1e-2, 1.0, 1e2}) {
    const double dt = ratio * s.relaxation_time();
    const auto numbering = NodeNumbering::own_all(self, s.soil_nodes, s.water_nodes);
    drag.solve(s.grid, s.soil, s.soil_drag, s.soil_nodes, s.water_nodes, dt, numbering);
    const Velocities<Dim> consistent = velocities(s);
    solve_grid_velocities(s.soil_nodes, s.water_nodes, dt, DragScheme::lumped);
    const Velocities<Dim> lumped = velocities(s);
    const auto all = [](std::size_t) { return true; };
    EXPECT_LT(largest_difference(consistent, lumped, all), 1e-10 * largest(lumped, all)) << "dt = " << ratio << " tau";
  }
}

// d. On the test's ranks: every rank holds the whole grid and node fields, but only every
// size-th soil particle's drag terms and a contiguous share of the coupled nodes, numbered in
// slot order: equal shares, or (lopsided) rank 0 owning three quarters of them and the other ranks
// the rest in equal shares. Each rank's owned and uncoupled nodes must get the 1-rank solution
// (computed on MPI_COMM_SELF) and the dense one, within a's bound (the sums over ranks only change
// the order of additions; measured: below 1e-13); the other ranks' nodes stay as they were. The
// Krylov solve holds equal shares of the rows with DragRows::balanced whatever the owners hold,
// the owners' with DragRows::owners, and with DragRows::automatic equal shares where the busiest
// owner holds more than 1.2 times the mean (lopsided over several ranks: 3/4 of the nodes on
// rank 0 is at least 1.5 times the mean), the owners' otherwise.
template <int Dim>
void expect_split_solve_is_the_one_rank_solve(bool lopsided, DragRows rows) {
  const mpi::Comm& comm = environment->comm();
  const mpi::Comm self(MPI_COMM_SELF);
  Scene<Dim> s = irregular_scene<Dim>(5);
  const double dt = 10 * s.relaxation_time();
  const Velocities<Dim> dense = dense_solve(s, dt);

  // The 1-rank solution.
  Scene<Dim> whole = s;
  ConsistentDrag<Dim> one(self);
  one.solve(whole.grid, whole.soil, whole.soil_drag, whole.soil_nodes, whole.water_nodes, dt,
            NodeNumbering::own_all(self, whole.soil_nodes, whole.water_nodes));
  const Velocities<Dim> single = velocities(whole);

  // This rank's soil particles and nodes.
  Particles<Dim> mine;
  std::vector<double> my_drag;
  for (std::size_t p = static_cast<std::size_t>(comm.rank()); p < s.soil.size();
       p += static_cast<std::size_t>(comm.size())) {
    mine.add(s.soil.x[p], s.soil.v[p], s.soil.mass[p], s.soil.volume0[p]);
    my_drag.push_back(s.soil_drag[p]);
  }
  NodeNumbering numbering;
  numbering.global.assign(s.grid.nodes(), -1);
  long coupled = 0;
  for (std::size_t i = 0; i < s.grid.nodes(); ++i)
    if (drag_coupled(s.soil_nodes.mass[i], s.water_nodes.mass[i])) numbering.global[i] = coupled++;
  // Rank r owns nodes start(r) .. start(r + 1) - 1.
  const auto start = [&](long r) {
    if (!lopsided || r == 0 || r == comm.size()) return coupled * r / comm.size();
    const long first = 3 * coupled / 4;
    return first + (coupled - first) * (r - 1) / (comm.size() - 1);
  };
  numbering.first = start(comm.rank());
  numbering.owned = start(comm.rank() + 1) - numbering.first;

  const Vec<Dim> untouched = Vec<Dim>::Constant(12345.0);
  std::fill(s.soil_nodes.velocity.begin(), s.soil_nodes.velocity.end(), untouched);
  std::fill(s.water_nodes.velocity.begin(), s.water_nodes.velocity.end(), untouched);
  ConsistentDrag<Dim> split(comm, "drag_", rows);
  const SolveStats stats = split.solve(s.grid, mine, my_drag, s.soil_nodes, s.water_nodes, dt, numbering);
  EXPECT_EQ(stats.unknowns, 2 * coupled);
  EXPECT_EQ(stats.owned_nodes, numbering.owned);
  const long equal_share = coupled * (comm.rank() + 1) / comm.size() - coupled * comm.rank() / comm.size();
  const bool shares = rows == DragRows::balanced || (rows == DragRows::automatic && lopsided && comm.size() > 1);
  EXPECT_EQ(stats.solved_nodes, shares ? equal_share : numbering.owned);
  const Velocities<Dim> mine_v = velocities(s);

  const auto computed_here = [&](std::size_t i) {
    return numbering.global[i] < 0 || numbering.owns(numbering.global[i]);
  };
  const auto ghost = [&](std::size_t i) { return !computed_here(i); };
  const double scale = largest(dense, [](std::size_t) { return true; });
  EXPECT_LT(largest_difference(mine_v, single, computed_here), 1e-10 * scale);
  EXPECT_LT(largest_difference(mine_v, dense, computed_here), 1e-10 * scale);
  for (std::size_t i = 0; i < s.grid.nodes(); ++i)
    if (ghost(i)) {
      EXPECT_EQ(mine_v.soil[i], untouched) << "slot " << i;
      EXPECT_EQ(mine_v.water[i], untouched) << "slot " << i;
    }
  EXPECT_EQ(comm.sum(static_cast<long long>(numbering.owned)), static_cast<long long>(coupled));
}

TYPED_TEST(ConsistentDragTest, SplitOverRanksGivesTheOneRankSolution) {
  expect_split_solve_is_the_one_rank_solve<TypeParam::value>(false, DragRows::balanced);
  expect_split_solve_is_the_one_rank_solve<TypeParam::value>(false, DragRows::owners);
  expect_split_solve_is_the_one_rank_solve<TypeParam::value>(false, DragRows::automatic);
}

TYPED_TEST(ConsistentDragTest, LopsidedOwnersStillGiveTheOneRankSolution) {
  expect_split_solve_is_the_one_rank_solve<TypeParam::value>(true, DragRows::balanced);
  expect_split_solve_is_the_one_rank_solve<TypeParam::value>(true, DragRows::owners);
  expect_split_solve_is_the_one_rank_solve<TypeParam::value>(true, DragRows::automatic);
}

// d'. own_all on the test's ranks: each rank's coupled nodes get a disjoint range, in rank order.
TYPED_TEST(ConsistentDragTest, OwnAllNumbersEachRanksNodesAfterTheLowerRanks) {
  constexpr int Dim = TypeParam::value;
  const mpi::Comm& comm = environment->comm();
  const Scene<Dim> s = irregular_scene<Dim>(static_cast<unsigned>(20 + comm.rank()));
  const auto numbering = NodeNumbering::own_all(comm, s.soil_nodes, s.water_nodes);
  EXPECT_EQ(numbering.first, static_cast<long>(comm.exclusive_prefix_sum(numbering.owned)));
  long next = numbering.first;
  for (std::size_t i = 0; i < s.grid.nodes(); ++i) {
    if (drag_coupled(s.soil_nodes.mass[i], s.water_nodes.mass[i]))
      EXPECT_EQ(numbering.global[i], next++);
    else
      EXPECT_EQ(numbering.global[i], -1);
  }
  EXPECT_EQ(next, numbering.first + numbering.owned);
}

// e. One CG iteration cannot solve this system: KSP_DIVERGED_ITS becomes a LibraryError that
// names the prefix and the reason.
TYPED_TEST(ConsistentDragTest, ADivergedSolveIsAnErrorNamingThePrefix) {
  constexpr int Dim = TypeParam::value;
  const mpi::Comm self(MPI_COMM_SELF);
  Scene<Dim> s = irregular_scene<Dim>(7);
  ConsistentDrag<Dim> drag(self, "stop_");
  try {
    drag.solve(s.grid, s.soil, s.soil_drag, s.soil_nodes, s.water_nodes, 100 * s.relaxation_time(),
               NodeNumbering::own_all(self, s.soil_nodes, s.water_nodes));
    ADD_FAILURE() << "one iteration was enough";
  } catch (const LibraryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'stop_'"), std::string::npos) << what;
    EXPECT_NE(what.find("DIVERGED_ITS"), std::string::npos) << what;
  }
}

// f. Whole steps of the model with `drag: consistent`: soil and water particles at the same
// places, water moving, soil at rest, no other forces (soft materials, no gravity). One step
// from co-located species gives every particle the closed form's relative velocity
// 1 / (1 + dt / tau_d) (c above: the consistent solution equals the lumped one), the total
// momentum is conserved, and at dt = 100 tau_d the solve stays bounded (1/101).
TYPED_TEST(ConsistentDragTest, ModelStepWithTheConsistentDragRelaxesAsTheClosedForm) {
  constexpr int Dim = TypeParam::value;
  for (double dt_over_tau : {0.5, 100.0}) {
    SimulationSettings<Dim> s;
    s.h = 0.1;
    s.walls.lo = Vec<Dim>::Constant(-100), s.walls.hi = Vec<Dim>::Constant(100);
    for (auto& axis : s.walls.kind) axis = {WallKind::open, WallKind::open};
    s.water.eos.bulk_modulus = 100;
    s.soil.material = HenckyDruckerPrager::from_young(2e3, 0.3, 0.5, 0.0, true);
    s.drag = DragScheme::consistent;
    Simulation<Dim> sim(s, mpi::Comm(MPI_COMM_SELF));
    const int per_axis = 6;
    const double spacing = s.h / 2, volume = std::pow(spacing, Dim);
    int total = 1;
    for (int d = 0; d < Dim; ++d) total *= per_axis;
    Vec<Dim> vw = Vec<Dim>::Zero();
    vw[0] = 1e-3;
    for (int n = 0; n < total; ++n) {
      Vec<Dim> x;
      for (int d = 0, r = n; d < Dim; ++d, r /= per_axis) x[d] = 1.0 + (r % per_axis + 0.5) * spacing;
      sim.soil().add(x, Vec<Dim>::Zero(), s.soil.density * volume, volume);
      sim.water().add(x, vw, s.water.density * volume, volume);
    }
    const double rate = s.soil.drag_coefficient(s.water.density) * (1 / s.soil.density + 1 / s.water.density);
    const Vec<Dim> p0 = sim.soil().momentum() + sim.water().momentum();
    sim.step(dt_over_tau / rate);
    const double expected = 1 / (1 + dt_over_tau);
    for (int p = 0; p < total; ++p)  // -drag_ksp_rtol 1e-14 on a system of condition about 1 + dt/tau
      EXPECT_NEAR((sim.water().v[p][0] - sim.soil().v[p][0]) / vw[0], expected, 1e-10) << "dt/tau " << dt_over_tau;
    EXPECT_LT((sim.soil().momentum() + sim.water().momentum() - p0).norm(), 1e-12 * p0.norm());
    EXPECT_GT(sim.drag_stats().iterations, 0);
  }
}

// g. The domain decomposition over the test's ranks (nothing to decompose on one): a water
// column collapsing towards a slumping sand block, seeded on rank 0 and distributed. After every
// step each particle is on the rank owning its home block (migrate() looks up only the particles
// whose home block changed: one it missed would stay on the wrong rank), and the particle counts
// and masses summed over the ranks are the seeded ones (closed box: none is lost or doubled).
TYPED_TEST(ConsistentDragTest, DecomposedStepsKeepEveryParticleAtItsBlocksOwner) {
  constexpr int Dim = TypeParam::value;
  const mpi::Comm& comm = environment->comm();
  SimulationSettings<Dim> s;
  s.h = 0.1;
  s.gravity[1] = -9.81;
  s.walls.lo = Vec<Dim>::Zero(), s.walls.hi = Vec<Dim>::Constant(2.0);
  s.water.eos.bulk_modulus = 2e4;  // a wave speed of 4.5 m/s: steps of 9 ms, 0.36 s in all
  s.dt_max = 0.1;
  s.soil.material = HenckyDruckerPrager::from_young(1e5, 0.3, 30 * M_PI / 180, 0.0, true);
  Simulation<Dim> sim(s, comm);
  const auto seed = [&](Particles<Dim>& P, double lo, double hi, double height, double density) {
    const double spacing = s.h / 2, volume = std::pow(spacing, Dim);
    Vec<Dim> x;
    const auto fill = [&](auto&& self, int d) -> void {
      if (d == Dim) return P.add(x, Vec<Dim>::Zero(), density * volume, volume);
      const double a = d == 0 ? lo : 0.0, b = d == 0 ? hi : d == 1 ? height : 0.4;
      for (x[d] = a + spacing / 2; x[d] < b; x[d] += spacing) self(self, d + 1);
    };
    if (comm.is_root()) fill(fill, 0);
  };
  seed(sim.water(), 0.0, 0.8, 1.2, s.water.density);
  seed(sim.soil(), 1.2, 1.8, 0.6, s.soil.density);
  sim.distribute();
  const auto totals = [&] {
    return std::array<double, 4>{comm.sum(static_cast<double>(sim.water().size())),
                                 comm.sum(static_cast<double>(sim.soil().size())), comm.sum(sim.water().total_mass()),
                                 comm.sum(sim.soil().total_mass())};
  };
  const auto seeded = totals();
  ASSERT_GT(seeded[0], 0);
  const auto migrated = [&] {
    return sim.decomposition() ? comm.sum(double(sim.decomposition()->stats().migrated)) : 0.0;
  };
  const double distributed = migrated();
  for (int step = 0; step < 40; ++step) {
    sim.step(sim.stable_dt().dt);
    const auto now = totals();
    EXPECT_EQ(now[0], seeded[0]) << "step " << step;
    EXPECT_EQ(now[1], seeded[1]) << "step " << step;
    EXPECT_NEAR(now[2], seeded[2], 1e-12 * seeded[2]) << "step " << step;
    EXPECT_NEAR(now[3], seeded[3], 1e-12 * seeded[3]) << "step " << step;
    const auto* dd = sim.decomposition();
    if (!dd) continue;
    const auto keys = dd->owned_keys();
    const std::set<long long> owned(keys.begin(), keys.end());
    long long misplaced = 0;
    for (const auto* P : {&sim.water(), &sim.soil()})
      for (const auto& x : P->x) misplaced += !owned.count(BlockGrid<Dim>::key(BlockGrid<Dim>::home_block(x, s.h)));
    // Summed over the ranks, so that every rank stops here together (no rank left in a step).
    ASSERT_EQ(comm.sum(static_cast<double>(misplaced)), 0.0) << "step " << step;
  }
  // The steps moved particles between ranks (the water's front crosses the partition).
  if (sim.decomposition()) {
    EXPECT_GT(migrated(), distributed);
  }
}

}  // namespace
}  // namespace suite::mpm2grid
