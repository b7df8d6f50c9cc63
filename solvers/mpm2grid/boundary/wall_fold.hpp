#pragma once
// The walls' mirror condition on the cubic B-spline grid (WallFold): across every slip and sticky
// wall, but the inlet's x_low side, the node one cell beyond the wall is folded into its mirror,
// the node one cell inside. P2G's fold() adds the beyond node's scalars and its vector
// components times S (the normal one reversed, or all for a sticky wall) into the mirror's and
// empties it; G2P's mirror() sets it back from the mirror. Both work on one node tile at a time
// (a tile holds both nodes of every pair its particles reach), so no other rank's nodes are
// involved. Grid spacing h in m.
// Why and how: docs/methods/mpm2grid.md, "Step 4: boundary conditions on the grid velocities".
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

// A tile of a scalar (field 0) and a vector (fields 1 .. Dim).
template <int Dim>
constexpr std::array<TileField, 1 + Dim> scalar_and_vector_fields() {
  std::array<TileField, 1 + Dim> f{};
  for (int a = 0; a < Dim; ++a) f[static_cast<std::size_t>(1 + a)] = {TileField::component, a};
  return f;
}

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
