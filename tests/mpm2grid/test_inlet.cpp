// The water inlet and the outlet record (boundary/inlet.hpp, boundary/outlet_record.hpp) in whole
// steps of the model: the emitted mass follows the prescribed discharge within one particle
// layer, for a constant velocity (Table 3.4's form) and for a hydrograph table; water that
// leaves through the open side is booked so that mass balance closes to round-off; in a
// frictionless channel without gravity the outflow discharge equals the inflow's.
#include <gtest/gtest.h>

#include <cmath>

#include "core/config/config.hpp"
#include "solvers/mpm2grid/boundary/outlet_record.hpp"
#include "solvers/mpm2grid/model/simulation.hpp"
#include "solvers/mpm2grid/scenes/scene.hpp"

namespace suite::mpm2grid {
namespace {

template <class T>
class InletSteps : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(InletSteps, Dims);

constexpr double kDensity = 1000;  // kg/m^3

// A channel along x: inlet on x_low (slip), outlet on x_high (open), slip floor and sides, open top.
// In 3D the channel is `depth` deep along z.
template <int Dim>
SimulationSettings<Dim> channel(double h, double length, double height, double depth, double gravity) {
  SimulationSettings<Dim> s;
  s.h = h;
  s.walls.lo = Vec<Dim>::Zero();
  s.walls.hi = Vec<Dim>::Constant(depth);
  s.walls.hi[0] = length, s.walls.hi[1] = height;
  for (auto& axis : s.walls.kind) axis = {WallKind::slip, WallKind::slip};
  s.walls.kind[0][1] = WallKind::open;
  s.walls.kind[1][1] = WallKind::open;
  s.gravity[1] = -gravity;
  s.water.density = kDensity;
  s.water.eos.bulk_modulus = 2e5;  // sound speed sqrt(7 k / rho) = 37 m/s
  s.dt_max = 1e-3;
  return s;
}

template <int Dim>
InletSettings<Dim> inlet_of(const SimulationSettings<Dim>& s, double spacing, double height, Hydrograph q) {
  InletSettings<Dim> in;
  in.height = height, in.spacing = spacing, in.density = kDensity;
  in.lo = s.walls.lo, in.hi = s.walls.hi;
  in.discharge = std::move(q);
  return in;
}

// Width across the flow: 1 m (per metre) in 2D, the channel's depth in 3D.
template <int Dim>
double width(const SimulationSettings<Dim>& s) {
  double w = 1;
  for (int d = 2; d < Dim; ++d) w *= s.walls.hi[d] - s.walls.lo[d];
  return w;
}

TYPED_TEST(InletSteps, ConstantInflowEmitsRhoVHtWithinOneLayerAndMassBalanceCloses) {
  constexpr int Dim = TypeParam::value;
  // Table 3.4's form, scaled down: height 0.5 m, velocity 2 m/s into a 1.5 m channel under gravity,
  // with an initial pool, so that water also leaves through the outlet (3D on a coarser grid).
  const double h = Dim == 2 ? 0.05 : 0.1, spacing = h / 2, H = 0.5, v = 2.0;
  auto s = channel<Dim>(h, 1.5, 2.0, 0.1, 9.81);
  s.inlet = inlet_of(s, spacing, H, Hydrograph::constant(v * H));
  Simulation<Dim> sim(s);
  // The pool: 0.5 m x 0.25 m of water at x in [0.5, 1).
  {
    Index<Dim> count;
    count[0] = static_cast<int>(std::lround(0.5 / spacing)), count[1] = count[0] / 2;
    for (int d = 2; d < Dim; ++d) count[d] = static_cast<int>(std::lround(0.1 / spacing));
    int total = 1;
    for (int d = 0; d < Dim; ++d) total *= count[d];
    const double volume = std::pow(spacing, Dim);
    for (int n = 0; n < total; ++n) {
      int r = n;
      Vec<Dim> x;
      for (int d = 0; d < Dim; ++d) {
        x[d] = (r % count[d] + 0.5) * spacing;
        r /= count[d];
      }
      x[0] += 0.5;
      sim.water().add(x, Vec<Dim>::Zero(), kDensity * volume, volume);
    }
  }
  const double initial = sim.water().total_mass();
  const auto* inlet = sim.inlet();
  ASSERT_NE(inlet, nullptr);
  EXPECT_EQ(inlet->rows(), static_cast<int>(std::lround(H / spacing)));
  const double layer = kDensity * spacing * H * width(s);
  EXPECT_NEAR(inlet->layer_mass(), layer, 1e-12 * layer);
  double worst_shortfall = 0;
  bool left = false;
  while (sim.time() < 0.6 - 1e-12) {
    sim.step(std::min(sim.stable_dt().dt, 0.6 - sim.time()));
    // The inflow so far, rho q t per metre (times the width in 3D): the emitted mass falls short
    // of it by less than one layer, never exceeds it (a layer is emitted once it has fully entered).
    const double expected = kDensity * v * H * sim.time() * width(s);
    const double shortfall = expected - sim.inflow_mass();
    EXPECT_GE(shortfall, -1e-9 * expected);
    EXPECT_LT(shortfall, layer);
    worst_shortfall = std::max(worst_shortfall, shortfall);
    // Mass balance: what is in the domain plus what left equals what was there plus what came in.
    // Sums of a few thousand particle masses: round-off of N eps relative, 1e-12.
    const double in_domain = sim.water().total_mass(), out = sim.outflow().water_mass;
    EXPECT_NEAR(in_domain + out, initial + sim.inflow_mass(), 1e-12 * (initial + sim.inflow_mass()));
    left = left || out > 0;
  }
  EXPECT_TRUE(left) << "no water reached the outlet: the mass balance was not tested with outflow";
  this->RecordProperty("worst_shortfall_in_layers", std::to_string(worst_shortfall / layer));
}

TYPED_TEST(InletSteps, EmittedLayersCarryTheInletVelocityOnTheSeedingLattice) {
  constexpr int Dim = TypeParam::value;
  // Without gravity the emitted water moves as a rigid slab at v (uniform velocity, J = 1, no
  // pressure), so every emitted particle keeps v and stays on a lattice of spacing s in x.
  const double h = 0.1, spacing = h / 2, H = 0.3, v = 1.5;
  auto s = channel<Dim>(h, 5.0, 1.0, 0.2, 0.0);
  s.inlet = inlet_of(s, spacing, H, Hydrograph::constant(v * H));
  Simulation<Dim> sim(s);
  for (int i = 0; i < 300; ++i) sim.step(1e-3);
  const auto& w = sim.water();
  ASSERT_GT(w.size(), 0u);
  for (std::size_t p = 0; p < w.size(); ++p) {
    // Velocities: round-off of the grid's momentum / mass (1e-12 relative).
    EXPECT_NEAR(w.v[p][0], v, 1e-12 * v);
    EXPECT_NEAR(w.v[p][1], 0.0, 1e-12 * v);
    EXPECT_NEAR(w.J[p], 1.0, 1e-12);
    // x = L - (k + 1/2) s with L = v t: the lattice offset is s/2 + v t mod s, to round-off.
    const double offset = std::fmod(w.x[p][0] - v * sim.time() + 1000 * spacing, spacing);
    EXPECT_NEAR(std::min(std::abs(offset - 0.5 * spacing), spacing - std::abs(offset - 0.5 * spacing)), 0.0, 1e-9);
    EXPECT_LT(w.x[p][1], H);
  }
}

TYPED_TEST(InletSteps, OutflowDischargeEqualsInflowInAFrictionlessChannel) {
  constexpr int Dim = TypeParam::value;
  // The slab of the test above reaches the outlet at t = 1 m / v; from then on the mean outflow
  // discharge over an interval T is q within one layer's volume over T (layers leave whole).
  const double h = 0.1, spacing = h / 2, H = 0.3, v = 2.0, q = v * H, T = 0.5;
  auto s = channel<Dim>(h, 1.0, 1.0, 0.1, 0.0);
  s.inlet = inlet_of(s, spacing, H, Hydrograph::constant(q));
  Simulation<Dim> sim(s);
  OutletRecord record;
  const double dt = 1e-3;
  int samples = 0;
  for (double next = T; next <= 3.0 + 1e-9; next += T) {
    while (sim.time() < next - 1e-9) sim.step(std::min(dt, next - sim.time()));
    const auto Q = record.sample(sim.time(), sim.outflow().water_mass, sim.outflow().soil_mass, kDensity, 2000);
    if (sim.time() > 1.0 / v + T) {
      EXPECT_NEAR(Q.water / width(s), q, spacing * H / T * 1.000001) << "t = " << sim.time();
      ++samples;
    }
    EXPECT_EQ(Q.soil, 0.0);
  }
  EXPECT_GE(samples, 3);
  EXPECT_NEAR(record.peak_water_discharge / width(s), q, spacing * H / T * 1.000001);
}

// The hydrograph-table form, read from a scene: the emitted volume follows the trapezoid
// integral of the table (computed here by hand) within one layer, and the last layer moves at
// q(t) / H.
TEST(InletTable, EmittedVolumeFollowsTheTrapezoidIntegralOfTheTable) {
  const auto cfg = config::Config::from_string(R"(
dimension: 2
grid: {spacing: 0.1 m, particles_per_cell: 2}
domain: {lo: [0, 0], hi: [20, 2]}
walls: {x_low: slip, x_high: open, y_low: slip, y_high: open}
gravity: 9.81 m/s^2
water: {density: 1000 kg/m^3, bulk_modulus: 0.2 MPa, regions: []}
inlet:
  height: 0.5 m
  discharge: {columns: [min, m^2/s], rows: [[0, 0], [0.01, 1.2], [0.02, 0.3], [0.03, 0.3], [0.04, 0]]}
time: {end: 3 s}
)",
                                               "inlet_table.yaml");
  const auto scene = read_scene<2>(cfg);
  ASSERT_TRUE(scene.simulation.inlet.has_value());
  Simulation<2> sim(scene.simulation);
  const double H = 0.5, spacing = 0.05, layer_volume = spacing * H;
  // Rows in minutes: (0 s, 0), (0.6 s, 1.2), (1.2 s, 0.3), (1.8 s, 0.3), (2.4 s, 0) m^2/s.
  const double t[] = {0, 0.6, 1.2, 1.8, 2.4}, q[] = {0, 1.2, 0.3, 0.3, 0};
  auto integral = [&](double x) {  // trapezoid rule on the table, exact for the piecewise-linear q
    double v = 0;
    for (int i = 1; i < 5; ++i) {
      if (x <= t[i - 1]) break;
      const double b = std::min(x, t[i]);
      const double qb = q[i - 1] + (q[i] - q[i - 1]) * (b - t[i - 1]) / (t[i] - t[i - 1]);
      v += 0.5 * (q[i - 1] + qb) * (b - t[i - 1]);
    }
    return v;
  };
  EXPECT_NEAR(integral(2.4), 0.36 + 0.45 + 0.18 + 0.09, 1e-12);
  int emissions = 0;
  for (double at : {0.3, 0.6, 0.9, 1.2, 1.5, 2.0, 2.4, 3.0}) {
    while (sim.time() < at - 1e-12) {
      const std::size_t before = sim.water().size();
      sim.step(std::min(sim.stable_dt().dt, at - sim.time()));
      // A layer emitted in this step leaves the inlet at the velocity q(t) / H of the step's end
      // (H = 10 rows of 0.05 m exactly, so q / H to round-off).
      if (sim.water().size() > before) {
        const double v = scene.simulation.inlet->discharge(sim.time()) / H;
        EXPECT_NEAR(sim.water().v.back()[0], v, 1e-12 * v) << "t = " << sim.time();
        ++emissions;
      }
    }
    const double emitted = sim.inflow_mass() / 1000;
    EXPECT_GE(integral(at) - emitted, -1e-12) << "t = " << at;
    EXPECT_LT(integral(at) - emitted, layer_volume) << "t = " << at;
  }
  EXPECT_EQ(emissions, static_cast<int>(std::floor(integral(2.4) / layer_volume)));
  // After the table's last row the discharge is its last value (0): nothing more comes in.
  EXPECT_NEAR(sim.inflow_mass() / 1000, integral(2.4), layer_volume);
}

}  // namespace
}  // namespace suite::mpm2grid
