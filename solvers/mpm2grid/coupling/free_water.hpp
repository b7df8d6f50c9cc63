#pragma once
// The free water's own field and its contact with the soil (SimulationSettings::free_water_field;
// docs/methods/mpm2grid.md, "Free water and pore water").
//
// The Darcy drag couples the soil with the water in its pores. The water above and beside the
// soil (free water) is a fluid of its own: it presses on the soil and slides along it, and where
// it shares grid nodes with the soil the drag must not lock it to the grains (a cell-thick layer
// of overflow dragged the dam's surface soil along, docs/mpm2grid.md "Bed shear and excess-stress
// erosion"). So each water particle is pore water where the soil fills its place, free water
// elsewhere, and the two go to separate grid fields; the free water meets the mixture (soil and
// pore water) through a frictionless no-penetration contact (Bardenhagen et al. 2000):
//   shape   P2G of the soil's mass and mass-weighted offsets, m_i = sum_p w_ip m_p and
//           o_i = sum_p w_ip m_p (x_i - x_p): the soil's fill phi_i = m_i / (rho_s h^Dim) (1 inside
//           the soil, 0 away from it) and the outward normal n_i = o_i / |o_i| (from the soil's
//           local centre of mass to the node). The walls fold it as mirror images (a sticky wall
//           as a slip one: the image of the soil beyond the wall).
//   sort    a water particle is free where the fill sampled at it is below one half (the soil's
//           surface as the fill's half level).
//   contact at a node where free water (mass m_f, velocity v_f) and mixture (M = m_s + m_pw,
//           v_m = (m_s v_s + m_pw v_pw) / M) touch (kTouching, kLeastFill) and approach each other,
//           (v_f - v_m) . n < 0, the
//           normal relative velocity goes to zero: v_f -= M / (m_f + M) ((v_f - v_m) . n) n and
//           both mixture species gain m_f / (m_f + M) ((v_f - v_m) . n) n (their relative
//           velocity, the drag's, unchanged). Momentum is conserved; tangential slip is free (the
//           bed-shear closure brakes the free water along its bed).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <span>
#include <vector>

#include "solvers/mpm2grid/boundary/wall_fold.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/grid/node_tile.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"
#include "solvers/mpm2grid/transfer/stencil_rows.hpp"

namespace suite::mpm2grid {

// A water particle is free water where the soil's fill sampled at it is below this.
inline constexpr double kFreeWaterFill = 0.5;

// The free water touches the soil at a node where their fills add up to this. Two half-spaces
// filled without a gap add up to 1 at every node; a gap g (small against h) lowers the node at the
// soil's surface by about (2/3) g / h, so the free water rests within 0.15 h of the soil. (Without
// it the contact held the free water two cells above the soil, where the kernels' tails meet.)
inline constexpr double kTouching = 0.9;
// And the soil's fill is at least this: a node more than about 0.7 h outside the soil's surface
// has only its kernel tails (one cell out the fill is 1/24), which the contact would set moving
// with the free water. Without it the overflow's velocity went to the soil's tails a cell above
// the dam's surface, and example 2 at h = 0.0625 m blew up (a soil particle at 89 m/s after
// 5.1 s). (The free water's tails inside the soil must stay in the contact: without them it sank
// into the soil, and the channel over the soil bed ran 17-28% slow.)
inline constexpr double kLeastFill = 0.1;

// Adds the soil's mass and mass-weighted offsets to `shape` (mass and momentum; reset by the
// caller), folded by `walls`.
template <int Dim>
void spread_soil_shape(const Particles<Dim>& soil, const BlockGrid<Dim>& grid, const WallFold<Dim>& walls,
                       NodeFields<Dim>& shape, std::span<const ParticleRun> runs = {}) {
  using Tile = NodeTile<Dim, 1 + Dim>;
  auto tile = std::make_unique<Tile>();
  constexpr auto fields = scalar_and_vector_fields<Dim>();  // the mass and the offsets
  const auto leave = [&] {
    walls.fold(*tile, fields);
    tile->for_each_node([&](int t, long slot) {
      const auto i = static_cast<std::size_t>(slot);
      shape.mass[i] += tile->field(0)[t];
      for (int a = 0; a < Dim; ++a) shape.momentum[i][a] += tile->field(1 + a)[t];
    });
  };
  const Vec<Dim> zero = Vec<Dim>::Zero();
  const Mat<Dim> offsets = Mat<Dim>::Identity(), no_stress = Mat<Dim>::Zero();
  // APIC's momentum with v = 0 and C = I is sum_p w_ip m_p (x_i - x_p).
  sweep_groups(
      soil.x, grid, *tile, [&] { tile->zero(); }, leave,
      [&](std::size_t p, const StencilRows<Dim>& s, int first) {
        scatter_apic<StressForm::none, true>(*tile, s, first, soil.mass[p], zero, offsets, no_stress, zero, 0.0);
      },
      {}, runs);
}

// Per water particle of `run`, 1 where it is free water: the soil's fill (per slot, complete on
// the nodes the particles reach) sampled at it below kFreeWaterFill. `free` has a place for each
// water particle.
template <int Dim>
void sort_free_water(const Particles<Dim>& water, const BlockGrid<Dim>& grid, const std::vector<double>& fill,
                     const WallFold<Dim>& walls, std::vector<char>& free, ParticleRun run) {
  using Tile = NodeTile<Dim, 1>;
  auto tile = std::make_unique<Tile>();
  constexpr std::array<TileField, 1> read{TileField{TileField::scalar}};
  sweep_groups(
      water.x, grid, *tile,
      [&] {
        tile->gather(0, fill);
        walls.mirror(*tile, read);
      },
      [] {},
      [&](std::size_t p, const StencilRows<Dim>& s, int first) {
        free[p] = sample_field<false, kNoAxes>(*tile, 0, s, first).value < kFreeWaterFill;
      },
      {}, std::span<const ParticleRun>(&run, 1));
}

// The contact of the free water with the mixture on every node (above) where the two touch: the
// soil's fill and the free water's, m_f / (rho_w h^Dim), add up to at least kTouching, the soil's
// at least kLeastFill.
template <int Dim>
void free_water_contact(const NodeFields<Dim>& shape, const std::vector<double>& soil_fill, double free_per_kg,
                        NodeFields<Dim>& soil, NodeFields<Dim>& pore, NodeFields<Dim>& free, int threads = 1) {
  const std::size_t nodes = free.mass.size();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::size_t i = 0; i < nodes; ++i) {
    const double mf = free.mass[i], ms = soil.mass[i], mp = pore.mass[i], M = ms + mp;
    const double fill_s = soil_fill[i], fill_f = free_per_kg * mf;
    if (!(mf > 0) || !(M > 0) || fill_s + fill_f < kTouching || fill_s < kLeastFill) continue;
    const double length = shape.momentum[i].norm();
    if (!(length > 0)) continue;
    const Vec<Dim> n = shape.momentum[i] / length;
    const Vec<Dim> vm = (ms * soil.velocity[i] + mp * pore.velocity[i]) / M;
    const double approach = (free.velocity[i] - vm).dot(n);
    if (!(approach < 0)) continue;
    free.velocity[i] -= (M / (mf + M) * approach) * n;
    const Vec<Dim> gain = (mf / (mf + M) * approach) * n;
    if (ms > 0) soil.velocity[i] += gain;
    if (mp > 0) pore.velocity[i] += gain;
  }
}

}  // namespace suite::mpm2grid
