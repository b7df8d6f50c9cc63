#pragma once
// An mpm2grid scene: read_scene() reads and checks its YAML keys into a Scene<Dim> (SI units: m,
// s, kg, Pa; Dim = 2 or 3, the scene's `dimension`), and seed_particles() puts the particles of
// its regions on the seeding lattice (COLLECTIVE over several ranks). A bad key throws
// InputError naming it. Every key with its unit and default: docs/mpm2grid.md, "Scene keys".
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
  bool saturated = false;  // soil regions: seed pore water with the soil (docs/mpm2grid.md, "Saturated soil regions")
  double surcharge = 0;    // soil regions: Pa on the upper surface (docs/mpm2grid.md, "Mixture")

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

// How the particles start (docs/mpm2grid.md, "Initial state"; scenes/initial_state.hpp).
struct InitialSettings {
  bool geostatic = true;      // soil at its geostatic effective stresses (false: stress-free)
  std::optional<double> k0;   // sigma'_h / sigma'_v; 1 - sin(phi) when not given
  bool hydrostatic = true;    // water at the hydrostatic J under its free surface (false: J = 1)
};

template <int Dim>
struct Scene {
  std::string name;
  SimulationSettings<Dim> simulation;
  int particles_per_cell = 2;  // per axis
  std::vector<Region> water_regions, soil_regions;
  std::optional<double> hydrostatic_surface;  // y (m) of the free surface the water starts at rest
                                              // under: p = rho_w g (surface - y), J from p (found
                                              // per column when not given)
  InitialSettings initial;
  TimeSettings time;
  std::string petsc_options;  // PETSc options database string for the consistent drag (prefix drag_)
  checkpoint::ScheduleSettings checkpoints;  // checkpoint: {every_steps, every (wall time), keep}
};

// The scene's `dimension` (2 or 3), read before the rest.
int scene_dimension(const config::Config& scene);

// Reads and checks every key; the dimension must match Dim.
template <int Dim>
Scene<Dim> read_scene(const config::Config& scene);

// What the seeding lattice puts at the point x: a soil particle where a soil region is; a water
// particle where a water region is and no soil region, or with the soil where its region is
// saturated (its pore water); both or none.
struct Seeded {
  bool soil = false, water = false;
};
template <int Dim>
Seeded seeded_at(const Scene<Dim>& scene, const Vec<Dim>& x);

// Particles on a regular lattice, particles_per_cell per axis in every cell, where the regions are,
// at rest in the scene's initial state (scenes/initial_state.hpp): water at the hydrostatic J,
// soil at its geostatic F_E, each with volume0 = lattice volume / J (det F_E for the soil), so that
// it fills its lattice cell at that stress. Particle ids follow the lattice's numbering (x
// fastest), per species.
// With a communicator of several ranks, each rank seeds a band of the lattice (whole layers
// across its last axis) holding about its share of the particles, with the ids one rank would
// give them; Simulation::distribute() then partitions. COLLECTIVE there.
template <int Dim>
void seed_particles(const Scene<Dim>& scene, Simulation<Dim>& simulation, const mpi::Comm* comm = nullptr);

}  // namespace suite::mpm2grid
