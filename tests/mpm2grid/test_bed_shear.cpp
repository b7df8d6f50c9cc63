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
#include <vector>

#include "solvers/mpm2grid/model/simulation.hpp"
#include "tests/mpm2grid/channel.hpp"

namespace suite::mpm2grid {
namespace {

using namespace channel;

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

TEST(BedShear, CohesiveBedErodesAtTheExcessStressRate) {
  for (double slope : {0.02, 0.03, 0.04}) {
    Channel c;
    c.slope = slope;
    c.soil = 0.15;
    c.kd = 4e-3;  // m^3/(N s): an erodible test soil, two to seven layers of 1 cm in the run
    c.tau_c = 2;
    expect_erodes_at_the_law(c, erode_cohesive_bed(c, 1.5), "explicit forces");
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
