// Scenes that start at rest (scenes/initial_state.hpp; docs/mpm2grid.md, "Initial state"):
// water at the hydrostatic J under the free surface the seeding finds per column, soil at its
// geostatic effective stress (sigma'_v from the overburden, K0 sigma'_v across). The scenes here
// give no hydrostatic_surface and no stresses: the scene reader builds the state itself.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "solvers/mpm2grid/model/simulation.hpp"
#include "solvers/mpm2grid/scenes/scene.hpp"

namespace suite::mpm2grid {
namespace {

constexpr double kG = 9.81, kRhoW = 1000;

Scene<2> scene(const std::string& yaml) {
  return read_scene<2>(config::Config::from_string(yaml, "<test scene>"));
}

// sigma_yy and sigma_xx of a soil particle (Cauchy, compression positive), Pa.
std::pair<double, double> soil_stress(const Simulation<2>& sim, std::size_t p) {
  const Mat<2>& F = sim.soil().F[p];
  const Mat<2> sigma = sim.settings().soil.material.template kirchhoff<2>(F) / F.determinant();
  return {-sigma(1, 1), -sigma(0, 0)};
}

// A reservoir 2 m deep behind nothing but walls, and a saturated soil layer under 1 m of water:
// at the first step the water's pressure is rho_w g (surface - y) with the surface the seeding
// found, the skeleton's sigma'_v the buoyant weight above it and sigma'_h = K0 sigma'_v.
TEST(InitialState, WaterAndSaturatedSoilStartHydrostaticAndGeostatic) {
  const double surface = 1.5, layer = 0.5, rho_d = 1600, n = 0.4;
  auto sc = scene(fmt::format(R"(
dimension: 2
grid: {{spacing: 0.05 m, particles_per_cell: 2}}
domain: {{lo: [0, 0], hi: [0.5, 2.0]}}
walls: {{x_low: slip, x_high: slip, y_low: slip, y_high: slip}}
water: {{density: 1000 kg/m^3, bulk_modulus: 1 MPa, regions: [{{box: {{lo: [0, 0], hi: [0.5, {}]}}}}]}}
soil: {{density: {} kg/m^3, young: 20 MPa, poisson: 0.3, friction_angle: 30 deg, porosity: {},
        regions: [{{box: {{lo: [0, 0], hi: [0.5, {}]}}, saturated: true}}]}}
time: {{end: 1 s}}
)",
                              surface, rho_d, n, layer));
  Simulation<2> sim(sc.simulation);
  seed_particles(sc, sim);
  const auto& eos = sc.simulation.water.eos;
  double worst_pressure = 0;
  for (std::size_t p = 0; p < sim.water().size(); ++p) {
    const double expected = kRhoW * kG * (surface - sim.water().x[p][1]);
    worst_pressure = std::max(worst_pressure, std::abs(eos.pressure(sim.water().J[p]) - expected));
  }
  EXPECT_LT(worst_pressure, 1e-9 * kRhoW * kG * surface);
  const double k0 = 1 - std::sin(30 * M_PI / 180), buoyant = (rho_d - (1 - n) * kRhoW) * kG;
  double worst_v = 0, worst_h = 0;
  for (std::size_t p = 0; p < sim.soil().size(); ++p) {
    const auto [sv, sh] = soil_stress(sim, p);
    const double expected = buoyant * (layer - sim.soil().x[p][1]);
    worst_v = std::max(worst_v, std::abs(sv - expected));
    worst_h = std::max(worst_h, std::abs(sh - k0 * expected));
  }
  // Exact up to round-off: the strain is the inverse of the Hencky law at the target stress.
  EXPECT_LT(worst_v, 1e-9 * buoyant * layer);
  EXPECT_LT(worst_h, 1e-9 * buoyant * layer);
}

// The mean pressure error of the water particles in the layer one cell high on the floor,
// relative to rho_w g H, against rho_w g (H - y).
double floor_layer_error(const Simulation<2>& sim, double depth) {
  const auto& w = sim.water();
  double sum = 0;
  int n = 0;
  for (std::size_t p = 0; p < w.size(); ++p) {
    if (w.x[p][1] >= sim.grid().spacing()) continue;
    sum += sim.settings().water.eos.pressure(w.J[p]) - kRhoW * kG * (depth - w.x[p][1]);
    ++n;
  }
  return sum / n / (kRhoW * kG * depth);
}

// A full reservoir (2 m of water, 8 cells deep) whose scene gives no surface: its floor layer is
// at rho_w g H from the first step on, not ringing between 0 and twice that. On a slip floor and
// on the dam scenes' friction floor (mu = 0.7), along which the water slips (Walls::for_water();
// before, the friction floor's plain condition held the layer 20-27% above rho_w g H).
TEST(InitialState, ReservoirFloorPressureFromTheFirstStep) {
  const double depth = 2.0;
  for (const char* floor : {"slip", "friction"}) {
    auto sc = scene(fmt::format(R"(
dimension: 2
grid: {{spacing: 0.25 m, particles_per_cell: 2}}
domain: {{lo: [0, 0], hi: [4, 3]}}
walls: {{x_low: slip, x_high: slip, y_low: {}, y_high: slip}}
wall_friction: 0.7
water: {{density: 1000 kg/m^3, bulk_modulus: 100 kPa, regions: [{{box: {{lo: [0, 0], hi: [4, {}]}}}}]}}
time: {{end: 1 s}}
)",
                                floor, depth));
    Simulation<2> sim(sc.simulation);
    seed_particles(sc, sim);
    double worst = std::abs(floor_layer_error(sim, depth));
    while (sim.time() < 1.0) {
      sim.step(std::min(sim.stable_dt().dt, 1.0 - sim.time()));
      worst = std::max(worst, std::abs(floor_layer_error(sim, depth)));
    }
    std::printf("reservoir, %s floor: the floor layer's mean pressure within %.3f%% of rho g H over 1 s\n", floor,
                100 * worst);
    // 0.5% of rho g H at every step (issue 26's bound for a still tank on a friction floor;
    // measured 0.41% on both floors, the worst step of the first second; the walls' mirror keeps
    // the time-averaged floor layer within 0.3% at 8 cells: tests/mpm2grid/test_buoyancy.cpp; a
    // start at J = 1 would swing it by 100%).
    EXPECT_LT(worst, 0.005) << floor << " floor";
  }
}

