// Scene seeding (scenes/scene.hpp): a soil region with `saturated: true` starts with its pores
// full of water, one water particle per soil particle (at the water's own density: without
// mixture: true the water does not see the solid's volume), so that the soil's saturation seen from the
// water grid is 1 inside the region and its cohesion c0 (1 - S) is 0.
#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>
#include <string>

#include "core/config/config.hpp"
#include "solvers/mpm2grid/model/simulation.hpp"
#include "solvers/mpm2grid/scenes/memory_estimate.hpp"
#include "solvers/mpm2grid/scenes/scene.hpp"

namespace suite::mpm2grid {
namespace {

// Two soil blocks side by side on the floor, the left one saturated, the right one dry, 10 cm
// apart (more than the 2h reach of a cubic B-spline stencil on each side); `mixture` adds
// mixture: true and a surcharge of 4 kPa on the left block.
Scene<2> two_blocks(bool mixture = false) {
  std::string yaml = R"(
dimension: 2
grid: {spacing: 10 mm, particles_per_cell: 2}
domain: {lo: [0, 0], hi: [0.8, 0.4]}
walls: {x_low: slip, x_high: slip, y_low: friction, y_high: open}
water: {density: 1000 kg/m^3, bulk_modulus: 57 kPa, regions: []}
soil:
  density: 1800 kg/m^3
  young: 2 MPa
  friction_angle: 30 deg
  cohesion: 1 kPa
  porosity: 0.4
  regions:
    - box: {lo: [0, 0], hi: [0.2, 0.2]}
      saturated: true
    - box: {lo: [0.3, 0], hi: [0.5, 0.2]}
time: {end: 1 s}
)";
  if (mixture) {
    yaml += "mixture: true\n";
    yaml.replace(yaml.find("saturated: true"), 15, "saturated: true\n      surcharge: 4 kPa");
  }
  return read_scene<2>(config::Config::from_string(yaml, "two_blocks.yaml"));
}

TEST(SceneSeeding, ASaturatedSoilRegionGetsOnePoreWaterParticlePerSoilParticle) {
  const auto scene = two_blocks();
  ASSERT_TRUE(scene.soil_regions.at(0).saturated);
  ASSERT_FALSE(scene.soil_regions.at(1).saturated);
  Simulation<2> sim(scene.simulation);
  seed_particles(scene, sim);
  const auto& soil = sim.soil();
  const auto& water = sim.water();
  // 0.2 m x 0.2 m at a spacing of 5 mm: 1600 particles per block; water only in the left one.
  ASSERT_EQ(soil.size(), 3200u);
  ASSERT_EQ(water.size(), 1600u);
  const double volume = 0.005 * 0.005;
  std::size_t w = 0;
  for (std::size_t p = 0; p < soil.size(); ++p) {
    if (!scene.soil_regions[0].contains<2>(soil.x[p])) continue;
    ASSERT_LT(w, water.size());
    EXPECT_EQ(water.x[w], soil.x[p]) << "pore water seeded at its soil particle's point";
    EXPECT_DOUBLE_EQ(water.mass[w], 1000.0 * volume);
    // At the hydrostatic pressure under the block's top (0.2 m; docs/mpm2grid.md, "Initial
    // state"), filling its lattice cell there: volume0 J = the lattice volume.
    const double p_w = 1000.0 * 9.81 * (0.2 - water.x[w][1]);
    EXPECT_NEAR(scene.simulation.water.eos.pressure(water.J[w]), p_w, 1e-9 * p_w + 1e-9);
    EXPECT_DOUBLE_EQ(water.volume0[w] * water.J[w], volume);
    ++w;
  }
  EXPECT_EQ(w, water.size());
}

// In the mixture the pore water fills the pores only (mass n rho_w V, volume n V), and the
// surcharge loads the region's top lattice row only, s * 4 kPa per particle (N/m in 2D), down.
TEST(SceneSeeding, TheMixtureSeedsPoreWaterInThePoresAndASurchargeLoadsTheTopRow) {
  const auto scene = two_blocks(true);
  ASSERT_TRUE(scene.simulation.mixture);
  Simulation<2> sim(scene.simulation);
  seed_particles(scene, sim);
  const auto& soil = sim.soil();
  const auto& water = sim.water();
  const double s = 0.005, volume = s * s;
  ASSERT_EQ(water.size(), 1600u);
  for (std::size_t w = 0; w < water.size(); ++w) {
    EXPECT_DOUBLE_EQ(water.mass[w], 0.4 * 1000.0 * volume);
    EXPECT_DOUBLE_EQ(water.volume0[w] * water.J[w], 0.4 * volume);  // at its hydrostatic J
  }
  int loaded = 0;
  for (std::size_t p = 0; p < soil.size(); ++p) {
    const bool top = soil.x[p][0] < 0.2 && soil.x[p][1] > 0.2 - s;
    EXPECT_EQ(soil.load[p], top ? Vec<2>(0, -4000 * s) : Vec<2>::Zero()) << soil.x[p].transpose();
    loaded += top;
  }
  EXPECT_EQ(loaded, 40);  // 0.2 m at 5 mm
}

TEST(SceneSeeding, PoreWaterSaturatesTheSoilAndRemovesItsCohesion) {
  const auto scene = two_blocks();
  Simulation<2> sim(scene.simulation);
  seed_particles(scene, sim);
  sim.step(sim.stable_dt().dt);  // the saturation is computed at the end of a step
  const auto& soil = sim.soil();
  const double h = scene.simulation.h;
  int inner = 0;
  for (std::size_t p = 0; p < soil.size(); ++p) {
    const auto& x = soil.x[p];
    const double S = soil.saturation[p];
    if (x[0] > 0.3) {
      EXPECT_EQ(S, 0.0) << "the dry block sees no water";
      continue;
    }
    // A particle's saturation reads the nodes within 2h of it, and each of those nodes the
    // water particles within 2h of the node: farther than 4h from the block's sides, every node
    // it reads holds rho_w h^2 >= n rho_w h^2, so S = 1 and c = 0. Nearer a side, free surface,
    // wall or floor alike, some of those nodes miss the water beyond it, and S may fall below 1.
    if (x[0] > 4 * h && x[0] < 0.2 - 4 * h && x[1] > 4 * h && x[1] < 0.2 - 4 * h) {
      EXPECT_NEAR(S, 1.0, 1e-9) << "x = " << x.transpose();
      EXPECT_NEAR(scene.simulation.soil.material.cohesion_at(S), 0.0, 1e-6);
      ++inner;
    }
  }
  EXPECT_EQ(inner, 576);  // (0.2 - 8h) / (h / 2) = 24 rows and columns
}

// In the mixture the pore water fills the pores exactly (phi_i = n in the interior), so the
// saturation is 1 only where the nodes' water is counted in full: at the walls, whose nodes hold
// part of an interior node's weight (the slip wall's node half, the friction floor's nodes half
// and 1/24), it is divided by that part (docs/methods/mpm2grid.md, "Saturation"); the water folds at
// the friction floor (it slips there), and the soil reads the node beyond the floor as its mirror.
// Next to the walls S then stays within the lattice's quadrature error of 1 (measured 1.0000; 0.993
// before the water folded at the floor; without the division 0.43 at the block's corner), and
// farther than 4h from the walls and the block's free sides it is 1 to round-off.
TEST(SceneSeeding, MixturePoreWaterSaturatesTheSoilUpToTheWalls) {
  const auto scene = two_blocks(true);
  Simulation<2> sim(scene.simulation);
  seed_particles(scene, sim);
  sim.step(sim.stable_dt().dt);
  const auto& soil = sim.soil();
  const double h = scene.simulation.h;
  double lowest_at_walls = 1;
  int at_walls = 0, inner = 0;
  for (std::size_t p = 0; p < soil.size(); ++p) {
    const auto& x = soil.x[p];
    if (x[0] > 0.2 - 4 * h || x[1] > 0.2 - 4 * h) continue;  // the saturated block, away from its free sides
    const double S = soil.saturation[p];
    if (x[0] < 4 * h || x[1] < 4 * h) {
      lowest_at_walls = std::min(lowest_at_walls, S), ++at_walls;
    } else {
      EXPECT_NEAR(S, 1.0, 1e-9) << "x = " << x.transpose();
      ++inner;
    }
  }
  std::printf("mixture: saturation next to the walls at least %.4f (%d particles)\n", lowest_at_walls, at_walls);
  EXPECT_GE(lowest_at_walls, 0.98);
  EXPECT_EQ(at_walls + inner, 32 * 32);  // 0.16 m at 5 mm a row and a column
}

}  // namespace
}  // namespace suite::mpm2grid

