#pragma once
// The walls of the scene's box (docs/methods/mpm2grid.md, step 4). Each side is a wall or open:
//   slip      no flow into the wall, free tangential motion: v -= min(v . n, 0) n
//   sticky    no motion at the wall: v = 0
//   friction  Coulomb: the normal velocity into the wall is removed and the tangential speed
//             reduced by mu times that normal speed (to zero at most). For the soil only: the
//             water, inviscid, slips along a friction wall (Walls::for_water()).
//   open      nothing; particles that leave through an open side leave the model (outflow)
// n is the inward normal. The conditions act on the grid nodes on or beyond the wall plane (the
// B-spline stencils of particles near a wall reach those nodes), so the box should have its sides
// on grid planes (multiples of h).
#include <array>

#include "solvers/mpm2grid/grid/block_grid.hpp"

namespace suite::mpm2grid {

enum class WallKind { slip, sticky, friction, open };

template <int Dim>
struct Walls {
  Vec<Dim> lo = Vec<Dim>::Zero(), hi = Vec<Dim>::Ones();
  std::array<std::array<WallKind, 2>, Dim> kind{};  // [axis][0: low side, 1: high side]
  double friction = 0;                              // Coulomb coefficient for friction walls

  // The walls the water sees: every friction wall a slip wall. Coulomb friction is the soil's
  // grains against the wall; an inviscid fluid has no wall friction, and the friction law, whose
  // impulse follows the normal velocity the transfers bring back to a wall node every step, made
  // the water's flow depend on the step count (docs/mpm2grid.md, "What a step does", step 4).
  Walls for_water() const {
    Walls w = *this;
    for (auto& sides : w.kind)
      for (WallKind& k : sides)
        if (k == WallKind::friction) k = WallKind::slip;
    return w;
  }

  // The walls with every closed side a slip wall: across each a mirror image of what lies inside
  // (the soil's shape for the free water's contact, coupling/free_water.hpp).
  Walls all_slip() const {
    Walls w = *this;
    for (auto& sides : w.kind)
      for (WallKind& k : sides)
        if (k != WallKind::open) k = WallKind::slip;
    return w;
  }

  // True when some side is open (particles can leave the model).
  bool any_open() const {
    for (const auto& sides : kind)
      for (const WallKind k : sides)
        if (k == WallKind::open) return true;
    return false;
  }

  // True when x has left the box through an open side.
  bool left_through_open_side(const Vec<Dim>& x) const {
    for (int d = 0; d < Dim; ++d) {
      if (x[d] < lo[d] && kind[d][0] == WallKind::open) return true;
      if (x[d] > hi[d] && kind[d][1] == WallKind::open) return true;
    }
    return false;
  }

  // Keeps a particle inside the closed sides (a safety net; the grid conditions keep particles
  // from crossing except by round-off).
  void clamp(Vec<Dim>& x) const {
    for (int d = 0; d < Dim; ++d) {
      if (kind[d][0] != WallKind::open && x[d] < lo[d]) x[d] = lo[d];
      if (kind[d][1] != WallKind::open && x[d] > hi[d]) x[d] = hi[d];
    }
  }

  // The part of a node's B-spline weight that lies inside the box, in [0, 1]: prod over the sides
  // of integral N over the inside. A material that fills the box up to a wall gives the nodes on
  // and next to the wall only this part of an interior node's volume (1/2 on the wall, 1/24 one
  // cell beyond it); dividing a node's volume fraction by it removes that wall layer.
  double inside_fraction(const Vec<Dim>& node, double h) const {
    double f = 1;
    for (int d = 0; d < Dim; ++d)
      f *= cubic_bspline_integral((node[d] - lo[d]) / h) * cubic_bspline_integral((hi[d] - node[d]) / h);
    return f;
  }

  // The walls' conditions on the velocities of the nodes on or beyond them (with threads, each
  // thread a share of the nodes).
  void apply(const BlockGrid<Dim>& grid, NodeFields<Dim>& nodes, int threads = 1) const {
    const double tol = 1e-9 * grid.spacing();
    const long n = static_cast<long>(nodes.mass.size());
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
    for (long i = 0; i < n; ++i) {
      if (!(nodes.mass[i] > 0)) continue;
      const Vec<Dim> x = grid.position(i);
      for (int d = 0; d < Dim; ++d)
        for (int side = 0; side < 2; ++side) {
          const bool beyond = side == 0 ? x[d] <= lo[d] + tol : x[d] >= hi[d] - tol;
          if (beyond) impose(kind[d][side], d, side == 0 ? 1.0 : -1.0, nodes.velocity[i]);
        }
    }
  }

 private:
  void impose(WallKind k, int axis, double inward, Vec<Dim>& v) const {
    if (k == WallKind::open) return;
    if (k == WallKind::sticky) {
      v.setZero();
      return;
    }
    const double vn = v[axis] * inward;  // > 0: moving away from the wall
    if (vn >= 0) return;
    v[axis] = 0;  // remove the motion into the wall
    if (k == WallKind::friction) {
      const double vt = v.norm();
      v *= vt > 0 ? std::max(0.0, 1 - friction * (-vn) / vt) : 0.0;
    }
  }
};

}  // namespace suite::mpm2grid
