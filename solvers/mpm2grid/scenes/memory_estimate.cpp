#include "solvers/mpm2grid/scenes/memory_estimate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"

namespace suite::mpm2grid {

namespace {

// The bytes one particle's state takes in its species' arrays.
template <int Dim>
double state_bytes() {
  Particles<Dim> one;
  one.add(Vec<Dim>::Zero(), Vec<Dim>::Zero(), 1.0, 1.0);
  double bytes = 0;
  one.for_each_array([&](auto& values) { bytes += sizeof(values[0]); });
  return bytes;
}

// A particle costs more than its state during a run: the arrays' spare capacity, the reorder's
// and the migration's copies and the per-particle data of the transfers. A grid node costs its
// fields (mass, momentum, force, velocity, drag, pressure) and their copies in the halo and the
// node tiles. The two factors reproduce the slope of the peak resident memory against the
// particle count at 2 particles per cell and axis, 2D and 3D (docs/mpm2grid.md, "Memory").
constexpr double kParticleStateCopies = 1.3;
template <int Dim>
constexpr double kNodeBytes = 2.0 * (3 + 3 * Dim) * sizeof(double);
// What a rank takes before it holds a particle: the MPI, HDF5 and PETSc libraries and buffers.
constexpr double kRankBytes = 40e6;

}  // namespace

std::string MemoryEstimate::breakdown() const {
  return fmt::format("{:.3g} soil and {:.3g} water particles, {:.3g} grid nodes", soil_particles, water_particles,
                     nodes);
}

template <int Dim>
MemoryEstimate estimate_memory(const Scene<Dim>& sc) {
  const auto& s = sc.simulation;
  const double spacing = s.h / sc.particles_per_cell;
  // The lattice's points per axis, and a stride that samples at most about 1e6 of them.
  double lattice = 1;
  Vec<Dim> count;
  for (int d = 0; d < Dim; ++d) {
    count[d] = std::round((s.walls.hi[d] - s.walls.lo[d]) / spacing);
    lattice *= count[d];
  }
  const double stride = std::max(1.0, std::ceil(std::pow(lattice / 1e6, 1.0 / Dim)));
  Index<Dim> samples;
  long long total = 1;
  for (int d = 0; d < Dim; ++d) {
    samples[d] = static_cast<int>(std::max(1.0, std::floor(count[d] / stride)));
    total *= samples[d];
  }
  double soil = 0, water = 0, pore_water = 0;
  for (long long n = 0; n < total; ++n) {
    long long r = n;
    Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) {
      // The lattice point at the middle of the stride's run of points.
      const double i = std::floor((static_cast<double>(r % samples[d]) + 0.5) * count[d] / samples[d]);
      x[d] = s.walls.lo[d] + (i + 0.5) * spacing;
      r /= samples[d];
    }
    const Seeded at = seeded_at(sc, x);
    soil += at.soil;
    water += at.water;
    pore_water += at.soil && at.water;
  }
  MemoryEstimate e;
  const double per_sample = lattice / static_cast<double>(total);
  e.soil_particles = soil * per_sample;
  e.water_particles = water * per_sample;
  if (s.inlet) {
    double depth = 1;  // 3D: the inlet spans the domain along z
    if constexpr (Dim == 3) depth = s.walls.hi[2] - s.walls.lo[2];
    const double inflow = s.inlet->discharge.cumulative(sc.time.end) * depth / std::pow(spacing, Dim);
    // The water cannot outgrow the lattice points the soil leaves free, besides the pore water.
    e.water_particles = std::min(e.water_particles + inflow, lattice - e.soil_particles + pore_water * per_sample);
  }
  // The nodes of the blocks around the material: its cells grown by the stencil's reach (2 cells
  // on each side of a 4-cell block: about (1 + 4/4)^Dim times the cells), for each species.
  const double cells_per_particle = 1.0 / std::pow(sc.particles_per_cell, Dim);
  e.nodes = (e.soil_particles + e.water_particles) * cells_per_particle * std::pow(2.0, Dim);
  e.bytes =
      (e.soil_particles + e.water_particles) * kParticleStateCopies * state_bytes<Dim>() + e.nodes * kNodeBytes<Dim>;
  // A FLIP share: the species' node fields before the forces, and per particle a probe's
  // position, velocity and C and the velocity before the step.
  if (sc.simulation.water.flip > 0)
    e.bytes += e.nodes / 2 * kNodeBytes<Dim> / 2 + e.water_particles * (3 * Dim + Dim * Dim) * sizeof(double);
  if (sc.simulation.soil.flip > 0)
    e.bytes += e.nodes / 2 * kNodeBytes<Dim> / 2 + e.soil_particles * (3 * Dim + Dim * Dim) * sizeof(double);
  // The free water's own field: its node fields (and before the forces with a FLIP share) and
  // the soil's shape, each one species' share of the nodes, the soil's fill per node, a flag per
  // water particle.
  if (sc.simulation.free_water_field)
    e.bytes += e.nodes / 2 * kNodeBytes<Dim> / 2 * (sc.simulation.water.flip > 0 ? 3 : 2) +
               e.nodes / 2 * sizeof(double) + e.water_particles;
  // Implicit forces: per particle a mass-free probe (position, velocity, C, mass, volume, J), the
  // trial pressure and J (water) or trial F and stress (soil); per node (each species' nodes counted) a
  // second set of node fields for the forces and PETSc's vectors of Dim unknowns: the solution,
  // the residual, GMRES's 30 Krylov vectors and the differencing's few.
  if (sc.simulation.forces == ForceScheme::implicit_end) {
    const double probe = (3 * Dim + Dim * Dim + 3) * sizeof(double);
    e.bytes += e.water_particles * (probe + 2 * sizeof(double)) +
               e.soil_particles * (probe + 2 * Dim * Dim * sizeof(double)) +
               e.nodes * (kNodeBytes<Dim> / 2 + 40.0 * Dim * sizeof(double));
  }
  e.bytes_per_rank = kRankBytes;
  // Each rank's index of the blocks over the walls' box (BlockGrid::set_walls_box).
  if (const double blocks = BlockGrid<Dim>::walls_box_blocks(s.walls.lo, s.walls.hi, s.h);
      blocks <= static_cast<double>(BlockGrid<Dim>::kDenseBlocks))
    e.bytes_per_rank += blocks * sizeof(int);
  return e;
}

template MemoryEstimate estimate_memory<2>(const Scene<2>&);
template MemoryEstimate estimate_memory<3>(const Scene<3>&);

}  // namespace suite::mpm2grid
