#pragma once
// The halo of a rank's grid (spec/mpm2grid.md, "Decomposition and performance design"). A rank's
// grid holds the blocks its particles' stencils touch: the ones it owns and, where its particles
// sit within two cells of another rank's blocks, some of that rank's ("ghost" blocks: the 2-cell
// halo of cubic B-splines). Per step:
//   reverse(): after P2G, every ghost block's node values are added into the owner's copy, so
//              the owner holds the complete sums (mass, momentum, force, drag);
//   forward(): after the grid solve, the owner's results (velocities) overwrite the ghost copies,
//              so G2P reads the same node values on every rank.
// plan() sets up who sends what: each rank tells each owner which of its blocks it holds as
// ghosts, and the owner activates any of them its own particles do not touch. Blocks travel in
// the ghost holder's order and are summed in rank order: the sums do not depend on timing.
#include <utility>
#include <vector>

#include "solvers/mpm2grid/decomposition/block_owners.hpp"
#include "solvers/mpm2grid/decomposition/exchange.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"

namespace suite::mpm2grid {

template <int Dim>
class HaloExchange {
 public:
  static constexpr int kNodes = BlockGrid<Dim>::kNodes;

  // COLLECTIVE. Every block of `grid` must have an owner. May add blocks to `grid` (owned ones
  // that only other ranks' particles touch).
  void plan(const mpi::Comm& comm, BlockGrid<Dim>& grid, const BlockOwners& owners) {
    const auto ranks = static_cast<std::size_t>(comm.size());
    ghosts_.assign(ranks, {});
    shared_.assign(ranks, {});
    std::vector<std::vector<typename BlockGrid<Dim>::Key>> keys(ranks);
    for (std::size_t b = 0; b < grid.blocks(); ++b) {
      const auto key = BlockGrid<Dim>::key(grid.block_coord(b));
      const int r = owners.owner(key);
      if (r < 0) throw LibraryError("HaloExchange::plan: a grid block has no owner (claim it first)");
      if (r == comm.rank()) continue;
      ghosts_[static_cast<std::size_t>(r)].push_back(static_cast<int>(b));
      keys[static_cast<std::size_t>(r)].push_back(key);
    }
    const auto wanted = all_to_all(comm, keys);
    for (std::size_t r = 0; r < ranks; ++r)
      for (const auto key : wanted[r]) shared_[r].push_back(grid.activate(BlockGrid<Dim>::unkey(key)));
    owned_.assign(grid.blocks(), 1);
    for (const auto& list : ghosts_)
      for (const int b : list) owned_[static_cast<std::size_t>(b)] = 0;
  }

  // Per block of the planned grid: 1 when this rank owns it.
  const std::vector<char>& owned() const { return owned_; }
  // Bytes this rank has sent in reverse() and forward() calls since the last take_bytes().
  long long take_bytes() { return std::exchange(bytes_, 0); }

  // pack(slot, double* out) writes `width` doubles of a ghost node; add(slot, const double* in)
  // adds them into the owned node. COLLECTIVE.
  template <class Pack, class Add>
  void reverse(const mpi::Comm& comm, int width, Pack&& pack, Add&& add) {
    move(comm, width, ghosts_, shared_, pack, add);
  }
  // pack(slot, out) writes `width` doubles of an owned node; set(slot, in) stores them in the
  // ghost copy. COLLECTIVE.
  template <class Pack, class Set>
  void forward(const mpi::Comm& comm, int width, Pack&& pack, Set&& set) {
    move(comm, width, shared_, ghosts_, pack, set);
  }

 private:
  template <class Pack, class Unpack>
  void move(const mpi::Comm& comm, int width, const std::vector<std::vector<int>>& from,
            const std::vector<std::vector<int>>& to, Pack& pack, Unpack& unpack) {
    const auto ranks = static_cast<std::size_t>(comm.size());
    const auto w = static_cast<std::size_t>(width);
    std::vector<std::vector<double>> send(ranks);
    for (std::size_t r = 0; r < ranks; ++r) {
      send[r].resize(from[r].size() * kNodes * w);
      double* out = send[r].data();
      for (const int b : from[r])
        for (int n = 0; n < kNodes; ++n, out += w) pack(static_cast<long>(b) * kNodes + n, out);
      bytes_ += static_cast<long long>(send[r].size() * sizeof(double));
    }
    const auto received = all_to_all(comm, send);
    for (std::size_t r = 0; r < ranks; ++r) {
      if (received[r].size() != to[r].size() * kNodes * w)
        throw LibraryError("HaloExchange: a neighbour sent another number of node values than planned");
      const double* in = received[r].data();
      for (const int b : to[r])
        for (int n = 0; n < kNodes; ++n, in += w) unpack(static_cast<long>(b) * kNodes + n, in);
    }
  }

  std::vector<std::vector<int>> ghosts_;  // per owner rank: this rank's ghost blocks of it, in sent order
  std::vector<std::vector<int>> shared_;  // per rank: this rank's blocks it holds as ghosts, in its order
  std::vector<char> owned_;
  long long bytes_ = 0;
};

}  // namespace suite::mpm2grid
