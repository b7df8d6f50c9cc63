// The walls (boundary/walls.hpp, boundary/wall_fold.hpp) against exact statements:
//   - the folded grid next to a slip wall represents a velocity field whose normal component is
//     odd and tangential components even about the wall (a sticky wall: all odd) exactly: G2P of
//     v = (c + b y, a y) on a slip floor gives every particle within two cells of it that v, as
//     one far from any wall gets it (the cubic B-splines reproduce linear fields);
//   - the fold moves the beyond nodes' sums to their mirrors without losing any: the grid's mass
//     and tangential momentum equal the particles', to round-off;
//   - a rigid block sliding on a friction floor decelerates at mu g (Coulomb), and on a slip floor
//     keeps its momentum along the floor to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "solvers/mpm2grid/boundary/wall_fold.hpp"
#include "solvers/mpm2grid/model/simulation.hpp"
#include "solvers/mpm2grid/transfer/apic.hpp"

namespace suite::mpm2grid {
namespace {

constexpr double kH = 0.1;

// Walls on every side of [0, 1]^Dim, of `floor` on y_low and open elsewhere.
template <int Dim>
Walls<Dim> box(WallKind floor) {
  Walls<Dim> w;
  w.lo = Vec<Dim>::Zero(), w.hi = Vec<Dim>::Ones();
  for (auto& axis : w.kind) axis = {WallKind::open, WallKind::open};
  w.kind[1][0] = floor;
  return w;
}

// Particles at random places within two cells of the floor (y in [0, 2h)), and in the middle.
template <int Dim>
Particles<Dim> near_floor(int count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.3, 0.7), y(0.0, 2 * kH);
  Particles<Dim> P;
  for (int n = 0; n < count; ++n) {
    Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) x[d] = u(rng);
    x[1] = n % 4 == 3 ? 0.5 : y(rng);
    P.add(x, Vec<Dim>::Zero(), 1.0 + 0.1 * (n % 5), 1e-3);
  }
  return P;
}

template <int Dim>
void check_mirrored_fields(WallKind floor) {
  const Walls<Dim> walls = box<Dim>(floor);
  const WallFold<Dim> fold(walls, kH, false);
  auto P = near_floor<Dim>(200);
  BlockGrid<Dim> grid(kH);
  touch_blocks(P, grid);
  NodeFields<Dim> nodes;
  nodes.reset(grid.nodes());
  // The field's odd and even parts about y = 0: slip: v_y = a y odd, v_x = c + b y even only
  // for b = 0 (a shear b y is odd), so slip takes (c, a y) and sticky (b y, a y).
  const double a = 0.7, b = floor == WallKind::sticky ? -1.3 : 0.0, c = floor == WallKind::sticky ? 0.0 : 0.4;
  const auto field = [&](const Vec<Dim>& x) {
    Vec<Dim> v = Vec<Dim>::Zero();
    v[0] = c + b * x[1];
    v[1] = a * x[1];
    return v;
  };
  for (long i = 0; i < static_cast<long>(grid.nodes()); ++i)
    nodes.velocity[static_cast<std::size_t>(i)] = field(grid.position(i));
  // The nodes beyond the floor hold garbage that the mirror must replace.
  for (long i = 0; i < static_cast<long>(grid.nodes()); ++i)
    if (grid.node_of(i)[1] < 0) nodes.velocity[static_cast<std::size_t>(i)] = Vec<Dim>::Constant(1e3);
  std::vector<Mat<Dim>> grad_v;
  grid_to_particles(P, grid, nodes, grad_v, nullptr, nullptr, &fold);
  Mat<Dim> grad = Mat<Dim>::Zero();
  grad(0, 1) = b, grad(1, 1) = a;
  for (std::size_t p = 0; p < P.size(); ++p) {
    EXPECT_LT((P.v[p] - field(P.x[p])).norm(), 1e-13) << "particle at y = " << P.x[p][1];
    EXPECT_LT((grad_v[p] - grad).norm(), 1e-12) << "particle at y = " << P.x[p][1];
  }
}

TEST(WallFold, MirroredGridReadsOddNormalAndEvenTangentialFieldsExactly) {
  check_mirrored_fields<2>(WallKind::slip);
  check_mirrored_fields<3>(WallKind::slip);
  check_mirrored_fields<2>(WallKind::sticky);
  check_mirrored_fields<3>(WallKind::sticky);
}

