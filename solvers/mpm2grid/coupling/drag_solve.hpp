#pragma once
// The drag-coupled grid velocity update (docs/methods/mpm2grid.md, step 3), node by node with the lumped
// drag matrix: with b_a = (m v)_a + dt f_a (f including gravity) and d = sum_p c_E V_p w_ip,
//   [ m_s + dt d   -dt d     ] [v_s]   [b_s]
//   [ -dt d        m_w + dt d] [v_w] = [b_w]
// has the closed form  det = m_s m_w + dt d (m_s + m_w),
//   v_s = ((m_w + dt d) b_s + dt d b_w) / det,   v_w = ((m_s + dt d) b_w + dt d b_s) / det.
// It conserves the node's total momentum (m_s v_s + m_w v_w = b_s + b_w) for any dt, and the
// relative velocity decays by 1 / (1 + dt d (m_s + m_w) / (m_s m_w)) per step: unconditionally
// stable. The explicit (forward Euler) drag, v_s = (b_s + dt d (v_w^n - v_s^n)) / m_s, is kept
// to show where explicit coupling fails (relative velocity factor 1 - dt d (m_s + m_w)/(m_s m_w),
// divergent above dt = 2 tau_d).
#include "solvers/mpm2grid/grid/block_grid.hpp"

namespace suite::mpm2grid {

// lumped and explicit_euler are solved here; consistent by ConsistentDrag (consistent_drag.hpp).
enum class DragScheme { lumped, explicit_euler, consistent };

// Sets soil.velocity and water.velocity on every node with mass (scheme: lumped or explicit_euler).
// The momentum and force sums already hold gravity (P2G spreads m_p g with the other forces) and
// the soil's loads. With threads, each solves a share of the nodes.
template <int Dim>
void solve_grid_velocities(NodeFields<Dim>& soil, NodeFields<Dim>& water, double dt, DragScheme scheme,
                           int threads = 1) {
  const std::size_t n = soil.mass.size();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::size_t i = 0; i < n; ++i) {
    const double ms = soil.mass[i], mw = water.mass[i], d = soil.drag[i];
    const Vec<Dim> bs = soil.momentum[i] + dt * soil.force[i];
    const Vec<Dim> bw = water.momentum[i] + dt * water.force[i];
    if (ms > 0 && mw > 0 && d > 0) {
      if (scheme == DragScheme::lumped) {
        const double a = dt * d, det = ms * mw + a * (ms + mw);
        soil.velocity[i] = ((mw + a) * bs + a * bw) / det;
        water.velocity[i] = ((ms + a) * bw + a * bs) / det;
      } else {
        const Vec<Dim> relative = water.momentum[i] / mw - soil.momentum[i] / ms;
        soil.velocity[i] = (bs + dt * d * relative) / ms;
        water.velocity[i] = (bw - dt * d * relative) / mw;
      }
      continue;
    }
    soil.velocity[i] = ms > 0 ? Vec<Dim>(bs / ms) : Vec<Dim>::Zero();
    water.velocity[i] = mw > 0 ? Vec<Dim>(bw / mw) : Vec<Dim>::Zero();
  }
}

}  // namespace suite::mpm2grid
