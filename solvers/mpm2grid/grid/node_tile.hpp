#pragma once
// A dense scratch copy of the grid nodes around one block, through which the transfers move
// values between particles and the sparse block grid (grid/block_grid.hpp).
//
// A particle's group is the block holding the first node (Stencil::base) of its cubic B-spline
// stencil. Its stencil's nodes base .. base + 3 then lie in the group's block and the next one
// along each axis: in the 2^Dim blocks g + {0, 1}^Dim, 8 nodes per axis, which the tile holds as
// one dense array, x fastest (tile index tx + 8 ty [+ 64 tz]). There a stencil's row along x is
// 4 consecutive values: the transfers work on whole rows (loops the compiler vectorizes), with no
// slot to find per node. Particles taken in group order (transfer/particle_order.hpp) fill or
// read one tile per group; each group's tile is added to (flush) or read from (gather) the block
// grid's slots once.
//
// The tile holds `Fields` scalar fields, each 8^Dim doubles (structure of arrays).
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "solvers/mpm2grid/grid/block_grid.hpp"

namespace suite::mpm2grid {

template <int Dim, int Fields>
class NodeTile {
 public:
  using Grid = BlockGrid<Dim>;
  static constexpr int kSide = 2 * Grid::kSide;         // 8 nodes per axis
  static constexpr int kSize = Dim == 2 ? 64 : 512;     // nodes per field
  static constexpr int kBlocks = Grid::kStencilBlocks;  // 2^Dim blocks
  static_assert(Fields >= 1);

  // The group of a stencil whose first node is `base`.
  static Index<Dim> group_of(const Index<Dim>& base) { return Grid::block_holding(base); }
  // Tile index of a stencil's first node in its group's tile.
  static int first_index(const Index<Dim>& base, const Index<Dim>& group) {
    int t = 0, stride = 1;
    for (int d = 0; d < Dim; ++d) {
      t += (base[d] - group[d] * Grid::kSide) * stride;
      stride *= kSide;
    }
    return t;
  }
  // Where row r of a stencil (its nodes base + (0..3, j[, k]), r = j [+ 4 k]) starts, from the
  // stencil's first tile index.
  static constexpr int row_offset(int r) { return Dim == 2 ? kSide * r : kSide * (r & 3) + kSide * kSide * (r >> 2); }

  // True when the tile is covering some group, and group g.
  bool covering() const { return covering_; }
  // (Compared as packed keys in registers: comparing the Index arrays made the compiler store
  // g as two ints and load them back as one 8-byte word, a store-forwarding stall per particle;
  // docs/mpm2grid.md, "Benchmarks".)
  bool covers(const Index<Dim>& g) const { return covering_ && Grid::key(g) == key_; }

  // Covers group g: finds its 2^Dim blocks in the grid (a block that is not active: -1, its
  // nodes neither read nor written). The values are left as they were (zero() or gather()).
  void cover(const Grid& grid, const Index<Dim>& g) {
    key_ = Grid::key(g);
    covering_ = true;
    for (int c = 0; c < kBlocks; ++c) {
      Index<Dim> b = g;
      for (int d = 0; d < Dim; ++d) b[d] += (c >> d) & 1;
      blocks_[static_cast<std::size_t>(c)] = grid.find_block(b);
    }
  }
  // The covered group's first node (the tile's index 0).
  Index<Dim> first_node() const {
    Index<Dim> n = Grid::unkey(key_);
    for (int d = 0; d < Dim; ++d) n[d] *= Grid::kSide;
    return n;
  }
  // Forgets the group (the next covers() is false).
  void release() { covering_ = false; }

  void zero() { std::fill(data_.begin(), data_.end(), 0.0); }
  // Zeroes the tile and copies values[slot] of the covered blocks' nodes into field f.
  void gather(int f, const std::vector<double>& values) {
    zero();
    for_each_node([&](int t, long slot) { field(f)[t] = values[static_cast<std::size_t>(slot)]; });
  }
  double* field(int f) { return data_.data() + f * kSize; }
  const double* field(int f) const { return data_.data() + f * kSize; }

  // Calls f(tile index, slot) for every node of the covered group's active blocks, block by block
  // in corner order and slot order within a block.
  template <class F>
  void for_each_node(F&& f) const {
    for (int c = 0; c < kBlocks; ++c) {
      const int b = blocks_[static_cast<std::size_t>(c)];
      if (b < 0) continue;
      const long first = static_cast<long>(b) * Grid::kNodes;
      const auto& index = kIndex[static_cast<std::size_t>(c)];
      for (int l = 0; l < Grid::kNodes; ++l) f(static_cast<int>(index[static_cast<std::size_t>(l)]), first + l);
    }
  }

 private:
  // kIndex[c][l]: tile index of node l (block-local order, x fastest) of corner block c.
  using IndexTable = std::array<std::array<std::int16_t, Grid::kNodes>, kBlocks>;
  static constexpr IndexTable make_index() {
    IndexTable table{};
    for (int c = 0; c < kBlocks; ++c)
      for (int l = 0; l < Grid::kNodes; ++l) {
        int t = 0, stride = 1, r = l;
        for (int d = 0; d < Dim; ++d) {
          t += (((c >> d) & 1) * Grid::kSide + r % Grid::kSide) * stride;
          r /= Grid::kSide;
          stride *= kSide;
        }
        table[static_cast<std::size_t>(c)][static_cast<std::size_t>(l)] = static_cast<std::int16_t>(t);
      }
    return table;
  }
  static constexpr IndexTable kIndex = make_index();

  typename Grid::Key key_ = 0;  // the covered group's key (BlockGrid::key)
  bool covering_ = false;
  std::array<int, kBlocks> blocks_{};
  alignas(64) std::array<double, static_cast<std::size_t>(Fields) * kSize> data_{};
};

}  // namespace suite::mpm2grid
