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
#include <array>
#include <cstring>
#include <vector>

#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"

namespace suite::mpm2grid {

template <int Dim>
using CornerList = std::vector<typename BlockGrid<Dim>::Corners>;

// Each particle's stencil (B-spline weights) and the indices of the grid blocks it touches
// (Corners), found once a step by touch_blocks and used by every transfer of that step instead
// of evaluating the B-splines and looking the blocks up again. A stencil depends on the
// particle's position alone: one kept for the position a particle still has is not evaluated
// again (the saturation update keeps those of the soil's new positions for the next step).
template <int Dim>
struct ParticleStencils {
  std::vector<Stencil<Dim>> stencil;
  CornerList<Dim> corners;
  std::vector<Vec<Dim>> position;  // the position stencil[p] is of, where kept[p]
  std::vector<char> kept;

  // Room for n particles (the kept stencils of the first ones stay).
  void resize(std::size_t n) {
    stencil.resize(n);
    corners.resize(n);
    position.resize(n);
    kept.resize(n, 0);
  }
  // Particle p's stencil at x: the one kept for p when it is of x bit for bit, else a new one,
  // kept.
  const Stencil<Dim>& update(std::size_t p, const Vec<Dim>& x, double h) {
    if (!kept[p] || std::memcmp(position[p].data(), x.data(), sizeof(Vec<Dim>)) != 0) {
      stencil[p] = Stencil<Dim>(x, h);
      position[p] = x;
      kept[p] = 1;
    }
    return stencil[p];
  }
};

// Activates the grid blocks the particles' stencils touch; with `stencils`, also keeps each
// particle's stencil and block indices (one entry per particle).
template <int Dim>
void touch_blocks(const Particles<Dim>& particles, BlockGrid<Dim>& grid, ParticleStencils<Dim>* stencils = nullptr) {
  const double h = grid.spacing();
  if (stencils) stencils->resize(particles.size());
  typename BlockGrid<Dim>::Corners corners{};
  Index<Dim> previous{};
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const Stencil<Dim> s = stencils ? stencils->update(p, particles.x[p], h) : Stencil<Dim>(particles.x[p], h);
    // Neighbouring particles mostly lie in the same blocks as the one before them: then those
    // blocks are active and their indices known, without looking them up.
    if (p == 0 || !BlockGrid<Dim>::same_blocks(s.base, previous)) grid.touch(s, corners);
    previous = s.base;
    if (stencils) stencils->corners[p] = corners;
  }
}

// The particles' stencils on a grid whose blocks are already active (looked up, not activated).
template <int Dim>
ParticleStencils<Dim> find_stencils(const Particles<Dim>& particles, const BlockGrid<Dim>& grid) {
  ParticleStencils<Dim> out;
  out.resize(particles.size());
  for (std::size_t p = 0; p < particles.size(); ++p)
    grid.stencil_corners(out.update(p, particles.x[p], grid.spacing()), out.corners[p]);
  return out;
}

// One particle's stencil nodes as a transfer loops over them (Stencil::for_each order): each
// node's slot, weight and, when asked for, weight gradient.
template <int Dim>
struct StencilNodes {
  static constexpr int kNodes = BlockGrid<Dim>::kNodes;
  std::array<long, kNodes> slot;
  std::array<double, kNodes> weight;
  std::array<Vec<Dim>, kNodes> gradient;

  void fill(const BlockGrid<Dim>& grid, const ParticleStencils<Dim>& stencils, std::size_t p, bool gradients) {
    const Stencil<Dim>& s = stencils.stencil[p];
    grid.slots_from_corners(s, stencils.corners[p], slot);
    s.weights(weight);
    if (gradients) s.gradients(gradient);
  }
};

// x_i - x_p per axis for the stencil's nodes base + k: offset[d][k] = (base[d] + k) h - x_p[d].
template <int Dim>
std::array<std::array<double, 4>, Dim> node_offsets(const Stencil<Dim>& s, const Vec<Dim>& x, double h) {
  std::array<std::array<double, 4>, Dim> offset;
  for (int d = 0; d < Dim; ++d)
    for (int k = 0; k < 4; ++k) offset[d][k] = (s.base[d] + k) * h - x[d];
  return offset;
}

