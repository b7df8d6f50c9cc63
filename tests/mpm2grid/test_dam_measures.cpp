// The dam outputs (io/dam_measures.hpp): the crest profile of a seeded dam follows its trapezoid
// and reads the dam rather than grains strewn on it, and a dry dam with a strong cohesion that
// stands under gravity erodes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/config/config.hpp"
#include "solvers/mpm2grid/io/dam_measures.hpp"
#include "solvers/mpm2grid/model/simulation.hpp"
#include "solvers/mpm2grid/scenes/scene.hpp"

namespace suite::mpm2grid {
namespace {

// The dam of Table 3.4's examples 1-5 (height 3.75 m, crest 6 m, slopes 0.8333 V/H) at 15 cells per
// height, dry, with the given soil; the scene's gravity of 3 m/s^2 as published.
Scene<2> dry_dam(const std::string& young, const std::string& cohesion) {
  const auto cfg = config::Config::from_string(R"(
dimension: 2
grid: {spacing: 0.25 m, particles_per_cell: 2}
domain: {lo: [0, 0], hi: [32, 12]}
walls: {x_low: slip, x_high: open, y_low: friction, y_high: slip}
wall_friction: 0.7
gravity: 3 m/s^2
soil:
  density: 2200 kg/m^3
  young: )" + young + R"(
  poisson: 0.3
  friction_angle: 35 deg
  cohesion: )" + cohesion + R"(
  regions: [{trapezoid: {toe: 6.75, height: 3.75, crest_width: 6, upstream_slope: 0.8333, downstream_slope: 0.8333}}]
time: {end: 1 s}
)",
                                               "dry_dam.yaml");
  return read_scene<2>(cfg);
}

// The trapezoid's surface height at x (0 outside its footprint).
double surface(const Region& r, double x) {
  const double a = r.toe, b = a + r.height / r.upstream_slope, c = b + r.crest_width,
               d = c + r.height / r.downstream_slope;
  if (x <= a || x >= d) return 0;
  if (x < b) return (x - a) * r.upstream_slope;
  if (x <= c) return r.height;
  return (d - x) * r.downstream_slope;
}

TEST(DamMeasures, CrestProfileOfTheSeededDamFollowsTheTrapezoid) {
  const auto scene = dry_dam("10 MPa", "1 MPa");
  Simulation<2> sim(scene.simulation);
  seed_particles(scene, sim);
  const double h = scene.simulation.h, s = h / scene.particles_per_cell;
  const Region& dam = scene.soil_regions.at(0);
  const auto profile = crest_profile(sim.soil(), 0.0, 0.0, h, s * s / (h * h));
  ASSERT_FALSE(profile.empty());
  for (const auto& c : profile) {
    // A lattice row is seeded where its centre lies below the surface, so each lattice column's
    // soil (its highest centre + s/2) is within s/2 of the surface at its centre; the column of
    // width h holds two of them and reads the mean of their heights.
    const double mean = 0.5 * (surface(dam, c.x - s / 2) + surface(dam, c.x + s / 2));
    EXPECT_LE(std::abs(c.top - mean), s / 2 + 1e-12) << "x = " << c.x;
  }
  // The height 3.75 m is 30 spacings of 0.125 m: the crest's top row reaches it exactly.
  EXPECT_NEAR(crest_height(profile, 0.0), 3.75, 1e-12);
  // At the start every particle is in the dam: nothing eroded. The seeded volume is the
  // trapezoid's area up to lattice quantisation: each lattice row of height s holds the number of
  // centres in [left, right), which differs from (right - left) / s by less than one, so the
  // area differs by less than s^2 per row, H s over the H / s rows.
  EXPECT_EQ(count_within(sim.soil(), scene.soil_regions, s / 2), static_cast<long long>(sim.soil().size()));
  const double seeded = static_cast<double>(sim.soil().size()) * s * s;
  EXPECT_LT(std::abs(seeded - dam.trapezoid_area()), dam.height * s);
}

// Grains strewn on the crest and a one-particle filament three cells tall leave the crest within
// half a cell of the dam's top; a block of soil as dense as the dam lifts it by its height.
TEST(DamMeasures, CrestReadsTheDamNotStrayGrains) {
  const auto scene = dry_dam("10 MPa", "1 MPa");
  Simulation<2> sim(scene.simulation);
  seed_particles(scene, sim);
  const double h = scene.simulation.h, s = h / scene.particles_per_cell, top = 3.75;
  auto& soil = sim.soil();
  const double m = soil.mass[0], v = soil.volume0[0];
  for (int k = 0; k < 12; ++k)  // a grain in each of 12 columns over the crest, some a row higher
    soil.add({11.5 + k * h + s / 2, top + s / 2 + (k % 3 == 0 ? s : 0.0)}, Vec<2>::Zero(), m, v);
  for (int k = 0; k < 6; ++k) soil.add({16.5 + s / 2, top + s / 2 + k * s}, Vec<2>::Zero(), m, v);  // the filament
  const double fill = s * s / (h * h);
  const double strewn = crest_height(crest_profile(soil, 0.0, 0.0, h, fill), 0.0);
  std::printf("crest with strewn grains and a filament: %.4f m (as built %.2f m)\n", strewn, top);
  EXPECT_GE(strewn, top);
  EXPECT_LE(strewn, top + h / 2);
  for (int i = 0; i < 4; ++i)  // a block two cells wide and tall, at the seeding's density
    for (int j = 0; j < 4; ++j) soil.add({14.5 + (i + 0.5) * s, top + (j + 0.5) * s}, Vec<2>::Zero(), m, v);
  EXPECT_NEAR(crest_height(crest_profile(soil, 0.0, 0.0, h, fill), 0.0), top + 2 * h, 1e-12);
}

TEST(DamMeasures, ADryCohesiveDamStandingUnderGravityErodesNothing) {
  // Dry soil (no water: saturation 0, full cohesion) with c0 = 1 MPa, far above the largest
  // stress under its own weight (rho g H = 2200 * 3 * 3.75 = 25 kPa), stays elastic. It starts at
  // its geostatic stresses (docs/mpm2grid.md, "Initial state") and moves only as its slopes
  // readjust (the K0 state leaves out their shear stresses); started stress-free with E = 10 MPa
  // it would settle by about rho g H^2 / (2 E_oed) = 3.5 mm, twice that at the peak of the
  // undamped oscillation. A particle counts as eroded once it has left the dam's section grown
  // by s/2 along x and y, which is at least (s/2) sin(beta) away from the sloping faces (beta the
  // face angle) and s/2 from the crest: a particle that moved less than that cannot have left it.
  const auto scene = dry_dam("10 MPa", "1 MPa");
  Simulation<2> sim(scene.simulation);
  seed_particles(scene, sim);
  const double s = scene.simulation.h / scene.particles_per_cell;
  const auto start = sim.soil().x;
  const long long initial = count_within(sim.soil(), scene.soil_regions, s / 2);
  double largest = 0;
  while (sim.time() < 1.0 - 1e-12) {
    sim.step(std::min(sim.stable_dt().dt, 1.0 - sim.time()));
    // Particle ids are their seeding indices, whatever order the steps put them in.
    for (std::size_t p = 0; p < start.size(); ++p) {
      const auto seeded = static_cast<std::size_t>(sim.soil().id[p]);
      largest = std::max(largest, (sim.soil().x[p] - start[seeded]).norm());
    }
  }
  ASSERT_EQ(sim.soil().size(), start.size());
  const double slope = scene.soil_regions[0].upstream_slope, sin_beta = slope / std::hypot(1.0, slope);
  EXPECT_LT(largest, 0.5 * s * sin_beta) << "the dam moved more than this test's premise allows";
  // Eroded: nothing (every particle is still inside the grown section).
  EXPECT_EQ(initial - count_within(sim.soil(), scene.soil_regions, s / 2), 0);
  // The crest stayed within the same half spacing.
  EXPECT_NEAR(crest_height(crest_profile(sim.soil(), 0.0, 0.0, scene.simulation.h, 0.25), 0.0), 3.75, 0.5 * s);
  RecordProperty("largest_displacement_m", std::to_string(largest));
}

}  // namespace
}  // namespace suite::mpm2grid
