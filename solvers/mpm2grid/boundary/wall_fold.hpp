#pragma once
// The walls' mirror condition on the cubic B-spline grid: the node one cell beyond a wall folded
// into its mirror, the node one cell inside.
//
// Why. A particle within a cell of a wall spreads to the node one cell beyond it (weight up to
// 1/6). The wall conditions (boundary/walls.hpp) act on the nodes on and beyond the wall, and the
// node one cell inside, whose B-spline is 1/6 at the wall, got no reaction from it: its weak form
// kept the boundary term -sigma_n N_1(wall) of the stress at the wall, which the particles next to
// the wall balanced by themselves. In a still tank their pressure stood 23% of rho g H above
// hydrostatic (20% of the load in Terzaghi's column), at every h.
//
// What. The velocity field is continued across the wall as its mirror image: a node one cell
// beyond the wall moves as its mirror node one cell inside with the normal component reversed
// (slip walls: free slip, dv_t/dn = 0) or with every component reversed (sticky walls: no
// slip), v_beyond = S v_mirror. Putting that into the weak form adds the beyond node's
// equation into its mirror's with S: P2G adds the beyond node's masses, drag coefficients and
// pressure sums into the mirror node's, and its momentum and forces times S, and leaves the
// beyond node empty (it takes no part in the grid solve); G2P reads the beyond node's velocity as
// S times the mirror's (and its scalars as the mirror's). The mirror node's basis is then
// N_1 + N_-1 for the tangential components and N_1 - N_-1 for the normal one, which vanishes at
// the wall: the boundary term is gone, and a hydrostatic pressure balances gravity node by node.
// The node on the wall is its own mirror (its normal velocity is zero, as before). Over several
// walls (edges, corners) the folds compose axis by axis. Nothing changes for a particle more than
// a cell from every wall.
//
// Where. Every slip and sticky wall, except the x_low side of a scene with an inlet, whose nodes
// carry the inflow velocity. Open sides fold nothing, and neither do friction walls: their Coulomb
// condition acts on the nodes on and beyond the wall, and a block sliding on a friction floor
// decelerates at mu g that way (test_walls.cpp), while with the slip mirror it decelerated at
// 0.79 and 1.85 times mu g (mu = 0.2 and 0.5). Both nodes of a
// pair lie in the same node tile whenever a particle's stencil reaches the beyond node (a
// stencil base .. base + 3 that holds wall - 1 holds wall + 1 too, and the tile holds 8 nodes from
// the group's first), so the fold is done per tile, before P2G adds a tile to the grid and after
// G2P reads one: no other rank's node is involved.
//
// What it leaves out. The consistent (PETSc) drag matrix is assembled from the particles'
// B-spline weights without the fold: the beyond node, now without mass, is not coupled, and its
// share of D is dropped (the lumped drag folds its coefficient like the mass).
#include <array>
#include <cmath>
#include <cstddef>

#include "solvers/mpm2grid/boundary/walls.hpp"
#include "solvers/mpm2grid/grid/node_tile.hpp"
#include "solvers/mpm2grid/kernels/bspline.hpp"

namespace suite::mpm2grid {

// What a tile field holds, for the fold's sign: a scalar, a vector's component along an axis, or
// nothing the fold touches (values a transfer only reads, mirrored separately).
struct TileField {
  enum Kind { scalar, component, untouched } kind = scalar;
  int axis = 0;  // for component
};

template <int Dim>
class WallFold {
 public:
  // The folding sides of `walls` (grid spacing h; the sides on grid planes): the slip and sticky
  // walls, but the x_low side when `inlet_on_x_low`.
  WallFold(const Walls<Dim>& walls, double h, bool inlet_on_x_low) {
    for (int d = 0; d < Dim; ++d)
      for (int side = 0; side < 2; ++side) {
        const WallKind k = walls.kind[d][side];
        Side& s = sides_[static_cast<std::size_t>(d)][static_cast<std::size_t>(side)];
        s.folds = (k == WallKind::slip || k == WallKind::sticky) && !(inlet_on_x_low && d == 0 && side == 0);
        s.sticky = k == WallKind::sticky;
        s.wall = static_cast<int>(std::lround((side == 0 ? walls.lo[d] : walls.hi[d]) / h));
        any_ = any_ || s.folds;
      }
  }

  // P2G: in a tile, adds the nodes one cell beyond each folding wall into their mirrors
  // (scalars as they are, components times S) and zeroes them, axis by axis. Fields marked
  // untouched keep their values.
  template <int Fields, std::size_t N>
  void fold(NodeTile<Dim, Fields>& tile, const std::array<TileField, N>& fields) const {
    pairs(tile, fields, [](double& beyond, double& mirror, double sign) {
      mirror += sign * beyond;
      beyond = 0;
    });
  }

