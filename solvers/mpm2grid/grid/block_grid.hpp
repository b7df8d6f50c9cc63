#pragma once
// The sparse background grid (docs/methods/mpm2grid.md, "Model no more than the scene needs"): nodes
// exist only in blocks of 4^Dim nodes that some particle's B-spline stencil touches, found from
// the particles every step, never a dense box over the domain. Node (i, j[, k]) sits at
// (i h, j h[, k h]); block b holds nodes 4 b .. 4 b + 3 per axis. Both species' grids use the
// same blocks (co-located nodes), each with its own node fields (NodeFields). A block's index is
// looked up in an array over a box (the scene's walls; set_dense_box) and, outside it, in a hash
// table.
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "solvers/mpm2grid/kernels/bspline.hpp"

namespace suite::mpm2grid {

template <int Dim>
class BlockGrid {
 public:
  static constexpr int kSide = 4;                    // nodes per block side
  static constexpr int kNodes = Dim == 2 ? 16 : 64;  // nodes per block (and per stencil)
  static constexpr int kStencilBlocks = 1 << Dim;    // blocks a stencil can touch

  using Key = std::uint64_t;  // a block's coordinates packed into one integer (key())

  explicit BlockGrid(double h) : h_(h) {}

  double spacing() const { return h_; }
  std::size_t blocks() const { return coords_.size(); }
  std::size_t nodes() const { return coords_.size() * kNodes; }

  // Drops every block (keeps the storage for the next step).
  void clear() {
    for (const Index<Dim>& b : coords_)
      if (const long i = dense_entry(b); i >= 0) dense_[static_cast<std::size_t>(i)] = -1;
    coords_.clear();
    lookup_.clear();
  }

  // The dense box of a scene whose walls span lo .. hi: their blocks and two more on each side (the
  // blocks any stencil of a particle inside reaches, one block past the walls, and the halo's).
  // walls_box_blocks: its blocks, in floating point (walls far apart must not overflow an int).
  static double walls_box_blocks(const Vec<Dim>& lo, const Vec<Dim>& hi, double h) {
    double blocks = 1;
    for (int d = 0; d < Dim; ++d) blocks *= (hi[d] - lo[d]) / (kSide * h) + 6;
    return blocks;
  }
  bool set_walls_box(const Vec<Dim>& lo, const Vec<Dim>& hi) {
    if (!(walls_box_blocks(lo, hi, h_) <= static_cast<double>(kDenseBlocks))) return false;
    Index<Dim> first = home_block(lo), last = home_block(hi);
    for (int d = 0; d < Dim; ++d) first[d] -= 2, last[d] += 2;
    return set_dense_box(first, last);
  }

  // A box of blocks, lo .. hi per axis, where the blocks' indices are looked up in an array, not
  // in the hash table (which holds the blocks outside it): the blocks a scene's walls enclose.
  // Refused (the hash table alone, as without a box) where the box has more than kDenseBlocks
  // blocks. Set while no block is active.
  static constexpr std::size_t kDenseBlocks = std::size_t{1} << 22;  // 16 MiB of indices
  bool set_dense_box(const Index<Dim>& lo, const Index<Dim>& hi) {
    if (!coords_.empty()) throw std::logic_error("BlockGrid::set_dense_box: blocks are active");
    std::size_t count = 1;
    for (int d = 0; d < Dim; ++d) {
      if (hi[d] < lo[d]) return false;
      count *= static_cast<std::size_t>(hi[d] - lo[d]) + 1;
      if (count > kDenseBlocks) return false;
    }
    box_lo_ = lo;
    std::size_t stride = 1;
    for (int d = 0; d < Dim; ++d) {
      box_size_[d] = hi[d] - lo[d] + 1;
      box_stride_[d] = stride;
      stride *= static_cast<std::size_t>(box_size_[d]);
    }
    dense_.assign(count, -1);
    return true;
  }

  // The indices of the 2^Dim blocks a stencil may touch, in corner order (-1: not active). A
  // particle's corners, found once a step (touch), spare the hash lookups of every later transfer
  // (slots_from_corners); blocks added later do not change the indices of earlier ones.
  using Corners = std::array<int, kStencilBlocks>;

  // Activates the blocks the 4^Dim nodes of the stencil with first node `base` lie in, and gives
  // their indices.
  void touch(const Index<Dim>& base, Corners& corners) {
    for_stencil_blocks(base, [&](int corner, const Index<Dim>& b) { corners[corner] = activate(b); });
  }
  void touch(const Stencil<Dim>& s) {
    Corners corners;
    touch(s.base, corners);
  }