template <int Dim>
void check_fold_keeps_sums() {
  const Walls<Dim> walls = box<Dim>(WallKind::slip);
  const WallFold<Dim> fold(walls, kH, false);
  auto P = near_floor<Dim>(200);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (std::size_t p = 0; p < P.size(); ++p)
    for (int d = 0; d < Dim; ++d) {
      P.v[p][d] = u(rng);
      for (int e = 0; e < Dim; ++e) P.C[p](d, e) = u(rng);
    }
  BlockGrid<Dim> grid(kH);
  touch_blocks(P, grid);
  NodeFields<Dim> nodes;
  nodes.reset(grid.nodes());
  particles_to_grid(P, {.walls = &fold}, grid, nodes);
  double mass = 0, grid_mass = 0, beyond = 0;
  Vec<Dim> momentum = Vec<Dim>::Zero(), grid_momentum = Vec<Dim>::Zero();
  for (std::size_t p = 0; p < P.size(); ++p) mass += P.mass[p], momentum += P.mass[p] * P.v[p];
  for (long i = 0; i < static_cast<long>(grid.nodes()); ++i) {
    const auto k = static_cast<std::size_t>(i);
    grid_mass += nodes.mass[k], grid_momentum += nodes.momentum[k];
    if (grid.node_of(i)[1] < 0) beyond += std::abs(nodes.mass[k]) + nodes.momentum[k].norm();
  }
  EXPECT_EQ(beyond, 0.0) << "the nodes beyond the floor are left empty";
  EXPECT_NEAR(grid_mass, mass, 1e-13 * mass);
  for (int d = 0; d < Dim; ++d) {
    if (d == 1) continue;  // the floor's normal
    EXPECT_NEAR(grid_momentum[d], momentum[d], 1e-13 * mass) << "tangential axis " << d;
  }
}

TEST(WallFold, FoldKeepsMassAndTangentialMomentum) {
  check_fold_keeps_sums<2>();
  check_fold_keeps_sums<3>();
}

// A stiff, strongly cohesive soil block (0.2 x 0.1 m) set sliding at 1 m/s on a floor under
// gravity: its mean velocity over time, and the fitted slope over 0.02-0.15 s (after the
// first elastic transients; the block stops at v0 / (mu g) >= 0.2 s).
struct Slide {
  double deceleration = 0, first = 0, last = 0;
};

Slide slide(WallKind floor, double mu) {
  SimulationSettings<2> s;
  s.h = 0.02;
  s.walls.lo = Vec<2>(0, 0), s.walls.hi = Vec<2>(4, 1);
  s.walls.kind[0] = {WallKind::open, WallKind::open};
  s.walls.kind[1] = {floor, WallKind::open};
  s.walls.friction = mu;
  s.gravity[1] = -9.81;
  s.soil.material = HenckyDruckerPrager::from_young(5e6, 0.3, 0.5, 1e6, true);
  s.buoyancy = false;
  Simulation<2> sim(s);
  const double spacing = s.h / 2;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 10; ++j)
      sim.soil().add(Vec<2>(0.5 + (i + 0.5) * spacing, (j + 0.5) * spacing), Vec<2>(1.0, 0.0),
                     s.soil.density * spacing * spacing, spacing * spacing);
  const auto mean_velocity = [&] {
    double m = 0, p = 0;
    for (std::size_t q = 0; q < sim.soil().size(); ++q)
      m += sim.soil().mass[q], p += sim.soil().mass[q] * sim.soil().v[q][0];
    return p / m;
  };
  Slide r;
  r.first = mean_velocity();
  double st = 0, sv = 0, stt = 0, stv = 0;
  int n = 0;
  while (sim.time() < 0.15) {
    sim.step(sim.stable_dt().dt);
    const double t = sim.time(), v = mean_velocity();
    if (t > 0.02) st += t, sv += v, stt += t * t, stv += t * v, ++n;
  }
  r.last = mean_velocity();
  r.deceleration = -(n * stv - st * sv) / (n * stt - st * st);
  return r;
}

TEST(Walls, FrictionFloorDeceleratesASlidingBlockAtMuG) {
  for (const double mu : {0.2, 0.5}) {
    const Slide r = slide(WallKind::friction, mu);
    std::printf("friction floor, mu = %.1f: deceleration %.4f m/s^2 (mu g = %.4f)\n", mu, r.deceleration, mu * 9.81);
    // 1% (issue 26's bound): the measured 0.1-0.2% is the elastic block's normal force ringing
    // about m g.
    EXPECT_NEAR(r.deceleration, mu * 9.81, 0.01 * mu * 9.81);
  }
  // A slip floor takes nothing along x (the fold keeps the tangential momentum).
  const Slide r = slide(WallKind::slip, 0.5);
  std::printf("slip floor: mean velocity %.15f -> %.15f m/s\n", r.first, r.last);
  EXPECT_NEAR(r.last, r.first, 1e-10);
}

}  // namespace
}  // namespace suite::mpm2grid