// Runs `seconds` and returns the largest particle displacement (m) and kinetic energy (J/m) seen.
struct Motion {
  double displacement = 0, kinetic = 0;
};
Motion run(Simulation<2>& sim, double seconds) {
  std::map<std::int64_t, Vec<2>> start;  // by particle id: the step reorders the particles
  for (std::size_t p = 0; p < sim.soil().size(); ++p) start[sim.soil().id[p]] = sim.soil().x[p];
  Motion m;
  while (sim.time() < seconds) {
    sim.step(std::min(sim.stable_dt().dt, seconds - sim.time()));
    m.kinetic = std::max(m.kinetic, sim.kinetic_energy());
    const auto& soil = sim.soil();
    for (std::size_t p = 0; p < soil.size(); ++p)
      m.displacement = std::max(m.displacement, (soil.x[p] - start.at(soil.id[p])).norm());
  }
  return m;
}

// The dry 05-HR-a embankment (3.3 m high, slopes 0.3882 and 0.3143 V/H, Table 3.4's geometry)
// of the scenes' compacted soil (E = 24 MPa, c0 = 4935 Pa) on its friction floor: started
// geostatic it stands as built, where started stress-free it drops and rings.
std::string dry_dam(bool geostatic) {
  return fmt::format(R"(
dimension: 2
grid: {{spacing: 0.25 m, particles_per_cell: 2}}
domain: {{lo: [0, 0], hi: [35, 10]}}
walls: {{x_low: slip, x_high: open, y_low: friction, y_high: slip}}
wall_friction: 0.7
gravity: 9.8 m/s^2
soil: {{density: 2200 kg/m^3, young: 24 MPa, poisson: 0.3, friction_angle: 35 deg, cohesion: 4935 Pa,
        regions: [{{trapezoid: {{toe: 4.75, height: 3.3, crest_width: 1.0, upstream_slope: 0.3882,
                                 downstream_slope: 0.3143}}}}]}}
initial_state: {{geostatic: {}}}
time: {{end: 2 s}}
)",
                     geostatic ? "true" : "false");
}

TEST(InitialState, DryDamStandsAsBuilt) {
  const double H = 3.3, rho = 2200, g = 9.8;
  Motion m[2];
  for (const bool geostatic : {false, true}) {
    auto sc = scene(dry_dam(geostatic));
    Simulation<2> sim(sc.simulation);
    seed_particles(sc, sim);
    m[geostatic] = run(sim, 2.0);
    std::printf(
        "dry dam, %s: largest displacement %.4f m (%.3f%% of H), largest kinetic energy %.3e J/m "
        "(%.2e of rho g H^2)\n",
        geostatic ? "geostatic" : "stress-free", m[geostatic].displacement, 100 * m[geostatic].displacement / H,
        m[geostatic].kinetic, m[geostatic].kinetic / (rho * g * H * H));
  }
  EXPECT_LT(m[1].displacement, 0.005 * H);
  EXPECT_LT(m[1].kinetic, 1e-4 * rho * g * H * H);
}

}  // namespace
}  // namespace suite::mpm2grid
