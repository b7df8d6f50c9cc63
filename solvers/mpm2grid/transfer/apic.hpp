#pragma once
// APIC transfers with cubic B-splines (Jiang et al. 2015; spec/mpm2grid.md, steps 1, 2 and 5),
// one species at a time:
//   P2G  m_i = sum_p w_ip m_p,   (m v)_i = sum_p w_ip m_p (v_p + C_p (x_i - x_p)),
//        f_i = -sum_p V_p^0 tau_p grad w_ip   (tau_p the Kirchhoff stress: V^0 P F^T = V^0 tau),
//        d_i = sum_p (c_E V)_p w_ip           (drag coefficients, soil only, when given);
//   G2P  v_p = sum_i w_ip v_i,   C_p = sum_i w_ip v_i (x_i - x_p)^T D^-1,  D^-1 = 3 / h^2,
//        grad v_p = sum_i v_i (grad w_ip)^T.
// P2G conserves mass, linear and angular momentum exactly (the weights are a partition of unity
// and reproduce linear functions); G2P then P2G loses no angular momentum either.
// Both go through a NodeTile per particle group (grid/node_tile.hpp) with the row kernels of
// transfer/stencil_rows.hpp; they give the same sums for particles in any order, and work
// fastest in group order (transfer/particle_order.hpp).
#include <memory>
#include <vector>

#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/grid/node_tile.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"
#include "solvers/mpm2grid/transfer/stencil_rows.hpp"

namespace suite::mpm2grid {

// Activates the grid blocks the particles' stencils touch. With `groups`, also gives each
// particle's group (grid/node_tile.hpp) as the index of its block (one entry per particle).
template <int Dim>
void touch_blocks(const Particles<Dim>& particles, BlockGrid<Dim>& grid, std::vector<int>* groups = nullptr) {
  const double h = grid.spacing();
  if (groups) groups->resize(particles.size());
  typename BlockGrid<Dim>::Corners corners{};
  Index<Dim> previous{};
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const Index<Dim> base = stencil_base(particles.x[p], h);
    // Neighbouring particles mostly lie in the same blocks as the one before them: then those
    // blocks are active and their indices known, without looking them up.
    if (p == 0 || (base != previous && !BlockGrid<Dim>::same_blocks(base, previous))) grid.touch(base, corners);
    previous = base;
    if (groups) (*groups)[p] = corners[0];  // corner 0: the block of the stencil's first node
  }
}

// Adds one species' particles to its node fields (reset to the grid's size by the caller).
// tau: one Kirchhoff stress per particle (Pa), or empty for none; drag: c_E V per particle
// (kg/s), or empty; pressure: p per particle (Pa), added as w m p, or empty (not both drag and
// pressure). The particles' stencils must lie in active blocks (touch_blocks).
template <int Dim>
void particles_to_grid(const Particles<Dim>& P, const std::vector<Mat<Dim>>& tau, const std::vector<double>& drag,
                       const BlockGrid<Dim>& grid, NodeFields<Dim>& nodes, const std::vector<double>& pressure = {}) {
  using Tile = NodeTile<Dim, 2 * Dim + 2>;  // mass, momentum, force, drag or pressure
  auto tile = std::make_unique<Tile>();
  const bool stresses = !tau.empty(), has_drag = !drag.empty(), has_pressure = !pressure.empty();
  std::vector<double>& extra_field = has_drag ? nodes.drag : nodes.pressure;
  const bool extra = has_drag || has_pressure;
  const auto leave = [&] {
    const double *M = tile->field(0), *X = tile->field(1 + 2 * Dim);
    tile->for_each_node([&](int t, long slot) {
      const auto i = static_cast<std::size_t>(slot);
      nodes.mass[i] += M[t];
      for (int a = 0; a < Dim; ++a) nodes.momentum[i][a] += tile->field(1 + a)[t];
      if (stresses)
        for (int a = 0; a < Dim; ++a) nodes.force[i][a] += tile->field(1 + Dim + a)[t];
      if (extra) extra_field[i] += X[t];
    });
  };
  sweep_groups(
      P.x, grid, *tile, [&] { tile->zero(); }, leave,
      [&](std::size_t p, const StencilRows<Dim>& s, int first) {
        const Mat<Dim> stress = stresses ? Mat<Dim>(P.volume0[p] * tau[p]) : Mat<Dim>::Zero();
        const double e = has_drag ? drag[p] : has_pressure ? P.mass[p] * pressure[p] : 0.0;
        scatter_apic(*tile, s, first, P.mass[p], P.v[p], P.C[p], stresses ? &stress : nullptr, extra ? &e : nullptr);
      });
}

// Interpolates the node velocities back: v_p, C_p and grad v_p (one per particle, resized).
template <int Dim>
void grid_to_particles(Particles<Dim>& P, const BlockGrid<Dim>& grid, const NodeFields<Dim>& nodes,
                       std::vector<Mat<Dim>>& grad_v) {
  using Tile = NodeTile<Dim, Dim>;  // velocity
  auto tile = std::make_unique<Tile>();
  const double inverse_d = apic_inverse_d(grid.spacing());
  grad_v.resize(P.size());
  const auto enter = [&] {
    tile->zero();
    tile->for_each_node([&](int t, long slot) {
      for (int a = 0; a < Dim; ++a) tile->field(a)[t] = nodes.velocity[static_cast<std::size_t>(slot)][a];
    });
  };
  sweep_groups(
      P.x, grid, *tile, enter, [] {},
      [&](std::size_t p, const StencilRows<Dim>& s, int first) {
        for (int a = 0; a < Dim; ++a) {
          const FieldSample<Dim> va = sample_field<true, true>(*tile, a, s, first);
          P.v[p][a] = va.value;
          P.C[p].row(a) = inverse_d * va.moment.transpose();
          grad_v[p].row(a) = va.gradient.transpose();
        }
      });
}

}  // namespace suite::mpm2grid
