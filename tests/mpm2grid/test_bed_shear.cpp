// The bed-shear closure and the excess-stress erosion (erosion/bed_shear.hpp; issue 27, rungs 2a
// and 2b of its validation ladder), on open-channel flow down a slope S = sin(theta): gravity
// tilted by theta against the grid, the floor the bed, an inlet at x = 0 feeding q per metre at
// Manning's normal depth, the channel's end open. In steady uniform flow gravity's pull along the
// bed balances the bed shear, tau = rho g d S (wide channel: the hydraulic radius is the depth),
// and Manning's law, tau = rho g0 n^2 u^2 / d^(1/3), then gives the normal flow
// q = d_n^(5/3) sqrt(S g / g0) / n; the channel starts in it, fed at d_n = 0.12 m.
//   2a. Rigid rough bed: after 2 s of flow from the normal state the flow in the middle of the
//       channel is steady and uniform at three resolutions (3, 6 and 12 cells over the depth):
//       the closure's shear equals rho g d S within 5% (the bound; it holds only if the
//       friction takes out of the water exactly the shear it reports), and depth and velocity
//       equal Manning's normal values within 5%.
//   2b. Cohesive bed: a soil layer under the flow erodes at kd (tau - tau_c): the bed's lowering in
//       the middle of the channel (its surface, measured from the bed particles, plus the part of
//       the top layer eroded so far) equals the integral of kd (tau - tau_c) over the closure's
//       shear at every step within 2% (the issue asks 10%; both sides take the same shear, so what
//       is left is the top-layer rule on a bed that lowers unevenly across columns, measured
//       0.03-0.3% once at least two layers came off), at three slopes (mean shear 5.7 to 11.4 Pa);
//       with tau_c above the flow's shear nothing erodes at all.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <unordered_set>
#include <vector>

#include "solvers/mpm2grid/model/simulation.hpp"

namespace suite::mpm2grid {
namespace {

constexpr double kG = 9.81, kG0 = 9.80665, kRho = 1000;

struct Channel {
  double h = 0.02;          // grid spacing, m
  double slope = 0.02;      // S = sin(theta)
  double manning_n = 0.02;  // s/m^(1/3)
  // The normal depth, m: a whole number of particle rows at every resolution below, so that
  // the inlet's section (whole rows) carries the normal flow.
  double depth = 0.12;
  double length = 2.0;      // m
  double soil = 0;          // thickness of a soil layer on the floor, m (0: the rigid floor is the bed)
  double kd = 0, tau_c = 0;
  bool free_field = false;  // the free water on a field of its own (SimulationSettings::free_water_field)

