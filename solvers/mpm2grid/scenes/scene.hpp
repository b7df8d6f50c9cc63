#pragma once
// An mpm2grid scene (YAML; docs/methods/mpm2grid.md, "Scenes"): the box, the grid spacing, the species
// with their materials and regions, walls, gravity and time control. Example
// (scenes/water_column_collapse.yaml):
//
//   dimension: 2
//   grid: {spacing: 3.5719 mm, particles_per_cell: 2}       # particles per cell per axis
//   domain: {lo: [0, 0], hi: [0.4, 0.16]}                    # m, sides on grid planes
//   walls: {x_low: slip, x_high: slip, y_low: slip, y_high: open}   # slip|sticky|friction|open
//   wall_friction: 0.3
//   gravity: 9.81 m/s^2                                      # along -y
//   water: {density: 1000 kg/m^3, bulk_modulus: 57 kPa, gamma: 7,
//           regions: [{box: {lo: [0, 0], hi: [0.05715, 0.1143]}}]}
//   inlet: {height: 7.25 m, velocity: 2 m/s}     # or discharge: {columns, rows}: scenes/read_inlet.hpp
//   soil: {density: 2000 kg/m^3, young: 10 MPa, poisson: 0.3, friction_angle: 30 deg, cohesion: 0 Pa,
//          porosity: 0.4, conductivity: 1e-3 m/s,
//          regions: [{trapezoid: {toe: 1.0, height: 3.75, crest_width: 6, upstream_slope: 0.8333,
//                                 downstream_slope: 0.8333}}]}
//   drag: lumped                            # lumped | consistent (PETSc CG) | explicit
//   petsc_options: "-drag_ksp_rtol 1e-10 -drag_pc_type pbjacobi"   # the consistent solve's KSP
//   time: {end: 0.2 s, cfl: 0.4, dt_max: 1 ms, series: 2 ms, output: 20 ms, max_steps: 0}
//   checkpoint: {every_steps: 1000, every: 30 min, keep: 2}      # and on SIGUSR1 / SIGTERM
//   decomposition: {check_every: 20, imbalance: 1.1}   # over several ranks: load checks (steps),
//                                                      # repartition above this max/mean ratio
//
// Soil cohesion: `cohesion` (Pa, c0 of dry soil), or `cohesion_shift` (the dissertation's
// dimensionless strain-space c_C, mapped to c0 = K tan(phi_f) c_C / alpha, see
// cohesion_of_strain_shift in materials/hencky_drucker_prager.hpp).
// Buoyancy: `buoyancy: true` (the default with both species; model/simulation.hpp). Water:
// `hydrostatic_surface: 0.4 m` starts the water at the hydrostatic pressure under that level
// (without it at p = 0, J = 1).
// Regions: `box` {lo, hi} (m), or `trapezoid` (a dam cross-section in x-y standing on the
// domain's floor, extruded over z in 3D): upstream toe at x = toe, height, crest width, slopes
// as V/H. Water regions leave out the points inside soil regions.
// A soil region may say `saturated: true` (default false): its pores start full of water. Every
// soil particle seeded there gets a water particle at the same point, as a water region would
// seed it (mass rho_w V, volume V, at the hydrostatic J under hydrostatic_surface if given). Without
// mixture: true the water does not see the solid's volume (model/simulation.hpp, buoyancy), so the
// pore water is water at its own density: its pressure then continues that of free water above
// the soil, and the soil's saturation is S = min(phi_w / n, 1) = 1 there (c = 0). Needs the
// water: section (density, bulk_modulus); the scene's water regions stay as they are.
// Mixture: `mixture: true` (default false) makes the pore water's volume balance count the soil's
// (model/simulation.hpp): compressing the skeleton compresses its pore water (Terzaghi's
// consolidation); a saturated region's pore water is then seeded at its partial volume n V and
// mass n rho_w V. Needs buoyancy.
// Surcharge: a soil region's `surcharge: 20 kPa` (default 0) presses on its upper surface: each
// of its particles with no particle of the region one lattice spacing above carries the load
// surcharge s^(Dim-1) down (s the lattice spacing, Pa per horizontal area). All loads grow
// linearly from zero to full over the soil's `surcharge_ramp` (default 0 s: at once).
#include <optional>
#include <string>
#include <vector>

#include "core/checkpoint/schedule.hpp"
#include "core/config/config.hpp"
#include "core/mpi/comm.hpp"
#include "solvers/mpm2grid/model/simulation.hpp"

namespace suite::mpm2grid {

struct Region {
  enum class Kind { box, trapezoid } kind = Kind::box;
  std::vector<double> lo, hi;  // box, m
  double toe = 0, height = 0, crest_width = 0, upstream_slope = 1, downstream_slope = 1;  // trapezoid
  double floor = 0;  // trapezoid: the y of its base (the domain's floor)
  bool saturated = false;  // soil regions: seed pore water with the soil (see above)
  double surcharge = 0;    // soil regions: Pa on the upper surface (see above)

  // True when x lies in the region ([lo, hi) per axis; the trapezoid's cross-section in x-y, half
  // open at its right and top) grown outwards by `margin` (m) along the axes: the trapezoid's
  // sides move by margin along x, its top up by margin and its base down by margin.
  template <int Dim>
  bool contains(const Vec<Dim>& x, double margin = 0) const;
  double trapezoid_area() const;  // m^2
};

struct TimeSettings {
  double end = 0;          // s
  double series = 0;       // s between rows of series.csv
  double output = 0;       // s between particle files
  long long max_steps = 0; // stop with a checkpoint after this many steps of this run (0: never)
};

template <int Dim>
struct Scene {
  std::string name;
  SimulationSettings<Dim> simulation;
  int particles_per_cell = 2;  // per axis
  std::vector<Region> water_regions, soil_regions;
  std::optional<double> hydrostatic_surface;  // y (m) of the free surface the water starts at rest
                                              // under: p = rho_w g (surface - y), J from p
  TimeSettings time;
  std::string petsc_options;  // PETSc options database string for the consistent drag (prefix drag_)
  checkpoint::ScheduleSettings checkpoints;  // checkpoint: {every_steps, every (wall time), keep}

  // The values a restart must share with the run that wrote the checkpoint.
  std::vector<double> fingerprint() const;
};

// The scene's `dimension` (2 or 3), read before the rest.
int scene_dimension(const config::Config& scene);

// Reads and checks every key; the dimension must match Dim.
template <int Dim>
Scene<Dim> read_scene(const config::Config& scene);

// Particles on a regular lattice, particles_per_cell per axis in every cell, where the regions are;
// water at the hydrostatic J under hydrostatic_surface if given (volume0 = lattice volume / J, so
// that the particle fills its lattice cell at the hydrostatic pressure). Particle ids follow the
// lattice's numbering (x fastest), per species.
// With a communicator of several ranks, each rank seeds a band of the lattice (whole layers
// across its last axis) holding about its share of the particles, with the ids one rank would
// give them; Simulation::distribute() then partitions. COLLECTIVE there.
template <int Dim>
void seed_particles(const Scene<Dim>& scene, Simulation<Dim>& simulation, const mpi::Comm* comm = nullptr);

}  // namespace suite::mpm2grid