// Adds one species' particles to its node fields (reset to the grid's size by the caller).
// tau: one Kirchhoff stress per particle (Pa), or empty for none; drag: c_E V per particle
// (kg/s), or empty; pressure: p per particle (Pa), added as w m p, or empty; stencils: from
// touch_blocks for these particles and this grid, or null (then looked up).
template <int Dim>
void particles_to_grid(const Particles<Dim>& P, const std::vector<Mat<Dim>>& tau, const std::vector<double>& drag,
                       const BlockGrid<Dim>& grid, NodeFields<Dim>& nodes, const std::vector<double>& pressure = {},
                       const ParticleStencils<Dim>* stencils = nullptr) {
  if (!stencils) {
    const ParticleStencils<Dim> found = find_stencils(P, grid);
    particles_to_grid(P, tau, drag, grid, nodes, pressure, &found);
    return;
  }
  const double h = grid.spacing();
  StencilNodes<Dim> sn;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Stencil<Dim>& s = stencils->stencil[p];
    sn.fill(grid, *stencils, p, !tau.empty());
    const auto offset = node_offsets(s, P.x[p], h);
    const Mat<Dim> stress = tau.empty() ? Mat<Dim>::Zero() : Mat<Dim>(P.volume0[p] * tau[p]);
    const double m = P.mass[p];
    for (int n = 0; n < StencilNodes<Dim>::kNodes; ++n) {
      const auto i = static_cast<std::size_t>(sn.slot[n]);
      const double w = sn.weight[n], wm = w * m;
      Vec<Dim> dx;
      for (int d = 0; d < Dim; ++d) dx[d] = offset[d][Stencil<Dim>::corner_index(n, d)];
      nodes.mass[i] += wm;
      nodes.momentum[i] += wm * (P.v[p] + P.C[p] * dx);
      if (!tau.empty()) nodes.force[i] -= stress * sn.gradient[n];
      if (!drag.empty()) nodes.drag[i] += w * drag[p];
      if (!pressure.empty()) nodes.pressure[i] += wm * pressure[p];
    }
  }
}

// Interpolates the node velocities back: v_p, C_p and grad v_p (one per particle, resized).
// stencils: from touch_blocks for these particles and this grid, or null (then looked up).
template <int Dim>
void grid_to_particles(Particles<Dim>& P, const BlockGrid<Dim>& grid, const NodeFields<Dim>& nodes,
                       std::vector<Mat<Dim>>& grad_v, const ParticleStencils<Dim>* stencils = nullptr) {
  if (!stencils) {
    const ParticleStencils<Dim> found = find_stencils(P, grid);
    grid_to_particles(P, grid, nodes, grad_v, &found);
    return;
  }
  const double h = grid.spacing(), inverse_d = apic_inverse_d(h);
  grad_v.resize(P.size());
  StencilNodes<Dim> sn;
  for (std::size_t p = 0; p < P.size(); ++p) {
    sn.fill(grid, *stencils, p, true);
    const auto offset = node_offsets(stencils->stencil[p], P.x[p], h);
    // v = sum w v_i, B = sum w v_i (x_i - x_p)^T, G = sum v_i (grad w)^T, coefficient by
    // coefficient (Eigen's expressions here go through temporaries in memory).
    Vec<Dim> v = Vec<Dim>::Zero();
    Mat<Dim> B = Mat<Dim>::Zero(), G = Mat<Dim>::Zero();
    for (int n = 0; n < StencilNodes<Dim>::kNodes; ++n) {
      const Vec<Dim>& vi = nodes.velocity[static_cast<std::size_t>(sn.slot[n])];
      const Vec<Dim>& grad = sn.gradient[n];
      const double w = sn.weight[n];
      for (int a = 0; a < Dim; ++a) {
        const double wv = w * vi[a];
        v[a] += wv;
        for (int b = 0; b < Dim; ++b) {
          B(a, b) += wv * offset[b][Stencil<Dim>::corner_index(n, b)];
          G(a, b) += vi[a] * grad[b];
        }
      }
    }
    P.v[p] = v;
    P.C[p] = inverse_d * B;
    grad_v[p] = G;
  }
}

}  // namespace suite::mpm2grid
