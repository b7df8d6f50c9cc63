#pragma once
// How much memory a scene will take, from the scene alone, before any particle is seeded: the
// particles the regions hold on the seeding lattice (counted on a sample of the lattice, at most
// about a million points), plus the water the inlet adds over the run (never more than the
// domain can hold), times the bytes a particle costs over a run, plus the grid nodes around them.
// docs/mpm2grid.md ("Memory") gives the measurements behind the per-particle and per-node costs.
#include <string>

#include "solvers/mpm2grid/scenes/scene.hpp"

namespace suite::mpm2grid {

struct MemoryEstimate {
  double soil_particles = 0, water_particles = 0;  // at the most: the start plus the inflow
  double nodes = 0;                                // grid nodes of both species
  double bytes = 0;                                // the particles and nodes, over all ranks
  double bytes_per_rank = 0;                       // besides: what each rank takes to start
  std::string breakdown() const;                   // "4.3e+05 particles, 2.1e+05 grid nodes"
};

template <int Dim>
MemoryEstimate estimate_memory(const Scene<Dim>& scene);

}  // namespace suite::mpm2grid