  // Activates one block (if it is not active yet) and returns its index.
  int activate(const Index<Dim>& b) {
    const auto fresh = static_cast<int>(coords_.size());
    if (const long i = dense_entry(b); i >= 0) {
      int& index = dense_[static_cast<std::size_t>(i)];
      if (index < 0) index = fresh, coords_.push_back(b);
      return index;
    }
    const auto [it, added] = lookup_.try_emplace(pack(b), fresh);
    if (added) coords_.push_back(b);
    return it->second;
  }

  // Index of the block with coordinates b, or -1 when it is not active.
  int find_block(const Index<Dim>& b) const {
    if (const long i = dense_entry(b); i >= 0) return dense_[static_cast<std::size_t>(i)];
    const auto it = lookup_.find(pack(b));
    return it == lookup_.end() ? -1 : it->second;
  }

  // Index of the block holding `node`, or -1 when that block is not active.
  int block_of_node(const Index<Dim>& node) const { return find_block(block_holding(node)); }

  // The coordinates of the block that holds `node` (active or not).
  static Index<Dim> block_holding(const Index<Dim>& node) {
    Index<Dim> b;
    for (int d = 0; d < Dim; ++d) b[d] = floor_div(node[d]);
    return b;
  }
  // A particle's home block: the block holding the lower corner floor(x / h) of its cell, a node
  // of its stencil. The rank owning that block owns the particle (decomposition/).
  Index<Dim> home_block(const Vec<Dim>& x) const { return home_block(x, h_); }
  static Index<Dim> home_block(const Vec<Dim>& x, double h) {
    Index<Dim> node;
    for (int d = 0; d < Dim; ++d) node[d] = static_cast<int>(std::floor(in_cells(x[d], h)));
    return block_holding(node);
  }
  // A block's key, unique per coordinates, and back.
  static Key key(const Index<Dim>& b) { return pack(b); }
  static Index<Dim> unkey(Key key) {
    Index<Dim> b;
    for (int d = Dim - 1; d >= 0; --d) {
      b[d] = static_cast<int>(key & 0x1FFFFF) - (1 << 20);
      key >>= 21;
    }
    return b;
  }

  // Slot (0 .. nodes() - 1) of an active node, or -1.
  long slot_of(const Index<Dim>& node) const {
    const int b = block_of_node(node);
    return b < 0 ? -1 : static_cast<long>(b) * kNodes + local(node);
  }

  // The corners of a stencil by lookup (-1 for a block that is not active).
  void stencil_corners(const Stencil<Dim>& s, Corners& corners) const {
    for_stencil_blocks(s.base, [&](int corner, const Index<Dim>& b) { corners[corner] = find_block(b); });
  }

  // The slots of a stencil's 4^Dim nodes, in Stencil::for_each order, from its corners (-1 for a
  // node of a block that is not active).
  void slots_from_corners(const Stencil<Dim>& s, const Corners& corners, std::array<long, kNodes>& out) const {
    // Per axis, for the stencil's nodes base + k: the corner bit of the block holding the node
    // (0: the block of base, 1: the next one) and the node's place in its block times the axis'
    // stride in a block.
    std::array<std::array<int, 4>, Dim> corner_bit, place;
    int stride = 1;
    for (int d = 0; d < Dim; ++d) {
      const int first = floor_div(s.base[d]);
      for (int k = 0; k < 4; ++k) {
        const int node = s.base[d] + k, b = floor_div(node);
        corner_bit[d][k] = (b - first) << d;
        place[d][k] = (node - b * kSide) * stride;
      }
      stride *= kSide;
    }
    for (int n = 0; n < kNodes; ++n) {
      int corner = 0, l = 0;
      for (int d = 0; d < Dim; ++d) {
        corner |= corner_bit[d][Stencil<Dim>::corner_index(n, d)];
        l += place[d][Stencil<Dim>::corner_index(n, d)];
      }
      const int b = corners[static_cast<std::size_t>(corner)];
      out[n] = b < 0 ? -1 : static_cast<long>(b) * kNodes + l;
    }
  }

  // The slots of a stencil's 4^Dim nodes, in Stencil::for_each order (-1 where the block is not
  // active).
  void stencil_slots(const Stencil<Dim>& s, std::array<long, kNodes>& out) const {
    Corners corners;
    stencil_corners(s, corners);
    slots_from_corners(s, corners, out);
  }