namespace suite::mpm2grid {
namespace {

// The memory estimate counts the particles from the scene alone, on a sample of the lattice: on
// scenes whose lattice it samples in full, and on ones it samples sparsely, the count is that of
// the seeding within a few lattice rows of the regions' outline (2%); an inlet adds the water
// its hydrograph brings over the run.
template <int Dim>
void expect_counts_match(const std::string& file, const std::vector<std::string>& overrides, double tolerance) {
  const auto scene = read_scene<Dim>(config::Config::from_file(std::string(SUITE_SOURCE_DIR) + "/" + file, overrides));
  Simulation<Dim> sim(scene.simulation);
  seed_particles(scene, sim);
  const auto e = estimate_memory(scene);
  EXPECT_NEAR(e.soil_particles, static_cast<double>(sim.soil().size()), tolerance * sim.soil().size() + 1) << file;
  double inflow = 0;
  if (scene.simulation.inlet)
    inflow = scene.simulation.inlet->discharge.cumulative(scene.time.end) /
             std::pow(scene.simulation.h / scene.particles_per_cell, Dim);
  EXPECT_NEAR(e.water_particles, static_cast<double>(sim.water().size()) + inflow,
              tolerance * (sim.water().size() + inflow) + 1)
      << file;
  EXPECT_GT(e.bytes, 0);
}

TEST(MemoryEstimate, CountsTheParticlesTheSeedingMakes) {
  const std::string scenes = "solvers/mpm2grid/scenes/";
  // Sampled in full: the count is exact (an inlet's inflow aside, within a layer).
  expect_counts_match<2>(scenes + "water_column_collapse.yaml", {}, 1e-12);
  expect_counts_match<2>(scenes + "terzaghi.yaml", {}, 1e-12);  // saturated soil: pore water
  expect_counts_match<2>(scenes + "table_3_4_example2.yaml", {}, 1e-3);
  expect_counts_match<3>("tests/mpm2grid/two_species_3d.yaml", {"drag=lumped"}, 1e-12);
  // 2.5 million lattice points, sampled every other point per axis.
  expect_counts_match<2>(scenes + "table_3_4_example2.yaml", {"grid.spacing=0.025 m"}, 0.02);
}

}  // namespace
}  // namespace suite::mpm2grid
