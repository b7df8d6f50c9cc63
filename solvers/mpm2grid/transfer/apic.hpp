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
#include <vector>

#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"

namespace suite::mpm2grid {

template <int Dim>
using CornerList = std::vector<typename BlockGrid<Dim>::Corners>;

// Activates the grid blocks the particles' stencils touch; with `corners`, also the indices of
// each particle's blocks (one entry per particle), which the transfers below then use instead of
// looking the blocks up again.
template <int Dim>
void touch_blocks(const Particles<Dim>& particles, BlockGrid<Dim>& grid, CornerList<Dim>* corners = nullptr) {
  const double h = grid.spacing();
  if (corners) corners->resize(particles.size());
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const Stencil<Dim> s(particles.x[p], h);
    if (corners)
      grid.touch(s, (*corners)[p]);
    else
      grid.touch(s);
  }
}

// A particle's node slots: from its corners when given, else by lookup.
template <int Dim>
void particle_slots(const BlockGrid<Dim>& grid, const Stencil<Dim>& s, const CornerList<Dim>* corners, std::size_t p,
                    std::array<long, BlockGrid<Dim>::kNodes>& slots) {
  if (corners)
    grid.slots_from_corners(s, (*corners)[p], slots);
  else
    grid.stencil_slots(s, slots);
}

// Adds one species' particles to its node fields (reset to the grid's size by the caller).
// tau: one Kirchhoff stress per particle (Pa), or empty for none; drag: c_E V per particle
// (kg/s), or empty; pressure: p per particle (Pa), added as w m p, or empty; corners: from
// touch_blocks for these particles and this grid, or null.
template <int Dim>
void particles_to_grid(const Particles<Dim>& P, const std::vector<Mat<Dim>>& tau, const std::vector<double>& drag,
                       const BlockGrid<Dim>& grid, NodeFields<Dim>& nodes, const std::vector<double>& pressure = {},
                       const CornerList<Dim>* corners = nullptr) {
  const double h = grid.spacing();
  std::array<long, BlockGrid<Dim>::kNodes> slots;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Stencil<Dim> s(P.x[p], h);
    particle_slots(grid, s, corners, p, slots);
    const Mat<Dim> stress = tau.empty() ? Mat<Dim>::Zero() : Mat<Dim>(P.volume0[p] * tau[p]);
    const double m = P.mass[p];
    int n = 0;
    s.for_each([&](const Index<Dim>& k, const Index<Dim>& node) {
      const long i = slots[n++];
      const double w = s.weight(k);
      Vec<Dim> xi;
      for (int d = 0; d < Dim; ++d) xi[d] = node[d] * h;
      nodes.mass[i] += w * m;
      nodes.momentum[i] += w * m * (P.v[p] + P.C[p] * (xi - P.x[p]));
      if (!tau.empty()) nodes.force[i] -= stress * s.gradient(k);
      if (!drag.empty()) nodes.drag[i] += w * drag[p];
      if (!pressure.empty()) nodes.pressure[i] += w * m * pressure[p];
    });
  }
}

// Interpolates the node velocities back: v_p, C_p and grad v_p (one per particle, resized).
template <int Dim>
void grid_to_particles(Particles<Dim>& P, const BlockGrid<Dim>& grid, const NodeFields<Dim>& nodes,
                       std::vector<Mat<Dim>>& grad_v, const CornerList<Dim>* corners = nullptr) {
  const double h = grid.spacing(), inverse_d = apic_inverse_d(h);
  grad_v.resize(P.size());
  std::array<long, BlockGrid<Dim>::kNodes> slots;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Stencil<Dim> s(P.x[p], h);
    particle_slots(grid, s, corners, p, slots);
    Vec<Dim> v = Vec<Dim>::Zero();
    Mat<Dim> B = Mat<Dim>::Zero(), G = Mat<Dim>::Zero();
    int n = 0;
    s.for_each([&](const Index<Dim>& k, const Index<Dim>& node) {
      const Vec<Dim>& vi = nodes.velocity[slots[n++]];
      const double w = s.weight(k);
      Vec<Dim> xi;
      for (int d = 0; d < Dim; ++d) xi[d] = node[d] * h;
      v += w * vi;
      B += w * vi * (xi - P.x[p]).transpose();
      G += vi * s.gradient(k).transpose();
    });
    P.v[p] = v;
    P.C[p] = inverse_d * B;
    grad_v[p] = G;
  }
}

}  // namespace suite::mpm2grid