  // The node index and position of a slot.
  Index<Dim> node_of(long slot) const {
    const Index<Dim>& b = coords_[static_cast<std::size_t>(slot / kNodes)];
    int r = static_cast<int>(slot % kNodes);
    Index<Dim> node;
    for (int d = 0; d < Dim; ++d) {
      node[d] = b[d] * kSide + r % kSide;
      r /= kSide;
    }
    return node;
  }
  Vec<Dim> position(long slot) const {
    const Index<Dim> n = node_of(slot);
    Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) x[d] = n[d] * h_;
    return x;
  }
  const Index<Dim>& block_coord(std::size_t b) const { return coords_[b]; }

 private:
  // floor(i / kSide): an arithmetic shift (C++20 defines >> of a negative value as one).
  static_assert(kSide == 4, "floor_div shifts by log2(kSide)");
  static int floor_div(int i) { return i >> 2; }
  static int local(const Index<Dim>& node) {
    int l = 0, stride = 1;
    for (int d = 0; d < Dim; ++d) {
      l += (node[d] - floor_div(node[d]) * kSide) * stride;
      stride *= kSide;
    }
    return l;
  }
  // Block coordinates fit in 21 bits each (+- 10^6 blocks of 4 nodes per axis).
  static std::uint64_t pack(const Index<Dim>& b) {
    std::uint64_t key = 0;
    for (int d = 0; d < Dim; ++d) key = (key << 21) | static_cast<std::uint64_t>((b[d] + (1 << 20)) & 0x1FFFFF);
    return key;
  }
  // f(corner bits, block) for the 2^Dim blocks a stencil (nodes base .. base + 3) may touch; when the
  // stencil lies in one block along an axis, the corner's block repeats that one.
  template <class F>
  void for_stencil_blocks(const Index<Dim>& base, F&& f) const {
    for (int corner = 0; corner < kStencilBlocks; ++corner) {
      Index<Dim> b;
      for (int d = 0; d < Dim; ++d) b[d] = floor_div(base[d] + ((corner >> d) & 1) * 3);
      f(corner, b);
    }
  }

  // The entry of block b in dense_, or -1 outside the dense box (or without one).
  long dense_entry(const Index<Dim>& b) const {
    if (dense_.empty()) return -1;
    std::size_t i = 0;
    for (int d = 0; d < Dim; ++d) {
      const auto offset = static_cast<unsigned>(b[d] - box_lo_[d]);  // below lo: wraps past the size
      if (offset >= static_cast<unsigned>(box_size_[d])) return -1;
      i += offset * box_stride_[d];
    }
    return static_cast<long>(i);
  }

  double h_;
  std::vector<Index<Dim>> coords_;
  std::unordered_map<std::uint64_t, int> lookup_;  // the active blocks outside the dense box
  // The dense box: its first block, blocks per axis, the axes' strides, and per block its index
  // (-1: not active).
  Index<Dim> box_lo_{};
  std::array<int, Dim> box_size_{};
  std::array<std::size_t, Dim> box_stride_{};
  std::vector<int> dense_;
};

// One species' grid values, one entry per node slot.
template <int Dim>
struct NodeFields {
  std::vector<double> mass;        // kg (per metre of thickness in 2D)
  std::vector<Vec<Dim>> momentum;  // kg m/s: sum_p w_ip m_p (v_p + C_p (x_i - x_p)), plus dt
                                   // times the particles' forces where P2G folds them in
                                   // (P2GSources::fold_dt, transfer/apic.hpp)
  std::vector<Vec<Dim>> force;     // N: the particles' forces (unless folded), gravity, loads
  std::vector<Vec<Dim>> velocity;  // m/s after the grid solve
  std::vector<double> drag;        // kg/s: sum_p c_E,p V_p w_ip (soil only)
  std::vector<double> pressure;    // water only, with buoyancy: sum_p w_ip m_p p_p after P2G,
                                   // then the mass-weighted pressure (Pa)

  // Every field `nodes` long and zero; with threads, each zeroes a share of the nodes.
  void reset(std::size_t nodes, int threads = 1) {
    if (threads == 1) {
      mass.assign(nodes, 0.0);
      momentum.assign(nodes, Vec<Dim>::Zero());
      force.assign(nodes, Vec<Dim>::Zero());
      velocity.assign(nodes, Vec<Dim>::Zero());
      drag.assign(nodes, 0.0);
      pressure.assign(nodes, 0.0);
      return;
    }
    mass.resize(nodes), momentum.resize(nodes), force.resize(nodes), velocity.resize(nodes);
    drag.resize(nodes), pressure.resize(nodes);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::size_t i = 0; i < nodes; ++i) {
      mass[i] = drag[i] = pressure[i] = 0;
      momentum[i].setZero(), force[i].setZero(), velocity[i].setZero();
    }
  }
};

}  // namespace suite::mpm2grid