  // G2P: in a tile, sets the nodes one cell beyond each folding wall from their mirrors
  // (scalars as they are, components times S), axis by axis. Fields marked untouched keep
  // their values.
  template <int Fields, std::size_t N>
  void mirror(NodeTile<Dim, Fields>& tile, const std::array<TileField, N>& fields) const {
    pairs(tile, fields, [](double& beyond, double& mirror, double sign) { beyond = sign * mirror; });
  }

  // A vector added at a node outside the tiles (the soil's loads): where the node lies one cell
  // beyond a folding wall, the node it goes to instead (its mirror, axis by axis) and the vector
  // times S; elsewhere the node and the vector as they are.
  void redirect(Index<Dim>& node, Vec<Dim>& value) const {
    for (int d = 0; d < Dim; ++d)
      for (int side = 0; side < 2; ++side) {
        const Side& s = sides_[static_cast<std::size_t>(d)][static_cast<std::size_t>(side)];
        const int out = side == 0 ? -1 : 1;
        if (!s.folds || node[d] != s.wall + out) continue;
        node[d] = s.wall - out;
        for (int a = 0; a < Dim; ++a) value[a] *= sign({TileField::component, a}, s, d);
      }
  }

  // The part of a node's B-spline weight that a material filling the box up to the walls gives
  // it, in [0, 1] (walls.inside_fraction, with the fold): one cell inside a folding wall the node
  // has its own part 23/24 and its mirror's 1/24, i.e. all of it; beyond the wall nothing.
  double inside_fraction(const Walls<Dim>& walls, const Vec<Dim>& node, double h) const {
    double f = 1;
    for (int d = 0; d < Dim; ++d)
      for (int side = 0; side < 2; ++side) {
        const Side& s = sides_[static_cast<std::size_t>(d)][static_cast<std::size_t>(side)];
        const double r = side == 0 ? (node[d] - walls.lo[d]) / h : (walls.hi[d] - node[d]) / h;
        if (!s.folds) {
          f *= cubic_bspline_integral(r);
        } else {
          const long k = std::lround(r);
          f *= k == 1  ? cubic_bspline_integral(1.0) + cubic_bspline_integral(-1.0)
               : k < 0 ? 0.0
                       : cubic_bspline_integral(r);
        }
      }
    return f;
  }

 private:
  struct Side {
    bool folds = false, sticky = false;
    int wall = 0;  // the wall's node index along its axis
  };

  static double sign(const TileField& field, const Side& s, int axis) {
    if (field.kind != TileField::component) return 1.0;
    return s.sticky || field.axis == axis ? -1.0 : 1.0;
  }

  // op(beyond value, mirror value, sign of S) for each field the fold touches at each pair of
  // tile nodes one cell beyond and one cell inside a folding wall, both in the tile, axis by
  // axis (x first).
  template <int Fields, std::size_t N, class Op>
  void pairs(NodeTile<Dim, Fields>& tile, const std::array<TileField, N>& fields, Op&& op) const {
    static_assert(N == Fields, "one TileField per tile field");
    for_each_pair(tile, [&](int beyond, int mirror, const Side& s, int d) {
      for (int f = 0; f < Fields; ++f) {
        const TileField& field = fields[static_cast<std::size_t>(f)];
        if (field.kind == TileField::untouched) continue;
        double* v = tile.field(f);
        op(v[beyond], v[mirror], sign(field, s, d));
      }
    });
  }

  // f(beyond, mirror, side, axis) for each pair of tile indices one cell beyond and one cell
  // inside a folding wall, both in the tile, axis by axis (x first).
  template <int Fields, class F>
  void for_each_pair(const NodeTile<Dim, Fields>& tile, F&& f) const {
    using Tile = NodeTile<Dim, Fields>;
    if (!any_) return;
    const Index<Dim> origin = tile.first_node();
    int stride = 1;
    for (int d = 0; d < Dim; ++d, stride *= Tile::kSide)
      for (int side = 0; side < 2; ++side) {
        const Side& s = sides_[static_cast<std::size_t>(d)][static_cast<std::size_t>(side)];
        if (!s.folds) continue;
        const int out = side == 0 ? -1 : 1;
        const int beyond = s.wall + out - origin[d], mirror = s.wall - out - origin[d];
        if (beyond < 0 || beyond >= Tile::kSide || mirror < 0 || mirror >= Tile::kSide) continue;
        // The plane of the beyond nodes, in ascending tile index: the axes below d (low) and
        // above it (high).
        for (int high = 0; high < Tile::kSize / (stride * Tile::kSide); ++high)
          for (int low = 0; low < stride; ++low) {
            const int t = low + stride * (beyond + Tile::kSide * high);
            f(t, t + (mirror - beyond) * stride, s, d);
          }
      }
  }

  std::array<std::array<Side, 2>, Dim> sides_{};
  bool any_ = false;  // some side folds
};

}  // namespace suite::mpm2grid