  // The discharge per metre of the normal flow, m^2/s.
  double q() const { return std::pow(depth, 5.0 / 3.0) * std::sqrt(slope * kG / kG0) / manning_n; }
};

// The channel in 2D, or in 3D over `width` (m) across z between slip walls.
template <int Dim>
SimulationSettings<Dim> settings(const Channel& c, double width = 0) {
  SimulationSettings<Dim> s;
  s.h = c.h;
  s.walls.lo.setZero();
  s.walls.hi[0] = c.length, s.walls.hi[1] = 1.0;
  if constexpr (Dim == 3) s.walls.hi[2] = width;
  s.walls.kind[0] = {WallKind::slip, WallKind::open};
  // The soil layer held by a sticky floor (the bed erodes; it does not slide).
  s.walls.kind[1] = {c.soil > 0 ? WallKind::sticky : WallKind::slip, WallKind::slip};
  if constexpr (Dim == 3) s.walls.kind[2] = {WallKind::slip, WallKind::slip};
  s.walls.friction = 0.7;
  s.gravity.setZero();
  s.gravity[0] = kG * c.slope, s.gravity[1] = -kG * std::sqrt(1 - c.slope * c.slope);
  s.water.density = kRho;
  s.water.eos.bulk_modulus = 5e4;  // sound speed 18.7 m/s, about 10 times the flow
  s.soil.density = 2000;
  s.soil.porosity = 0.4;
  s.soil.conductivity = 1e-3;
  s.soil.material = HenckyDruckerPrager::from_young(2e6, 0.3, 0.6, 2e4, true);
  s.bed_shear.manning_n = c.manning_n;
  s.free_water_field = c.free_field;
  if (c.soil > 0) s.erosion = {.on = true, .kd = c.kd, .tau_c = c.tau_c, .settling_velocity = 0.01};
  s.dt_max = 1e-3;
  InletSettings<Dim> in;
  in.height = c.depth;
  in.spacing = c.h / 2;
  in.density = kRho;
  in.lo = s.walls.lo, in.hi = s.walls.hi;
  in.lo[1] = c.soil;  // the inlet's section starts on the bed
  in.discharge = Hydrograph::constant(c.q());
  s.inlet = in;
  return s;
}

// The channel at its normal state: the soil layer (saturated, a water particle in its pores) and
// the water above it at the inlet's depth and velocity, hydrostatic normal to the bed.
template <int Dim>
void seed(const Channel& c, Simulation<Dim>& sim) {
  const double s = c.h / 2, volume = std::pow(s, Dim), cos_theta = std::sqrt(1 - c.slope * c.slope);
  const auto* inlet = sim.inlet();
  const double top = c.soil + inlet->section_height(), speed = inlet->velocity(0);
  const auto& eos = sim.settings().water.eos;
  const double width = Dim == 3 ? sim.settings().walls.hi[Dim - 1] : s;  // one layer in 2D
  for (double z = s / 2; z < width; z += s)
    for (double y = s / 2; y < top; y += s)
      for (double x = s / 2; x < c.length; x += s) {
        const double p = kRho * kG * cos_theta * (top - y);
        const double J = std::pow(1 + p / eos.bulk_modulus, -1 / eos.gamma);
        const bool soil = y < c.soil;
        Vec<Dim> at = Vec<Dim>::Zero(), v = Vec<Dim>::Zero();
        at[0] = x, at[1] = y;
        if constexpr (Dim == 3) at[2] = z;
        if (!soil) v[0] = speed;
        if (soil) sim.soil().add(at, Vec<Dim>::Zero(), sim.settings().soil.density * volume, volume);
        sim.water().add(at, v, kRho * volume, volume / J);
        sim.water().J.back() = J;
      }
}

// The columns whose centres lie in the channel's middle, [0.4, 0.8] of its length.
template <int Dim>
std::vector<std::size_t> middle(const Channel& c, const BedShear<Dim>& b) {
  std::vector<std::size_t> m;
  for (std::size_t k = 0; k < b.columns().size(); ++k) {
    const double x = b.column_centre(k)[0];
    if (x > 0.4 * c.length && x < 0.8 * c.length) m.push_back(k);
  }
  return m;
}

struct Flow {
  double depth = 0, speed = 0, shear = 0;
};

template <int Dim>
Flow mean_flow(const Channel& c, const BedShear<Dim>& b) {
  Flow f;
  const auto cols = middle(c, b);
  for (auto k : cols) {
    const auto& col = b.columns()[k];
    f.depth += col.depth, f.speed += col.velocity.norm(), f.shear += col.shear;
  }
  const auto n = static_cast<double>(cols.size());
  return {f.depth / n, f.speed / n, f.shear / n};
}

// 2 s of the channel from its normal state: the flow in the middle then and at 1.5 s.
template <int Dim>
std::array<Flow, 2> run_channel(const Channel& c, double width = 0) {
  Simulation<Dim> sim(settings<Dim>(c, width));
  seed(c, sim);
  Flow before;
  while (sim.time() < 2.0) {
    sim.step(std::min(sim.stable_dt().dt, 2.0 - sim.time()));
    if (before.depth == 0 && sim.time() >= 1.5) before = mean_flow(c, *sim.bed_shear());
  }
  return {mean_flow(c, *sim.bed_shear()), before};
}

// Rung 2a's checks of the flow at 2 s (`f`) and at 1.5 s.
void expect_normal_flow(const Channel& c, const Flow& f, const Flow& before, const char* what) {
  const double dn = c.depth, un = c.q() / dn, gravity_pull = kRho * kG * f.depth * c.slope;
  std::printf("%s, h = %g m: depth %.4f m (normal %.4f), speed %.4f m/s (%.4f; at 1.5 s %.4f), shear %.3f Pa, "
              "rho g d S %.3f Pa\n",
              what, c.h, f.depth, dn, f.speed, un, before.speed, f.shear, gravity_pull);
  SCOPED_TRACE(::testing::Message() << what << ", h = " << c.h);
  EXPECT_NEAR(f.shear / gravity_pull, 1.0, 0.05);
  EXPECT_NEAR(f.depth / dn, 1.0, 0.05);
  EXPECT_NEAR(f.speed / un, 1.0, 0.05);
  // Steady: over the last half second the speed changed by less than a tenth of what gravity's pull
  // along the bed alone would add (g S 0.5 s; measured under 4% of it).
  EXPECT_LT(std::abs(f.speed - before.speed), 0.1 * kG * c.slope * 0.5);
}

TEST(BedShear, UniformFlowDownARoughInclineBalancesGravity) {
  for (double h : {0.04, 0.02, 0.01}) {
    Channel c;
    c.h = h;
    const auto [f, before] = run_channel<2>(c);
    expect_normal_flow(c, f, before, "2D");
  }
}

// The same in 3D (columns over x and z), 4 cells across between slip walls.
TEST(BedShear, UniformFlowDownARoughInclineIn3D) {
  Channel c;
  c.h = 0.04;
  const auto [f, before] = run_channel<3>(c, 4 * c.h);
  expect_normal_flow(c, f, before, "3D");
}

// The same flow over a saturated soil layer that does not erode (tau_c far above the flow's
// shear), with the free water on its own field (coupling/free_water.hpp): the drag locks only the
// pore water to the soil, and the free water slides along the soil's surface, braked by the
// closure alone. The flow then is Manning's: depth and speed within 5% at each resolution
// (measured -3.4 / -0.9 / 0.0% and +2.5 / +0.8 / -0.0% at h = 0.04 / 0.02 / 0.01 m). The closure's
// shear exceeds rho g d S by 10.2 / 2.9 / -0.04%: the contact's free water rests on the soil within
// a fraction of a cell (its kTouching), which the resolution sets; the bound is 12% and the excess
// must fall as h falls. With the free water in the pore water's field (the old interface) the flow
// crawled: speed 0.578 / 0.973 / 1.133 m/s against 1.721, shear 2.1 / 6.6 / 9.2 Pa against 50.0 /
// 36.9 / 33.3 Pa.
TEST(BedShear, UniformFlowOverAFirmSoilBed) {
  double excess_before = 1;
  for (double h : {0.04, 0.02, 0.01}) {
    Channel c;
    c.h = h;
    c.soil = 0.12;
    c.kd = 1e-3;
    c.tau_c = 1000;
    c.free_field = true;
    const auto [f, before] = run_channel<2>(c);
    const double dn = c.depth, un = c.q() / dn, gravity_pull = kRho * kG * f.depth * c.slope;
    std::printf(
        "over a soil bed, h = %g m: depth %.4f m (normal %.4f), speed %.4f m/s (%.4f; at 1.5 s %.4f), "
        "shear %.3f Pa, rho g d S %.3f Pa\n",
        c.h, f.depth, dn, f.speed, un, before.speed, f.shear, gravity_pull);
    SCOPED_TRACE(::testing::Message() << "h = " << c.h);
    EXPECT_NEAR(f.depth / dn, 1.0, 0.05);
    EXPECT_NEAR(f.speed / un, 1.0, 0.05);
    EXPECT_LT(std::abs(f.speed - before.speed), 0.1 * kG * c.slope * 0.5);
    const double excess = f.shear / gravity_pull - 1;
    EXPECT_LT(std::abs(excess), 0.12);
    EXPECT_LT(std::abs(excess), std::abs(excess_before));
    excess_before = excess;
  }
}

// The same channel with the free-water field over the rigid floor (no soil: every water particle
// is free water, nothing to touch): the rung 2a flow as without the field (measured at h = 0.04
// m: speed 1.700 against Manning's 1.721, shear 23.0 against rho g d S 23.5 Pa).
TEST(BedShear, FreeWaterFieldOverTheRigidBedIsUnchanged) {
  Channel c;
  c.h = 0.04;
  c.free_field = true;
  const auto [f, before] = run_channel<2>(c);
  expect_normal_flow(c, f, before, "free-water field, rigid bed");
}

// The bed's lowering in the middle columns (m) from its seeded surface: the drop of the surface
// (the highest top of the column's bed particles) plus the eroded depth of the top layer's
// particles (their mean per column), read from the particles as they are.
double lowering(const Channel& c, const Simulation<2>& sim) {
  const auto& b = *sim.bed_shear();
  const auto& soil = sim.soil();
  const std::size_t n = b.columns().size();
  std::vector<double> bed(n, 0.0), partial(n, 0.0), exposed(n, 0.0);
  for (std::size_t p = 0; p < soil.size(); ++p)
    if (!b.suspended(soil, p)) {
      double& top = bed[b.column_of(soil.x[p])];
      top = std::max(top, soil.x[p][1] + b.side(soil, p) / 2);
    }
  for (std::size_t p = 0; p < soil.size(); ++p) {
    const std::size_t k = b.column_of(soil.x[p]);
    if (b.suspended(soil, p) || soil.x[p][1] + b.side(soil, p) < bed[k]) continue;
    partial[k] += soil.eroded[p], exposed[k] += 1;
  }
  double sum = 0;
  const auto cols = middle(c, b);
  for (auto k : cols) sum += c.soil - bed[k] + (exposed[k] > 0 ? partial[k] / exposed[k] : 0.0);
  return sum / static_cast<double>(cols.size());
}

TEST(BedShear, CohesiveBedErodesAtTheExcessStressRate) {
  for (double slope : {0.02, 0.03, 0.04}) {
    Channel c;
    c.slope = slope;
    c.soil = 0.15;
    c.kd = 4e-3;  // m^3/(N s): an erodible test soil, two to seven layers of 1 cm in the run
    c.tau_c = 2;
    Simulation<2> sim(settings<2>(c));
    seed(c, sim);
    double expected = 0, tau_mean = 0, expected_volume = 0, deposited = 0;
    long steps = 0;
    const auto cols = [&] { return middle(c, *sim.bed_shear()); };
    std::unordered_set<long long> detached;  // the ids of the suspended particles before the step
    while (sim.time() < 1.5) {
      const double dt = std::min(sim.stable_dt().dt, 1.5 - sim.time());
      sim.step(dt);
      const auto& b = *sim.bed_shear();
      // Detached particles that settled back on the bed count as bed soil again.
      const auto& soil = sim.soil();
      std::unordered_set<long long> now;
      for (std::size_t p = 0; p < soil.size(); ++p) {
        if (b.suspended(soil, p))
          now.insert(soil.id[p]);
        else if (detached.count(soil.id[p]))
          deposited += std::pow(b.side(soil, p), 2);
      }
      detached.swap(now);
      // The volume every column with a top layer under an eroding flow lost (per metre).
      for (const auto& col : b.columns())
        if (col.depth > 0 && col.top_layer > 0 && col.shear > c.tau_c)
          expected_volume += dt * c.kd * (col.shear - c.tau_c) * col.secant * c.h;
      // The rate this step's erosion used, in the middle columns.
      double rate = 0, tau = 0;
      for (auto k : cols()) {
        const auto& col = b.columns()[k];
        rate += col.depth > 0 ? c.kd * std::max(0.0, col.shear - c.tau_c) * col.secant : 0.0;
        tau += col.shear;
      }
      expected += dt * rate / static_cast<double>(cols().size());
      tau_mean += tau / static_cast<double>(cols().size()), ++steps;
    }
    const double measured = lowering(c, sim);
    SCOPED_TRACE(::testing::Message() << "S = " << slope << ": mean shear " << tau_mean / steps << " Pa, lowering "
                                      << measured << " m, kd (tau - tau_c) integrated " << expected << " m");
    std::printf("S = %g: mean shear %.2f Pa, lowering %.5f m, kd (tau - tau_c) integrated %.5f m\n", slope,
                tau_mean / static_cast<double>(steps), measured, expected);
    EXPECT_GT(expected, c.h);  // at least two layers came off
    EXPECT_NEAR(measured / expected, 1.0, 0.02);
    // The whole bed: what the erosion took (the detached particles whole, the others' eroded
    // depth, with the particles that left through the outlet) is the columns' kd (tau - tau_c)
    // integrated over the bed less the deposits, to the depth a particle overshoots when it is
    // detached (at most one step's, dt kd tau < 1e-5 m of a 1 cm particle: 0.1%).
    double taken = sim.outflow().shear_eroded_volume;
    for (std::size_t p = 0; p < sim.soil().size(); ++p) taken += sim.bed_shear()->eroded_volume(sim.soil(), p);
    std::printf("S = %g: eroded volume %.6f m^2, columns' kd (tau - tau_c) integrated %.6f m^2, deposited %.6f m^2\n",
                slope, taken, expected_volume, deposited);
    EXPECT_NEAR(taken / (expected_volume - deposited), 1.0, 0.002);
    // The gross counter is that integral itself (summed per step first): equal to round-off.
    EXPECT_NEAR(sim.outflow().law_eroded_volume / expected_volume, 1.0, 1e-9);
    EXPECT_GT(sim.outflow().law_eroded_volume, 0.0);
  }
}

TEST(BedShear, NothingErodesBelowTheCriticalStress) {
  Channel c;
  c.soil = 0.15;
  c.kd = 3e-3;
  c.tau_c = 1000;
  Simulation<2> sim(settings<2>(c));
  seed(c, sim);
  while (sim.time() < 0.5) sim.step(std::min(sim.stable_dt().dt, 0.5 - sim.time()));
  EXPECT_GT(sim.bed_shear()->largest_shear(), 5.0);
  for (std::size_t p = 0; p < sim.soil().size(); ++p) ASSERT_EQ(sim.soil().eroded[p], 0.0) << "particle " << p;
  EXPECT_EQ(sim.outflow().law_eroded_volume, 0.0);
}

}  // namespace
}  // namespace suite::mpm2grid
